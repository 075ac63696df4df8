//! Occluders gathered through the scene BSP give the same visible part as
//! every polygon of the scene, and leave most of a sparse scene out.

use bsp_core::{BuildOptions, ConvexPolygon, GridPoint, SceneBsp};
use illum::{AreaLight, Sidedness, VisiblePart, occluders_between, visible_irradiance};
use rand::{Rng, SeedableRng};

#[test]
fn bsp_candidates_give_the_same_irradiance_as_every_polygon() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    // Small triangles scattered over a wide slab between the floor (z = 0)
    // and a square light at z = 1000 emitting down.
    let mut polygons = Vec::new();
    while polygons.len() < 400 {
        let c = [
            rng.random_range(-4000..4000),
            rng.random_range(-4000..4000),
            rng.random_range(100..900),
        ];
        let corner = |rng: &mut rand_pcg::Pcg64| GridPoint {
            x: c[0] + rng.random_range(-60..60),
            y: c[1] + rng.random_range(-60..60),
            z: c[2] + rng.random_range(-60..60),
        };
        let t = [corner(&mut rng), corner(&mut rng), corner(&mut rng)];
        if let Ok(p) = ConvexPolygon::from_grid_points(&t, polygons.len() as u32) {
            polygons.push(p);
        }
    }
    let bsp = SceneBsp::build(polygons, &BuildOptions::default());
    let outlines: Vec<Vec<[f64; 3]>> = bsp
        .polygons()
        .iter()
        .map(ConvexPolygon::vertices_f64)
        .collect();
    let light = AreaLight::new(
        &[
            [-150.0, -150.0, 1000.0],
            [-150.0, 150.0, 1000.0],
            [150.0, 150.0, 1000.0],
            [150.0, -150.0, 1000.0],
        ],
        1.0,
    )
    .unwrap();
    let mut scratch = VisiblePart::new();
    let mut fewer = 0;
    let mut shadowed = 0;
    for _ in 0..200 {
        let p = [
            rng.random_range(-600.0..600.0),
            rng.random_range(-600.0..600.0),
            0.0,
        ];
        let n = [0.0, 0.0, 1.0];
        let candidates = occluders_between(&bsp, p, &light);
        let chosen: Vec<&[[f64; 3]]> = candidates
            .iter()
            .map(|&i| outlines[i as usize].as_slice())
            .collect();
        let all: Vec<&[[f64; 3]]> = outlines.iter().map(Vec::as_slice).collect();
        let from_bsp = visible_irradiance(&light, &chosen, p, n, Sidedness::OneSided, &mut scratch);
        let from_all = visible_irradiance(&light, &all, p, n, Sidedness::OneSided, &mut scratch);
        assert!(
            (from_bsp - from_all).abs() <= 1e-12 + 1e-9 * from_all,
            "{from_bsp} vs {from_all}"
        );
        if from_all < light.irradiance(p, n, Sidedness::OneSided) * (1.0 - 1e-6) {
            shadowed += 1;
        }
        if candidates.len() * 4 < outlines.len() {
            fewer += 1;
        }
    }
    // The hull of a point and the light is thin: most queries keep less
    // than a quarter of the scene.
    assert!(fewer > 150, "only {fewer} queries pruned the scene");
    // And the comparison is not vacuous: some queries are occluded.
    assert!(shadowed > 10, "only {shadowed} queries were occluded");
}
