//! From the scene's input polygons to convex planar pieces on one grid.
//!
//! Every input polygon is snapped to a single [`Grid`] laid over the scene
//! and its lights, its object's T-junctions welded (a corner on another
//! face's edge made that face's corner too, module `weld`), then:
//! - a planar convex face becomes one piece, as is;
//! - a concave planar face, or a non-planar one, is cut into triangles by
//!   ear clipping on its projection along the dominant axis of its exact
//!   vector area. Every orientation and containment test is on integer grid
//!   coordinates, so it is exact (no `spade`: a simple polygon needs no
//!   Delaunay property, and ear clipping on `i64` needs no conversion back
//!   from floating point). A planar face's triangles are then merged back
//!   across diagonals while the union stays strictly convex
//!   (Hertel-Mehlhorn: at most four times the fewest convex parts), and
//!   tile it exactly; a non-planar face keeps its triangles, each planar;
//! - a face that is degenerate once snapped (zero area) is dropped and
//!   listed in [`Pieces::dropped`]; that is not an error.
//!
//! Each piece's [`ConvexPolygon::source`] is its own index in
//! [`Pieces::polygons`]; [`Pieces::input_of`] maps it to the input polygon.

use bsp_core::{ConvexPolygon, Grid, GridPoint};

use crate::error::{Error, Result};
use crate::input_frame::{InputFrames, planar_normal};
use crate::scene::{LightKind, Scene};
use crate::vec3::{by_largest, dot};
use crate::weld::{ON_EDGE, weld_t_junctions, welded_pieces};

/// How much the grid's box is grown on every side, as a fraction of the
/// scene's largest extent.
pub const GRID_MARGIN: f64 = 0.01;

/// The scene's polygons as convex planar pieces on one grid.
#[derive(Debug, Clone)]
pub struct Pieces {
    /// The grid every piece and light is snapped to.
    pub grid: Grid,
    /// The pieces; piece `k` has `source() == k`.
    pub polygons: Vec<ConvexPolygon>,
    /// For each piece, the index of its input polygon.
    pub input_of: Vec<u32>,
    /// For each piece, whether it blocks light.
    pub casts_shadows: Vec<bool>,
    /// For each piece, whether it receives on both sides.
    pub two_sided: Vec<bool>,
    /// For each piece, the unit normal light falls on: its input polygon's
    /// where that is planar and faces the same way, else its own. (A thin
    /// polygon's snapped plane turns by up to a grid step over its width:
    /// a needle 8 steps wide, by 7 degrees.)
    pub normals: Vec<[f64; 3]>,
    /// Number of input polygons.
    pub input_polygons: usize,
    /// Input polygons that had zero area once snapped, dropped.
    pub dropped: Vec<u32>,
    /// Largest distance (world units) any scene or light vertex moved when
    /// snapped.
    pub max_snap_distance: f64,
    /// The lights on the grid, in scene order.
    pub lights: Vec<SnappedLight>,
    /// Per input polygon, how points of its pieces are put back onto it
    /// for output.
    pub frames: InputFrames,
}

/// An object that will move in equal straight steps (`umbra update`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// The scene object's index.
    pub object: usize,
    /// One step (world units).
    pub by: [f64; 3],
    /// How many steps.
    pub steps: u32,
}

impl Motion {
    /// The whole way: `steps` times `by`.
    pub fn way(&self) -> [f64; 3] {
        self.by.map(|x| x * f64::from(self.steps))
    }
}

/// A light placed on the grid.
#[derive(Debug, Clone)]
pub enum SnappedLight {
    /// A point light at a grid point.
    Point(GridPoint),
    /// A light at infinity: the direction it travels as integers (grids
    /// scale uniformly, so a world direction is a grid direction), scaled so
    /// that its largest component is `±DIRECTION_SCALE`; see
    /// [`integer_direction`].
    Directional([i32; 3]),
    /// An area light: a convex polygon on the grid whose source is the
    /// light's index.
    Area(ConvexPolygon),
}

