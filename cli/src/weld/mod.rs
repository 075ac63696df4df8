//! T-junctions of an object welded before its faces are cut into pieces.
//!
//! A face whose edge runs through another face's corner (a face split in
//! strips against an unsplit neighbour) is watertight in the input: the
//! corner lies on the edge, up to floating point. Snapped to the grid
//! apart, the corner and the edge part by up to half a grid step, and the
//! crack between them lets light through (a thin lit line across a
//! shadow). So a corner that lies on an edge of another face of its
//! object, within [`ON_EDGE`] of a grid step, becomes a corner of that
//! face too, at the same grid point: the face is then cut into pieces
//! that meet the neighbours' exactly. Only an object's own faces are
//! welded, so that a moved object's faces, and the others', stay as they
//! are.

use std::collections::HashMap;

use bsp_core::GridPoint;

use crate::vec3::{dot, sub};

mod cut;
pub use cut::welded_pieces;

/// A corner welded into an edge of another face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weld {
    /// The corner, snapped.
    pub point: GridPoint,
    /// Where its input corner lies along the input edge, as a fraction from
    /// the edge's start.
    pub along: f64,
}

/// How near an edge a corner counts as on it, in grid steps: far below a
/// step (so no gap the grid can hold is closed), far above the rounding of
/// world coordinates.
pub const ON_EDGE: f64 = 1e-3;

