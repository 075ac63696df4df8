//! Tests of joint bodies: exact unions by faces, bent ones by surfaces,
//! flat joints and edge contact.

use super::super::convex_groups;
use super::*;
use crate::test_shapes::cuboid;

/// The bodies of `boxes`, each box its own object.
fn unions(boxes: &[([i32; 3], [i32; 3])]) -> Vec<Vec<usize>> {
    let mut pieces = Vec::new();
    let mut objects = Vec::new();
    for (k, (lo, hi)) in boxes.iter().enumerate() {
        let faces = cuboid(*lo, *hi);
        objects.extend(std::iter::repeat_n(Some(k as u32), faces.len()));
        pieces.extend(faces);
    }
    let groups = convex_groups(&pieces, &objects);
    assert_eq!(groups.len(), boxes.len());
    let refs: Vec<&ConvexGroup> = groups.iter().collect();
    convex_unions(&refs).into_iter().map(|(m, _)| m).collect()
}

#[test]
fn boxes_side_by_side_make_one_body() {
    assert_eq!(
        unions(&[([0, 0, 0], [10, 10, 10]), ([10, 0, 0], [20, 10, 10])]),
        vec![vec![0, 1]]
    );
}

#[test]
fn a_row_of_three_makes_one_body_and_no_smaller_one() {
    let row = [
        ([20, 0, 0], [30, 10, 10]),
        ([0, 0, 0], [10, 10, 10]),
        ([10, 0, 0], [20, 10, 10]),
    ];
    assert_eq!(unions(&row), vec![vec![0, 1, 2]]);
}

#[test]
fn a_two_by_two_square_joins_rows_that_an_l_would_not() {
    let square = [
        ([0, 0, 0], [10, 10, 10]),
        ([10, 0, 0], [20, 10, 10]),
        ([0, 0, 10], [10, 10, 20]),
        ([10, 0, 10], [20, 10, 20]),
    ];
    assert_eq!(unions(&square), vec![vec![0, 1, 2, 3]]);
    // Three of them make an L: only its two straight pairs are convex.
    assert_eq!(unions(&square[..3]), vec![vec![0, 1], vec![0, 2]]);
}

#[test]
fn a_small_box_on_a_big_one_or_apart_makes_none() {
    // Not convex together.
    assert!(unions(&[([0, 0, 0], [20, 10, 20]), ([5, 10, 5], [15, 20, 15])]).is_empty());
    // Offset faces in one plane: an L in profile.
    assert!(unions(&[([0, 0, 0], [10, 10, 10]), ([10, 0, 5], [20, 10, 15])]).is_empty());
    // A gap between them.
    assert!(unions(&[([0, 0, 0], [10, 10, 10]), ([11, 0, 0], [21, 10, 10])]).is_empty());
}

/// The rectangle `[x0, x0 + w] x [z0, z0 + d]` in the plane at height `y`,
/// facing up.
fn panel(y: i32, x0: i32, z0: i32, w: i32, d: i32) -> ConvexPolygon {
    let g = |x, z| GridPoint { x, y, z };
    let corners = [g(x0, z0), g(x0, z0 + d), g(x0 + w, z0 + d), g(x0 + w, z0)];
    ConvexPolygon::from_grid_points(&corners, 0).unwrap()
}

/// A 20 x 10 panel as a 10 x 10 quad beside two 10 x 5 halves: the
/// quad's edge runs past the halves' common corner (a T-junction), so no
/// whole edge joins it to them; the three still cover one convex polygon.
#[test]
fn panels_meeting_in_a_t_junction_make_one_flat_group() {
    let rect = |x0: i32, z0: i32, w: i32, d: i32| panel(5, x0, z0, w, d);
    let pieces = vec![rect(0, 0, 10, 10), rect(10, 0, 10, 5), rect(10, 5, 10, 5)];
    // One object: one flat group of the three, in place of the halves'.
    let groups = convex_groups(&pieces, &[Some(0); 3]);
    assert_eq!(groups.len(), 1);
    assert!(groups[0].is_flat());
    assert_eq!(groups[0].pieces, vec![0, 1, 2]);
    // The halves one object, the quad another: a flat joint.
    let (groups, unions) = flat_joints(&pieces, &[Some(0), Some(1), Some(1)]);
    assert_eq!(groups.len(), 1);
    assert_eq!(groups[0].pieces, vec![0, 1, 2]);
    assert!(unions.is_empty());
    // The halves shifted off the quad's edge: no T-junction, only theirs.
    let apart = vec![rect(0, 0, 10, 10), rect(11, 0, 10, 5), rect(11, 5, 10, 5)];
    let groups = convex_groups(&apart, &[Some(0); 3]);
    assert_eq!(groups.len(), 1);
    assert_eq!(groups[0].pieces, vec![1, 2]);
}