/// The grid [`Pieces::from_scene_moving`] lays for `scene` and `motion`:
/// over the box of every scene vertex, point-light position and area-light
/// vertex, and of the moving object at the end of its way, grown by
/// [`GRID_MARGIN`]; its step holds one step's lengths exactly when it can
/// ([`Grid::fitted`]). (With `steps` 0 the box is the scene's own.)
pub fn scene_grid(scene: &Scene, motion: Option<Motion>) -> Result<Grid> {
    let mut points: Vec<&[f64; 3]> = scene
        .input_polygons()
        .flat_map(|(_, p)| p.vertices.iter())
        .collect();
    let way_end: Vec<[f64; 3]> = match motion {
        Some(m) => {
            let way = m.way();
            scene
                .input_polygons()
                .filter(|&(o, _)| o == m.object)
                .flat_map(|(_, p)| p.vertices.iter())
                .map(|v| [0, 1, 2].map(|a| v[a] + way[a]))
                .collect()
        }
        None => Vec::new(),
    };
    points.extend(way_end.iter());
    for light in &scene.lights {
        match &light.kind {
            LightKind::Point { position } => points.push(position),
            LightKind::Area { vertices } => points.extend(vertices.iter()),
            LightKind::Directional { .. } => {}
        }
    }
    let step = motion.map(|m| m.by);
    let lengths = step.as_ref().map_or(&[][..], |by| by.as_slice());
    Grid::fitted(points, GRID_MARGIN, lengths).map_err(|source| Error::Grid {
        path: scene.path.clone(),
        source,
    })
}

impl Pieces {
    /// Cuts the scene into pieces on a grid over the bounding box of every
    /// scene vertex, point-light position and area-light vertex, grown by
    /// [`GRID_MARGIN`].
    pub fn from_scene(scene: &Scene) -> Result<Self> {
        Self::from_scene_moving(scene, None)
    }

    /// [`Self::from_scene`] for a scene whose object will move
    /// (`motion`): the grid's box holds the object at the end of its way
    /// too (the steps are straight, so every place between), and its step
    /// is chosen to hold one step's lengths exactly when it can
    /// ([`Grid::fitted`]).
    pub fn from_scene_moving(scene: &Scene, motion: Option<Motion>) -> Result<Self> {
        let grid_error = |source| Error::Grid {
            path: scene.path.clone(),
            source,
        };
        let grid = scene_grid(scene, motion)?;

        let mut out = Self {
            grid,
            polygons: Vec::new(),
            input_of: Vec::new(),
            casts_shadows: Vec::new(),
            two_sided: Vec::new(),
            normals: Vec::new(),
            input_polygons: 0,
            dropped: Vec::new(),
            max_snap_distance: 0.0,
            lights: Vec::with_capacity(scene.lights.len()),
            frames: InputFrames::new(grid),
        };
        let mut index = 0_u32;
        for o in &scene.objects {
            let mut snapped = Vec::with_capacity(o.polygons.len());
            for polygon in &o.polygons {
                let (points, moved) = grid.snap_all(&polygon.vertices).map_err(grid_error)?;
                out.max_snap_distance = out.max_snap_distance.max(moved);
                snapped.push(points);
            }
            let input: Vec<&[[f64; 3]]> =
                o.polygons.iter().map(|p| p.vertices.as_slice()).collect();
            let welds = weld_t_junctions(&input, &snapped, ON_EDGE * grid.cell_size());
            for ((points, welded), polygon) in snapped.iter().zip(&welds).zip(&o.polygons) {
                let inserted: Vec<Vec<GridPoint>> = welded
                    .iter()
                    .map(|edge| edge.iter().map(|w| w.point).collect())
                    .collect();
                let pieces = welded_pieces(points, &inserted);
                out.frames.push(&polygon.vertices, points, welded, &pieces);
                let normal = planar_normal(&polygon.vertices);
                if pieces.is_empty() {
                    out.dropped.push(index);
                }
                for piece in pieces {
                    let k = out.polygons.len() as u32;
                    let own = piece.support().unit_normal_f64();
                    out.polygons.push(piece.with_source(k));
                    out.input_of.push(index);
                    out.casts_shadows.push(o.casts_shadows);
                    out.two_sided.push(o.two_sided);
                    out.normals.push(match normal {
                        Some(n) if dot(n, own) > 0.0 => n,
                        _ => own,
                    });
                }
                out.input_polygons += 1;
                index += 1;
            }
        }
        for (i, light) in scene.lights.iter().enumerate() {
            let snapped = match &light.kind {
                LightKind::Point { position } => {
                    let (g, moved) = grid.snap_with_distance(*position).map_err(grid_error)?;
                    out.max_snap_distance = out.max_snap_distance.max(moved);
                    SnappedLight::Point(g)
                }
                LightKind::Directional { direction } => {
                    SnappedLight::Directional(integer_direction(*direction))
                }
                LightKind::Area { vertices } => {
                    // One convex planar piece, however the light is tilted
                    // (a tilted quad's nearest grid points are not coplanar).
                    let (polygon, moved) = ConvexPolygon::snap_planar(&grid, vertices, i as u32)
                        .map_err(|e| match e {
                            bsp_core::Error::OutsideGrid { .. }
                            | bsp_core::Error::NonFinite { .. } => grid_error(e),
                            e => Error::Field {
                                path: scene.path.clone(),
                                field: format!("light[{i}].vertices"),
                                message: format!("once snapped to the grid: {e}"),
                            },
                        })?;
                    out.max_snap_distance = out.max_snap_distance.max(moved);
                    SnappedLight::Area(polygon)
                }
            };
            out.lights.push(snapped);
        }
        Ok(out)
    }

