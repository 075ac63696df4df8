//! Output points put back onto the input polygons they lie on.
//!
//! The kernel works on the input snapped to a grid, so the corners of a
//! polygon's fragments lie on its snapped copy: within half a grid step of
//! the input polygon, not on it, and their areas add up to the snapped
//! copy's area. Written as they are, a small or thin polygon's fragments
//! miss its area by a visible fraction (a needle 150 grid steps wide, by
//! 6e-4).
//!
//! Triangles and planar quadrilaterals are mapped back exactly, by the one
//! projective map of the plane that takes each snapped corner to its input
//! corner (an affine map for a triangle). It takes straight lines to
//! straight lines, so fragments stay convex, keep their shared edges and
//! their T-vertices on the edges they touch, and tile the input polygon
//! exactly, up to the rounding of their coordinates; a fragment corner at a
//! polygon corner is written as the input has it. The map works in the
//! coordinate plane that the input polygon's plane projects onto best, so a
//! snapped quadrilateral bent into two triangles maps onto the input plane
//! as well. Other polygons (five corners or more, or not planar) are
//! written as snapped.
//!
//! Nothing decided in the exact kernel changes: the map only moves where
//! the output coordinates are written, by at most about a grid step.

use std::collections::HashMap;

use bsp_core::{Grid, GridPoint, VertexPosition};
use smallvec::SmallVec;

use crate::mesh::OutputMesh;
use crate::vec3::{cross, dot, norm, sub};

/// A planar input polygon counts as planar when its corners lie this close
/// to their mean plane, relative to its size.
const PLANARITY: f64 = 1e-9;

/// Per input polygon, the map from its snapped copy back onto it.
#[derive(Debug, Clone)]
pub struct InputFrames {
    grid: Grid,
    frames: Vec<Option<Box<Frame>>>,
}

/// One polygon's corners, snapped and as input, and the map between them.
#[derive(Debug, Clone)]
struct Frame {
    corners: SmallVec<[Corner; 4]>,
    /// `None` where no point moves: every snapped corner is its input
    /// corner (a scene on the grid), or the polygon is not mapped.
    map: Option<PlaneMap>,
}

/// A corner of an input polygon.
#[derive(Debug, Clone, Copy)]
struct Corner {
    /// Where it snapped.
    grid: GridPoint,
    /// As input (world units).
    input: [f64; 3],
}

/// A projective map between two nearly equal planar polygons, in the
/// coordinate plane of axes `u`, `v` (the input plane's normal is largest
/// along the third axis `k`).
#[derive(Debug, Clone)]
struct PlaneMap {
    u: usize,
    v: usize,
    k: usize,
    /// Snapped corner 0 in the coordinate plane: points are mapped relative
    /// to it, so that the map's entries stay well scaled.
    from_origin: [f64; 2],
    /// Input corner 0, where `from_origin` goes.
    to_origin: [f64; 2],
    /// Homogeneous 3 x 3 matrix, relative coordinates to relative
    /// coordinates.
    h: [[f64; 3]; 3],
    /// The input plane `normal . x = offset` (unit normal).
    normal: [f64; 3],
    offset: f64,
}

impl InputFrames {
    /// No polygons yet; they will be snapped to `grid`.
    pub fn new(grid: Grid) -> Self {
        Self {
            grid,
            frames: Vec::new(),
        }
    }

    /// Adds the next input polygon: its corners as input (world units) and
    /// snapped, in the same order.
    pub fn push(&mut self, input: &[[f64; 3]], snapped: &[GridPoint]) {
        self.frames
            .push(Frame::new(&self.grid, input, snapped).map(Box::new));
    }

    /// Input polygon `source` moved: its snapped copy by `units` grid
    /// units, the input by `by` world units.
    pub fn translate(&mut self, source: u32, units: [i64; 3], by: [f64; 3]) {
        let Some(Some(frame)) = self.frames.get_mut(source as usize) else {
            return;
        };
        let mut input = Vec::with_capacity(frame.corners.len());
        let mut snapped = Vec::with_capacity(frame.corners.len());
        for corner in &frame.corners {
            let (g, p) = (corner.grid.to_i64(), corner.input);
            let Ok(g) = GridPoint::new(g[0] + units[0], g[1] + units[1], g[2] + units[2]) else {
                // Off the grid: the pieces could not move there either.
                return;
            };
            snapped.push(g);
            input.push([p[0] + by[0], p[1] + by[1], p[2] + by[2]]);
        }
        self.frames[source as usize] = Frame::new(&self.grid, &input, &snapped).map(Box::new);
    }