#[test]
fn coplanar_panels_of_several_objects_join() {
    let g = |x, y, z| GridPoint { x, y, z };
    let quad = |x0: i32, z0: i32| {
        let corners = [
            g(x0, 5, z0),
            g(x0, 5, z0 + 10),
            g(x0 + 10, 5, z0 + 10),
            g(x0 + 10, 5, z0),
        ];
        ConvexPolygon::from_grid_points(&corners, 0).unwrap()
    };
    // Two side by side: one convex polygon. A third beside the first
    // the other way: an L, a flat union.
    let pieces = vec![quad(0, 0), quad(10, 0), quad(0, 10), quad(40, 40)];
    let (groups, unions) = flat_joints(&pieces[..2], &[Some(0), Some(1)]);
    assert_eq!(groups.len(), 1);
    assert!(groups[0].is_flat());
    assert_eq!(groups[0].pieces, vec![0, 1]);
    assert!(unions.is_empty());
    let objects = [Some(3), Some(1), Some(2), Some(1)];
    let (groups, unions) = flat_joints(&pieces, &objects);
    assert!(groups.is_empty());
    assert_eq!(unions.len(), 1);
    assert_eq!(unions[0].pieces, vec![0, 1, 2]);
    // Of one object, they are not joints (its own groups).
    let (groups, unions) = flat_joints(&pieces[..2], &[Some(0), Some(0)]);
    assert!(groups.is_empty() && unions.is_empty());
    // Nor when one casts no shadow.
    let (groups, unions) = flat_joints(&pieces[..2], &[Some(0), None]);
    assert!(groups.is_empty() && unions.is_empty());
    // One turned over, of one object or two: they still join.
    let turned = vec![pieces[0].clone(), pieces[1].flipped()];
    for objects in [[Some(0), Some(0)], [Some(0), Some(1)]] {
        let (groups, unions) = flat_joints(&turned, &objects);
        assert_eq!(groups.len(), 1);
        assert_eq!(groups[0].pieces, vec![0, 1]);
        assert!(unions.is_empty());
    }
}

#[test]
fn far_coplanar_panels_change_no_flat_joint() {
    let rect = |x0: i32, z0: i32, w: i32, d: i32| panel(5, x0, z0, w, d);
    // An L of two panels meeting in a T-junction (the short one's
    // corner on the long one's edge), then 80 panels far off in the
    // plane, each its own object: more than the T-junction search
    // takes in one set.
    let mut pieces = vec![rect(0, 0, 20, 10), rect(0, 10, 10, 10)];
    let alone = flat_joints(&pieces, &[Some(0), Some(1)]);
    assert_eq!(alone.1.len(), 1);
    pieces.extend((0..80).map(|k| rect(100 + 30 * k, 0, 10, 10)));
    let objects: Vec<Option<u32>> = (0..pieces.len() as u32).map(Some).collect();
    let crowded = flat_joints(&pieces, &objects);
    assert!(crowded.0.is_empty());
    assert_eq!(crowded.1.len(), 1);
    assert_eq!(crowded.1[0].pieces, vec![0, 1]);
}

#[test]
fn edge_contact_is_a_shared_corner_or_a_corner_on_an_edge() {
    let rect = |x0: i32, z0: i32, w: i32, d: i32| panel(0, x0, z0, w, d);
    let floor = rect(-100, -100, 200, 200);
    // A box's bottom inside the floor: no contact (the floor's pieces
    // and the boxes' bottoms stay apart).
    assert!(!edge_contact(&floor, &rect(0, 0, 10, 10)));
    assert!(!edge_contact(&floor, &rect(0, 0, 10, 10).flipped()));
    // Side by side, a T-junction, a corner only: contact.
    assert!(edge_contact(&rect(0, 0, 10, 10), &rect(10, 0, 10, 10)));
    assert!(edge_contact(&rect(0, 0, 20, 10), &rect(0, 10, 10, 10)));
    assert!(edge_contact(&rect(0, 0, 10, 10), &rect(10, 10, 10, 10)));
    // Apart.
    assert!(!edge_contact(&rect(0, 0, 10, 10), &rect(11, 0, 10, 10)));
    // The floor with 100 boxes' bottoms inside it makes no joint.
    let mut pieces = vec![floor];
    pieces
        .extend((0..100).map(|k| rect(-90 + 17 * (k % 10), -90 + 17 * (k / 10), 10, 10).flipped()));
    let objects: Vec<Option<u32>> = (0..pieces.len() as u32).map(Some).collect();
    let (groups, unions) = flat_joints(&pieces, &objects);
    assert!(groups.is_empty() && unions.is_empty());
}