    /// The pieces of one input polygon.
    pub fn pieces_of(&self, input: u32) -> impl Iterator<Item = &ConvexPolygon> + '_ {
        self.polygons
            .iter()
            .zip(&self.input_of)
            .filter(move |(_, i)| **i == input)
            .map(|(p, _)| p)
    }
}

/// Largest component of an [`integer_direction`], `2^20` (the kernel
/// accepts directions below `2^24`).
pub const DIRECTION_SCALE: i32 = 1 << 20;

/// A non-zero finite direction as integers whose largest component is
/// `±DIRECTION_SCALE`: the only rounding of a directional light, by at most
/// about `2^-21` radians.
pub fn integer_direction(d: [f64; 3]) -> [i32; 3] {
    if !d.iter().all(|c| c.is_finite()) {
        return [0; 3];
    }
    by_largest(d).map(|c| (c * f64::from(DIRECTION_SCALE)).round() as i32)
}

/// Convex planar pieces (with source 0) of one polygon given by grid points,
/// counter-clockwise; empty if the polygon has zero area.
pub fn convex_pieces(points: &[GridPoint]) -> Vec<ConvexPolygon> {
    let mut pts: Vec<GridPoint> = Vec::with_capacity(points.len());
    for &p in points {
        if pts.last() != Some(&p) {
            pts.push(p);
        }
    }
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    if pts.len() < 3 {
        return Vec::new();
    }
    let planar = match ConvexPolygon::from_grid_points(&pts, 0) {
        Ok(p) => return vec![p],
        // Planarity is checked before convexity: a non-convex polygon is
        // planar.
        Err(bsp_core::Error::NonConvex) => true,
        Err(_) => false,
    };
    let Some(projection) = Projection::new(&pts) else {
        return Vec::new();
    };
    let triangles: Vec<Vec<usize>> = ear_clip(&projection).into_iter().map(Vec::from).collect();
    let parts = if planar && triangles.len() <= MERGE_LIMIT {
        merge_convex(triangles, &projection)
    } else {
        triangles
    };
    parts
        .into_iter()
        .filter_map(|part| {
            let corners: Vec<GridPoint> = part.iter().map(|&i| pts[i]).collect();
            ConvexPolygon::from_grid_points(&corners, 0).ok()
        })
        .collect()
}

/// The triangles (indices into `points`) that [`convex_pieces`] cuts a
/// non-planar face into, before any merging; `None` when the face has
/// repeated corners or no area.
pub(crate) fn corner_triangles(points: &[GridPoint]) -> Option<Vec<[usize; 3]>> {
    let n = points.len();
    if n < 3 || (0..n).any(|i| points[i] == points[(i + 1) % n]) {
        return None;
    }
    Projection::new(points).map(|projection| ear_clip(&projection))
}

/// Faces cut into more triangles than this keep their triangles (merging
/// them back into convex parts is quadratic in their number, or worse).
const MERGE_LIMIT: usize = 256;

