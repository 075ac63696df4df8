//! The boundary of `A op B` from the boundaries of `A` and `B` (Thibault &
//! Naylor 1987, boundary evaluation by classifying each solid's faces
//! against the other's tree), welded into a closed mesh without
//! T-junctions.
//!
//! Each face of `A` is partitioned exactly by `B`'s tree
//! ([`BspSolid::partition_polygon`]) and each face of `B` by `A`'s; the
//! operation keeps:
//!
//! | op | pieces of `A` | pieces of `B` |
//! | --- | --- | --- |
//! | union | outside `B`, on `B`'s boundary facing the same way | outside `A` |
//! | intersection | inside `B`, on `B`'s boundary facing the same way | inside `A` |
//! | difference | outside `B`, on `B`'s boundary facing the other way | inside `A`, flipped |
//!
//! so a coplanar overlap is kept once (from `A`), and faces where the
//! solids touch from opposite sides are dropped when they end up inside the
//! result.
//!
//! Pieces of neighbouring faces are cut at different places along their
//! shared edges, so [`weld`] merges equal vertices (decided exactly) and
//! inserts into every edge the vertices that lie on it: a vertex lies on an
//! edge when it is on the piece's support plane and on the edge plane
//! (exactly) and strictly behind the planes of the two neighbouring edges.
//! The result is an indexed mesh in which every edge of a closed input is
//! used exactly twice, once in each direction.

use crate::SetOp;
use bsp_core::predicates::Side;
use bsp_core::{BspSolid, Containment, ConvexPolygon};
use rustc_hash::FxHashMap;
use std::collections::HashMap;

/// The boundary of a set operation: exact pieces and a welded mesh.
#[derive(Debug, Clone)]
pub struct CsgBoundary {
    /// The boundary as exact convex pieces, outward. A piece of `A`'s face
    /// `i` has source `i`; a piece of `B`'s face `j` has source
    /// `a_faces.len() + j`.
    pub polygons: Vec<ConvexPolygon>,
    /// The same pieces welded into a mesh without T-junctions.
    pub mesh: IndexedMesh,
}

/// A polygon mesh with shared vertices, in grid units (`f64`, for output).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct IndexedMesh {
    /// Vertex positions; each exact point appears once.
    pub vertices: Vec<[f64; 3]>,
    /// Faces as counter-clockwise (seen from outside) vertex index lists.
    /// A face may have collinear vertices where T-junctions were removed.
    pub faces: Vec<Vec<u32>>,
    /// For each face, the index of the polygon it came from.
    pub face_polygon: Vec<u32>,
}

impl IndexedMesh {
    /// Enclosed volume (divergence theorem, `f64`), in cubic grid units.
    pub fn volume(&self) -> f64 {
        let Some(origin) = self.vertices.first().copied() else {
            return 0.0;
        };
        let at = |i: u32| {
            let p = self.vertices[i as usize];
            [p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]]
        };
        let mut six = 0.0;
        for face in &self.faces {
            let a = at(face[0]);
            for k in 1..face.len() - 1 {
                let (b, c) = (at(face[k]), at(face[k + 1]));
                six += a[0] * (b[1] * c[2] - b[2] * c[1])
                    + a[1] * (b[2] * c[0] - b[0] * c[2])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]);
            }
        }
        six / 6.0
    }

    /// Edges that break closedness: `(from, to, uses of from -> to, uses of
    /// to -> from)` for every directed edge used a different number of
    /// times in the two directions. Empty for a closed, consistently
    /// oriented mesh.
    pub fn open_edges(&self) -> Vec<(u32, u32, u32, u32)> {
        let count = self.edge_uses();
        let mut bad: Vec<(u32, u32, u32, u32)> = count
            .iter()
            .filter_map(|(&(a, b), &n)| {
                let back = count.get(&(b, a)).copied().unwrap_or(0);
                (n != back).then_some((a, b, n, back))
            })
            .collect();
        bad.sort_unstable();
        bad
    }

    /// Whether every edge is used as often in one direction as in the
    /// other: the mesh bounds a volume.
    pub fn is_closed(&self) -> bool {
        self.open_edges().is_empty()
    }

    /// Whether every edge is used exactly once in each direction: closed
    /// and two-manifold along edges. Solids that touch along an edge give a
    /// closed result with edges used twice in each direction.
    pub fn is_closed_manifold(&self) -> bool {
        let count = self.edge_uses();
        count
            .iter()
            .all(|(&(a, b), &n)| n == 1 && count.get(&(b, a)) == Some(&1))
    }

    fn edge_uses(&self) -> HashMap<(u32, u32), u32> {
        let mut count: HashMap<(u32, u32), u32> = HashMap::new();
        for face in &self.faces {
            for k in 0..face.len() {
                let e = (face[k], face[(k + 1) % face.len()]);
                *count.entry(e).or_default() += 1;
            }
        }
        count
    }

    /// Writes the mesh in Wavefront OBJ form (1-based indices).
    pub fn write_obj(&self, out: &mut impl std::fmt::Write) -> std::fmt::Result {
        for v in &self.vertices {
            writeln!(out, "v {} {} {}", v[0], v[1], v[2])?;
        }
        for face in &self.faces {
            write!(out, "f")?;
            for i in face {
                write!(out, " {}", i + 1)?;
            }
            writeln!(out)?;
        }
        Ok(())
    }
}