    /// `mesh` with every face's corners moved onto its input polygon, and,
    /// per vertex of the result, the vertex of `mesh` it came from. A
    /// vertex shared by faces of polygons that place it differently is
    /// written once for each place.
    pub fn place(&self, mesh: OutputMesh) -> (OutputMesh, Vec<u32>) {
        let moves = |s: u32| {
            self.frames
                .get(s as usize)
                .and_then(Option::as_deref)
                .is_some_and(|f| f.map.is_some())
        };
        if !mesh.faces.iter().any(|f| moves(f.source)) {
            let origin = (0..mesh.vertices.len() as u32).collect();
            return (mesh, origin);
        }
        let OutputMesh {
            vertices,
            mut faces,
        } = mesh;
        let mut placed: Vec<([f64; 3], f32)> = Vec::with_capacity(vertices.len());
        let mut origin: Vec<u32> = Vec::with_capacity(vertices.len());
        // Per vertex of `mesh`: its first placement; further ones (other
        // polygons' places for it) in `others`.
        let mut first = vec![u32::MAX; vertices.len()];
        let mut others: HashMap<(u32, [u64; 3]), u32> = HashMap::new();
        for face in &mut faces {
            let frame = self
                .frames
                .get(face.source as usize)
                .and_then(Option::as_deref);
            for slot in &mut face.vertices {
                let v = *slot;
                let (p, e) = vertices[v as usize];
                let q = frame.map_or(p, |f| f.place(&self.grid, p));
                let bits = q.map(f64::to_bits);
                let f = first[v as usize];
                *slot = if f == u32::MAX {
                    first[v as usize] = placed.len() as u32;
                    placed.push((q, e));
                    origin.push(v);
                    placed.len() as u32 - 1
                } else if placed[f as usize].0.map(f64::to_bits) == bits {
                    f
                } else {
                    *others.entry((v, bits)).or_insert_with(|| {
                        placed.push((q, e));
                        origin.push(v);
                        placed.len() as u32 - 1
                    })
                };
            }
        }
        (
            OutputMesh {
                vertices: placed,
                faces,
            },
            origin,
        )
    }
}

impl Frame {
    /// `None` for a polygon with no corners to keep.
    fn new(grid: &Grid, input: &[[f64; 3]], snapped: &[GridPoint]) -> Option<Self> {
        if input.len() != snapped.len() {
            return None;
        }
        let mut corners: SmallVec<[Corner; 4]> = SmallVec::new();
        for (&grid, &input) in snapped.iter().zip(input) {
            match corners.last() {
                // A repeated input corner (it snaps to the same point).
                Some(c) if c.input == input => continue,
                // Two corners snapped to one: the snapped copy has fewer.
                Some(c) if c.grid == grid => return None,
                _ => corners.push(Corner { grid, input }),
            }
        }
        while corners.len() > 1
            && corners.first().map(|c| c.input) == corners.last().map(|c| c.input)
        {
            corners.pop();
        }
        if corners.len() > 1 && corners.first().map(|c| c.grid) == corners.last().map(|c| c.grid) {
            return None;
        }
        if !(3..=4).contains(&corners.len()) {
            return None;
        }
        let from: SmallVec<[[f64; 3]; 4]> = corners.iter().map(|c| grid.to_world(c.grid)).collect();
        let to: SmallVec<[[f64; 3]; 4]> = corners.iter().map(|c| c.input).collect();
        let exact = from == to;
        let map = if exact {
            None
        } else {
            PlaneMap::new(&from, &to)
        };
        Some(Self { corners, map })
    }

    /// Where the point `p` (world units) of the snapped polygon's pieces
    /// lies on the input polygon.
    fn place(&self, grid: &Grid, p: [f64; 3]) -> [f64; 3] {
        let Some(map) = &self.map else {
            return p;
        };
        // A snapped corner, as closely as an implicit point's coordinates
        // come out (a fragment's corner is the meet of planes): the input
        // corner itself, the same for every polygon that has it.
        let at = grid.world_to_grid(p);
        let corner = |g: GridPoint| {
            let g = g.to_f64();
            (0..3).all(|a| (at[a] - g[a]).abs() <= VertexPosition::coordinate_error(g[a]))
        };
        match self.corners.iter().find(|c| corner(c.grid)) {
            Some(c) => c.input,
            None => map.apply(p),
        }
    }
}

