//! Boxes of different objects that touch face to face and make one box:
//! the umbra they make together (a joint body) against an exact oracle at
//! floor points, and against fresh builds as one box moves into contact
//! and away again.

use crate::common::{TestScene, class_areas, floor, floor_cells, gp, light, triangulated_cuboid};
use bsp_core::ConvexPolygon;
use bsp_core::predicates::{Side, side_of_point};
use dm_mesh::CellClass;
use proptest::prelude::*;
use svbsp::PieceFlags;

/// `a / b` against `c / d` (positive denominators).
fn cmp(a: i128, b: i128, c: i128, d: i128) -> std::cmp::Ordering {
    (a * d).cmp(&(c * b))
}

/// Whether the segment from `p` to `q` meets the closed box `lo..hi`
/// past its start, exactly: a point on the box's surface with the box
/// behind it (a floor point on the top of a box below the floor) sees
/// past it.
fn meets_box(p: [i64; 3], q: [i64; 3], lo: [i64; 3], hi: [i64; 3]) -> bool {
    // The segment's parameter interval inside the box, as fractions.
    let (mut from, mut to) = ((0_i128, 1_i128), (1_i128, 1_i128));
    for a in 0..3 {
        let (pa, d) = (i128::from(p[a]), i128::from(q[a] - p[a]));
        let (l, h) = (i128::from(lo[a]) - pa, i128::from(hi[a]) - pa);
        if d == 0 {
            if l > 0 || h < 0 {
                return false;
            }
            continue;
        }
        let (mut enter, mut leave) = ((l, d), (h, d));
        if d < 0 {
            (enter, leave) = ((h, d), (l, d));
        }
        let (enter, leave) = (
            (enter.0 * d.signum(), d.abs()),
            (leave.0 * d.signum(), d.abs()),
        );
        if cmp(enter.0, enter.1, from.0, from.1).is_gt() {
            from = enter;
        }
        if cmp(leave.0, leave.1, to.0, to.1).is_lt() {
            to = leave;
        }
    }
    cmp(from.0, from.1, to.0, to.1).is_le() && to.0 > 0
}

/// The box `lo..hi` cut across axis `axis` at `at` sixteenths, and the
/// upper part again across `again` when given.
fn cut_box(
    lo: [i64; 3],
    hi: [i64; 3],
    axis: usize,
    at: i64,
    again: Option<(usize, i64)>,
) -> Vec<([i64; 3], [i64; 3])> {
    let split = |lo: [i64; 3], hi: [i64; 3], axis: usize, at: i64| {
        let c = lo[axis] + (hi[axis] - lo[axis]) * at / 16;
        let (mut low_hi, mut high_lo) = (hi, lo);
        low_hi[axis] = c;
        high_lo[axis] = c;
        [(lo, low_hi), (high_lo, hi)]
    };
    let [low, high] = split(lo, hi, axis, at);
    match again {
        Some((axis, at)) => {
            let [a, b] = split(high.0, high.1, axis, at);
            vec![low, a, b]
        }
        None => vec![low, high],
    }
}

/// A box of corner `lo` (raised by 20) and size `size`, cut across
/// `axis` at `at` sixteenths (and its upper part again across `again`);
/// its parts' faces cut into triangles by `cuts`, over a floor under a
/// light of corner, sides and height `light_at`.
#[derive(Debug, Clone)]
struct CutBox {
    lo: [i64; 3],
    size: [i64; 3],
    axis: usize,
    at: i64,
    again: Option<(usize, i64)>,
    cuts: u32,
    light_at: (i64, i64, i64, i64, i64),
}

