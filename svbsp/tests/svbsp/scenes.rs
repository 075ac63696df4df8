//! Random test scenes: triangles over a floor, boxes standing on it.

use bsp_core::{ConvexPolygon, GridPoint};
use proptest::prelude::*;

pub fn gp(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).unwrap()
}

/// A floor square at y = 0, facing up.
pub fn floor(half: i64) -> ConvexPolygon {
    ConvexPolygon::from_grid_points(
        &[
            gp(-half, 0, half),
            gp(half, 0, half),
            gp(half, 0, -half),
            gp(-half, 0, -half),
        ],
        0,
    )
    .unwrap()
}

/// The six outward faces of the box `[lo, hi]`.
pub fn box_faces(lo: [i64; 3], hi: [i64; 3]) -> Vec<ConvexPolygon> {
    let c = |x: bool, y: bool, z: bool| {
        gp(
            if x { hi[0] } else { lo[0] },
            if y { hi[1] } else { lo[1] },
            if z { hi[2] } else { lo[2] },
        )
    };
    let (f, t) = (false, true);
    let quads = [
        [c(f, f, f), c(f, t, f), c(t, t, f), c(t, f, f)],
        [c(f, f, t), c(t, f, t), c(t, t, t), c(f, t, t)],
        [c(f, f, f), c(t, f, f), c(t, f, t), c(f, f, t)],
        [c(f, t, f), c(f, t, t), c(t, t, t), c(t, t, f)],
        [c(f, f, f), c(f, f, t), c(f, t, t), c(f, t, f)],
        [c(t, f, f), c(t, t, f), c(t, t, t), c(t, f, t)],
    ];
    quads
        .iter()
        .map(|q| ConvexPolygon::from_grid_points(q, 0).unwrap())
        .collect()
}

/// Triangles floating between y = 20 and y = 200 over a floor.
pub fn triangles_over_floor() -> impl Strategy<Value = Vec<ConvexPolygon>> {
    prop::collection::vec(
        (
            prop::array::uniform3(-300_i64..300),
            prop::collection::vec(prop::array::uniform3(-80_i64..80), 3),
        ),
        1..14,
    )
    .prop_map(|tris| {
        let mut out = vec![floor(600)];
        for (c, corners) in tris {
            let pts: Vec<GridPoint> = corners
                .iter()
                .map(|d| gp(c[0] + d[0], 110 + c[1] / 4 + d[1], c[2] + d[2]))
                .collect();
            if let Ok(t) = ConvexPolygon::from_grid_points(&pts, 0) {
                out.push(t);
            }
        }
        out
    })
}

/// Boxes standing on the floor (coplanar contact) or floating, some
/// touching each other.
pub fn boxes_on_floor() -> impl Strategy<Value = Vec<ConvexPolygon>> {
    prop::collection::vec(
        (
            prop::array::uniform3(-200_i64..200),
            prop::array::uniform3(10_i64..90),
            prop::bool::ANY,
        ),
        1..6,
    )
    .prop_map(|boxes| {
        let mut out = vec![floor(600)];
        for (c, size, grounded) in boxes {
            let y0 = if grounded { 0 } else { 20 + c[1].abs() / 4 };
            let lo = [c[0], y0, c[2]];
            let hi = [c[0] + size[0], y0 + size[1], c[2] + size[2]];
            out.extend(box_faces(lo, hi));
        }
        out
    })
}
