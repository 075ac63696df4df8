//! A welded face cut into convex pieces with no sliver.
//!
//! A corner welded onto an edge lies on it only up to half a grid step. In
//! a planar face that is harmless: the pieces keep the face's plane. In a
//! non-planar one each triangle takes its own plane, and a triangle of
//! three points nearly on one edge (its two ends and a welded corner, or
//! two welded corners and an end) is a sliver whose plane is tilted
//! anywhere, even facing back. So a non-planar welded face is cut as it
//! would be unwelded (ear clipping its own corners), and each of those
//! triangles is then fanned out to the welded corners on its edges, every
//! fan from a point off the line it fans over.

use bsp_core::{ConvexPolygon, GridPoint};

use crate::decompose::{convex_pieces, corner_triangles};

/// The convex pieces of a face with snapped `corners`, where `inserted[i]`
/// are the corners welded into its edge from corner `i` to corner `i + 1`,
/// in order along it.
pub fn welded_pieces(corners: &[GridPoint], inserted: &[Vec<GridPoint>]) -> Vec<ConvexPolygon> {
    if inserted.iter().all(Vec::is_empty) || inserted.len() != corners.len() {
        return convex_pieces(corners);
    }
    let ring = ring(corners, inserted);
    match ConvexPolygon::from_grid_points(&ring, 0) {
        Ok(piece) => return vec![piece],
        // Planarity is checked before convexity: the face is planar.
        Err(bsp_core::Error::NonConvex) => return convex_pieces(&ring),
        Err(_) => {}
    }
    let Some(triangles) = corner_triangles(corners) else {
        return convex_pieces(&ring);
    };
    let n = corners.len();
    let side = |i: usize, j: usize| -> Vec<GridPoint> {
        if j == (i + 1) % n {
            inserted[i].clone()
        } else {
            Vec::new()
        }
    };
    let mut out = Vec::new();
    for [a, b, c] in triangles {
        fan_out(
            [corners[a], corners[b], corners[c]],
            [side(a, b), side(b, c), side(c, a)],
            &mut out,
        );
    }
    out.into_iter()
        .filter_map(|t| ConvexPolygon::from_grid_points(&t, 0).ok())
        .collect()
}

/// The face's corners with the welded ones in between, in order.
fn ring(corners: &[GridPoint], inserted: &[Vec<GridPoint>]) -> Vec<GridPoint> {
    corners
        .iter()
        .zip(inserted)
        .flat_map(|(c, on)| std::iter::once(*c).chain(on.iter().copied()))
        .collect()
}