/// The pieces of `A op B`'s boundary, from the faces of `A` and `B` (closed,
/// outward) and their solids.
///
/// Each face's kept part comes in as few pieces as the other solid's tree
/// allows ([`BspSolid::partition_polygon_by`], keyed by whether a piece is
/// kept): a tree's cut with kept pieces alone on both sides leaves no
/// seam. Seams would be slivers wherever a plane passes near a corner, and
/// a result fed back in would fold along them once snapped.
pub fn boundary_pieces(
    a: &BspSolid,
    a_faces: &[ConvexPolygon],
    b: &BspSolid,
    b_faces: &[ConvexPolygon],
    op: SetOp,
) -> Vec<ConvexPolygon> {
    let keeps_a = |class| {
        matches!(
            (op, class),
            (
                SetOp::Union,
                Containment::Outside | Containment::BoundarySame
            ) | (
                SetOp::Intersection,
                Containment::Inside | Containment::BoundarySame
            ) | (
                SetOp::Difference,
                Containment::Outside | Containment::BoundaryOpposite
            )
        )
    };
    let keeps_b = |class| {
        matches!(
            (op, class),
            (SetOp::Union, Containment::Outside)
                | (SetOp::Intersection | SetOp::Difference, Containment::Inside)
        )
    };
    let mut out = Vec::new();
    for (i, face) in a_faces.iter().enumerate() {
        for (piece, keep) in b.partition_polygon_by(face, keeps_a) {
            if keep {
                out.push(piece.with_source(i as u32));
            }
        }
    }
    let offset = a_faces.len() as u32;
    for (j, face) in b_faces.iter().enumerate() {
        for (piece, keep) in a.partition_polygon_by(face, keeps_b) {
            if keep {
                let piece = match op {
                    SetOp::Difference => piece.flipped(),
                    SetOp::Union | SetOp::Intersection => piece,
                };
                out.push(piece.with_source(offset + j as u32));
            }
        }
    }
    out
}

/// The boundary of `A op B`: exact pieces ([`boundary_pieces`]) and the
/// welded mesh ([`weld`]).
pub fn boundary(
    a: &BspSolid,
    a_faces: &[ConvexPolygon],
    b: &BspSolid,
    b_faces: &[ConvexPolygon],
    op: SetOp,
) -> CsgBoundary {
    let polygons = boundary_pieces(a, a_faces, b, b_faces, op);
    let mesh = weld(&polygons);
    CsgBoundary { polygons, mesh }
}

/// A polygon's vertex: `(polygon, vertex)`.
type VertexRef = (u32, u32);

/// Whether two polygon vertices are the same point, exactly.
fn same_point(polygons: &[ConvexPolygon], a: VertexRef, b: VertexRef) -> bool {
    let (pa, pb) = (&polygons[a.0 as usize], &polygons[b.0 as usize]);
    if let (Some(p), Some(q)) = (
        pa.vertex_grid_point(a.1 as usize),
        pb.vertex_grid_point(b.1 as usize),
    ) {
        return p == q;
    }
    pb.vertex_planes(b.1 as usize)
        .iter()
        .all(|plane| pa.vertex_side(a.1 as usize, plane) == Side::On)
}

/// Half-width of the `f64` neighbourhood in which two representations of
/// one exact point can fall: vertex coordinates are within `2^-20` grid
/// units of the truth (see `bsp_core::predicates::implicit_to_f64`). Only a
/// search radius: every decision is exact.
const NEAR: f64 = 1.0 / 65536.0;