/// For each face (`snapped[i]`, of the input corners `input[i]`, world
/// units), the other faces' corners to weld into each of its edges: those
/// that lie on the edge from its corner `j` to corner `j + 1` strictly
/// between its ends, within `tolerance` (world units), in order along the
/// edge, at `[i][j]` ([`welded_pieces`] cuts the face with their points).
pub fn weld_t_junctions(
    input: &[&[[f64; 3]]],
    snapped: &[Vec<GridPoint>],
    tolerance: f64,
) -> Vec<Vec<Vec<Weld>>> {
    let corners = Corners::new(input, snapped);
    input
        .iter()
        .zip(snapped)
        .map(|(raw, own)| {
            let n = raw.len();
            if corners.points.is_empty() || n < 3 || own.len() != n {
                return vec![Vec::new(); own.len()];
            }
            (0..n)
                .map(|i| {
                    let (a, c) = (raw[i], raw[(i + 1) % n]);
                    let mut on: Vec<(f64, GridPoint)> = corners
                        .near_segment(a, c, tolerance)
                        .filter(|&k| !own.contains(&corners.points[k].1))
                        .filter(|&k| corners.edge_along(k, a, c, tolerance))
                        .filter_map(|k| {
                            let (p, g) = corners.points[k];
                            along(a, c, p, tolerance).map(|t| (t, g))
                        })
                        .collect();
                    on.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
                    on.dedup_by_key(|x| x.1);
                    on.into_iter()
                        .map(|(along, point)| Weld { point, along })
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// Where `p` lies along the segment from `a` to `c`, as a fraction
/// strictly between its ends (more than `tolerance` from either), when it
/// lies within `tolerance` of the segment.
fn along(a: [f64; 3], c: [f64; 3], p: [f64; 3], tolerance: f64) -> Option<f64> {
    let d = sub(c, a);
    let length2 = dot(d, d);
    if length2 == 0.0 {
        return None;
    }
    let t = dot(sub(p, a), d) / length2;
    let length = length2.sqrt();
    if t * length <= tolerance || (1.0 - t) * length <= tolerance {
        return None;
    }
    let foot = [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]];
    let off = sub(p, foot);
    (dot(off, off) <= tolerance * tolerance).then_some(t)
}

/// Whether `p` lies within `tolerance` of the line through `a` and `c`.
fn on_line(a: [f64; 3], c: [f64; 3], p: [f64; 3], tolerance: f64) -> bool {
    let d = sub(c, a);
    let length2 = dot(d, d);
    if length2 == 0.0 {
        return false;
    }
    let v = sub(p, a);
    let t = dot(v, d) / length2;
    let off = [v[0] - t * d[0], v[1] - t * d[1], v[2] - t * d[2]];
    dot(off, off) <= tolerance * tolerance
}

/// An object's corners (input and snapped), bucketed in space.
struct Corners {
    points: Vec<([f64; 3], GridPoint)>,
    /// Per corner, the input corners next to it along the faces it is a
    /// corner of.
    neighbours: Vec<Vec<[f64; 3]>>,
    /// Bucket side, world units.
    side: f64,
    buckets: HashMap<[i64; 3], Vec<usize>>,
}

/// Buckets an edge's box may span before its corners are all looked at
/// instead.
const MAX_BUCKETS: i64 = 512;

impl Corners {
    fn new(input: &[&[[f64; 3]]], snapped: &[Vec<GridPoint>]) -> Self {
        // Each corner of each face: snapped, then input, with the input
        // corners before and after it.
        let mut all: Vec<(GridPoint, [[f64; 3]; 3])> = input
            .iter()
            .zip(snapped)
            .filter(|(raw, grid)| raw.len() == grid.len())
            .flat_map(|(raw, grid)| {
                let n = raw.len();
                (0..n).map(move |i| (grid[i], [raw[i], raw[(i + n - 1) % n], raw[(i + 1) % n]]))
            })
            .collect();
        all.sort_by_key(|x| x.0);
        let mut points: Vec<([f64; 3], GridPoint)> = Vec::new();
        let mut neighbours: Vec<Vec<[f64; 3]>> = Vec::new();
        for (g, [p, before, after]) in all {
            if points.last().is_none_or(|last| last.1 != g) {
                points.push((p, g));
                neighbours.push(Vec::new());
            }
            if let Some(next_to) = neighbours.last_mut() {
                next_to.extend([before, after]);
            }
        }
        // Buckets about as long as an average edge.
        let (mut total, mut edges) = (0.0, 0_usize);
        for raw in input {
            for i in 0..raw.len() {
                let d = sub(raw[(i + 1) % raw.len()], raw[i]);
                total += dot(d, d).sqrt();
                edges += 1;
            }
        }
        let side = if edges == 0 || total == 0.0 {
            1.0
        } else {
            total / edges as f64
        };
        let mut buckets: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (k, (p, _)) in points.iter().enumerate() {
            buckets.entry(bucket(*p, side)).or_default().push(k);
        }
        Self {
            points,
            neighbours,
            side,
            buckets,
        }
    }

    /// Whether corner `k` has an edge of its own along the line through
    /// `a` and `c` (one of its neighbours on that line, within
    /// `tolerance`): its face meets the edge from `a` to `c` along it, a
    /// T-junction. A face that only touches that edge at the corner (a
    /// wall standing on a floor, its corner on the floor's border) is no
    /// crack when snapped, and welding it would only bend the edge's face.
    fn edge_along(&self, k: usize, a: [f64; 3], c: [f64; 3], tolerance: f64) -> bool {
        self.neighbours[k]
            .iter()
            .any(|&n| on_line(a, c, n, tolerance))
    }

    /// The corners within `margin` of the box of the segment from `a` to
    /// `c` (and maybe others).
    fn near_segment(
        &self,
        a: [f64; 3],
        c: [f64; 3],
        margin: f64,
    ) -> impl Iterator<Item = usize> + '_ {
        let lo = bucket(std::array::from_fn(|k| a[k].min(c[k]) - margin), self.side);
        let hi = bucket(std::array::from_fn(|k| a[k].max(c[k]) + margin), self.side);
        // (Counted without overflow: a far corner puts a bucket number
        // near `i64::MAX`, and a wrapped count would have the loops below
        // walk that many buckets.)
        let span = (0..3).try_fold(1_i64, |count, k| {
            hi[k].checked_sub(lo[k])?.checked_add(1)?.checked_mul(count)
        });
        let all = span.is_none_or(|span| span > MAX_BUCKETS);
        let mut found: Vec<usize> = if all {
            (0..self.points.len()).collect()
        } else {
            let mut found = Vec::new();
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        if let Some(ks) = self.buckets.get(&[x, y, z]) {
                            found.extend(ks);
                        }
                    }
                }
            }
            found
        };
        found.sort_unstable();
        found.into_iter()
    }
}