impl PlaneMap {
    /// The map taking the corners `from` (a snapped polygon, possibly bent
    /// along a diagonal) to `to` (a planar polygon), 3 or 4 of each in the
    /// same order; `None` when `to` is not planar, either is degenerate or
    /// the two turn differently at some corner.
    fn new(from: &[[f64; 3]], to: &[[f64; 3]]) -> Option<Self> {
        let n = to.len();
        let normal = planar_normal(to)?;
        let centroid = centroid(to);
        let size = (0..n)
            .map(|i| norm(sub(to[i], to[(i + 1) % n])))
            .fold(0.0, f64::max);
        let k = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs()))?;
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        let from_origin = [from[0][u], from[0][v]];
        let to_origin = [to[0][u], to[0][v]];
        let flat = |p: &[f64; 3], o: [f64; 2]| [p[u] - o[0], p[v] - o[1]];
        let a: SmallVec<[[f64; 2]; 4]> = from.iter().map(|p| flat(p, from_origin)).collect();
        let b: SmallVec<[[f64; 2]; 4]> = to.iter().map(|p| flat(p, to_origin)).collect();
        // Same non-zero turn at every corner: the same shape, so the map
        // keeps the side each fragment faces.
        let turn = |q: &[[f64; 2]], i: usize| {
            let (p0, p1, p2) = (q[i], q[(i + 1) % n], q[(i + 2) % n]);
            (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0])
        };
        if (0..n).any(|i| {
            let (s, t) = (turn(&a, i), turn(&b, i));
            s == 0.0 || t == 0.0 || (s > 0.0) != (t > 0.0)
        }) {
            return None;
        }
        let h = if n == 3 {
            mul(
                &affine_from_triangle(&b)?,
                &inverse(&affine_from_triangle(&a)?)?,
            )
        } else {
            mul(&from_unit_square(&b)?, &inverse(&from_unit_square(&a)?)?)
        };
        let map = Self {
            u,
            v,
            k,
            from_origin,
            to_origin,
            h,
            normal,
            offset: dot(normal, centroid),
        };
        // The map must keep every corner's side of the line at infinity
        // (then so does all of the polygon, their convex hull) and take it
        // where it belongs.
        let sign = map.h[2][2].signum();
        let lands = from.iter().zip(to).all(|(p, q)| {
            let w = map.weight(*p);
            w * sign > 0.0 && norm(sub(map.apply(*p), *q)) <= 1e-6 * size
        });
        lands.then_some(map)
    }

    /// The homogeneous weight of the point `p`.
    fn weight(&self, p: [f64; 3]) -> f64 {
        let x = [
            p[self.u] - self.from_origin[0],
            p[self.v] - self.from_origin[1],
        ];
        self.h[2][0] * x[0] + self.h[2][1] * x[1] + self.h[2][2]
    }

    /// The image of `p` on the input plane.
    fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let x = [
            p[self.u] - self.from_origin[0],
            p[self.v] - self.from_origin[1],
            1.0,
        ];
        let y = [0, 1, 2].map(|r| self.h[r][0] * x[0] + self.h[r][1] * x[1] + self.h[r][2] * x[2]);
        let a = self.to_origin[0] + y[0] / y[2];
        let b = self.to_origin[1] + y[1] / y[2];
        let mut q = [0.0; 3];
        q[self.u] = a;
        q[self.v] = b;
        q[self.k] =
            (self.offset - self.normal[self.u] * a - self.normal[self.v] * b) / self.normal[self.k];
        q
    }
}

/// The unit normal of a planar polygon (counter-clockwise seen from its
/// front), `None` when it is degenerate or its corners stray from their
/// mean plane by more than [`PLANARITY`] of its size.
pub(crate) fn planar_normal(corners: &[[f64; 3]]) -> Option<[f64; 3]> {
    let n = corners.len();
    let mut normal = [0.0; 3];
    for i in 0..n {
        let c = cross(corners[i], corners[(i + 1) % n]);
        normal = [normal[0] + c[0], normal[1] + c[1], normal[2] + c[2]];
    }
    let length = norm(normal);
    if !(length > 0.0 && length.is_finite()) {
        return None;
    }
    let normal = normal.map(|x| x / length);
    let centroid = centroid(corners);
    let size = (0..n)
        .map(|i| norm(sub(corners[i], corners[(i + 1) % n])))
        .fold(0.0, f64::max);
    let planar = corners
        .iter()
        .all(|&p| dot(normal, sub(p, centroid)).abs() <= PLANARITY * size);
    planar.then_some(normal)
}

fn centroid(points: &[[f64; 3]]) -> [f64; 3] {
    points
        .iter()
        .fold([0.0; 3], |s, p| [s[0] + p[0], s[1] + p[1], s[2] + p[2]])
        .map(|x| x / points.len() as f64)
}

type Matrix = [[f64; 3]; 3];

/// The affine map taking (0, 0), (1, 0), (0, 1) to the corners `t`.
fn affine_from_triangle(t: &[[f64; 2]]) -> Option<Matrix> {
    let [p0, p1, p2] = [t[0], t[1], t[2]];
    Some([
        [p1[0] - p0[0], p2[0] - p0[0], p0[0]],
        [p1[1] - p0[1], p2[1] - p0[1], p0[1]],
        [0.0, 0.0, 1.0],
    ])
}

