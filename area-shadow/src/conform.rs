//! A conforming mesh from fragments: every vertex shared by the fragments
//! that meet at it, and no T-vertex.
//!
//! Splitting leaves T-junctions: a fragment's edge may have, inside it, a
//! vertex of a neighbouring fragment (of the same polygon, cut differently
//! on the other side of a shadow boundary, or of an adjacent polygon). An
//! interpolated shading then cracks there. [`conform`] gives every distinct
//! point one index and inserts into each fragment's outline, in order,
//! every point that lies strictly inside one of its edges.
//!
//! Floating point only finds candidates (a uniform bucket grid over the
//! points' coordinates, with a margin far above their rounding); whether
//! two vertices are the same point and whether a point lies inside an edge
//! are exact predicates, as is the order of the points inserted into an
//! edge.

use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, ImplicitPoint, Plane};
use rayon::prelude::*;

/// A vertex of the mesh, exact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MeshPoint {
    /// An input grid point.
    Grid(GridPoint),
    /// The intersection of three planes.
    Implicit(ImplicitPoint),
}

impl MeshPoint {
    /// Vertex `k` of `polygon`.
    pub fn vertex(polygon: &ConvexPolygon, k: usize) -> Self {
        match polygon.vertex_grid_point(k) {
            Some(g) => MeshPoint::Grid(g),
            None => {
                let [s, a, b] = polygon.vertex_planes(k);
                MeshPoint::Implicit(
                    ImplicitPoint::new(*s, *a, *b).expect("a polygon's vertex is a point"),
                )
            }
        }
    }

    /// Side of `plane`, exact.
    pub fn side(&self, plane: &Plane) -> Side {
        match self {
            MeshPoint::Grid(g) => side_of_point(plane, *g),
            MeshPoint::Implicit(p) => p.side(plane),
        }
    }

    /// Whether `self` and `other` are the same point, exact.
    pub fn same_point(&self, other: &MeshPoint) -> bool {
        match (self, other) {
            (MeshPoint::Grid(a), MeshPoint::Grid(b)) => a == b,
            (MeshPoint::Implicit(a), MeshPoint::Implicit(b)) => a.same_point(b),
            (MeshPoint::Grid(g), MeshPoint::Implicit(p))
            | (MeshPoint::Implicit(p), MeshPoint::Grid(g)) => {
                p.planes().iter().all(|q| side_of_point(q, *g) == Side::On)
            }
        }
    }

    /// Coordinates in grid units.
    pub fn to_f64(&self) -> [f64; 3] {
        match self {
            MeshPoint::Grid(g) => g.to_f64(),
            MeshPoint::Implicit(p) => p.to_f64(),
        }
    }

    /// A plane through the point that the line through `a` and `b` (two
    /// other points) crosses: orders points along that line.
    fn crossing_plane(&self, a: &MeshPoint, b: &MeshPoint, direction: [f64; 3]) -> Option<Plane> {
        match self {
            MeshPoint::Grid(g) => {
                let axis = (0..3)
                    .max_by(|&i, &j| direction[i].abs().total_cmp(&direction[j].abs()))
                    .unwrap_or(0);
                let mut normal = [0_i64; 3];
                normal[axis] = 1;
                Plane::with_normal_through(normal, *g)
            }
            MeshPoint::Implicit(p) => p
                .planes()
                .iter()
                .find(|q| a.side(q) != Side::On || b.side(q) != Side::On)
                .copied(),
        }
    }
}

/// The result of [`conform`].
#[derive(Debug, Clone, Default)]
pub struct ConformingMesh {
    /// Distinct points, exact.
    pub points: Vec<MeshPoint>,
    /// Their coordinates in grid units.
    pub coords: Vec<[f64; 3]>,
    /// Per input fragment, its outline as point indices, counter-clockwise,
    /// with the points inside its edges inserted.
    pub faces: Vec<Vec<u32>>,
    /// How many points were inserted into edges (T-vertices removed).
    pub inserted: usize,
}

/// Point indices over a uniform grid of cells, sorted by cell.
struct Buckets {
    cell: f64,
    /// (cell, index), sorted; a cell packed into one integer (see
    /// [`pack`]) so that the searches compare integers, not arrays.
    entries: Vec<(u128, u32)>,
    /// Per index, its place in `entries`.
    position: Vec<u32>,
    /// Per place in `entries`, the range of its cell's entries.
    runs: Vec<(u32, u32)>,
}

/// `x` rounded down, as an integer (for cell keys; `f64::floor` is a
/// library call).
fn floor(x: f64) -> i64 {
    let i = x as i64;
    if (i as f64) > x { i - 1 } else { i }
}

/// Cell coordinates are offset by this, so that they pack unsigned.
const CELL_OFFSET: i64 = 1 << 40;