fn bucket(p: [f64; 3], side: f64) -> [i64; 3] {
    p.map(|c| (c / side).floor() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gp(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint::new(x, y, z).unwrap()
    }

    /// A square split in two strips against its unsplit neighbour: the
    /// strips' corner on the shared edge becomes the neighbour's corner.
    /// A triangle that only touches the neighbour's other edge at a corner
    /// is no T-junction and stays out of it.
    #[test]
    fn a_corner_on_an_edge_is_welded_into_it() {
        let big: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 0.0, 2.0],
            [0.0, 0.0, 2.0],
        ];
        // The strips' corner (0, 0, 1) lies on the big square's edge from
        // (0, 0, 2) to (0, 0, 0), up to rounding, and their edges run
        // along it.
        let low: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0 + 1e-15],
            [-2.0, 0.0, 1.0],
            [-2.0, 0.0, 0.0],
        ];
        let high: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 1.0 + 1e-15],
            [0.0, 0.0, 2.0],
            [-2.0, 0.0, 2.0],
            [-2.0, 0.0, 1.0],
        ];
        let touching: Vec<[f64; 3]> = vec![[2.0, 0.0, 1.5], [3.0, 0.0, 1.5], [3.0, 0.0, 1.25]];
        let input: Vec<&[[f64; 3]]> = vec![&big, &low, &high, &touching];
        let snap = |ps: &[[f64; 3]]| -> Vec<GridPoint> {
            ps.iter()
                .map(|p| {
                    gp(
                        (p[0] * 4.0).round() as i64,
                        (p[1] * 4.0).round() as i64,
                        (p[2] * 4.0).round() as i64,
                    )
                })
                .collect()
        };
        let snapped: Vec<Vec<GridPoint>> = input.iter().map(|p| snap(p)).collect();
        let welds = weld_t_junctions(&input, &snapped, 1e-3 * 0.25);
        // Into the big square's edge from (0, 0, 8) to (0, 0, 0) (its
        // fourth), the strips' corner, halfway; nothing else anywhere.
        let points: Vec<Vec<GridPoint>> = welds[0]
            .iter()
            .map(|edge| edge.iter().map(|w| w.point).collect())
            .collect();
        assert_eq!(points, [vec![], vec![], vec![], vec![gp(0, 0, 4)]]);
        assert!((welds[0][3][0].along - 0.5).abs() < 1e-12);
        assert!(welds[1..].iter().flatten().all(Vec::is_empty));
    }

    /// A corner a grid step off the edge (a real gap) is left alone, and
    /// so is one beyond the edge's ends.
    #[test]
    fn corners_off_the_edge_are_not_welded() {
        let edge: Vec<[f64; 3]> = vec![[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]];
        let off: Vec<[f64; 3]> = vec![[2.0, -0.25, 0.0], [5.0, 0.0, 0.0], [3.0, -1.0, 0.0]];
        let input: Vec<&[[f64; 3]]> = vec![&edge, &off];
        let snapped: Vec<Vec<GridPoint>> = vec![
            vec![gp(0, 0, 0), gp(16, 0, 0), gp(0, 16, 0)],
            vec![gp(8, -1, 0), gp(20, 0, 0), gp(12, -4, 0)],
        ];
        let welds = weld_t_junctions(&input, &snapped, 1e-3 * 0.25);
        assert!(welds.iter().flatten().all(Vec::is_empty));
    }

    /// A tolerance huge beside the object's edges (the grid set by a far
    /// corner of another object: 1e17 world units across), and a corner
    /// far out: an edge's box spans more buckets than an `i64` counts, and
    /// every corner is looked at instead (the count once wrapped, and the
    /// search walked the buckets for ever).
    #[test]
    fn far_corners_and_coarse_grids_look_at_every_corner() {
        let small: Vec<[f64; 3]> = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]];
        let far: Vec<[f64; 3]> = vec![[-1e17, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]];
        for (input, tolerance) in [(vec![&small[..]], 5e6), (vec![&far[..], &small[..]], 1e-3)] {
            let snapped: Vec<Vec<GridPoint>> = input
                .iter()
                .map(|ps| {
                    ps.iter()
                        .map(|p| gp(p[0].max(-1e6) as i64, 0, p[2] as i64))
                        .collect()
                })
                .collect();
            let welds = weld_t_junctions(&input, &snapped, tolerance);
            // (The small triangle's corner at the origin is 1 unit from
            // the far edge's end, 1e-17 of its length: at its end in
            // `f64`.)
            assert_eq!(welds.len(), input.len());
            assert!(welds.iter().flatten().all(Vec::is_empty), "{welds:?}");
        }
    }
}
