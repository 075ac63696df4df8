//! Point and directional lights in a DM run. Discontinuity meshes are an
//! area light's; the shadows of the other lights are cut into the cells
//! at output: each cell is split along the exact shadow fragments those
//! lights make on its receiver (`svbsp`), and every vertex is then
//! illuminated from scratch (`illum`), as `umbra shadow` does.

use area_shadow::{
    LightFigures, SceneLight, ShadowGroups, compute_shadows_with_groups, conform_fragments,
};
use bsp_core::{BuildOptions, ConvexPolygon, Split};
use rayon::prelude::*;
use svbsp::{Fragment, PieceFlags};

use crate::decompose::{Pieces, SnappedLight};
use crate::error::{Error, Result};
use crate::illuminate::{IllumLight, Illuminator};
use crate::mesh::OutputMesh;
use crate::scene::Scene;
use crate::shadow::{MAX_FACE_CORNERS, illum_lights, illuminated_mesh, settle_beyond_range};
use crate::stats::LightStats;

/// How a DM run's lights stand in the scene's list.
#[derive(Debug, Clone)]
pub(crate) struct LightMap {
    /// The scene index of each DM (area) light.
    pub area: Vec<usize>,
    /// The point and directional lights, with their scene indices.
    pub others: Vec<(usize, svbsp::Light)>,
    /// Every light as `illum` evaluates it, in scene order.
    pub illum: Vec<IllumLight>,
}

impl LightMap {
    /// The lights of `scene` (snapped in `pieces`) sorted out.
    pub fn of(scene: &Scene, pieces: &Pieces) -> Result<Self> {
        let mut map = Self {
            area: Vec::new(),
            others: Vec::new(),
            illum: illum_lights(scene, pieces)?,
        };
        for (i, (light, snapped)) in scene.lights.iter().zip(&pieces.lights).enumerate() {
            let range = light.falloff.map(|f| f.range * pieces.grid.scale());
            let source = match snapped {
                SnappedLight::Area(_) => {
                    map.area.push(i);
                    continue;
                }
                SnappedLight::Point(p) => svbsp::LightSource::Point(*p),
                SnappedLight::Directional(d) => svbsp::LightSource::Directional(*d),
            };
            map.others.push((i, svbsp::Light { source, range }));
        }
        Ok(map)
    }

    /// The scene's mask bits of DM-light mask bits `dm`.
    pub fn scene_bits(&self, dm: u32) -> u32 {
        self.area
            .iter()
            .enumerate()
            .filter(|&(j, _)| dm & (1 << j) != 0)
            .fold(0, |bits, (_, &i)| bits | (1 << i))
    }

    /// Number of lights of the scene.
    pub fn len(&self) -> usize {
        self.area.len() + self.others.len()
    }
}

/// The cells (with their scene masks; `polygon.source()` the piece) cut
/// along the shadow fragments of the point and directional lights, and
/// illuminated: the output mesh, and the figures of those lights' passes
/// (scene index, statistics).
pub(crate) fn cut_by_other_lights(
    cells: Vec<Fragment>,
    pieces: &Pieces,
    flags: &[PieceFlags],
    groups: &ShadowGroups,
    map: &LightMap,
) -> Result<(OutputMesh, Vec<(usize, LightStats)>)> {
    let lights: Vec<SceneLight> = map
        .others
        .iter()
        .map(|&(_, l)| SceneLight::Svbsp(l))
        .collect();
    let shadows = compute_shadows_with_groups(
        &pieces.polygons,
        flags,
        groups,
        &lights,
        &BuildOptions::default(),
    )
    .map_err(|e| Error::Dm(e.to_string()))?;
    let to_scene = |bits: u32| {
        map.others
            .iter()
            .enumerate()
            .filter(|&(j, _)| bits & (1 << j) != 0)
            .fold(0_u32, |out, (_, &(i, _))| out | (1 << i))
    };
    // Each piece's shadow fragments with their boxes: a cell is clipped
    // only by those whose box meets its own (a receiver's thousands of
    // cells by each of its thousands of fragments was quadratic: 480
    // random triangles under a point light, 90 s).
    let mut by_piece: Vec<Vec<(Fragment, Box3)>> = vec![Vec::new(); pieces.polygons.len()];
    for f in shadows.fragments {
        let k = f.polygon.source() as usize;
        let bounds = widened_box(&f.polygon);
        by_piece[k].push((
            Fragment {
                lit_mask: to_scene(f.lit_mask),
                umbra_mask: to_scene(f.umbra_mask),
                polygon: f.polygon,
            },
            bounds,
        ));
    }
    let mut fragments: Vec<Fragment> = cells
        .par_iter()
        .flat_map_iter(|cell| {
            let bounds = widened_box(&cell.polygon);
            by_piece[cell.polygon.source() as usize]
                .iter()
                .filter(move |(_, other)| !apart(&bounds, other))
                .filter_map(move |(shadow, _)| {
                    Some(Fragment {
                        polygon: clipped(&cell.polygon, &shadow.polygon)?,
                        lit_mask: cell.lit_mask | shadow.lit_mask,
                        umbra_mask: cell.umbra_mask | shadow.umbra_mask,
                    })
                })
        })
        .collect();
    // Beyond a point light's range a cut fragment takes no part.
    settle_beyond_range(&mut fragments, map.others.iter().map(|(i, l)| (*i, l)));
    let (fragments, conforming) = conform_fragments(fragments, MAX_FACE_CORNERS);
    let illuminator = Illuminator::new(&map.illum, pieces);
    let (mesh, _) = illuminated_mesh(&fragments, &conforming, &illuminator, pieces);
    let figures = map
        .others
        .iter()
        .zip(&shadows.lights)
        .map(|(&(i, _), figures)| {
            let mut s = LightStats::default();
            if let LightFigures::Svbsp(f) = figures {
                s.front_facing_polygons = f.front_facing_polygons as u64;
                s.front_facing_edges = f.front_facing_edges as u64;
                s.tree_nodes = Some(f.tree_nodes as u64);
                s.cones = Some(f.cones as u64);
            }
            (i, s)
        })
        .collect();
    Ok((mesh, figures))
}