/// Twice the exact vector area `sum p_i x p_(i+1)`.
fn vector_area(pts: &[GridPoint]) -> [i128; 3] {
    let mut acc = [0_i128; 3];
    for (i, p) in pts.iter().enumerate() {
        let a = p.to_i64().map(i128::from);
        let b = pts[(i + 1) % pts.len()].to_i64().map(i128::from);
        acc[0] += a[1] * b[2] - a[2] * b[1];
        acc[1] += a[2] * b[0] - a[0] * b[2];
        acc[2] += a[0] * b[1] - a[1] * b[0];
    }
    acc
}

/// A polygon projected along the dominant axis of its vector area, with
/// orientation signs made positive for the polygon's own turning sense.
struct Projection {
    flat: Vec<[i64; 2]>,
    sign: i64,
}

impl Projection {
    /// `None` for a zero vector area (a degenerate or figure-eight face).
    fn new(pts: &[GridPoint]) -> Option<Self> {
        let area = vector_area(pts);
        let k = (0..3).max_by_key(|&k| area[k].unsigned_abs()).unwrap_or(0);
        if area[k] == 0 {
            return None;
        }
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        let flat = pts
            .iter()
            .map(|p| {
                let a = p.to_i64();
                [a[u], a[v]]
            })
            .collect();
        Some(Self {
            flat,
            sign: if area[k] > 0 { 1 } else { -1 },
        })
    }

    /// Positive for a left (convex) turn `a -> b -> c`; exact (coordinates
    /// below `2^25`, products below `2^51`).
    fn orient(&self, a: usize, b: usize, c: usize) -> i64 {
        let (a, b, c) = (self.flat[a], self.flat[b], self.flat[c]);
        self.sign * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    }
}

/// Triangles (vertex indices) of a polygon by ear clipping its projection,
/// keeping its orientation. Exact: every test is an integer orientation.
fn ear_clip(projection: &Projection) -> Vec<[usize; 3]> {
    let orient = |a, b, c| projection.orient(a, b, c);
    let flat = &projection.flat;
    let mut ring: Vec<usize> = (0..flat.len()).collect();
    let mut triangles = Vec::with_capacity(flat.len().saturating_sub(2));
    while ring.len() > 3 {
        let n = ring.len();
        let corners = |i: usize| (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
        let is_ear = |i: usize| {
            let (a, b, c) = corners(i);
            if orient(a, b, c) <= 0 {
                return false;
            }
            ring.iter().all(|&q| {
                let same = [a, b, c].iter().any(|&r| flat[r] == flat[q]);
                same || orient(a, b, q) < 0 || orient(b, c, q) < 0 || orient(c, a, q) < 0
            })
        };
        let turn = |i: usize| {
            let (a, b, c) = corners(i);
            orient(a, b, c)
        };
        let (i, emit) = (0..n)
            .find(|&i| is_ear(i))
            .map(|i| (i, true))
            // A straight or folded-back vertex adds no area: drop it.
            .or_else(|| (0..n).find(|&i| turn(i) == 0).map(|i| (i, false)))
            // No ear: the projection is not simple (a twisted face). Cut the
            // first convex corner anyway so that the loop ends.
            .or_else(|| (0..n).find(|&i| turn(i) > 0).map(|i| (i, true)))
            .unwrap_or((0, false));
        if emit {
            let (a, b, c) = corners(i);
            triangles.push([a, b, c]);
        }
        ring.remove(i);
    }
    if ring.len() == 3 {
        triangles.push([ring[0], ring[1], ring[2]]);
    }
    triangles
}

/// Hertel-Mehlhorn: merges parts across shared diagonals while the union
/// stays strictly convex (every turn to the left, exactly), so a concave
/// face becomes a few convex parts rather than many triangles. Strictness
/// keeps every part's corners at polygon vertices of its neighbours: no
/// part gets a straight corner where another part has a vertex.
fn merge_convex(mut parts: Vec<Vec<usize>>, projection: &Projection) -> Vec<Vec<usize>> {
    'again: loop {
        for i in 0..parts.len() {
            for j in i + 1..parts.len() {
                if let Some(merged) = merge_pair(&parts[i], &parts[j], projection) {
                    parts[i] = merged;
                    parts.swap_remove(j);
                    continue 'again;
                }
            }
        }
        return parts;
    }
}

