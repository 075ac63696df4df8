//! The figures of a [`DmRun`] (`--stats`): [`DmStats`] and how a run
//! counts them.

use dm_mesh::{CellClass, IllumStats};
use serde::Serialize;

use super::{DmRun, UpdateFigures};
use crate::atomic::Outputs;
use crate::error::Result;
use crate::stats::{LightStats, Seconds, Stats};

/// Figures of the DM-trees (beside FORMATS.md §3's fields).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct DmFigures {
    /// Receivers (convex pieces), one DM-tree each.
    pub receivers: u64,
    /// Inner nodes of all DM-trees.
    pub tree_nodes: u64,
    /// Cells (leaves) of all DM-trees.
    pub cells: u64,
    /// Distinct cell vertices (per receiver).
    pub vertices: u64,
    /// Vertex-light pairs whose visible part of the light was computed.
    pub visibility_vertices: u64,
    /// Light/occluder comparisons those computations made.
    pub comparisons: u64,
    /// Comparisons per vertex (the paper: 1.3 to 2.1).
    pub comparisons_per_vertex: f64,
    /// Comparisons per vertex that needed a visibility computation.
    pub comparisons_per_visibility_vertex: f64,
    /// Seconds building the trees (casting and merging shadows).
    pub build_seconds: f64,
    /// Seconds illuminating vertices.
    pub illum_seconds: f64,
    /// Seconds turning the cells into output faces, proving the cells in a
    /// joint umbra dark on the way (counted in `seconds.total`).
    pub output_seconds: f64,
}

/// What `umbra dm` / `umbra update` write with `--stats`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DmStats {
    /// The fields of FORMATS.md §3 (`shadow` holds the DM build, `bsp` and
    /// `grid` are zero).
    #[serde(flatten)]
    pub stats: Stats,
    /// DM-tree figures.
    pub dm: DmFigures,
    /// `umbra update` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub update: Option<UpdateFigures>,
}

impl DmStats {
    /// Writes the JSON to `path`, atomically.
    pub fn save(&self, path: &std::path::Path) -> Result<()> {
        let mut outputs = Outputs::default();
        self.stage(&mut outputs, path)?;
        outputs.commit()
    }

    /// [`Self::save`] as one of a run's [`Outputs`], written when they are.
    pub fn stage(&self, outputs: &mut Outputs, path: &std::path::Path) -> Result<()> {
        // Serialising plain numbers and structs cannot fail.
        let json = serde_json::to_string_pretty(self).unwrap_or_default();
        crate::stats::stage_json(outputs, path, &json)
    }
}

impl DmRun {
    pub(super) fn figures(
        &self,
        build: f64,
        illum_seconds: f64,
        illum: &IllumStats,
        total: f64,
    ) -> DmStats {
        let lights = self.dm.lights();
        let mut light_stats: Vec<LightStats> = self
            .dm
            .light_node_counts()
            .into_iter()
            .map(|(penumbra, umbra)| LightStats {
                penumbra_nodes: Some(penumbra as u64),
                umbra_nodes: Some(umbra as u64),
                ..LightStats::default()
            })
            .collect();
        let (mut nodes, mut cells, mut receivers) = (0, 0, 0);
        for (_, dm) in self.dm.receivers() {
            receivers += 1;
            nodes += dm.node_count() as u64;
            cells += dm.cell_count() as u64;
            for (i, s) in light_stats.iter_mut().enumerate() {
                if lights[i].source().reaches_front_of(dm.polygon().support()) {
                    s.front_facing_polygons += 1;
                    s.front_facing_edges += dm.polygon().len() as u64;
                }
                for (_, cell) in dm.cells() {
                    match dm.class(cell, i) {
                        CellClass::Lit => s.lit += 1,
                        CellClass::Penumbra => s.penumbra += 1,
                        CellClass::Umbra => s.umbra += 1,
                    }
                }
            }
        }
        // In the scene's order (the point and directional lights' figures
        // come with the output).
        let mut in_scene = vec![LightStats::default(); self.light_map.len()];
        for (s, &i) in light_stats.into_iter().zip(&self.light_map.area) {
            in_scene[i] = s;
        }
        let light_stats = in_scene;
        let per = |n: usize| {
            if n == 0 {
                0.0
            } else {
                illum.comparisons as f64 / n as f64
            }
        };
        DmStats {
            stats: Stats {
                input_polygons: self.pieces.input_polygons as u64,
                dropped_polygons: self.pieces.dropped.clone(),
                output_fragments: cells,
                seconds: Seconds {
                    bsp: 0.0,
                    shadow: build,
                    grid: 0.0,
                    illum: illum_seconds,
                    total,
                },
                lights: light_stats,
            },
            dm: DmFigures {
                receivers,
                tree_nodes: nodes,
                cells,
                vertices: illum.vertices as u64,
                visibility_vertices: illum.visibility as u64,
                comparisons: illum.comparisons as u64,
                comparisons_per_vertex: per(illum.vertices),
                comparisons_per_visibility_vertex: per(illum.visibility),
                build_seconds: build,
                illum_seconds,
                output_seconds: 0.0,
            },
            update: None,
        }
    }

    /// Recomputes the figures after updates (timings of the build kept).
    pub fn refresh_figures(&mut self) {
        let s = self.stats.dm.clone();
        let illum = IllumStats {
            vertices: s.vertices as usize,
            evaluated: s.vertices as usize,
            visibility: s.visibility_vertices as usize,
            comparisons: s.comparisons as usize,
            ..IllumStats::default()
        };
        let update = self.stats.update.take();
        self.stats = self.figures(
            s.build_seconds,
            s.illum_seconds,
            &illum,
            self.stats.stats.seconds.total,
        );
        self.stats.update = update;
    }
}