/// Welds `polygons` into an indexed mesh: equal vertices (decided exactly)
/// become one, and every vertex lying on another polygon's edge (decided
/// exactly) is inserted into that edge, so that a closed set of pieces
/// gives a closed mesh.
///
/// Vertices inserted into one edge are ordered along it by their `f64`
/// positions: exact membership, floating-point order (points closer than
/// about `2^-20` grid units along an edge could be swapped).
pub fn weld(polygons: &[ConvexPolygon]) -> IndexedMesh {
    // 1. Unique vertices, through a hash of f64 cells checked in the 27
    //    cells around each vertex.
    let cell = |p: [f64; 3]| p.map(|c| (c / (4.0 * NEAR)).floor() as i64);
    let mut buckets: FxHashMap<[i64; 3], Vec<u32>> = FxHashMap::default();
    let mut representative: Vec<VertexRef> = Vec::new();
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    let mut ids: Vec<Vec<u32>> = Vec::with_capacity(polygons.len());
    for (pi, polygon) in polygons.iter().enumerate() {
        let mut face_ids = Vec::with_capacity(polygon.len());
        for vi in 0..polygon.len() {
            let p = polygon.vertex_f64(vi);
            let me = (pi as u32, vi as u32);
            let c = cell(p);
            let mut found = None;
            'search: for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        if let Some(list) = buckets.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                            for &id in list {
                                if same_point(polygons, representative[id as usize], me) {
                                    found = Some(id);
                                    break 'search;
                                }
                            }
                        }
                    }
                }
            }
            let id = found.unwrap_or_else(|| {
                let id = vertices.len() as u32;
                vertices.push(p);
                representative.push(me);
                buckets.entry(c).or_default().push(id);
                id
            });
            face_ids.push(id);
        }
        ids.push(face_ids);
    }

    // 2. Vertices bucketed in a uniform grid of cells about as wide as an
    //    average edge, to find the candidates in an edge's box.
    let cells = CellGrid::new(&vertices, polygons, &ids);
    // 3. Faces with the vertices on their edges inserted.
    let mut faces = Vec::with_capacity(polygons.len());
    let mut on_edge: Vec<(f64, u32)> = Vec::new();
    for (pi, polygon) in polygons.iter().enumerate() {
        let n = polygon.len();
        let face_ids = &ids[pi];
        let mut face = Vec::with_capacity(n);
        for e in 0..n {
            let (u, v) = (face_ids[e], face_ids[(e + 1) % n]);
            face.push(u);
            let (pu, pv) = (vertices[u as usize], vertices[v as usize]);
            let lo: [f64; 3] = std::array::from_fn(|k| pu[k].min(pv[k]) - NEAR);
            let hi: [f64; 3] = std::array::from_fn(|k| pu[k].max(pv[k]) + NEAR);
            on_edge.clear();
            let dir = [pv[0] - pu[0], pv[1] - pu[1], pv[2] - pu[2]];
            for w in cells.in_box(lo, hi) {
                if w == u || w == v {
                    continue;
                }
                let pw = vertices[w as usize];
                if (0..3).any(|k| pw[k] < lo[k] || pw[k] > hi[k]) {
                    continue;
                }
                if lies_inside_edge(polygons, polygon, e, representative[w as usize]) {
                    let t = (pw[0] - pu[0]) * dir[0]
                        + (pw[1] - pu[1]) * dir[1]
                        + (pw[2] - pu[2]) * dir[2];
                    on_edge.push((t, w));
                }
            }
            on_edge.sort_by(|a, b| a.0.total_cmp(&b.0));
            face.extend(on_edge.iter().map(|&(_, w)| w));
        }
        faces.push(face);
    }
    IndexedMesh {
        vertices,
        faces,
        face_polygon: (0..polygons.len() as u32).collect(),
    }
}

/// Vertices bucketed in a uniform grid over their bounding box (counting
/// sort: each cell's vertices are a range of one list, in index order).
struct CellGrid {
    lo: [f64; 3],
    size: f64,
    dims: [usize; 3],
    start: Vec<u32>,
    ids: Vec<u32>,
}

