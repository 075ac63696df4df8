//! The pipeline against the oracle: fragments partition their pieces, every
//! fragment's class agrees with exact occlusion at interior points, and the
//! answers do not depend on input order or on the other lights.

use crate::oracle::{Caster, samples, sees_light};
use crate::scenes::{boxes_on_floor, gp, triangles_over_floor};
use bsp_core::predicates::Side;
use bsp_core::{BuildOptions, ConvexPolygon};
use proptest::prelude::*;
use svbsp::{
    Light, LightSource, PieceFlags, ShadowOptions, ShadowOutput, compute_shadows,
    compute_shadows_with,
};

fn run(pieces: &[ConvexPolygon], lights: &[Light]) -> ShadowOutput {
    compute_shadows(
        pieces,
        &vec![PieceFlags::default(); pieces.len()],
        lights,
        &BuildOptions::default(),
    )
    .unwrap()
}

/// A run whose cones hold at most `cone_pieces` pieces: small cones cut
/// the scene by many planes through the light.
fn run_in_cones(pieces: &[ConvexPolygon], lights: &[Light], cone_pieces: usize) -> ShadowOutput {
    let options = ShadowOptions {
        cone_pieces,
        ..ShadowOptions::default()
    };
    compute_shadows_with(
        pieces,
        &vec![PieceFlags::default(); pieces.len()],
        lights,
        &options,
    )
    .unwrap()
}

fn check_partition(pieces: &[ConvexPolygon], out: &ShadowOutput) -> Result<(), TestCaseError> {
    let mut area = vec![0.0; pieces.len()];
    for f in &out.fragments {
        f.polygon.check_invariants().map_err(TestCaseError::fail)?;
        area[f.polygon.source() as usize] += f.polygon.area();
    }
    for (got, piece) in area.iter().zip(pieces) {
        prop_assert!(
            (got - piece.area()).abs() <= 1e-9 * piece.area(),
            "{got} vs {}",
            piece.area()
        );
    }
    Ok(())
}

fn check_oracle(
    pieces: &[ConvexPolygon],
    out: &ShadowOutput,
    lights: &[Light],
) -> Result<(), TestCaseError> {
    let casters: Vec<Caster> = pieces.iter().map(Caster::new).collect();
    for f in &out.fragments {
        let own = f.polygon.source() as usize;
        for (i, light) in lights.iter().enumerate() {
            let bit = 1 << i;
            let (lit, umbra) = (f.lit_mask & bit != 0, f.umbra_mask & bit != 0);
            prop_assert!(
                lit != umbra,
                "a point light leaves no penumbra: lit {lit} umbra {umbra}"
            );
            let faces = light.source.side(f.polygon.support()) == Side::Front;
            if !faces {
                prop_assert!(umbra, "a fragment facing away from light {i} is lit");
                continue;
            }
            for s in samples(&f.polygon) {
                if let Some(sees) = sees_light(s, light.source, &casters, &pieces[own]) {
                    prop_assert_eq!(sees, lit, "light {} piece {} sample {:?}", i, own, s);
                }
            }
        }
    }
    Ok(())
}

/// Area per piece with light `i` lit.
fn lit_area(out: &ShadowOutput, pieces: usize, i: usize) -> Vec<f64> {
    let mut area = vec![0.0; pieces];
    for f in &out.fragments {
        if f.lit_mask & (1 << i) != 0 {
            area[f.polygon.source() as usize] += f.polygon.area();
        }
    }
    area
}

fn close(a: &[f64], b: &[f64], tolerance: f64) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= tolerance * x.abs().max(y.abs()).max(1.0))
}

fn light_above() -> impl Strategy<Value = Light> {
    (prop::array::uniform3(-300_i64..300))
        .prop_map(|c| Light::point(gp(c[0], 300 + c[1].abs(), c[2])))
}

fn light_anywhere() -> impl Strategy<Value = Light> {
    prop::array::uniform3(-400_i64..400)
        .prop_map(|c| Light::point(gp(c[0], c[1].abs() / 2 + 1, c[2])))
}

