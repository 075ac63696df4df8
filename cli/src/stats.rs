//! The statistics JSON (FORMATS.md §3).

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::atomic::Outputs;
use crate::error::Result;

/// One run's statistics, written by `--stats FILE.json`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Stats {
    /// Number of input polygons.
    pub input_polygons: u64,
    /// Number of output fragments (PLY faces).
    pub output_fragments: u64,
    /// Wall-clock seconds per phase.
    pub seconds: Seconds,
    /// One entry per light, in scene order.
    pub lights: Vec<LightStats>,
    /// Input polygons (numbered as FORMATS.md §1) left out of the output:
    /// they have no area once snapped to the scene's grid (degenerate, or
    /// smaller than a grid step in a scene the grid must span far).
    #[serde(default)]
    pub dropped_polygons: Vec<u32>,
}

/// Seconds spent in each phase.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Seconds {
    /// Building the scene BSP.
    pub bsp: f64,
    /// Shadow trees and classification.
    pub shadow: f64,
    /// Gridding / adaptive subdivision.
    pub grid: f64,
    /// Illumination at vertices.
    pub illum: f64,
    /// The whole run.
    pub total: f64,
}

/// Counts for one light, mirroring the tables of the Chin-Feiner papers.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LightStats {
    /// Polygons facing the light.
    pub front_facing_polygons: u64,
    /// Edges of those polygons.
    pub front_facing_edges: u64,
    /// SVBSP nodes (point and directional lights).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tree_nodes: Option<u64>,
    /// Cones the scene was cut into for this light, each with its own scene
    /// BSP and SVBSP tree (point and directional lights).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cones: Option<u64>,
    /// Penumbra tree nodes (area lights).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penumbra_nodes: Option<u64>,
    /// Umbra tree nodes (area lights).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub umbra_nodes: Option<u64>,
    /// Fragments that see all of the light.
    pub lit: u64,
    /// Fragments that see part of it.
    pub penumbra: u64,
    /// Fragments that see none of it.
    pub umbra: u64,
    /// Output mesh points (per receiving plane) evaluated with the whole
    /// light: the 1992 paper's Figure 8 "lit vertices".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lit_vertices: Option<u64>,
    /// Mesh points evaluated from the visible part of the light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penumbra_vertices: Option<u64>,
    /// Mesh points given no light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub umbra_vertices: Option<u64>,
}

impl Stats {
    /// The statistics as pretty-printed JSON.
    pub fn to_json(&self) -> String {
        // Serialising plain numbers and structs cannot fail.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Writes the JSON to `path`, atomically.
    pub fn save(&self, path: &Path) -> Result<()> {
        let mut outputs = Outputs::default();
        self.stage(&mut outputs, path)?;
        outputs.commit()
    }

    /// [`Self::save`] as one of a run's [`Outputs`], written when they are.
    pub fn stage(&self, outputs: &mut Outputs, path: &Path) -> Result<()> {
        stage_json(outputs, path, &self.to_json())
    }
}

/// Stages `json` and a newline as `path`.
pub(crate) fn stage_json(outputs: &mut Outputs, path: &Path, json: &str) -> Result<()> {
    outputs.stage(path, |w| {
        w.write_all(json.as_bytes())?;
        w.write_all(b"\n")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_names_follow_the_contract() {
        let stats = Stats {
            input_polygons: 4,
            output_fragments: 9,
            seconds: Seconds::default(),
            lights: vec![
                LightStats {
                    tree_nodes: Some(12),
                    cones: Some(3),
                    ..LightStats::default()
                },
                LightStats {
                    penumbra_nodes: Some(3),
                    umbra_nodes: Some(2),
                    ..LightStats::default()
                },
            ],
            dropped_polygons: vec![7],
        };
        let v: serde_json::Value = serde_json::from_str(&stats.to_json()).unwrap();
        for key in ["input_polygons", "output_fragments", "seconds", "lights"] {
            assert!(v.get(key).is_some(), "{key}");
        }
        assert_eq!(v["dropped_polygons"], serde_json::json!([7]));
        for key in ["bsp", "shadow", "grid", "illum", "total"] {
            assert!(v["seconds"].get(key).is_some(), "{key}");
        }
        let point = &v["lights"][0];
        for key in [
            "front_facing_polygons",
            "front_facing_edges",
            "tree_nodes",
            "lit",
            "penumbra",
            "umbra",
        ] {
            assert!(point.get(key).is_some(), "{key}");
        }
        assert!(point.get("penumbra_nodes").is_none());
        assert_eq!(point["cones"], 3);
        assert!(v["lights"][1].get("cones").is_none());
        assert_eq!(v["lights"][1]["umbra_nodes"], 2);
        assert!(v["lights"][1].get("tree_nodes").is_none());
        let back: Stats = serde_json::from_str(&stats.to_json()).unwrap();
        assert_eq!(back, stats);
    }
}
