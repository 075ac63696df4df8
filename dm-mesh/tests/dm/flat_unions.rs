//! A flat occluder that is no convex polygon (an L, a T, a U, a Z or a
//! ring of rectangles sharing whole edges), one object or each rectangle
//! its own, some maybe turned over: the umbra its pieces make together, as umbra-only bodies (or
//! joint bodies), against an exact oracle at floor
//! points; vertex irradiance against the visible part of the light; a move
//! against a fresh build.

use crate::common::{TestScene, class_areas, floor, floor_cells, gp, light};
use crate::illumination::check_vertices;
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint};
use dm_mesh::CellClass;
use proptest::prelude::*;
use svbsp::PieceFlags;

/// Cells `(column, row)` of a 3 x 3 layout: an L, a T, a U, a Z and a
/// ring (a frame round a hole).
const SHAPES: [&[(usize, usize)]; 5] = [
    &[(0, 0), (1, 0), (0, 1)],
    &[(0, 0), (1, 0), (2, 0), (1, 1)],
    &[(0, 0), (1, 0), (2, 0), (0, 1), (2, 1)],
    &[(0, 0), (1, 0), (1, 1), (2, 1)],
    &[
        (0, 0),
        (1, 0),
        (2, 0),
        (0, 1),
        (2, 1),
        (0, 2),
        (1, 2),
        (2, 2),
    ],
];

/// Cell `(i, j)` of the layout with column bounds `xs` and row bounds
/// `zs`: `[x0, x1, z0, z1]`.
fn cell(xs: &[i64; 4], zs: &[i64; 4], (i, j): (usize, usize)) -> [i64; 4] {
    [xs[i], xs[i + 1], zs[j], zs[j + 1]]
}

/// Whether the light `[x0, x1] x [z0, z1]` at height `y`, seen from floor
/// point `p` through the plane at height `h`, lies wholly in `rects` (not
/// overlapping): exactly, in coordinates scaled by `y - p.y`.
fn sees_none(p: GridPoint, light: [i64; 4], y: i64, h: i64, rects: &[[i64; 4]]) -> bool {
    let (py, y, h) = (i128::from(p.y), i128::from(y), i128::from(h));
    let image = |c: i64, pc: i32| i128::from(pc) * (y - h) + i128::from(c) * (h - py);
    let q = [
        image(light[0], p.x),
        image(light[1], p.x),
        image(light[2], p.z),
        image(light[3], p.z),
    ];
    let overlap = |a0: i128, a1: i128, b0: i128, b1: i128| (a1.min(b1) - a0.max(b0)).max(0);
    let covered: i128 = rects
        .iter()
        .map(|r| {
            let r = r.map(|v| i128::from(v) * (y - py));
            overlap(q[0], q[1], r[0], r[1]) * overlap(q[2], q[3], r[2], r[3])
        })
        .sum();
    covered == (q[1] - q[0]) * (q[3] - q[2])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn a_flat_union_hides_the_light_where_its_pieces_do_together(
        shape in 0_usize..5,
        origin in (-60_i64..0, -60_i64..0),
        widths in prop::array::uniform3(8_i64..50),
        depths in prop::array::uniform3(8_i64..50),
        h in 40_i64..120,
        up in any::<bool>(),
        light_at in (-60_i64..60, -60_i64..60, 2_i64..24, 2_i64..24, 170_i64..260),
        points in prop::collection::vec(prop::array::uniform2(-200_i64..200), 150),
        step in prop::array::uniform3(-20_i64..20),
        apart in any::<bool>(),
        turned in prop_oneof![Just(0_u8), any::<u8>()],
    ) {
        let (x, z) = origin;
        let xs = [x, x + widths[0], x + widths[0] + widths[1], x + widths.iter().sum::<i64>()];
        let zs = [z, z + depths[0], z + depths[0] + depths[1], z + depths.iter().sum::<i64>()];
        let rects: Vec<[i64; 4]> = SHAPES[shape].iter().map(|&c| cell(&xs, &zs, c)).collect();
        // The rectangles of `rects[range]`, moved by `dy`; rectangle `k`
        // turned over when bit `k` of `turned` is set (a polygon blocks
        // light whichever side faces it).
        let some = |range: std::ops::Range<usize>, dy: [i64; 3]| -> Vec<ConvexPolygon> {
            range
                .map(|k| (k, rects[k]))
                .map(|(k, [x0, x1, z0, z1])| {
                    let y = h + dy[1];
                    let (x0, x1, z0, z1) = (x0 + dy[0], x1 + dy[0], z0 + dy[2], z1 + dy[2]);
                    let mut c = vec![gp(x0, y, z0), gp(x0, y, z1), gp(x1, y, z1), gp(x1, y, z0)];
                    if !up ^ (turned >> k & 1 == 1) {
                        c.reverse();
                    }
                    ConvexPolygon::from_grid_points(&c, 0).unwrap()
                })
                .collect()
        };
        let pieces = |dy: [i64; 3]| some(0..rects.len(), dy);
        let (x0, z0, w, d, y) = light_at;
        // One object, or (`apart`) each rectangle its own: joint bodies.
        let mut objects = vec![(vec![floor(400)], PieceFlags::default())];
        if apart {
            objects.extend((0..rects.len()).map(|k| (some(k..k + 1, [0; 3]), PieceFlags::default())));
        } else {
            objects.push((pieces([0; 3]), PieceFlags::default()));
        }
        let t = TestScene {
            objects,
            light: light(x0, z0, w, d, y, 0),
        };
        let (mut scene, ids, floor_piece) = t.build_over_floor()?;
        let cells = floor_cells(&scene, floor_piece);
        for c in points {
            let p = gp(c[0], 0, c[1]);
            let Some((_, class)) = cells.iter().find(|(polygon, _)| {
                polygon.edges().all(|e| side_of_point(e, p) == Side::Back)
            }) else {
                continue;
            };
            let dark = sees_none(p, [x0, x0 + w, z0, z0 + d], y, h, &rects);
            prop_assert_eq!(
                *class == CellClass::Umbra,
                dark,
                "{:?} in a {:?} cell", p, class
            );
        }
        check_vertices(&t, &mut scene)?;
        // Moved (apart: the first rectangle alone), the same as built there.
        let moved = if apart { some(0..1, step) } else { pieces(step) };
        scene.move_object(ids[1], moved.clone()).unwrap();
        scene.check_invariants().map_err(TestCaseError::fail)?;
        let mut there = t.clone();
        there.objects[1].0 = moved;
        let (fresh, fresh_ids) = there.build();
        let (a, b) = (class_areas(&scene, floor_piece), class_areas(&fresh, fresh.object_pieces(fresh_ids[0]).unwrap()[0]));
        for k in 0..3 {
            prop_assert!((a[k] - b[k]).abs() <= 1e-9 * 640_000.0, "class {}: {} vs {}", k, a[k], b[k]);
        }
    }
}
