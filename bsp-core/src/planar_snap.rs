//! Snapping a convex planar polygon given in world coordinates to the grid
//! without losing its planarity, onto a plane dense in grid points.
//!
//! Each corner snapped to its nearest grid point keeps a triangle, or a
//! polygon in an axis-aligned plane, planar; but the corners of a tilted
//! quad move off one plane by up to half a step each, and a polygon that
//! must stay one convex piece (an area light) would be refused. So the
//! plane is chosen first: a plane with a small integer normal near the
//! polygon's, through the grid point nearest its centroid, whose grid
//! points form a lattice ([`PlaneLattice`]); every corner goes to the
//! nearest point of that lattice. A larger normal tilts the plane less but
//! spaces its lattice wider (a cell's area is the normal's length), so
//! normals of every size from 1 to `2^20` (in steps of `2^(1/8)`) are
//! tried and the one that moves the corners least wins. For a polygon
//! spanning `L` grid steps the corners move by about `L^(1/3)` steps (the
//! best balance of tilt, `L / size`, and lattice spacing, `sqrt(size)`): a
//! few hundred of the grid's `2^25`. Measured over 20,000 random polygons:
//! `0.3 L^(1/3)` typically, `1.8 L^(1/3)` at most.
//!
//! A triangle's nearest grid points are always coplanar, but the plane
//! through them has a normal of up to the square of its span and holds
//! hardly a grid point inside it; work that cuts the polygon at grid
//! points (a joint-umbra proof halving a light) then cannot. Such a plane
//! is replaced the same way.

use crate::{ConvexPolygon, Error, Grid, GridPoint, Plane, PlaneLattice};

/// The largest normal component tried, as a power of two.
const LARGEST_NORMAL_BITS: i32 = 20;

impl ConvexPolygon {
    /// The convex planar polygon `points` (world coordinates, in order)
    /// snapped to `grid`, with the farthest any corner moved (world units).
    ///
    /// Corners go to their nearest grid points when those lie in one plane
    /// and still make a convex polygon; otherwise to the nearest grid
    /// points of a plane close to the polygon's (see the module docs), so
    /// the polygon keeps its orientation, its convexity and its corners
    /// (but one all but in line with its neighbours, which may fall in
    /// line and be dropped).
    ///
    /// Errors: a point off the grid, or a polygon that no snap keeps convex
    /// and planar (one that is not, or too small for the grid): the error
    /// of snapping each corner to its nearest grid point.
    pub fn snap_planar(
        grid: &Grid,
        points: &[[f64; 3]],
        source: u32,
    ) -> Result<(Self, f64), Error> {
        let nearest = points
            .iter()
            .map(|&p| grid.snap(p))
            .collect::<Result<Vec<_>, _>>()?;
        let plain = Self::from_grid_points(&nearest, source);
        let refused = match plain {
            Ok(polygon) if dense(&polygon) => {
                return Ok((polygon, farthest(grid, points, &nearest)));
            }
            Ok(polygon) => Ok((polygon, farthest(grid, points, &nearest))),
            Err(e) => Err(e),
        };
        let in_units: Vec<[f64; 3]> = points.iter().map(|&p| grid.world_to_grid(p)).collect();
        let Some(normal) = unit_normal(&in_units) else {
            return refused;
        };
        let centroid =
            [0, 1, 2].map(|k| in_units.iter().map(|q| q[k]).sum::<f64>() / in_units.len() as f64);
        let Ok(anchor) = GridPoint::new(
            centroid[0].round() as i64,
            centroid[1].round() as i64,
            centroid[2].round() as i64,
        ) else {
            return refused;
        };
        let mut best: Option<((usize, f64), Self)> = None;
        let mut tried: Option<[i64; 3]> = None;
        for eighth_bits in 0..=8 * LARGEST_NORMAL_BITS {
            let size = 2f64.powf(f64::from(eighth_bits) / 8.0);
            let integer = primitive(normal.map(|c| (c * size).round() as i64));
            if integer == [0; 3] || tried == Some(integer) {
                continue;
            }
            tried = Some(integer);
            let Some(corners) = on_plane(integer, anchor, &in_units) else {
                continue;
            };
            let Ok(polygon) = Self::from_grid_points(&corners, source) else {
                continue;
            };
            let n = polygon.support().normal();
            let facing: f64 = (0..3).map(|k| n[k] as f64 * normal[k]).sum();
            if facing <= 0.0 {
                continue;
            }
            // Fewest corners lost (a corner all but in line with its
            // neighbours may fall in line), then least moved.
            let key = (
                points.len() - polygon.len(),
                farthest(grid, points, &corners),
            );
            if best.as_ref().is_none_or(|(b, _)| key < *b) {
                best = Some((key, polygon));
            }
        }
        match best {
            Some(((_, moved), polygon)) => Ok((polygon, moved)),
            None => refused,
        }
    }
}

/// Whether a polygon's plane holds grid points densely enough for work
/// that must cut it at grid points (a joint-umbra proof halves a light in
/// its plane's lattice): lattice steps (about the square root of the
/// primitive normal's length) at most 1/1024 of the polygon's span. Any
/// three grid points are coplanar, but a tilted triangle's plane through
/// them has a normal of up to the square of its span, and its lattice has
/// hardly a point inside it.
fn dense(polygon: &ConvexPolygon) -> bool {
    let n = polygon.support().normal().map(|c| c as f64);
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let corners = polygon.vertices_f64();
    let span = corners
        .iter()
        .flat_map(|a| {
            corners
                .iter()
                .map(move |b| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>())
        })
        .fold(0.0, f64::max)
        .sqrt();
    length.sqrt() * 1024.0 <= span
}

