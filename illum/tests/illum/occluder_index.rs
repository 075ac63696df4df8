//! Occluders found through the index give the same visible part as every
//! polygon of the scene, and leave most of a sparse scene out.

use illum::{AreaLight, OccluderIndex, Sidedness, Vec3, VisiblePart, visible_irradiance};
use rand::{Rng, SeedableRng};

/// Compares, at each point of `points` (with normal `n`), the irradiance
/// past the index's candidates with the irradiance past every outline (less
/// those in `skip(point)`'s plane, as a receiver drops its own plane).
/// Returns (queries that kept under a quarter of the scene, queries that
/// were shadowed).
fn compare(
    outlines: &[Vec<Vec3>],
    light: &AreaLight,
    points: &[(Vec3, Vec3)],
    skip: impl Fn(Vec3, &[Vec3]) -> bool,
) -> (usize, usize) {
    let index = OccluderIndex::new(outlines.to_vec());
    let mut scratch = VisiblePart::new();
    let mut candidates = Vec::new();
    let (mut fewer, mut shadowed) = (0, 0);
    for &(p, n) in points {
        index.candidates_between(p, light, &mut candidates);
        assert!(
            candidates.windows(2).all(|w| w[0] < w[1]),
            "sorted, once each"
        );
        let chosen: Vec<&[Vec3]> = candidates
            .iter()
            .map(|&i| outlines[i as usize].as_slice())
            .filter(|o| !skip(p, o))
            .collect();
        let all: Vec<&[Vec3]> = outlines
            .iter()
            .map(Vec::as_slice)
            .filter(|o| !skip(p, o))
            .collect();
        let from_index =
            visible_irradiance(light, &chosen, p, n, Sidedness::OneSided, &mut scratch);
        let from_all = visible_irradiance(light, &all, p, n, Sidedness::OneSided, &mut scratch);
        assert!(
            (from_index - from_all).abs() <= 1e-12 + 1e-9 * from_all,
            "at {p:?}: {from_index} vs {from_all}"
        );
        if from_all < light.irradiance(p, n, Sidedness::OneSided) * (1.0 - 1e-6) {
            shadowed += 1;
        }
        if candidates.len() * 4 < outlines.len() {
            fewer += 1;
        }
    }
    (fewer, shadowed)
}

#[test]
fn candidates_give_the_same_irradiance_as_every_polygon() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    // Small triangles scattered over a wide slab between the floor (z = 0)
    // and a square light at z = 1000 emitting down.
    let mut outlines = Vec::new();
    while outlines.len() < 400 {
        let c: Vec3 = [
            rng.random_range(-4000.0..4000.0),
            rng.random_range(-4000.0..4000.0),
            rng.random_range(100.0..900.0),
        ];
        let mut corner = || c.map(|x| x + rng.random_range(-60.0..60.0));
        outlines.push(vec![corner(), corner(), corner()]);
    }
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
    let points: Vec<(Vec3, Vec3)> = (0..200)
        .map(|_| {
            let p = [
                rng.random_range(-600.0..600.0),
                rng.random_range(-600.0..600.0),
                0.0,
            ];
            (p, [0.0, 0.0, 1.0])
        })
        .collect();
    let (fewer, shadowed) = compare(&outlines, &light, &points, |_, _| false);
    // The hull of a point and the light is thin: most queries keep less
    // than a quarter of the scene.
    assert!(fewer > 150, "only {fewer} queries pruned the scene");
    // And the comparison is not vacuous: some queries are occluded.
    assert!(shadowed > 10, "only {shadowed} queries were occluded");
}

/// The six faces of the box `lo..hi`, outward.
fn box_faces(lo: Vec3, hi: Vec3) -> Vec<Vec<Vec3>> {
    let (a, b) = (lo, hi);
    vec![
        vec![
            [a[0], a[1], a[2]],
            [a[0], b[1], a[2]],
            [b[0], b[1], a[2]],
            [b[0], a[1], a[2]],
        ],
        vec![
            [a[0], a[1], b[2]],
            [b[0], a[1], b[2]],
            [b[0], b[1], b[2]],
            [a[0], b[1], b[2]],
        ],
        vec![
            [a[0], a[1], a[2]],
            [b[0], a[1], a[2]],
            [b[0], a[1], b[2]],
            [a[0], a[1], b[2]],
        ],
        vec![
            [a[0], b[1], a[2]],
            [a[0], b[1], b[2]],
            [b[0], b[1], b[2]],
            [b[0], b[1], a[2]],
        ],
        vec![
            [a[0], a[1], a[2]],
            [a[0], a[1], b[2]],
            [a[0], b[1], b[2]],
            [a[0], b[1], a[2]],
        ],
        vec![
            [b[0], a[1], a[2]],
            [b[0], b[1], a[2]],
            [b[0], b[1], b[2]],
            [b[0], a[1], b[2]],
        ],
    ]
}

#[test]
fn candidates_in_a_hall_of_boxes_match_every_polygon() {
    // Closed boxes standing on the floor (z = 0) of a wide hall, a light
    // near the ceiling: points on the floor, on box tops and on box sides,
    // where neighbouring faces meet the receiver's plane.
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    let mut outlines = vec![vec![
        [-2000.0, -2000.0, 0.0],
        [2000.0, -2000.0, 0.0],
        [2000.0, 2000.0, 0.0],
        [-2000.0, 2000.0, 0.0],
    ]];
    let mut points = Vec::new();
    for _ in 0..150 {
        let lo = [
            rng.random_range(-1900.0..1850.0),
            rng.random_range(-1900.0..1850.0),
            0.0,
        ];
        let size = [
            rng.random_range(10.0..50.0),
            rng.random_range(10.0..50.0),
            rng.random_range(10.0..150.0),
        ];
        let hi = [lo[0] + size[0], lo[1] + size[1], size[2]];
        outlines.extend(box_faces(lo, hi));
        // A point on the top and one on the side facing -x.
        points.push((
            [lo[0] + 0.5 * size[0], lo[1] + 0.3 * size[1], hi[2]],
            [0.0, 0.0, 1.0],
        ));
        points.push((
            [lo[0], lo[1] + 0.5 * size[1], 0.4 * size[2]],
            [-1.0, 0.0, 0.0],
        ));
        // A floor point in front of that side, and one at its foot.
        points.push(([lo[0] - 30.0, lo[1] + 0.5 * size[1], 0.0], [0.0, 0.0, 1.0]));
        points.push(([lo[0], lo[1] + 0.25 * size[1], 0.0], [0.0, 0.0, 1.0]));
    }
    let light = AreaLight::new(
        &[
            [-100.0, -100.0, 790.0],
            [-100.0, 100.0, 790.0],
            [100.0, 100.0, 790.0],
            [100.0, -100.0, 790.0],
        ],
        1.0,
    )
    .unwrap();
    // A receiver drops the polygons in its own plane (as umbra's
    // illumination does, by an exact test); here the scene is axis-aligned,
    // so "in the plane" is a coordinate shared by every vertex.
    let in_own_plane = |p: Vec3, o: &[Vec3]| (0..3).any(|i| o.iter().all(|q| q[i] == p[i]));
    let (fewer, shadowed) = compare(&outlines, &light, &points, in_own_plane);
    assert!(fewer > 400, "only {fewer} queries pruned the scene");
    assert!(shadowed > 60, "only {shadowed} queries were occluded");
}