impl CellGrid {
    fn new(vertices: &[[f64; 3]], polygons: &[ConvexPolygon], face_ids: &[Vec<u32>]) -> Self {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        // Cells as wide as the mean longest extent of an edge, but no more
        // cells than about eight per vertex.
        let (mut sum, mut count) = (0.0, 0_usize);
        for (polygon, ids) in polygons.iter().zip(face_ids) {
            let n = polygon.len();
            for e in 0..n {
                let (p, q) = (
                    vertices[ids[e] as usize],
                    vertices[ids[(e + 1) % n] as usize],
                );
                sum += (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max);
                count += 1;
            }
        }
        let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let budget = (8 * vertices.len().max(1)) as f64;
        let mut size = if count > 0 {
            sum / count as f64
        } else {
            extent
        };
        let cells_for = |size: f64| {
            (0..3)
                .map(|k| ((hi[k] - lo[k]) / size).floor() + 1.0)
                .product::<f64>()
        };
        if size.is_nan() || size <= 0.0 || !size.is_finite() {
            size = extent.max(1.0);
        }
        while cells_for(size) > budget {
            size *= 2.0;
        }
        if vertices.is_empty() {
            lo = [0.0; 3];
        }
        let dims: [usize; 3] = std::array::from_fn(|k| {
            if vertices.is_empty() {
                1
            } else {
                ((hi[k] - lo[k]) / size).floor() as usize + 1
            }
        });
        let mut grid = Self {
            lo,
            size,
            dims,
            start: Vec::new(),
            ids: Vec::new(),
        };
        let cell_of: Vec<usize> = vertices.iter().map(|v| grid.index(grid.cell(*v))).collect();
        let mut start = vec![0_u32; dims[0] * dims[1] * dims[2] + 1];
        for &c in &cell_of {
            start[c + 1] += 1;
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let mut fill = start.clone();
        let mut ids = vec![0_u32; vertices.len()];
        for (v, &c) in cell_of.iter().enumerate() {
            ids[fill[c] as usize] = v as u32;
            fill[c] += 1;
        }
        grid.start = start;
        grid.ids = ids;
        grid
    }

    fn cell(&self, p: [f64; 3]) -> [usize; 3] {
        std::array::from_fn(|k| {
            let c = ((p[k] - self.lo[k]) / self.size).floor();
            (c.max(0.0) as usize).min(self.dims[k] - 1)
        })
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// Every vertex in the cells that meet the box `[lo, hi]` (a superset
    /// of the vertices in the box).
    fn in_box(&self, lo: [f64; 3], hi: [f64; 3]) -> impl Iterator<Item = u32> + '_ {
        let (a, b) = (self.cell(lo), self.cell(hi));
        (a[2]..=b[2]).flat_map(move |z| {
            (a[1]..=b[1]).flat_map(move |y| {
                let row = self.index([a[0], y, z]);
                let end = self.index([b[0], y, z]);
                self.ids[self.start[row] as usize..self.start[end + 1] as usize]
                    .iter()
                    .copied()
            })
        })
    }
}

/// Whether the vertex `w` lies on edge `e` of `polygon`, strictly between
/// its ends: on the support and edge planes, strictly behind the planes of
/// the neighbouring edges (which pass through the ends).
fn lies_inside_edge(
    polygons: &[ConvexPolygon],
    polygon: &ConvexPolygon,
    e: usize,
    w: VertexRef,
) -> bool {
    let n = polygon.len();
    let (q, j) = (&polygons[w.0 as usize], w.1 as usize);
    q.vertex_side(j, polygon.support()) == Side::On
        && q.vertex_side(j, polygon.edge(e)) == Side::On
        && q.vertex_side(j, polygon.edge((e + n - 1) % n)) == Side::Back
        && q.vertex_side(j, polygon.edge((e + 1) % n)) == Side::Back
}

#[cfg(test)]
mod tests {
    use super::*;
    use bsp_core::GridPoint;

    fn square(x0: i32, y0: i32, x1: i32, y1: i32) -> ConvexPolygon {
        let g = |x, y| GridPoint { x, y, z: 0 };
        ConvexPolygon::from_grid_points(&[g(x0, y0), g(x1, y0), g(x1, y1), g(x0, y1)], 0).unwrap()
    }

    #[test]
    fn vertices_on_edges_are_inserted() {
        // A 2x2 square beside two 1x1 squares: the point (2, 1) is a vertex
        // of both small squares and lies inside the big square's right edge.
        let polygons = [square(0, 0, 2, 2), square(2, 0, 3, 1), square(2, 1, 3, 2)];
        let mesh = weld(&polygons);
        assert_eq!(mesh.vertices.len(), 8);
        assert_eq!(mesh.faces[0].len(), 5);
        assert_eq!(mesh.faces[1].len(), 4);
        assert!(mesh.faces[0].contains(&mesh.faces[1][3]));
        // Split pieces share their implicit cut vertices exactly.
        let x = bsp_core::Plane::with_normal_through([1, 0, 0], GridPoint { x: 1, y: 0, z: 0 })
            .unwrap();
        let bsp_core::Split::Both(back, front) = square(0, 0, 2, 2).split(&x) else {
            panic!("x = 1 cuts the square");
        };
        let mesh = weld(&[back, front]);
        assert_eq!(mesh.vertices.len(), 6);
        assert_eq!(mesh.faces.iter().map(Vec::len).sum::<usize>(), 8);
    }
}
