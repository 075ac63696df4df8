//! The triangles of the case's shapes (boxes, dented boxes, frames), and
//! triangles as polygons on the grid.

use bsp_core::{ConvexPolygon, GridPoint};

use super::gp;

/// The box `lo..hi` with its top (`y = hi[1]`) replaced by the four
/// triangles from its edges down to `apex` (inside the box):
/// counter-clockwise seen from outside.
pub(super) fn dented_box_triangles(
    lo: [i64; 3],
    hi: [i64; 3],
    apex: [i64; 3],
) -> Vec<[[i64; 3]; 3]> {
    let top = [lo[0], hi[1], lo[2]];
    let mut out: Vec<[[i64; 3]; 3]> = box_triangles(lo, hi)
        .into_iter()
        .filter(|t| t.iter().any(|p| p[1] != hi[1]))
        .collect();
    // The top's corners counter-clockwise seen from above.
    let corners = [
        top,
        [lo[0], hi[1], hi[2]],
        [hi[0], hi[1], hi[2]],
        [hi[0], hi[1], lo[2]],
    ];
    for i in 0..4 {
        out.push([corners[i], corners[(i + 1) % 4], apex]);
    }
    out
}

/// The box `lo..hi` with a square hole from `y = lo[1]` to `hi[1]`, over
/// `x, z` in `hole_lo..hole_hi` (strictly inside the box's): 32
/// triangles, counter-clockwise seen from outside.
pub(super) fn frame_triangles(
    lo: [i64; 3],
    hi: [i64; 3],
    hole_lo: [i64; 2],
    hole_hi: [i64; 2],
) -> Vec<[[i64; 3]; 3]> {
    // The outer and the inner square's corners (x, z), in one turn.
    let outer = [
        [lo[0], lo[2]],
        [hi[0], lo[2]],
        [hi[0], hi[2]],
        [lo[0], hi[2]],
    ];
    let inner = [
        [hole_lo[0], hole_lo[1]],
        [hole_hi[0], hole_lo[1]],
        [hole_hi[0], hole_hi[1]],
        [hole_lo[0], hole_hi[1]],
    ];
    let at = |c: [i64; 2], y: i64| [c[0], y, c[1]];
    let middle = [
        (hole_lo[0] + hole_hi[0]) as f64 / 2.0,
        (hole_lo[1] + hole_hi[1]) as f64 / 2.0,
    ];
    let mut out = Vec::with_capacity(32);
    // A planar quad as two triangles, turned to face `out` (x, y, z).
    let mut quad = |q: [[i64; 3]; 4], outward: [f64; 3]| {
        let (a, b, c) = (q[0], q[1], q[2]);
        let e = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let f = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            e[1] * f[2] - e[2] * f[1],
            e[2] * f[0] - e[0] * f[2],
            e[0] * f[1] - e[1] * f[0],
        ];
        let facing: f64 = (0..3).map(|k| n[k] as f64 * outward[k]).sum();
        let [a, b, c, d] = if facing > 0.0 {
            q
        } else {
            [q[3], q[2], q[1], q[0]]
        };
        out.push([a, b, c]);
        out.push([a, c, d]);
    };
    for i in 0..4 {
        let j = (i + 1) % 4;
        for (y, up) in [(hi[1], 1.0), (lo[1], -1.0)] {
            quad(
                [
                    at(outer[i], y),
                    at(outer[j], y),
                    at(inner[j], y),
                    at(inner[i], y),
                ],
                [0.0, up, 0.0],
            );
        }
        // Walls: the outer ones face away from the hole, the inner ones
        // into it.
        for (square, sign) in [(&outer, 1.0), (&inner, -1.0)] {
            let mid = [
                (square[i][0] + square[j][0]) as f64 / 2.0 - middle[0],
                (square[i][1] + square[j][1]) as f64 / 2.0 - middle[1],
            ];
            quad(
                [
                    at(square[i], lo[1]),
                    at(square[j], lo[1]),
                    at(square[j], hi[1]),
                    at(square[i], hi[1]),
                ],
                [sign * mid[0], 0.0, sign * mid[1]],
            );
        }
    }
    out
}

/// The twelve triangles of the box `lo..hi`, counter-clockwise seen from
/// outside.
pub(super) fn box_triangles(lo: [i64; 3], hi: [i64; 3]) -> Vec<[[i64; 3]; 3]> {
    let c = |i: usize| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    let quads = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    quads
        .iter()
        .flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]])
        .collect()
}

pub(super) fn triangles(ts: &[[[i64; 3]; 3]], offset: [i64; 3]) -> Vec<ConvexPolygon> {
    ts.iter()
        .filter_map(|t| {
            let pts: Option<Vec<GridPoint>> = t
                .iter()
                .map(|p| gp([p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]]))
                .collect();
            ConvexPolygon::from_grid_points(&pts?, 0).ok()
        })
        .collect()
}