/// A direction with a downward component.
fn downward(m: i32) -> impl Strategy<Value = [i32; 3]> {
    (-m..=m, -m..=-1, -m..=m).prop_map(|(x, y, z)| [x, y, z])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn triangles_cast_exact_shadows(pieces in triangles_over_floor(), light in light_above()) {
        let out = run(&pieces, &[light]);
        check_partition(&pieces, &out)?;
        check_oracle(&pieces, &out, &[light])?;
    }

    #[test]
    fn lights_among_the_occluders(pieces in triangles_over_floor(), light in light_anywhere()) {
        let out = run(&pieces, &[light]);
        check_partition(&pieces, &out)?;
        check_oracle(&pieces, &out, &[light])?;
    }

    #[test]
    fn boxes_with_coplanar_contact(pieces in boxes_on_floor(), light in light_above()) {
        let out = run(&pieces, &[light]);
        check_partition(&pieces, &out)?;
        check_oracle(&pieces, &out, &[light])?;
    }

    #[test]
    fn directional_lights(pieces in boxes_on_floor(), d in downward(9)) {
        let light = Light::directional(d);
        let out = run(&pieces, &[light]);
        check_partition(&pieces, &out)?;
        check_oracle(&pieces, &out, &[light])?;
    }

    #[test]
    fn reordering_the_input_changes_no_area(pieces in triangles_over_floor(), light in light_above()) {
        let out = run(&pieces, &[light]);
        let mut reversed = pieces.clone();
        reversed.reverse();
        let out_r = run(&reversed, &[light]);
        let mut area_r = lit_area(&out_r, pieces.len(), 0);
        area_r.reverse();
        prop_assert!(close(&lit_area(&out, pieces.len(), 0), &area_r, 1e-9));
    }

    #[test]
    fn many_lights_combine_single_runs(
        pieces in boxes_on_floor(),
        a in light_above(),
        b in light_anywhere(),
        d in downward(5),
    ) {
        let lights = [a, b, Light::directional(d)];
        let together = run(&pieces, &lights);
        check_partition(&pieces, &together)?;
        check_oracle(&pieces, &together, &lights)?;
        for (i, light) in lights.iter().enumerate() {
            let alone = run(&pieces, &[*light]);
            prop_assert!(close(&lit_area(&together, pieces.len(), i), &lit_area(&alone, pieces.len(), 0), 1e-9));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn small_cones_give_exact_shadows(
        pieces in triangles_over_floor(),
        light in light_anywhere(),
        cone_pieces in 1_usize..6,
    ) {
        let out = run_in_cones(&pieces, &[light], cone_pieces);
        check_partition(&pieces, &out)?;
        check_oracle(&pieces, &out, &[light])?;
        let whole = run(&pieces, &[light]);
        prop_assert!(close(&lit_area(&out, pieces.len(), 0), &lit_area(&whole, pieces.len(), 0), 1e-9));
    }

    #[test]
    fn small_cones_of_several_lights(
        pieces in boxes_on_floor(),
        a in light_above(),
        b in light_anywhere(),
        d in downward(7),
        cone_pieces in 1_usize..6,
    ) {
        let lights = [a, Light::directional(d), b];
        let out = run_in_cones(&pieces, &lights, cone_pieces);
        check_partition(&pieces, &out)?;
        check_oracle(&pieces, &out, &lights)?;
    }

    #[test]
    fn closed_surfaces_skip_their_back_faces_without_changing_shadows(pieces in boxes_on_floor(), light in light_above()) {
        let open = run(&pieces, &[light]);
        let mut flags = vec![PieceFlags { closed_surface: true, ..PieceFlags::default() }; pieces.len()];
        flags[0].closed_surface = false;
        let closed = compute_shadows(&pieces, &flags, &[light], &BuildOptions::default()).unwrap();
        check_partition(&pieces, &closed)?;
        check_oracle(&pieces, &closed, &[light])?;
        prop_assert!(close(&lit_area(&open, pieces.len(), 0), &lit_area(&closed, pieces.len(), 0), 1e-9));
        // A closed surface's faces turned away from the light are settled
        // whole, without a tree. (The faces towards it may be cut
        // differently: their cones' scene BSPs no longer hold the others.)
        let away = |out: &ShadowOutput| {
            out.fragments
                .iter()
                .filter(|f| f.polygon.source() != 0 && light.source.side(pieces[f.polygon.source() as usize].support()) != Side::Front)
                .count()
        };
        let turned_away = (1..pieces.len())
            .filter(|&i| light.source.side(pieces[i].support()) != Side::Front)
            .count();
        prop_assert_eq!(away(&closed), turned_away);
        prop_assert!(away(&closed) <= away(&open));
    }

    #[test]
    fn receivers_that_cast_nothing(pieces in triangles_over_floor(), light in light_above(), mask in prop::collection::vec(prop::bool::ANY, 16)) {
        let flags: Vec<PieceFlags> = (0..pieces.len())
            .map(|i| PieceFlags { casts_shadows: mask[i % mask.len()], ..PieceFlags::default() })
            .collect();
        let out = compute_shadows(&pieces, &flags, &[light], &BuildOptions::default()).unwrap();
        check_partition(&pieces, &out)?;
        // The oracle over casting pieces only.
        let casting: Vec<ConvexPolygon> = pieces.iter().zip(&flags).filter(|(_, f)| f.casts_shadows).map(|(p, _)| p.clone()).collect();
        let casters: Vec<Caster> = casting.iter().map(Caster::new).collect();
        for f in &out.fragments {
            let own = &pieces[f.polygon.source() as usize];
            if light.source.side(own.support()) != Side::Front {
                prop_assert_eq!(f.umbra_mask, 1);
                continue;
            }
            for s in samples(&f.polygon) {
                if let Some(sees) = sees_light(s, light.source, &casters, own) {
                    prop_assert_eq!(sees, f.lit_mask == 1);
                }
            }
        }
    }
}

#[test]
fn many_cones_over_a_field_of_boxes() {
    let mut pieces = vec![crate::scenes::floor(600)];
    for i in 0..6_i64 {
        for j in 0..6_i64 {
            let (x, z) = (-300 + 100 * i + 7 * j, -300 + 100 * j - 5 * i);
            let y = 10 * ((i + j) % 3);
            pieces.extend(crate::scenes::box_faces(
                [x, y, z],
                [x + 40, y + 30 + 5 * i, z + 35],
            ));
        }
    }
    for light in [
        Light::point(gp(20, 400, -30)),
        Light::point(gp(-10, 25, 15)),
        Light::directional([2, -9, 1]),
    ] {
        let out = run_in_cones(&pieces, &[light], 4);
        assert!(out.lights[0].cones > 16, "{} cones", out.lights[0].cones);
        check_partition(&pieces, &out).unwrap();
        check_oracle(&pieces, &out, &[light]).unwrap();
        let whole = run_in_cones(&pieces, &[light], usize::MAX);
        assert_eq!(whole.lights[0].cones, 1);
        assert!(close(
            &lit_area(&out, pieces.len(), 0),
            &lit_area(&whole, pieces.len(), 0),
            1e-9
        ));
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let mut pieces = vec![crate::scenes::floor(600)];
    for i in 0..5_i64 {
        for j in 0..5_i64 {
            let (x, z) = (-250 + 110 * i + 9 * j, -250 + 110 * j - 7 * i);
            pieces.extend(crate::scenes::box_faces(
                [x, 10 * (i % 2), z],
                [x + 45, 60, z + 30],
            ));
        }
    }
    let lights = [
        Light::point(gp(30, 500, -20)),
        Light::directional([1, -7, 2]),
    ];
    let run_with = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run_in_cones(&pieces, &lights, 3))
    };
    let one = run_with(1);
    assert!(one.lights[0].cones > 8);
    for threads in [2, 3] {
        let many = run_with(threads);
        assert_eq!(one.fragments, many.fragments, "{threads} threads");
        assert_eq!(one.lights, many.lights);
    }
}

#[test]
fn a_directional_light_matches_a_very_far_point_light() {
    let mut pieces = vec![crate::scenes::floor(600)];
    pieces.extend(crate::scenes::box_faces([-50, 0, -40], [30, 70, 60]));
    pieces.extend(crate::scenes::box_faces([100, 30, 100], [160, 50, 170]));
    let d = [3, -10, 2];
    let far = 1_000_000;
    let point = Light::point(gp(-3 * far, 10 * far, -2 * far));
    let directional = Light::directional(d);
    let a = lit_area(&run(&pieces, &[directional]), pieces.len(), 0);
    let b = lit_area(&run(&pieces, &[point]), pieces.len(), 0);
    // A light 1e7 units away over a scene of 1e3: shadows differ by about
    // 1e-4 of their size.
    assert!(close(&a, &b, 1e-3), "{a:?} vs {b:?}");
    assert!(a[0] < pieces[0].area());
}

#[test]
fn ranges_leave_far_polygons_out() {
    let pieces = vec![
        crate::scenes::floor(600),
        ConvexPolygon::from_grid_points(
            &[
                gp(-10, 50, 10),
                gp(10, 50, 10),
                gp(10, 50, -10),
                gp(-10, 50, -10),
            ],
            0,
        )
        .unwrap(),
    ];
    let mut light = Light::point(gp(0, 100, 0));
    light.range = Some(60.0);
    let out = run(&pieces, &[light]);
    // The floor is 100 away: wholly beyond the range, it takes no part.
    for f in out.fragments.iter().filter(|f| f.polygon.source() == 0) {
        assert_eq!(f.umbra_mask, 1);
    }
    // The occluder is within range and faces away (its normal is +y, the
    // light above it): lit bit off, umbra on.
    let LightSource::Point(_) = light.source else {
        unreachable!()
    };
}

#[test]
fn more_than_32_lights_is_an_error() {
    let lights = vec![Light::point(gp(0, 10, 0)); 33];
    let r = compute_shadows(
        &[crate::scenes::floor(10)],
        &[PieceFlags::default()],
        &lights,
        &BuildOptions::default(),
    );
    assert_eq!(r.unwrap_err(), svbsp::Error::TooManyLights(33));
}