#[test]
fn the_union_is_the_hull_of_both() {
    let mut pieces = cuboid([0, 0, 0], [10, 10, 10]);
    pieces.extend(cuboid([0, 10, 0], [10, 30, 10]));
    let objects: Vec<Option<u32>> = (0..12).map(|k| Some(k / 6)).collect();
    let groups = convex_groups(&pieces, &objects);
    let refs: Vec<&ConvexGroup> = groups.iter().collect();
    let found = convex_unions(&refs);
    assert_eq!(found.len(), 1);
    let (members, union) = &found[0];
    assert_eq!(members, &vec![0, 1]);
    assert_eq!(union.pieces, (0..12).collect::<Vec<u32>>());
    let Shape::Solid(solid) = &union.shape else {
        panic!("a solid");
    };
    let g = |x, y, z| GridPoint { x, y, z };
    let mut corners = vec![];
    for x in [0, 10] {
        for y in [0, 30] {
            for z in [0, 10] {
                corners.push(g(x, y, z));
            }
        }
    }
    // Its corners are the tall box's; points on its boundary may stay.
    assert!(corners.iter().all(|c| solid.vertices().contains(c)));
    assert!(solid.vertices().iter().all(|p| {
        (0..=10).contains(&p.x) && (0..=30).contains(&p.y) && (0..=10).contains(&p.z)
    }));
    for face in solid.faces() {
        assert!(
            solid
                .vertices()
                .iter()
                .all(|&p| side_of_point(face, p) != Side::Front)
        );
    }
}

/// The faces of the box `lo..hi` (world units) turned by a rotation
/// about a skew axis, scaled by 1000 and rounded to the grid, each
/// face as two triangles by diagonal `diagonals >> face & 1`: the
/// rounding bends most faces, so the box is only nearly convex.
fn turned_box(lo: [f64; 3], hi: [f64; 3], diagonals: u32) -> Vec<ConvexPolygon> {
    let (s, c) = (0.3_f64.sin(), 0.3_f64.cos());
    let (t, d) = (0.5_f64.sin(), 0.5_f64.cos());
    let turn = |p: [f64; 3]| {
        // About z by 0.3, then about x by 0.5.
        let q = [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]];
        let r = [q[0], d * q[1] - t * q[2], t * q[1] + d * q[2]];
        GridPoint::new(
            (1000.0 * r[0]).round() as i64,
            (1000.0 * r[1]).round() as i64,
            (1000.0 * r[2]).round() as i64,
        )
        .unwrap()
    };
    let corner = |i: usize| {
        turn([
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ])
    };
    let quads = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    let mut out = Vec::new();
    for (f, q) in quads.iter().enumerate() {
        let q: Vec<GridPoint> = q.iter().map(|&i| corner(i)).collect();
        let triangles = if diagonals >> f & 1 == 0 {
            [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
        } else {
            [[q[1], q[2], q[3]], [q[1], q[3], q[0]]]
        };
        for t in triangles {
            out.push(ConvexPolygon::from_grid_points(&t, 0).unwrap());
        }
    }
    out
}

/// The unions of turned boxes, each its own object.
fn turned_unions(boxes: &[([f64; 3], [f64; 3], u32)]) -> Vec<(Vec<usize>, ConvexGroup)> {
    let mut pieces = Vec::new();
    let mut objects = Vec::new();
    for (k, (lo, hi, diagonals)) in boxes.iter().enumerate() {
        let faces = turned_box(*lo, *hi, *diagonals);
        objects.extend(std::iter::repeat_n(Some(k as u32), faces.len()));
        pieces.extend(faces);
    }
    let groups = convex_groups(&pieces, &objects);
    assert_eq!(groups.len(), boxes.len());
    assert!(
        groups.iter().all(|g| !g.joining_corners().is_empty()),
        "bent bodies"
    );
    let refs: Vec<&ConvexGroup> = groups.iter().collect();
    convex_unions(&refs)
}