/// The union of two parts sharing the edge `p[k] -> p[k+1]` (run the other
/// way in `q`), if it is strictly convex.
fn merge_pair(p: &[usize], q: &[usize], projection: &Projection) -> Option<Vec<usize>> {
    let (n, m) = (p.len(), q.len());
    for k in 0..n {
        let (a, b) = (p[k], p[(k + 1) % n]);
        let Some(l) = (0..m).find(|&l| q[l] == b && q[(l + 1) % m] == a) else {
            continue;
        };
        let mut merged: Vec<usize> = (1..=n).map(|t| p[(k + t) % n]).collect();
        merged.extend((2..m).map(|t| q[(l + t) % m]));
        let c = merged.len();
        let convex = (0..c)
            .all(|t| projection.orient(merged[t], merged[(t + 1) % c], merged[(t + 2) % c]) > 0);
        return convex.then_some(merged);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint::new(x, y, z).unwrap()
    }

    fn exact_area(pts: &[GridPoint]) -> f64 {
        let a = vector_area(pts).map(|c| c as f64);
        0.5 * (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
    }

    #[test]
    fn directions_become_integers() {
        assert_eq!(
            integer_direction([0.0, -2.0, 0.0]),
            [0, -DIRECTION_SCALE, 0]
        );
        assert_eq!(
            integer_direction([0.25, -0.5, 1.0]),
            [DIRECTION_SCALE / 4, -DIRECTION_SCALE / 2, DIRECTION_SCALE]
        );
        assert_eq!(
            integer_direction([1e-310, 0.0, -1e-310]),
            [DIRECTION_SCALE, 0, -DIRECTION_SCALE]
        );
    }

    #[test]
    fn convex_face_is_one_piece() {
        let square = [g(0, 0, 0), g(4, 0, 0), g(4, 4, 0), g(0, 4, 0)];
        let pieces = convex_pieces(&square);
        assert_eq!(pieces.len(), 1);
        assert_eq!(pieces[0].len(), 4);
    }

    #[test]
    fn concave_faces_tile_exactly_and_keep_their_front() {
        // An L and a comb, in a tilted plane x + y + z = const and facing
        // both ways.
        let l2 = [[0, 0], [6, 0], [6, 2], [2, 2], [2, 6], [0, 6]];
        let comb = [
            [0, 0],
            [9, 0],
            [9, 5],
            [7, 5],
            [7, 2],
            [5, 2],
            [5, 5],
            [3, 5],
            [3, 2],
            [1, 2],
            [1, 5],
            [0, 5],
        ];
        for outline in [&l2[..], &comb[..]] {
            for flip in [false, true] {
                let mut pts: Vec<GridPoint> =
                    outline.iter().map(|&[a, b]| g(a, b, 20 - a - b)).collect();
                if flip {
                    pts.reverse();
                }
                let pieces = convex_pieces(&pts);
                // Hertel-Mehlhorn: the L in 2 parts; the comb (5 reflex
                // corners) in at most 2 * 5 + 1.
                let most = if outline.len() == 6 { 2 } else { 11 };
                assert!(
                    pieces.len() >= 2 && pieces.len() <= most,
                    "{}",
                    pieces.len()
                );
                let total: f64 = pieces.iter().map(|p| p.area()).sum();
                let want = exact_area(&pts);
                assert!((total - want).abs() <= 1e-9 * want, "{total} vs {want}");
                let face = vector_area(&pts);
                for p in &pieces {
                    assert!(p.area() > 0.0);
                    let n = p.support().normal();
                    let along: i128 = (0..3).map(|k| i128::from(n[k]) * face[k]).sum();
                    assert!(along > 0, "piece faces the other way");
                }
            }
        }
    }

    #[test]
    fn non_planar_face_becomes_triangles() {
        let twisted = [g(0, 0, 0), g(4, 0, 0), g(4, 4, 1), g(0, 4, 0)];
        let pieces = convex_pieces(&twisted);
        assert_eq!(pieces.len(), 2);
        assert!(pieces.iter().all(|p| p.len() == 3));
    }

    #[test]
    fn degenerate_faces_give_nothing() {
        assert!(convex_pieces(&[g(0, 0, 0), g(1, 1, 1), g(2, 2, 2)]).is_empty());
        assert!(convex_pieces(&[g(0, 0, 0), g(0, 0, 0), g(1, 0, 0)]).is_empty());
        // A figure eight has zero vector area.
        assert!(convex_pieces(&[g(0, 0, 0), g(2, 2, 0), g(2, 0, 0), g(0, 2, 0)]).is_empty());
    }
}