/// The projective map taking the unit square's corners (0, 0), (1, 0),
/// (1, 1), (0, 1) to the corners `q` (Heckbert's closed form).
fn from_unit_square(q: &[[f64; 2]]) -> Option<Matrix> {
    let [p0, p1, p2, p3] = [q[0], q[1], q[2], q[3]];
    let sx = p0[0] - p1[0] + p2[0] - p3[0];
    let sy = p0[1] - p1[1] + p2[1] - p3[1];
    let (dx1, dx2) = (p1[0] - p2[0], p3[0] - p2[0]);
    let (dy1, dy2) = (p1[1] - p2[1], p3[1] - p2[1]);
    let den = dx1 * dy2 - dx2 * dy1;
    if den == 0.0 || !den.is_finite() {
        return None;
    }
    let g = (sx * dy2 - dx2 * sy) / den;
    let h = (dx1 * sy - sx * dy1) / den;
    Some([
        [p1[0] - p0[0] + g * p1[0], p3[0] - p0[0] + h * p3[0], p0[0]],
        [p1[1] - p0[1] + g * p1[1], p3[1] - p0[1] + h * p3[1], p0[1]],
        [g, h, 1.0],
    ])
}

fn mul(a: &Matrix, b: &Matrix) -> Matrix {
    let mut m = [[0.0; 3]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = (0..3).map(|i| a[r][i] * b[i][c]).sum();
        }
    }
    m
}

/// The inverse matrix.
fn inverse(m: &Matrix) -> Option<Matrix> {
    let c =
        |r0: usize, r1: usize, c0: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let adj = [
        [c(1, 2, 1, 2), -c(0, 2, 1, 2), c(0, 1, 1, 2)],
        [-c(1, 2, 0, 2), c(0, 2, 0, 2), -c(0, 1, 0, 2)],
        [c(1, 2, 0, 1), -c(0, 2, 0, 1), c(0, 1, 0, 1)],
    ];
    let det = m[0][0] * adj[0][0] + m[0][1] * adj[1][0] + m[0][2] * adj[2][0];
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    Some(adj.map(|row| row.map(|x| x / det)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A convex quad in a tilted plane, and the same with each corner
    /// moved by up to `jiggle` (as snapping would).
    fn quads(jiggle: f64) -> ([[f64; 3]; 4], [[f64; 3]; 4]) {
        let at = |x: f64, z: f64| [x, 0.3 * x - 0.2 * z + 1.0, z];
        let input = [at(0.0, 0.0), at(0.0, 1.0), at(2.0, 1.3), at(1.7, -0.1)];
        let moves = [
            [1.0, -0.5, 0.3],
            [-0.7, 0.2, 1.0],
            [0.4, 0.9, -1.0],
            [-1.0, -1.0, 0.6],
        ];
        let mut snapped = input;
        for (s, m) in snapped.iter_mut().zip(moves) {
            *s = [0, 1, 2].map(|a| s[a] + jiggle * m[a]);
        }
        (input, snapped)
    }

    fn between(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
        [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]))
    }

    #[test]
    fn corners_go_to_their_input_corners_and_lines_stay_lines() {
        let (input, snapped) = quads(1e-3);
        let map = PlaneMap::new(&snapped, &input).expect("a mappable quad");
        for (s, p) in snapped.iter().zip(&input) {
            assert!(norm(sub(map.apply(*s), *p)) < 1e-14, "{s:?}");
        }
        // Points along a snapped diagonal land on the input diagonal, in
        // the input plane.
        let normal = newell(&input);
        for t in [0.1, 0.37, 0.5, 0.93] {
            let q = map.apply(between(snapped[0], snapped[2], t));
            let off = cross(sub(q, input[0]), sub(input[2], input[0]));
            assert!(norm(off) < 1e-14, "t = {t}: {off:?}");
            assert!(dot(sub(q, input[0]), normal).abs() < 1e-14);
        }
    }

    #[test]
    fn a_quad_that_turns_the_other_way_is_not_mapped() {
        let (input, _) = quads(0.0);
        // Corner 3 pushed across the line of corners 2 and 0: the snapped
        // copy is concave where the input is convex.
        let mut snapped = input;
        snapped[3] = between(input[0], input[2], 0.5);
        snapped[3] = [0, 1, 2].map(|k| snapped[3][k] + 0.01 * (snapped[3][k] - input[3][k]));
        assert!(PlaneMap::new(&snapped, &input).is_none());
        // A non-planar input is not mapped either.
        let mut bent = input;
        bent[2][1] += 1e-3;
        assert!(PlaneMap::new(&input, &bent).is_none());
    }

    fn newell(points: &[[f64; 3]]) -> [f64; 3] {
        let mut n = [0.0; 3];
        for i in 0..points.len() {
            let c = cross(points[i], points[(i + 1) % points.len()]);
            n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
        }
        n
    }
}
