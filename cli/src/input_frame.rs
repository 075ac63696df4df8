//! Output points put back onto the input polygons they lie on.
//!
//! The kernel works on the input snapped to a grid, so the corners of a
//! polygon's fragments lie on its snapped copy: within half a grid step of
//! the input polygon, not on it, and their areas add up to the snapped
//! copy's area. Written as they are, a small or thin polygon's fragments
//! miss its area by a visible fraction (a needle 150 grid steps wide, by
//! 6e-4).
//!
//! Triangles and planar quadrilaterals are mapped back exactly: each
//! point of the snapped copy goes where a map taking every snapped corner
//! to its input corner, and every snapped side onto the input side, takes
//! it. A triangle's map is affine; a convex quad's bilinear (each point
//! moves by an average of its corners' moves, however thin the quad: the
//! projective map through the same corners, which would keep lines
//! straight, moves the middle of a needle by hundreds of grid steps); a
//! concave quad's projective, where it moves no point much farther than
//! the corners. The fragments' outlines list every vertex on their sides
//! (the meshes are conforming), so with each vertex placed on the input
//! polygon they still share their sides, and tile the input polygon
//! exactly, up to the rounding of their coordinates; a fragment corner at
//! a polygon corner is written as the input has it. The map works in the
//! coordinate plane that the input polygon's plane projects onto best, so
//! a snapped quad bent into two triangles maps onto the input plane as
//! well. A polygon whose map would turn a face over (a sliver thinner than
//! its corners' moves), and other polygons (five corners or more, or not
//! planar) are written as snapped.
//!
//! Nothing decided in the exact kernel changes: the map only moves where
//! the output coordinates are written, by at most about a grid step.

use std::collections::{HashMap, HashSet};

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

/// A map between two nearly equal planar polygons, worked in the
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
    /// Input corner 0.
    to_origin: [f64; 3],
    /// The input plane `normal . x = offset` (unit normal).
    normal: [f64; 3],
    offset: f64,
    kind: MapKind,
}

