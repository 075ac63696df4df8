//! `ConvexPolygon::snap_planar` against the polygon it was given: every
//! tilted convex polygon comes back convex, planar, with all its corners,
//! facing the same way, and close to where it was.

use bsp_core::{ConvexPolygon, Grid};
use proptest::prelude::*;

/// A strictly convex polygon in a random tilted plane: corners on an
/// ellipse at increasing angles (`gaps`, each at least a tenth of the even
/// share), in world units.
fn tilted_polygon() -> impl Strategy<Value = Vec<[f64; 3]>> {
    (
        prop::array::uniform3(-1.0..1.0_f64),
        prop::array::uniform3(-5.0..5.0_f64),
        0.05..3.0_f64,
        0.2..1.0_f64,
        0.0..std::f64::consts::TAU,
        prop::collection::vec(0.1..1.0_f64, 3..9),
    )
        .prop_filter_map("a normal", |(n, centre, radius, aspect, turn, gaps)| {
            let length = n.iter().map(|c| c * c).sum::<f64>().sqrt();
            if length < 0.1 {
                return None;
            }
            let n = n.map(|c| c / length);
            // Two unit vectors across n.
            let helper = if n[0].abs() < 0.9 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            let a = unit(cross(n, helper));
            let b = cross(n, a);
            let total: f64 = gaps.iter().sum();
            let mut angle = turn;
            let corners = gaps
                .iter()
                .map(|g| {
                    angle += g / total * std::f64::consts::TAU;
                    let (s, c) = angle.sin_cos();
                    [0, 1, 2].map(|k| centre[k] + radius * (c * a[k] + aspect * s * b[k]))
                })
                .collect();
            Some(corners)
        })
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = v.iter().map(|c| c * c).sum::<f64>().sqrt();
    v.map(|c| c / l)
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn tilted_convex_polygons_snap_whole(corners in tilted_polygon()) {
        // The scene box [-10, 10]^3, as a scene around the polygon would
        // give.
        let grid = Grid::new([-10.0; 3], [10.0; 3]).unwrap();
        let (polygon, moved) = ConvexPolygon::snap_planar(&grid, &corners, 3).unwrap();
        prop_assert_eq!(polygon.len(), corners.len());
        prop_assert_eq!(polygon.source(), 3);
        let step = 1.0 / grid.scale();
        let span = corners
            .iter()
            .flat_map(|p| corners.iter().map(move |q| distance(*p, *q)))
            .fold(0.0, f64::max)
            / step;
        // About span^(1/3) steps (module docs); at most 1.8 times that in
        // 20,000 random polygons.
        prop_assert!(
            moved <= (3.0 * span.cbrt() + 2.0) * step,
            "moved {} steps across a span of {span} steps", moved / step
        );
        let mut farthest = 0.0_f64;
        for (i, &p) in corners.iter().enumerate() {
            let g = polygon.vertex_grid_point(i).expect("a grid corner");
            farthest = farthest.max(distance(grid.to_world(g), p));
        }
        prop_assert_eq!(farthest, moved);
        // Newell's normal of the input and the snapped plane's agree.
        let mut area = [0.0; 3];
        for (i, p) in corners.iter().enumerate() {
            let c = cross(*p, corners[(i + 1) % corners.len()]);
            for k in 0..3 {
                area[k] += c[k];
            }
        }
        let (a, s) = (unit(area), polygon.support().unit_normal_f64());
        prop_assert!((0..3).map(|k| a[k] * s[k]).sum::<f64>() > 0.999);
    }
}
