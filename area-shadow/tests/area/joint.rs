//! Boxes of different objects that touch face to face and make one convex
//! box: together they hide the light where neither does alone, and the
//! floor's classes are exact there too.

use crate::groups::{box_faces, floor_classes_are_exact, light_strategy};
use crate::oracle::gp;
use area_shadow::{SceneLight, ShadowGroups, compute_shadows_with_groups};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{BuildOptions, ConvexPolygon};
use proptest::prelude::*;
use svbsp::PieceFlags;

/// The box `lo..hi` cut into two or three boxes: across axis `first` at
/// `at` (a fraction, in sixteenths), and the upper part again across axis
/// `second` when `twice`.
fn cut_box(
    lo: [i64; 3],
    hi: [i64; 3],
    first: usize,
    second: usize,
    at: [i64; 2],
    twice: bool,
) -> Vec<([i64; 3], [i64; 3])> {
    let split = |lo: [i64; 3], hi: [i64; 3], axis: usize, at: i64| {
        let c = lo[axis] + (hi[axis] - lo[axis]) * at / 16;
        let (mut low_hi, mut high_lo) = (hi, lo);
        low_hi[axis] = c;
        high_lo[axis] = c;
        [(lo, low_hi), (high_lo, hi)]
    };
    let [low, high] = split(lo, hi, first, at[0]);
    if twice {
        let [a, b] = split(high.0, high.1, second, at[1]);
        vec![low, a, b]
    } else {
        vec![low, high]
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Two or three boxes, each its own object, that together make one
    /// box over a floor: umbra fragments see none of the light, penumbra
    /// fragments some, lit ones all of it (the umbra the boxes make only
    /// together is umbra, not penumbra with no light).
    #[test]
    fn touching_boxes_over_a_floor_have_exact_classes(
        lo in prop::array::uniform3(-60_i64..20),
        size in prop::array::uniform3(32_i64..90),
        axes in (0_usize..3, 0_usize..3),
        at in prop::array::uniform2(4_i64..13),
        twice in any::<bool>(),
        cuts in any::<u32>(),
        light in light_strategy(),
    ) {
        let lo = [lo[0], lo[1] + 100, lo[2]];
        let hi = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
        let boxes = cut_box(lo, hi, axes.0, axes.1, at, twice);
        let floor = ConvexPolygon::from_grid_points(
            &[gp(-400, 0, 400), gp(400, 0, 400), gp(400, 0, -400), gp(-400, 0, -400)],
            0,
        ).unwrap();
        let mut pieces = vec![floor];
        let mut objects = vec![0];
        for (k, (lo, hi)) in boxes.iter().enumerate() {
            let faces = box_faces(*lo, *hi, cuts.rotate_left(7 * k as u32), false);
            objects.extend(std::iter::repeat_n(k as u32 + 1, faces.len()));
            pieces.extend(faces);
        }
        prop_assume!(pieces[1..].iter().all(|f| (0..f.len()).all(|k| {
            side_of_point(light.support(), f.vertex_grid_point(k).unwrap()) == Side::Front
        })));
        let pieces: Vec<ConvexPolygon> = pieces
            .into_iter()
            .enumerate()
            .map(|(k, p)| p.with_source(k as u32))
            .collect();
        let flags = vec![PieceFlags::default(); pieces.len()];
        let groups = ShadowGroups::of_objects(&pieces, &flags, &objects);
        // Every box a body, and one body of them all (beside the flat
        // polygons their coplanar faces make).
        prop_assert_eq!(groups.bodies.len(), boxes.len());
        let solids: Vec<_> = groups.joint_bodies.iter().filter(|g| !g.is_flat()).collect();
        prop_assert_eq!(solids.len(), 1);
        prop_assert_eq!(solids[0].pieces.len(), pieces.len() - 1);
        let out = compute_shadows_with_groups(
            &pieces,
            &flags,
            &groups,
            &[SceneLight::Area(light.clone())],
            &BuildOptions::default(),
        ).unwrap();
        floor_classes_are_exact(&out.fragments, &pieces, &light)?;
    }
}
