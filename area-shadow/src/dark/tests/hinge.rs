//! Hinges: occluders sharing an edge, proven to block together
//! ([`super::hinge`]), against segments sampled between the region and
//! the light.

use super::*;

/// A random point `centre + radii * u`, `u` in the unit cube.
fn around(rng: &mut Pcg64, centre: [f64; 3], radii: [f64; 3]) -> GridPoint {
    let c: [i64; 3] = std::array::from_fn(|k| {
        (centre[k] + radii[k] * rng.random_range(-1.0..1.0)).round() as i64
    });
    g(c[0], c[1], c[2])
}

/// Floor squares around the shadow of `centre` from the light's centre
/// (height 10 000) that `occluders` are proven to hide all of the light
/// `x, z` in `[-500, 500]` from, given as occluders only (no bodies): each
/// checked against sampled segments. Returns how many were proven, and
/// how many of those no single occluder hides the light from.
fn check_proofs(
    rng: &mut Pcg64,
    occluders: &[ConvexPolygon],
    centre: [f64; 3],
    spread: f64,
) -> (usize, usize) {
    let source = light(-500, 500, 10_000);
    let refs: Vec<&ConvexPolygon> = occluders.iter().collect();
    let t = 10_000.0 / (10_000.0 - centre[1]);
    let (mut proven, mut joint) = (0, 0);
    for _ in 0..8 {
        let (cx, cz, r) = (
            (centre[0] * t + rng.random_range(-1.0..1.0) * spread * t).round() as i64,
            (centre[2] * t + rng.random_range(-1.0..1.0) * spread * t).round() as i64,
            rng.random_range(5..100),
        );
        let region = floor(cx, cz, r);
        let Some(jointly) = proven_dark(&region, &source, &refs) else {
            continue;
        };
        proven += 1;
        joint += usize::from(jointly);
        assert_segments_meet(rng, (cx, cz, r), occluders);
    }
    (proven, joint)
}

/// A random fold: two parallelogram quads sharing the edge from the first
/// quad's corner 0 to its corner 1 (the second's 1 to 0), at a random
/// angle and turn, about a random centre 3000 to 7000 above the floor;
/// with that centre and the fold's size.
pub(super) fn random_fold(rng: &mut Pcg64) -> ([[GridPoint; 4]; 2], [f64; 3], f64) {
    let centre = [
        rng.random_range(-1500.0..1500.0),
        rng.random_range(3000.0..7000.0),
        rng.random_range(-1500.0..1500.0),
    ];
    let size = rng.random_range(300.0..2000.0);
    // The shared edge, and each quad a parallelogram off it.
    let a = around(rng, centre, [size; 3]);
    let b = around(rng, centre, [size; 3]);
    let mut side = || -> [i64; 3] {
        std::array::from_fn(|_| (size * rng.random_range(-1.0..1.0)).round() as i64)
    };
    let (u, v) = (side(), side());
    let off = |p: GridPoint, w: [i64; 3]| {
        g(
            i64::from(p.x) + w[0],
            i64::from(p.y) + w[1],
            i64::from(p.z) + w[2],
        )
    };
    let quads = [[a, b, off(b, u), off(a, u)], [b, a, off(a, v), off(b, v)]];
    (quads, centre, size)
}

/// Random folds (two quads sharing an edge, at a random angle, turned any
/// way, as a ridge, a valley or on edge) over random floor squares
/// (seeded): whatever the two are proven to hide is hidden, every sampled
/// segment meeting one of them; and the proofs find regions neither hides
/// alone.
#[test]
fn proven_dark_regions_under_random_folds_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(21);
    let (mut proven, mut joint) = (0, 0);
    for _ in 0..3000 {
        let (quads, centre, size) = random_fold(&mut rng);
        let Ok(pieces) = quads
            .iter()
            .map(|q| ConvexPolygon::from_grid_points(q, 0))
            .collect::<Result<Vec<_>, _>>()
        else {
            continue;
        };
        let (p, j) = check_proofs(&mut rng, &pieces, centre, 1.5 * size);
        proven += p;
        joint += j;
    }
    assert!(
        proven >= 300 && joint >= 80,
        "proven {proven}, joint {joint}"
    );
}