/// The nearest grid points to `points` (grid units) in the plane with
/// normal `normal` through `anchor`.
fn on_plane(normal: [i64; 3], anchor: GridPoint, points: &[[f64; 3]]) -> Option<Vec<GridPoint>> {
    let plane = Plane::with_normal_through(normal, anchor)?;
    let lattice = PlaneLattice::of(&plane, anchor)?;
    points.iter().map(|&q| lattice.nearest(q)).collect()
}

/// Newell's normal of a polygon, unit length; `None` if it has no area.
fn unit_normal(points: &[[f64; 3]]) -> Option<[f64; 3]> {
    let mut area = [0.0; 3];
    for (i, p) in points.iter().enumerate() {
        let q = points[(i + 1) % points.len()];
        area[0] += (p[1] - q[1]) * (p[2] + q[2]);
        area[1] += (p[2] - q[2]) * (p[0] + q[0]);
        area[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    let length = area.iter().map(|c| c * c).sum::<f64>().sqrt();
    (length > 0.0 && length.is_finite()).then(|| area.map(|c| c / length))
}

/// `v` divided by the gcd of its components (zero stays zero).
fn primitive(v: [i64; 3]) -> [i64; 3] {
    let gcd = |mut a: u64, mut b: u64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let g = gcd(
        gcd(v[0].unsigned_abs(), v[1].unsigned_abs()),
        v[2].unsigned_abs(),
    );
    if g <= 1 { v } else { v.map(|c| c / g as i64) }
}

/// The farthest any of `points` (world) is from its grid point.
fn farthest(grid: &Grid, points: &[[f64; 3]], snapped: &[GridPoint]) -> f64 {
    points
        .iter()
        .zip(snapped)
        .map(|(p, &g)| {
            let w = grid.to_world(g);
            (0..3).map(|k| (w[k] - p[k]).powi(2)).sum::<f64>().sqrt()
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tilted_triangle_goes_to_a_plane_dense_in_grid_points() {
        let triangle = [
            [
                -1.1575838019248348,
                -0.1982945797119009,
                -1.4568135662675603,
            ],
            [
                -1.060454586721948,
                0.091_563_397_705_811_82,
                -1.6703250650443702,
            ],
            [-1.6040091416277682, 0.33254635617886347, -1.44133926742636],
        ];
        let grid = Grid::new([-4.0; 3], [4.0; 3]).unwrap();
        let nearest: Vec<GridPoint> = triangle.iter().map(|&p| grid.snap(p).unwrap()).collect();
        // Its corners' nearest grid points make a triangle, on a plane
        // with hardly a grid point inside it.
        assert!(!dense(
            &ConvexPolygon::from_grid_points(&nearest, 0).unwrap()
        ));
        let (light, moved) = ConvexPolygon::snap_planar(&grid, &triangle, 0).unwrap();
        assert!(dense(&light));
        assert_eq!(light.len(), 3);
        assert!(
            moved <= 200.0 / grid.scale(),
            "moved {} steps",
            moved * grid.scale()
        );
    }
    use crate::predicates::{Side, side_of_point};

    /// The tilted light of a user's scene: its corners' nearest grid
    /// points are not coplanar.
    const TILTED: [[f64; 3]; 4] = [
        [-1.3898948642456967, 3.5282534945275446, -0.6631425633241408],
        [
            -0.19145700534392707,
            3.4792339852393814,
            -0.6631425633241408,
        ],
        [-0.18358269696526763, 3.6717465054724556, 0.4013633257258893],
        [-1.3820205558670373, 3.7207660147606187, 0.4013633257258893],
    ];

    fn scene_grid() -> Grid {
        Grid::enclosing(
            [[-3.0, 0.0, -3.0], [3.0, 0.0, 3.0]].iter().chain(&TILTED),
            0.0,
        )
        .unwrap()
    }

    #[test]
    fn a_tilted_quad_stays_one_convex_piece_close_to_its_corners() {
        let grid = scene_grid();
        let nearest: Vec<GridPoint> = TILTED.iter().map(|&p| grid.snap(p).unwrap()).collect();
        assert_eq!(
            ConvexPolygon::from_grid_points(&nearest, 0).unwrap_err(),
            Error::NonPlanar,
            "the case this module exists for"
        );
        let (light, moved) = ConvexPolygon::snap_planar(&grid, &TILTED, 7).unwrap();
        assert_eq!(light.len(), 4);
        assert_eq!(light.source(), 7);
        // Each corner is a grid point of the light's plane, within a few
        // hundred steps of where it was (the light spans ~2^22 steps; it moves
        // 51).
        let step = 1.0 / grid.scale();
        assert!(moved <= 200.0 * step, "moved {} steps", moved / step);
        for (i, p) in TILTED.iter().enumerate() {
            let corner = light.vertex_grid_point(i).expect("a grid corner");
            let w = grid.to_world(corner);
            let d = (0..3).map(|k| (w[k] - p[k]).powi(2)).sum::<f64>().sqrt();
            assert!(d <= moved);
            assert_eq!(side_of_point(light.support(), corner), Side::On);
        }
        // The plane turned by a hair at most: it faces as the corners'
        // order says.
        let tilted = unit_normal(&TILTED).unwrap();
        let snapped = light.support().unit_normal_f64();
        let cos = (0..3).map(|k| tilted[k] * snapped[k]).sum::<f64>();
        assert!(cos > 1.0 - 1e-8, "cos {cos}");
    }
}