#[derive(Debug, Clone)]
enum MapKind {
    /// A projective map (affine for a triangle): homogeneous 3 x 3 matrix
    /// from coordinates relative to `from_origin` to coordinates (`u`,
    /// `v`) relative to `to_origin`.
    Projective([[f64; 3]; 3]),
    /// Bilinear interpolation of the input corners (relative to
    /// `to_origin`) at the snapped quad's bilinear coordinates of a point:
    /// each point moves by an average of the corners' moves, however thin
    /// the quad (a projective map can move a thin quad's middle by many
    /// grid steps).
    Bilinear {
        from: [[f64; 2]; 4],
        to: [[f64; 3]; 4],
    },
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
        if !mesh.faces.iter().any(|f| self.frame(f.source).is_some()) {
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
        // Polygons whose map would turn a face over (a sliver thinner than
        // its corners' moves) are written as snapped.
        let turned: HashSet<u32> = faces
            .iter()
            .filter(|face| {
                self.frame(face.source).is_some_and(|frame| {
                    let corners = face.vertices.iter().map(|&v| vertices[v as usize].0);
                    frame.turns_over(&self.grid, corners)
                })
            })
            .map(|face| face.source)
            .collect();
        for face in &mut faces {
            let frame = self
                .frame(face.source)
                .filter(|_| !turned.contains(&face.source));
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

impl InputFrames {
    /// The frame of input polygon `source`, if it moves points.
    fn frame(&self, source: u32) -> Option<&Frame> {
        self.frames
            .get(source as usize)
            .and_then(Option::as_deref)
            .filter(|f| f.map.is_some())
    }
}

impl Frame {
    /// Whether placing the face of `corners` (world units) would reverse
    /// its turning sense in the coordinate plane of the map.
    fn turns_over(&self, grid: &Grid, corners: impl Iterator<Item = [f64; 3]>) -> bool {
        let Some(map) = &self.map else {
            return false;
        };
        let (mut before, mut after) = (0.0, 0.0);
        let corners: SmallVec<[[f64; 3]; 8]> = corners.collect();
        let origin = corners.first().copied().unwrap_or_default();
        let placed_origin = self.place(grid, origin);
        for (i, &p) in corners.iter().enumerate() {
            let q = corners[(i + 1) % corners.len()];
            let (a, b) = (map.flat(p), map.flat(q));
            let o = map.flat(origin);
            before += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
            let (a, b) = (map.flat(self.place(grid, p)), map.flat(self.place(grid, q)));
            let o = map.flat(placed_origin);
            after += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        }
        before != 0.0 && (after == 0.0 || (after > 0.0) != (before > 0.0))
    }

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
    /// same order: affine for a triangle, bilinear for a convex quad,
    /// projective for a concave one. `None` when `to` is not planar, either
    /// is degenerate, the two turn differently at some corner, or the map
    /// would move some point much farther than the corners moved.
    fn new(from: &[[f64; 3]], to: &[[f64; 3]]) -> Option<Self> {
        let n = to.len();
        let normal = planar_normal(to)?;
        let size = (0..n)
            .map(|i| norm(sub(to[i], to[(i + 1) % n])))
            .fold(0.0, f64::max);
        let k = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs()))?;
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        let from_origin = [from[0][u], from[0][v]];
        let flat = |p: &[f64; 3], o: [f64; 2]| [p[u] - o[0], p[v] - o[1]];
        let a: SmallVec<[[f64; 2]; 4]> = from.iter().map(|p| flat(p, from_origin)).collect();
        let b: SmallVec<[[f64; 2]; 4]> = to.iter().map(|p| flat(p, [to[0][u], to[0][v]])).collect();
        // Same non-zero turn at every corner: the same shape, so the map
        // keeps the side each fragment faces.
        let turn = |q: &[[f64; 2]], i: usize| {
            let (p0, p1, p2) = (q[i], q[(i + 1) % n], q[(i + 2) % n]);
            (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0])
        };
        let turns: SmallVec<[f64; 4]> = (0..n).map(|i| turn(&b, i)).collect();
        if (0..n).any(|i| {
            let (s, t) = (turn(&a, i), turns[i]);
            s == 0.0 || t == 0.0 || (s > 0.0) != (t > 0.0)
        }) {
            return None;
        }
        let convex = turns.iter().all(|&t| (t > 0.0) == (turns[0] > 0.0));
        let kind = if n == 3 {
            MapKind::Projective(mul(
                &affine_from_triangle(&b)?,
                &inverse(&affine_from_triangle(&a)?)?,
            ))
        } else if convex {
            let relative = |p: &[f64; 3]| sub(*p, to[0]);
            MapKind::Bilinear {
                from: [a[0], a[1], a[2], a[3]],
                to: [
                    relative(&to[0]),
                    relative(&to[1]),
                    relative(&to[2]),
                    relative(&to[3]),
                ],
            }
        } else {
            MapKind::Projective(mul(
                &from_unit_square(&b)?,
                &inverse(&from_unit_square(&a)?)?,
            ))
        };
        let map = Self {
            u,
            v,
            k,
            from_origin,
            to_origin: to[0],
            normal,
            offset: dot(normal, centroid(to)),
            kind,
        };
        // The corners land where they belong (a projective map keeps them
        // on its side of the line at infinity: then all of the polygon,
        // their convex hull, stays there), and the middle of the polygon
        // and of its sides move about as far as the corners did.
        let moved = from
            .iter()
            .zip(to)
            .map(|(p, q)| norm(sub(*p, *q)))
            .fold(0.0, f64::max);
        let sign = map.weight(from[0]).signum();
        let lands = from.iter().zip(to).all(|(p, q)| {
            map.weight(*p) * sign > 0.0 && norm(sub(map.apply(*p), *q)) <= 1e-6 * size
        });
        let middles = (0..n)
            .map(|i| mid(from[i], from[(i + 1) % n]))
            .chain([centroid(from)]);
        let tame = middles
            .into_iter()
            .all(|p| norm(sub(map.apply(p), p)) <= 4.0 * moved + 1e-9 * size);
        (lands && tame).then_some(map)
    }