/// A cell `[x, y, z]` as one integer ordered as the cells are, x first:
/// 42 bits per coordinate (cells are at least a grid unit, and grid
/// coordinates stay below `2^25`).
fn pack(k: [i64; 3]) -> u128 {
    let c = |v: i64| (v + CELL_OFFSET) as u128;
    (c(k[0]) << 84) | (c(k[1]) << 42) | c(k[2])
}

/// The cell of a packed key.
fn unpack(key: u128) -> [i64; 3] {
    let mask = (1_u128 << 42) - 1;
    [key >> 84, (key >> 42) & mask, key & mask].map(|v| v as i64 - CELL_OFFSET)
}

impl Buckets {
    /// The buckets of `coords` (index `i` for `coords[i]`).
    fn new(cell: f64, coords: &[[f64; 3]]) -> Self {
        let key = |p: [f64; 3]| pack(p.map(|c| floor(c / cell)));
        let mut entries: Vec<(u128, u32)> = coords
            .par_iter()
            .enumerate()
            .map(|(i, &p)| (key(p), i as u32))
            .collect();
        entries.par_sort_unstable();
        // Where each index sits, and the run of its cell.
        let mut position = vec![0_u32; entries.len()];
        let mut runs = vec![(0_u32, 0_u32); entries.len()];
        let mut start = 0;
        for p in 0..entries.len() {
            position[entries[p].1 as usize] = p as u32;
            if p + 1 == entries.len() || entries[p + 1].0 != entries[p].0 {
                for run in &mut runs[start..=p] {
                    *run = (start as u32, p as u32 + 1);
                }
                start = p + 1;
            }
        }
        Self {
            cell,
            entries,
            position,
            runs,
        }
    }

    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        p.map(|c| floor(c / self.cell))
    }

    /// The indices within [`MARGIN`] of point `i` (at `p`), and maybe
    /// more: when the margin box stays in `i`'s cell (nearly always: a cell
    /// is many grid units), that cell's run of entries, found without a
    /// search; else the box's cells. In (cell, index) order either way.
    fn query_near(&self, i: usize, p: [f64; 3], out: &mut Vec<u32>) {
        let (lo, hi) = (p.map(|x| x - MARGIN), p.map(|x| x + MARGIN));
        if self.key(lo) != self.key(hi) {
            self.query(lo, hi, out);
            return;
        }
        let (start, end) = self.runs[self.position[i] as usize];
        out.clear();
        out.extend(
            self.entries[start as usize..end as usize]
                .iter()
                .map(|&(_, id)| id),
        );
    }

    /// Indices in the cells that the box `[lo, hi]` touches, in (cell,
    /// index) order.
    fn query(&self, lo: [f64; 3], hi: [f64; 3], out: &mut Vec<u32>) {
        out.clear();
        let (a, b) = (self.key(lo), self.key(hi));
        let in_box = |k: [i64; 3]| (0..3).all(|i| a[i] <= k[i] && k[i] <= b[i]);
        // Cells with the same x and y are contiguous, and so are cells
        // with x in a range: one binary search per (x, y) column while
        // there are few columns, else one scan of the slab of x.
        let columns = (b[0] - a[0] + 1).saturating_mul(b[1] - a[1] + 1);
        if columns > 64 {
            // The first keys of x = a[0] and of x = b[0] + 1.
            let low = -CELL_OFFSET;
            let (from, to) = (pack([a[0], low, low]), pack([b[0] + 1, low, low]));
            let start = self.entries.partition_point(|&(k, _)| k < from);
            out.extend(
                self.entries[start..]
                    .iter()
                    .take_while(|&&(k, _)| k < to)
                    .filter(|&&(k, _)| in_box(unpack(k)))
                    .map(|&(_, id)| id),
            );
            return;
        }
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                let (from, to) = (pack([x, y, a[2]]), pack([x, y, b[2]]));
                let start = self.entries.partition_point(|&(k, _)| k < from);
                out.extend(
                    self.entries[start..]
                        .iter()
                        .take_while(|&&(k, _)| k <= to)
                        .map(|&(_, id)| id),
                );
            }
        }
    }
}

/// Far above the rounding of implicit points' coordinates (`2^-20` grid
/// units), far below the distance between distinct grid points.
const MARGIN: f64 = 1e-3;