/// Random fans of triangles around a point (a star-shaped polygon, bent
/// by random heights: the pieces of a concave face the grid left
/// non-planar, and tents), as occluders only: whatever they are proven to
/// hide is hidden; and the proofs find joint umbrae across the seams, by
/// hinges and by the fan about the hub ([`super::fan`]).
#[test]
fn proven_dark_regions_under_random_fans_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(22);
    let (mut proven, mut joint) = (0, 0);
    for _ in 0..2000 {
        let centre = [
            rng.random_range(-1500.0..1500.0),
            rng.random_range(3000.0..7000.0),
            rng.random_range(-1500.0..1500.0),
        ];
        let (size, lift) = (
            rng.random_range(500.0..2500.0),
            rng.random_range(0.0..0.6f64),
        );
        let n = rng.random_range(3..9);
        let hub = around(&mut rng, centre, [0.1 * size, lift * size, 0.1 * size]);
        let rim: Vec<GridPoint> = (0..n)
            .map(|i| {
                let angle =
                    std::f64::consts::TAU * (i as f64 + rng.random_range(0.0..0.8)) / n as f64;
                let reach = size * rng.random_range(0.3..1.0);
                let at = [
                    centre[0] + reach * angle.cos(),
                    centre[1] + lift * size * rng.random_range(-1.0..1.0),
                    centre[2] + reach * angle.sin(),
                ];
                g(
                    at[0].round() as i64,
                    at[1].round() as i64,
                    at[2].round() as i64,
                )
            })
            .collect();
        let fan: Vec<ConvexPolygon> = (0..n)
            .filter_map(|i| {
                ConvexPolygon::from_grid_points(&[hub, rim[(i + 1) % n], rim[i]], 0).ok()
            })
            .collect();
        let (p, j) = check_proofs(&mut rng, &fan, centre, size);
        proven += p;
        joint += j;
    }
    // (Hinges alone prove 666 and 579 of these: the rest is the fans'.)
    assert!(
        proven >= 780 && joint >= 700,
        "proven {proven}, joint {joint}"
    );
}

/// The light seen along the shared edge outside the hinge's angle and the
/// angle opposite: no proof through the hinge. Two panels meet along
/// `x = 0` at height 5000 as an upright "V" whose arms reach up and out;
/// a light low at one side, beyond the left arm's plane extended, sees
/// the two on one side of every plane through the edge.
#[test]
fn a_hinge_seen_from_outside_its_angles_proves_nothing() {
    let [a, b] = [g(0, 5000, -1000), g(0, 5000, 1000)];
    let left =
        ConvexPolygon::from_grid_points(&[a, b, g(-1000, 6000, 1000), g(-1000, 6000, -1000)], 0)
            .unwrap();
    let right =
        ConvexPolygon::from_grid_points(&[b, a, g(1000, 6000, -1000), g(1000, 6000, 1000)], 0)
            .unwrap();
    let occluders = [&left, &right];
    let (occluders_ok, hinges_found) = {
        let os: Vec<Occluder> = occluders.iter().filter_map(|o| Occluder::new(o)).collect();
        (os.len(), crate::dark::hinge::hinges(&os).len())
    };
    assert_eq!((occluders_ok, hinges_found), (2, 1));
    // Seen from straight above the edge, within the "V"'s angle: the
    // floor under the edge is dark.
    let above = light(-100, 100, 10_000);
    assert!(sees_none(&floor(0, 0, 20), false, &above, &occluders, &[]));
    // A light far to the left and low, where both arms lie on one side of
    // the planes through the edge and it: the hinge cannot vouch.
    let side = AreaSource::from_grid_points(&[
        g(-30_000, 5200, -100),
        g(-30_000, 5200, 100),
        g(-30_000, 5400, 100),
        g(-30_000, 5400, -100),
    ])
    .unwrap();
    let os: Vec<Occluder> = occluders.iter().filter_map(|o| Occluder::new(o)).collect();
    let [hinge] = &crate::dark::hinge::hinges(&os)[..] else {
        panic!("one hinge")
    };
    let corners: Vec<GridPoint> = side.vertices().collect();
    let region = floor(0, 0, 20);
    assert!(hinge.candidate_pairs(&os, &region, &corners).is_none());
}