/// A box, lower and upper corners, in grid units.
type Box3 = [[f64; 3]; 2];

/// The box of a polygon's corners in grid units, widened by a grid step
/// each way: the `f64` corners lie within a small fraction of a step of the
/// exact ones, so polygons whose widened boxes are apart share no area.
fn widened_box(polygon: &ConvexPolygon) -> Box3 {
    let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for i in 0..polygon.len() {
        let v = polygon.vertex_f64(i);
        for k in 0..3 {
            b[0][k] = b[0][k].min(v[k] - 1.0);
            b[1][k] = b[1][k].max(v[k] + 1.0);
        }
    }
    b
}

/// Whether two boxes are apart along some axis.
fn apart(a: &Box3, b: &Box3) -> bool {
    (0..3).any(|k| a[1][k] < b[0][k] || b[1][k] < a[0][k])
}

/// The part of `polygon` inside the convex `window` (in its plane): the
/// polygon cut by the window's edge planes, its source kept; `None` when
/// they meet in no area.
fn clipped(polygon: &ConvexPolygon, window: &ConvexPolygon) -> Option<ConvexPolygon> {
    let mut part = polygon.clone();
    for edge in window.edges() {
        part = match part.split(edge) {
            Split::Back => part,
            Split::Both(back, _) => back,
            Split::Front | Split::Coplanar(_) => return None,
        };
    }
    Some(part)
}

#[cfg(test)]
mod tests {
    use super::{apart, clipped, widened_box};
    use bsp_core::{ConvexPolygon, GridPoint};
    use proptest::prelude::*;

    /// A triangle of the plane y = 0 with corners near `(x, z)`.
    fn triangle() -> impl Strategy<Value = Option<ConvexPolygon>> {
        (-40_i64..40, -40_i64..40, prop::array::uniform4(-6_i64..=6)).prop_map(|(x, z, d)| {
            let g = |dx: i64, dz: i64| GridPoint::new(x + dx, 0, z + dz).unwrap();
            let [a, b, c] = [g(0, 0), g(d[0], d[1]), g(d[2], d[3])];
            ConvexPolygon::from_grid_points(&[a, b, c], 0)
                .or_else(|_| ConvexPolygon::from_grid_points(&[a, c, b], 0))
                .ok()
        })
    }

    proptest! {
        /// Polygons whose widened boxes are apart have no common area: the
        /// cells skipped by the box test are those the clip would drop.
        #[test]
        fn polygons_apart_by_their_boxes_do_not_overlap(a in triangle(), b in triangle()) {
            let (Some(a), Some(b)) = (a, b) else { return Ok(()); };
            if apart(&widened_box(&a), &widened_box(&b)) {
                prop_assert!(clipped(&a, &b).is_none());
                prop_assert!(clipped(&b, &a).is_none());
            }
        }
    }
}