/// The conforming mesh of `fragments` (convex polygons in grid units).
pub fn conform(fragments: &[ConvexPolygon]) -> ConformingMesh {
    let mut mesh = ConformingMesh::default();
    let corners: usize = fragments.iter().map(ConvexPolygon::len).sum();
    let (lo, hi) = fragments.iter().flat_map(|f| f.vertices_f64()).fold(
        ([f64::MAX; 3], [f64::MIN; 3]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        },
    );
    let extent = (0..3).map(|i| hi[i] - lo[i]).fold(1.0, f64::max);
    let cell = (extent / (corners.max(1) as f64).sqrt()).max(1.0);

    // Every corner as (fragment, vertex) and in f64, fragment after
    // fragment; its exact point is made only when compared (an implicit
    // point is a few hundred bytes: too many to keep for every corner).
    let corners: Vec<(u32, u32)> = fragments
        .iter()
        .enumerate()
        .flat_map(|(i, f)| (0..f.len() as u32).map(move |k| (i as u32, k)))
        .collect();
    let exact = |c: usize| {
        let (i, k) = corners[c];
        MeshPoint::vertex(&fragments[i as usize], k as usize)
    };
    let corner_coords: Vec<[f64; 3]> = corners
        .par_iter()
        .map(|&(i, k)| fragments[i as usize].vertex_f64(k as usize))
        .collect();
    let corner_buckets = Buckets::new(cell, &corner_coords);
    // Each corner's first corner at the same point (exact), found in
    // parallel: the same point's corners lie within the margin of each
    // other, so the buckets around it hold them all.
    let first_same: Vec<u32> = (0..corners.len())
        .into_par_iter()
        .map_init(Vec::new, |found, i| {
            let c = corner_coords[i];
            corner_buckets.query_near(i, c, found);
            let mut near = found.iter().copied().filter(|&j| {
                let d = corner_coords[j as usize];
                (j as usize) < i && (0..3).all(|a| (d[a] - c[a]).abs() <= 2.0 * MARGIN)
            });
            let Some(first) = near.next() else {
                return i as u32;
            };
            let point = exact(i);
            std::iter::once(first)
                .chain(near)
                .filter(|&j| exact(j as usize).same_point(&point))
                .min()
                .unwrap_or(i as u32)
        })
        .collect();
    // Distinct points numbered in order of first appearance.
    let firsts: Vec<usize> = (0..corners.len())
        .filter(|&i| first_same[i] as usize == i)
        .collect();
    mesh.points = firsts.par_iter().map(|&i| exact(i)).collect();
    mesh.coords = firsts.iter().map(|&i| corner_coords[i]).collect();
    let mut corner_ids: Vec<u32> = Vec::with_capacity(corners.len());
    let mut next_id = 0;
    for (i, &first) in first_same.iter().enumerate() {
        if first as usize == i {
            corner_ids.push(next_id);
            next_id += 1;
        } else {
            corner_ids.push(corner_ids[first as usize]);
        }
    }
    let mut outlines: Vec<Vec<u32>> = Vec::with_capacity(fragments.len());
    let mut next = 0;
    for f in fragments {
        outlines.push(corner_ids[next..next + f.len()].to_vec());
        next += f.len();
    }
    let buckets = Buckets::new(cell, &mesh.coords);

    // Points inside each edge, in order along it: each fragment reads the
    // points and buckets only, so fragments go in parallel (faces keep
    // their order).
    let faces: Vec<(Vec<u32>, usize)> = fragments
        .par_iter()
        .zip(outlines)
        .map_init(Vec::new, |found, (f, outline)| {
            conforming_face(f, &outline, &mesh, &buckets, found)
        })
        .collect();
    for (face, inserted) in faces {
        mesh.inserted += inserted;
        mesh.faces.push(face);
    }
    mesh
}

/// The face of fragment `f` (corners `outline`) with the mesh's points that
/// lie strictly inside its edges inserted in order; and how many were.
fn conforming_face(
    f: &ConvexPolygon,
    outline: &[u32],
    mesh: &ConformingMesh,
    buckets: &Buckets,
    found: &mut Vec<u32>,
) -> (Vec<u32>, usize) {
    let n = f.len();
    let mut face = Vec::with_capacity(n);
    let mut inserted = 0;
    for k in 0..n {
        let (a, b) = (outline[k], outline[(k + 1) % n]);
        face.push(a);
        let (pa, pb) = (mesh.coords[a as usize], mesh.coords[b as usize]);
        let lo = [0, 1, 2].map(|i| pa[i].min(pb[i]) - MARGIN);
        let hi = [0, 1, 2].map(|i| pa[i].max(pb[i]) + MARGIN);
        buckets.query(lo, hi, found);
        let edge = f.edge(k);
        let (prev, next) = (f.edge((k + n - 1) % n), f.edge((k + 1) % n));
        let mut inside: Vec<u32> = found
            .iter()
            .copied()
            .filter(|&id| id != a && id != b)
            .filter(|&id| near_segment(mesh.coords[id as usize], pa, pb))
            .filter(|&id| {
                let p = &mesh.points[id as usize];
                p.side(f.support()) == Side::On
                    && p.side(edge) == Side::On
                    && p.side(prev) == Side::Back
                    && p.side(next) == Side::Back
            })
            .collect();
        if inside.len() > 1 {
            let direction = [0, 1, 2].map(|i| pb[i] - pa[i]);
            let (start, end) = (mesh.points[a as usize], mesh.points[b as usize]);
            inside.sort_by(|&p, &q| {
                let (pp, qq) = (&mesh.points[p as usize], &mesh.points[q as usize]);
                // q is after p when it lies on the far side of a plane
                // through p that the edge crosses.
                match pp.crossing_plane(&start, &end, direction) {
                    Some(h) if qq.side(&h) == start.side(&h) => std::cmp::Ordering::Greater,
                    Some(_) => std::cmp::Ordering::Less,
                    None => std::cmp::Ordering::Equal,
                }
            });
        }
        inserted += inside.len();
        face.extend(inside);
    }
    (face, inserted)
}