/// Cuts the triangle `t` (counter-clockwise), with `sides[k]` the points on
/// its side from `t[k]` to `t[k + 1]` in order, into triangles none of
/// which has all three corners on one side: from a corner with no point
/// on either of its sides, a fan over the opposite side; else the last
/// point `w` of a side `p -> q` cuts off the triangle `w, q, r` (a fan
/// from `w` over `q -> r`: `w` is off that line) and the rest, `p, w, r`,
/// holds one point fewer.
fn fan_out(t: [GridPoint; 3], sides: [Vec<GridPoint>; 3], out: &mut Vec<[GridPoint; 3]>) {
    let fan =
        |apex: GridPoint, from: GridPoint, on: &[GridPoint], to: GridPoint, out: &mut Vec<_>| {
            let chain: Vec<GridPoint> = std::iter::once(from)
                .chain(on.iter().copied())
                .chain(std::iter::once(to))
                .collect();
            out.extend(chain.windows(2).map(|w| [apex, w[0], w[1]]));
        };
    if let Some(k) = (0..3).find(|&k| sides[k].is_empty() && sides[(k + 2) % 3].is_empty()) {
        let (q, r) = ((k + 1) % 3, (k + 2) % 3);
        fan(t[k], t[q], &sides[q], t[r], out);
        return;
    }
    // Every corner has a point on a side of its own: some side has one.
    let Some(k) = (0..3).find(|&k| !sides[k].is_empty()) else {
        return;
    };
    let (q, r) = ((k + 1) % 3, (k + 2) % 3);
    let mut before = sides[k].clone();
    let Some(w) = before.pop() else {
        return;
    };
    fan(w, t[q], &sides[q], t[r], out);
    fan_out([t[k], w, t[r]], [before, Vec::new(), sides[r].clone()], out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn gp(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint::new(x, y, z).unwrap()
    }

    /// Twice the signed area of a triangle in the plane z = 0.
    fn twice_area(t: &[GridPoint; 3]) -> i64 {
        let [a, b, c] = t.map(|p| p.to_i64());
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    }

    /// Points on every side: every triangle turns left (no three corners
    /// on one side: all points lie on the sides, so such a triangle would
    /// have no area), and together they cover the triangle once.
    #[test]
    fn a_triangle_with_points_on_every_side_fans_out_with_no_sliver() {
        let t = [gp(0, 0, 0), gp(60, 0, 0), gp(0, 60, 0)];
        let sides = [
            vec![gp(20, 0, 0), gp(40, 0, 0)],
            vec![gp(30, 30, 0)],
            vec![gp(0, 45, 0), gp(0, 15, 0)],
        ];
        let mut out = Vec::new();
        fan_out(t, sides, &mut out);
        // Eight points on the boundary, none inside: six triangles.
        assert_eq!(out.len(), 6);
        assert!(out.iter().all(|t| twice_area(t) > 0), "{out:?}");
        assert_eq!(out.iter().map(twice_area).sum::<i64>(), 3600);
    }

    /// A triangle with a corner welded onto its long edge, a grid unit out
    /// of the edge and of the plane: every piece keeps about the face's
    /// plane. (Ear clipping the four points would cut the right angle
    /// first and leave the sliver of the edge's ends and the welded
    /// corner, tilted by 35 degrees.)
    #[test]
    fn a_bent_welded_face_has_no_sliver() {
        let corners = [gp(0, 0, 0), gp(1000, 0, 0), gp(0, 1000, 5)];
        let inserted = [vec![], vec![gp(500, 501, 3)], vec![]];
        let pieces = welded_pieces(&corners, &inserted);
        // Seen from above (z), the pieces cover the ring once.
        assert_eq!(
            twice_xy_covered(&pieces),
            twice_xy_area(&ring(&corners, &inserted))
        );
        for piece in &pieces {
            let n = piece.support().normal().map(|c| c as f64);
            let cos = n[2] / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!(cos > 0.999, "{n:?}");
        }
        // Each corner of the ring is a corner of some piece.
        for p in corners.iter().chain(inserted.iter().flatten()) {
            assert!(
                pieces
                    .iter()
                    .any(|piece| (0..piece.len()).any(|i| piece.vertex_grid_point(i) == Some(*p)))
            );
        }
    }

    /// Whether `p` lies on the segment from `a` to `b`, exactly.
    fn on_segment(a: GridPoint, b: GridPoint, p: GridPoint) -> bool {
        let (a, b, p) = (a.to_i64(), b.to_i64(), p.to_i64());
        let (d, e) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [p[0] - a[0], p[1] - a[1], p[2] - a[2]],
        );
        let cross = [
            d[1] * e[2] - d[2] * e[1],
            d[2] * e[0] - d[0] * e[2],
            d[0] * e[1] - d[1] * e[0],
        ];
        let along = d[0] * e[0] + d[1] * e[1] + d[2] * e[2];
        cross == [0, 0, 0] && along >= 0 && along <= d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    }

    /// Twice the area of the ring `points` seen from above (z).
    fn twice_xy_area(points: &[GridPoint]) -> i64 {
        (0..points.len())
            .map(|i| {
                let (a, b) = (points[i].to_i64(), points[(i + 1) % points.len()].to_i64());
                a[0] * b[1] - a[1] * b[0]
            })
            .sum()
    }

    /// Twice the area the pieces cover seen from above, counted with sign.
    fn twice_xy_covered(pieces: &[ConvexPolygon]) -> i64 {
        pieces
            .iter()
            .map(|piece| {
                let corners: Vec<GridPoint> = (0..piece.len())
                    .map(|i| piece.vertex_grid_point(i).unwrap())
                    .collect();
                twice_xy_area(&corners)
            })
            .sum()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// A random convex face, near the plane z = x / 8 - y / 16, with
        /// corners welded onto its edges a grid unit or so off them (at
        /// least a tenth of the edge from its ends and from each other):
        /// seen from above the pieces cover the ring once, every piece
        /// keeps close to the face's plane (none facing back), and every
        /// point of the ring is a corner of a piece.
        #[test]
        fn welded_pieces_cover_the_ring_and_keep_its_plane(
            quad in any::<bool>(),
            bumps in prop::collection::vec(-1i64..=1, 4),
            spots in prop::collection::vec(prop::collection::vec((1u8..9, -1i64..=1, -1i64..=1, -1i64..=1), 0..3), 4),
        ) {
            let plane = |x: i64, y: i64, bump: i64| gp(x, y, x / 8 - y / 16 + bump);
            let mut corners = vec![plane(0, 0, bumps[0]), plane(4000, 300, bumps[1]), plane(3700, 3900, bumps[2])];
            if quad {
                corners.push(plane(-200, 3500, bumps[3]));
            }
            let n = corners.len();
            let inserted: Vec<Vec<GridPoint>> = (0..n)
                .map(|i| {
                    let (a, b) = (corners[i].to_i64(), corners[(i + 1) % n].to_i64());
                    let mut tenths: Vec<_> = spots[i].clone();
                    tenths.sort_by_key(|s| s.0);
                    tenths.dedup_by_key(|s| s.0);
                    tenths
                        .iter()
                        .map(|&(t, dx, dy, dz)| {
                            let at = |k: usize| a[k] + (b[k] - a[k]) * i64::from(t) / 10;
                            gp(at(0) + dx, at(1) + dy, at(2) + dz)
                        })
                        .collect()
                })
                .collect();
            let pieces = welded_pieces(&corners, &inserted);
            let ring = ring(&corners, &inserted);
            prop_assert_eq!(twice_xy_covered(&pieces), twice_xy_area(&ring));
            for piece in &pieces {
                let m = piece.support().normal().map(|c| c as f64);
                // The face's normal is about (-1/8, 1/16, 1).
                let face = [-0.125, 0.0625, 1.0];
                let cos = (m[0] * face[0] + m[1] * face[1] + m[2] * face[2])
                    / ((m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt()
                        * (face[0] * face[0] + face[1] * face[1] + face[2] * face[2]).sqrt());
                prop_assert!(cos > 0.99, "{:?}", m);
            }
            // (A point exactly on an edge needs no corner there: it leaves
            // no crack, and a convex piece drops it.)
            for p in &ring {
                let held = pieces.iter().any(|piece| {
                    let n = piece.len();
                    (0..n).any(|i| {
                        let a = piece.vertex_grid_point(i).unwrap();
                        let b = piece.vertex_grid_point((i + 1) % n).unwrap();
                        a == *p || on_segment(a, b, *p)
                    })
                });
                prop_assert!(held, "{:?} is on no piece's border", p);
            }
        }
    }
}