    /// The homogeneous weight of the point `p` (1 for a bilinear map).
    fn weight(&self, p: [f64; 3]) -> f64 {
        match &self.kind {
            MapKind::Projective(h) => {
                let x = self.flat(p);
                h[2][0] * x[0] + h[2][1] * x[1] + h[2][2]
            }
            MapKind::Bilinear { .. } => 1.0,
        }
    }

    /// `p` in the coordinate plane, relative to `from_origin`.
    fn flat(&self, p: [f64; 3]) -> [f64; 2] {
        [
            p[self.u] - self.from_origin[0],
            p[self.v] - self.from_origin[1],
        ]
    }

    /// The image of `p` on the input plane.
    fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let x = self.flat(p);
        match &self.kind {
            MapKind::Projective(h) => {
                let y = [0, 1, 2].map(|r| h[r][0] * x[0] + h[r][1] * x[1] + h[r][2]);
                let a = self.to_origin[self.u] + y[0] / y[2];
                let b = self.to_origin[self.v] + y[1] / y[2];
                let mut q = [0.0; 3];
                q[self.u] = a;
                q[self.v] = b;
                q[self.k] = (self.offset - self.normal[self.u] * a - self.normal[self.v] * b)
                    / self.normal[self.k];
                q
            }
            MapKind::Bilinear { from, to } => {
                let [s, t] = bilinear_coordinates(from, x);
                let q = [0, 1, 2].map(|c| {
                    let (q0, q1, q2, q3) = (to[0][c], to[1][c], to[2][c], to[3][c]);
                    q0 + s * (q1 - q0) + t * (q3 - q0) + s * t * (q0 - q1 + q2 - q3)
                });
                [0, 1, 2].map(|c| self.to_origin[c] + q[c])
            }
        }
    }
}