fn cut_boxes() -> impl Strategy<Value = CutBox> {
    (
        prop::array::uniform3(-60_i64..20),
        prop::array::uniform3(32_i64..90),
        0_usize..3,
        4_i64..13,
        prop::option::of((0_usize..3, 4_i64..13)),
        any::<u32>(),
        (-60_i64..60, -60_i64..60, 2_i64..40, 2_i64..40, 190_i64..260),
    )
        .prop_map(|(lo, size, axis, at, again, cuts, light_at)| CutBox {
            lo,
            size,
            axis,
            at,
            again,
            cuts,
            light_at,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn touching_boxes_hide_the_light_where_they_do_together(
        case in cut_boxes(),
        points in prop::collection::vec(prop::array::uniform2(-300_i64..300), 200),
        away in prop::array::uniform3(-30_i64..30),
    ) {
        joint_umbra_and_moves(&case, &points, away)?;
    }
}

/// Boxes stacked under the floor, their top in its plane, the top one
/// moved up through the floor and back (the proptest's find: the bottom
/// two boxes' joint body passed the floor's box test on the way up, and
/// its unit stayed on the floor after the body parted on the way back).
#[test]
fn a_box_moved_up_through_the_floor_and_back_leaves_nothing_behind() {
    let case = CutBox {
        lo: [0, -52, 0],
        size: [32, 32, 32],
        axis: 1,
        at: 4,
        again: Some((1, 4)),
        cuts: 0,
        light_at: (0, 0, 2, 2, 190),
    };
    let points: Vec<[i64; 2]> = (-300..300)
        .step_by(23)
        .flat_map(|x| (-300..300).step_by(29).map(move |z| [x, z]))
        .collect();
    joint_umbra_and_moves(&case, &points, [14, 11, 9]).unwrap();
}

/// The floor's umbra under the cut box against the exact oracle at
/// `points`; then the last part moved by `away` and back, the scene's
/// invariants kept and each time as a fresh build there.
fn joint_umbra_and_moves(
    case: &CutBox,
    points: &[[i64; 2]],
    away: [i64; 3],
) -> Result<(), TestCaseError> {
    let lo = [case.lo[0], case.lo[1] + 20, case.lo[2]];
    let hi: [i64; 3] = std::array::from_fn(|a| lo[a] + case.size[a]);
    let boxes = cut_box(lo, hi, case.axis, case.at, case.again);
    let (x0, z0, w, d, y) = case.light_at;
    let mut objects = vec![(vec![floor(400)], PieceFlags::default())];
    objects.extend(boxes.iter().enumerate().map(|(k, (lo, hi))| {
        (
            triangulated_cuboid(*lo, *hi, case.cuts.rotate_left(5 * k as u32)),
            PieceFlags::default(),
        )
    }));
    let t = TestScene {
        objects,
        light: light(x0, z0, w, d, y, 0),
    };
    let (mut scene, ids, floor_piece) = t.build_over_floor()?;
    let cells = floor_cells(&scene, floor_piece);
    let corners = [
        [x0, y, z0],
        [x0 + w, y, z0],
        [x0 + w, y, z0 + d],
        [x0, y, z0 + d],
    ];
    for c in points {
        let p = gp(c[0], 0, c[1]);
        let Some((_, class)) = cells
            .iter()
            .find(|(polygon, _)| polygon.edges().all(|e| side_of_point(e, p) == Side::Back))
        else {
            continue;
        };
        let q = [c[0], 0, c[1]];
        // From inside the box every segment meets it; from its
        // surface, those that go into it.
        let dark = corners.iter().all(|&k| meets_box(q, k, lo, hi));
        prop_assert_eq!(
            *class == CellClass::Umbra,
            dark,
            "{:?} in a {:?} cell",
            p,
            class
        );
    }
    // The last box moved away and back: as built there each time.
    let last = ids.len() - 1;
    let original = t.objects[last].0.clone();
    let moved: Vec<ConvexPolygon> = original
        .iter()
        .map(|p| p.translated(away).unwrap())
        .collect();
    for polygons in [moved, original] {
        scene.move_object(ids[last], polygons.clone()).unwrap();
        scene.check_invariants().map_err(TestCaseError::fail)?;
        let mut there = t.clone();
        there.objects[last].0 = polygons;
        let (fresh, fresh_ids) = there.build();
        let a = class_areas(&scene, floor_piece);
        let b = class_areas(&fresh, fresh.object_pieces(fresh_ids[0]).unwrap()[0]);
        for k in 0..3 {
            prop_assert!(
                (a[k] - b[k]).abs() <= 1e-9 * 640_000.0,
                "class {}: {} vs {}",
                k,
                a[k],
                b[k]
            );
        }
    }
    // Back in place, the same regions as first built.
    let back = floor_cells(&scene, floor_piece);
    for c in (-300_i64..300)
        .step_by(37)
        .flat_map(|x| (-300_i64..300).step_by(41).map(move |z| (x, z)))
    {
        let p = gp(c.0, 0, c.1);
        let class_at = |cells: &[(ConvexPolygon, CellClass)]| {
            cells
                .iter()
                .find(|(polygon, _)| polygon.edges().all(|e| side_of_point(e, p) == Side::Back))
                .map(|(_, class)| *class)
        };
        if let (Some(a), Some(b)) = (class_at(&cells), class_at(&back)) {
            prop_assert_eq!(a, b, "{:?}", p);
        }
    }
    Ok(())
}