#[test]
fn turned_boxes_side_by_side_join_by_their_surfaces() {
    // The face they touch by split the same way, and crosswise.
    for diagonals in [0, 1 << 1] {
        let found = turned_unions(&[
            ([0.0, 0.0, 0.0], [10.0, 10.0, 10.0], 0),
            ([10.0, 0.0, 0.0], [20.0, 10.0, 10.0], diagonals),
        ]);
        assert_eq!(found.len(), 1, "diagonals {diagonals}");
        let (members, union) = &found[0];
        assert_eq!(members, &vec![0, 1]);
        assert_eq!(union.pieces, (0..24).collect::<Vec<u32>>());
        // No face of the union has any of the two boxes' corners in
        // front: it is (nearly) the boxes' convex union.
        let Shape::Solid(solid) = &union.shape else {
            panic!("a solid");
        };
        assert!(!solid.is_closed_and_exact());
        for face in solid.faces() {
            assert!(
                solid
                    .vertices()
                    .iter()
                    .all(|&p| side_of_point(face, p) != Side::Front)
            );
        }
    }
    // A stack of three.
    let stack = turned_unions(&[
        ([0.0, 0.0, 0.0], [10.0, 10.0, 10.0], 0),
        ([0.0, 10.0, 0.0], [10.0, 20.0, 10.0], 0b1010),
        ([0.0, 20.0, 0.0], [10.0, 30.0, 10.0], 0b0101),
    ]);
    assert_eq!(
        stack.iter().map(|(m, _)| m.clone()).collect::<Vec<_>>(),
        vec![vec![0, 1, 2]]
    );
}

#[test]
fn turned_boxes_apart_or_askew_do_not_join() {
    // A gap.
    assert!(
        turned_unions(&[
            ([0.0, 0.0, 0.0], [10.0, 10.0, 10.0], 0),
            ([10.5, 0.0, 0.0], [20.0, 10.0, 10.0], 0),
        ])
        .is_empty()
    );
    // Sharing one edge only: their union is not convex.
    assert!(
        turned_unions(&[
            ([0.0, 0.0, 0.0], [10.0, 10.0, 10.0], 0),
            ([10.0, 10.0, 0.0], [20.0, 20.0, 10.0], 0),
        ])
        .is_empty()
    );
}

/// Boxes turned about z only keep planar faces (exact bodies), but the
/// grid may leave a crease between two side by side: one's top a step off
/// the other's plane. Where it folds in, their union is not exactly
/// convex; they join by their surfaces then.
#[test]
fn boxes_turned_about_one_axis_join_across_a_crease() {
    let mut creased = 0;
    for k in 1..40 {
        let angle = 0.05 * f64::from(k);
        let (s, c) = (angle.sin(), angle.cos());
        let cuboid = |lo: [f64; 3], hi: [f64; 3]| -> Vec<ConvexPolygon> {
            let corner = |i: usize| {
                let p = [
                    if i & 1 == 0 { lo[0] } else { hi[0] },
                    if i & 2 == 0 { lo[1] } else { hi[1] },
                    if i & 4 == 0 { lo[2] } else { hi[2] },
                ];
                GridPoint::new(
                    (c * p[0] - s * p[1]).round() as i64,
                    (s * p[0] + c * p[1]).round() as i64,
                    p[2].round() as i64,
                )
                .unwrap()
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
                .map(|q| {
                    let q: Vec<GridPoint> = q.iter().map(|&i| corner(i)).collect();
                    ConvexPolygon::from_grid_points(&q, 0).unwrap()
                })
                .collect()
        };
        let mut pieces = cuboid([0.0, 0.0, 0.0], [1000.0, 1000.0, 1000.0]);
        pieces.extend(cuboid([1000.0, 0.0, 0.0], [2000.0, 1000.0, 1000.0]));
        let objects: Vec<Option<u32>> = (0..12).map(|k| Some(k / 6)).collect();
        let groups = convex_groups(&pieces, &objects);
        assert_eq!(groups.len(), 2, "angle {angle}");
        let solids: Vec<&Solid> = groups
            .iter()
            .map(|g| match &g.shape {
                Shape::Solid(solid) => solid,
                Shape::Flat(_) => panic!("a solid"),
            })
            .collect();
        assert!(
            solids.iter().all(|s| s.is_closed_and_exact()),
            "angle {angle}"
        );
        creased += usize::from(joined(solids[0], solids[1]).is_none());
        let refs: Vec<&ConvexGroup> = groups.iter().collect();
        let found = convex_unions(&refs);
        assert_eq!(found.len(), 1, "angle {angle}");
        assert_eq!(found[0].0, vec![0, 1]);
    }
    // Some of the angles leave a crease that folds in.
    assert!(creased > 0);
}