/// The coordinates `(s, t)` of `x` in the bilinear patch of the convex
/// quad `q` (corner 0 at `(0, 0)`, 1 at `(1, 0)`, 2 at `(1, 1)`, 3 at
/// `(0, 1)`): Newton's method from the parallelogram of corners 0, 1, 3,
/// which a nearly parallelogram quad (a snapped one) all but is.
fn bilinear_coordinates(q: &[[f64; 2]; 4], x: [f64; 2]) -> [f64; 2] {
    let e = [q[1][0] - q[0][0], q[1][1] - q[0][1]];
    let f = [q[3][0] - q[0][0], q[3][1] - q[0][1]];
    let g = [
        q[0][0] - q[1][0] + q[2][0] - q[3][0],
        q[0][1] - q[1][1] + q[2][1] - q[3][1],
    ];
    let h = [x[0] - q[0][0], x[1] - q[0][1]];
    let solve = |a: [f64; 2], b: [f64; 2], r: [f64; 2]| {
        let det = a[0] * b[1] - a[1] * b[0];
        [
            (r[0] * b[1] - r[1] * b[0]) / det,
            (a[0] * r[1] - a[1] * r[0]) / det,
        ]
    };
    let mut st = solve(e, f, h);
    for _ in 0..16 {
        let [s, t] = st;
        let residual = [0, 1].map(|c| e[c] * s + f[c] * t + g[c] * s * t - h[c]);
        let step = solve(
            [e[0] + g[0] * t, e[1] + g[1] * t],
            [f[0] + g[0] * s, f[1] + g[1] * s],
            residual,
        );
        if !(step[0].is_finite() && step[1].is_finite()) {
            break;
        }
        st = [s - step[0], t - step[1]];
        if step[0].abs() + step[1].abs() <= 4.0 * f64::EPSILON * (1.0 + s.abs() + t.abs()) {
            break;
        }
    }
    st
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|c| 0.5 * (a[c] + b[c]))
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

    /// The largest distance between `a[i]` and `b[i]`.
    fn farthest(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(p, q)| norm(sub(*p, *q)))
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_convex_quad_maps_corner_to_corner_side_to_side_moving_no_point_farther() {
        let (input, snapped) = quads(1e-3);
        let map = PlaneMap::new(&snapped, &input).expect("a mappable quad");
        assert!(matches!(map.kind, MapKind::Bilinear { .. }));
        for (s, p) in snapped.iter().zip(&input) {
            assert!(norm(sub(map.apply(*s), *p)) < 1e-14, "{s:?}");
        }
        let normal = newell(&input);
        let moved = farthest(&snapped, &input);
        for i in 0..4 {
            let (s0, s1) = (snapped[i], snapped[(i + 1) % 4]);
            let (p0, p1) = (input[i], input[(i + 1) % 4]);
            for t in [0.1, 0.37, 0.5, 0.93] {
                // Along a side: onto the input side, at the same fraction.
                let q = map.apply(between(s0, s1, t));
                assert!(
                    norm(sub(q, between(p0, p1, t))) < 1e-14,
                    "side {i}, t = {t}"
                );
                // Inside: in the input plane, moved no farther than a corner.
                let inner = between(between(s0, s1, t), snapped[(i + 2) % 4], 0.6);
                let q = map.apply(inner);
                assert!(dot(sub(q, input[0]), normal).abs() < 1e-14);
                assert!(norm(sub(q, inner)) <= moved * (1.0 + 1e-9));
            }
        }
    }

    #[test]
    fn a_needle_moves_its_middle_no_farther_than_its_corners() {
        // 2000 long, 1 wide; the corners move by up to 0.005 across it.
        let input = [
            [0.0, 0.0, 0.0],
            [2000.0, 0.0, 0.0],
            [2000.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let moves = [
            [0.004, -0.003, 0.0],
            [-0.002, 0.005, 0.0],
            [0.003, -0.004, 0.0],
            [-0.005, 0.002, 0.0],
        ];
        let snapped: Vec<[f64; 3]> = input
            .iter()
            .zip(moves)
            .map(|(p, m)| [0, 1, 2].map(|c| p[c] + m[c]))
            .collect();
        let map = PlaneMap::new(&snapped, &input).expect("a mappable needle");
        let moved = farthest(&snapped, &input);
        for t in [0.25, 0.5, 0.75] {
            let p = between(
                between(snapped[0], snapped[1], t),
                between(snapped[3], snapped[2], t),
                0.5,
            );
            assert!(
                norm(sub(map.apply(p), p)) <= moved * (1.0 + 1e-9),
                "t = {t}"
            );
        }
        // The projective map through the same corners moves the middle by
        // hundreds of times as far.
        let flat = |q: &[[f64; 3]]| -> Vec<[f64; 2]> { q.iter().map(|p| [p[0], p[1]]).collect() };
        let h = mul(
            &from_unit_square(&flat(&input)).unwrap(),
            &inverse(&from_unit_square(&flat(&snapped)).unwrap()).unwrap(),
        );
        let p = between(
            between(snapped[0], snapped[1], 0.5),
            between(snapped[3], snapped[2], 0.5),
            0.5,
        );
        let y = [0, 1, 2].map(|r| h[r][0] * p[0] + h[r][1] * p[1] + h[r][2]);
        let q = [y[0] / y[2], y[1] / y[2], 0.0];
        assert!(norm(sub(q, p)) > 100.0 * moved, "{q:?}");
    }

    #[test]
    fn a_concave_quad_maps_projectively_lines_staying_lines() {
        // A dart: corner 2 turns the other way.
        let at = |x: f64, z: f64| [x, 0.3 * x - 0.2 * z + 1.0, z];
        let input = [at(0.0, 0.0), at(2.0, -1.0), at(0.8, 0.0), at(2.0, 1.0)];
        let moves = [
            [1.0, -0.5, 0.3],
            [-0.7, 0.2, 1.0],
            [0.4, 0.9, -1.0],
            [-1.0, -1.0, 0.6],
        ];
        let snapped: Vec<[f64; 3]> = input
            .iter()
            .zip(moves)
            .map(|(p, m)| [0, 1, 2].map(|c| p[c] + 1e-3 * m[c]))
            .collect();
        let map = PlaneMap::new(&snapped, &input).expect("a mappable dart");
        assert!(matches!(map.kind, MapKind::Projective(_)));
        for (s, p) in snapped.iter().zip(&input) {
            assert!(norm(sub(map.apply(*s), *p)) < 1e-14, "{s:?}");
        }
        // Points along the snapped line from corner 0 to corner 2 land on
        // the input line, in the input plane.
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