/// Whether `p` is within [`MARGIN`] of the segment `ab` (a candidate
/// filter only).
fn near_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> bool {
    let d = [0, 1, 2].map(|i| b[i] - a[i]);
    let w = [0, 1, 2].map(|i| p[i] - a[i]);
    let len2: f64 = d.iter().map(|x| x * x).sum();
    if len2 == 0.0 {
        return false;
    }
    let t = (0..3).map(|i| w[i] * d[i]).sum::<f64>() / len2;
    let closest = [0, 1, 2].map(|i| a[i] + t.clamp(0.0, 1.0) * d[i]);
    let dist2: f64 = (0..3).map(|i| (p[i] - closest[i]).powi(2)).sum();
    dist2 <= MARGIN * MARGIN * 4.0 + 1e-18 * len2
}

/// [`conform`], with every face kept to at most `max_corners` corners:
/// a fragment whose outline gathers more (a large cell beside many small
/// ones) is halved across its longer side ([`crate::halve`]) and the mesh
/// made again, until none does or none can be halved. Returns the
/// fragments as cut and their mesh (faces in fragment order).
pub fn conform_fragments(
    mut fragments: Vec<svbsp::Fragment>,
    max_corners: usize,
) -> (Vec<svbsp::Fragment>, ConformingMesh) {
    loop {
        let polygons: Vec<ConvexPolygon> = fragments.iter().map(|f| f.polygon.clone()).collect();
        let mesh = conform(&polygons);
        let mut halved = false;
        for (i, face) in mesh.faces.iter().enumerate() {
            if face.len() <= max_corners {
                continue;
            }
            if let Some((a, b)) = crate::halve(&fragments[i].polygon, 2.0) {
                let f = &fragments[i];
                let (lit_mask, umbra_mask) = (f.lit_mask, f.umbra_mask);
                fragments[i].polygon = a;
                fragments.push(svbsp::Fragment {
                    polygon: b,
                    lit_mask,
                    umbra_mask,
                });
                halved = true;
            }
        }
        if !halved {
            return (fragments, mesh);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_cells_order_as_the_cells_and_unpack() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        let mut cell = || -> [i64; 3] {
            let l = if rng.random_bool(0.5) { 1 << 26 } else { 3 };
            [0; 3].map(|_| rng.random_range(-l..=l))
        };
        for _ in 0..20_000 {
            let (a, b) = (cell(), cell());
            assert_eq!(unpack(pack(a)), a);
            assert_eq!(pack(a).cmp(&pack(b)), a.cmp(&b), "{a:?} {b:?}");
        }
    }

    #[test]
    fn floor_is_the_library_floor() {
        for x in [
            -2.5,
            -2.0,
            -1e-300,
            -0.0,
            0.0,
            1e-300,
            0.5,
            1.0,
            7.999,
            -7.999,
            1e12 + 0.5,
        ] {
            assert_eq!(floor(x), x.floor() as i64, "{x}");
        }
    }

    #[test]
    fn nearby_corners_come_from_their_cell_or_a_search() {
        // Points in one cell, and points straddling cell faces: both paths
        // give every index within the margin.
        let coords: Vec<[f64; 3]> = (0..200)
            .map(|i| {
                let t = f64::from(i);
                [t * 0.37 % 5.0, 10.0 - (t * 0.61) % 5.0, (t * 0.23) % 3.0]
            })
            .chain([
                [1.0, 1.0, 1.0],
                [1.0 + 1e-4, 1.0, 1.0],
                [2.0 - 1e-4, 1.5, 0.5],
            ])
            .collect();
        let buckets = Buckets::new(1.0, &coords);
        let mut found = Vec::new();
        for (i, &p) in coords.iter().enumerate() {
            buckets.query_near(i, p, &mut found);
            for (j, q) in coords.iter().enumerate() {
                if (0..3).all(|a| (q[a] - p[a]).abs() <= MARGIN) {
                    assert!(found.contains(&(j as u32)), "{j} near {i}");
                }
            }
        }
    }
}
