//! Fans: occluders about a corner they share, proven to block together
//! ([`super::fan`]), against segments sampled between the region and the
//! light.

use super::hinge::random_fold;
use super::*;

/// A quad cut into two triangles along the diagonal from its corner
/// `from` (0 or 1).
fn cut(q: [GridPoint; 4], from: usize) -> Vec<ConvexPolygon> {
    let t = if from == 0 {
        [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    } else {
        [[q[1], q[2], q[3]], [q[1], q[3], q[0]]]
    };
    t.iter()
        .filter_map(|t| ConvexPolygon::from_grid_points(t, 0).ok())
        .collect()
}

/// Four floor squares (centre `x`, `z` and half-width, at random) each
/// with a corner where the light corner `l` is seen exactly past `v`, one
/// on each side of it.
fn cornered_past(rng: &mut Pcg64, v: GridPoint, l: GridPoint) -> [(i64, i64, i64); 4] {
    let (lv, vv) = (l.to_f64(), v.to_f64());
    let t = lv[1] / (lv[1] - vv[1]);
    let k = [lv[0] + (vv[0] - lv[0]) * t, lv[2] + (vv[2] - lv[2]) * t];
    let r = rng.random_range(5..60);
    [(r, r), (r, -r), (-r, r), (-r, -r)]
        .map(|(sx, sz)| (k[0].round() as i64 + sx, k[1].round() as i64 + sz, r))
}

/// Whether some two of `occluders` are proven to hide all of `source`
/// from `region`.
fn proven_by_two(
    region: &ConvexPolygon,
    source: &AreaSource,
    occluders: &[&ConvexPolygon],
) -> bool {
    (0..occluders.len()).any(|i| {
        (i + 1..occluders.len())
            .any(|j| sees_none(region, false, source, &[occluders[i], occluders[j]], &[]))
    })
}

/// Random folds of two quads, each cut into two triangles (the grid cuts
/// a bent quad so), over floor squares with a corner where a light corner
/// is seen exactly past a corner of the fold (as the corners of DM cells
/// lie): whatever the four are proven to hide is hidden, every sampled
/// segment meeting one of them; and they prove, about the fold's corners,
/// regions that no two of them hide together, nor any one alone.
#[test]
fn proven_dark_regions_under_random_cut_folds_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(23);
    let source = light(-500, 500, 10_000);
    let light_corners: Vec<GridPoint> = source.vertices().collect();
    let (mut proven, mut beyond_pairs) = (0, 0);
    for _ in 0..300 {
        let ([a_quad, b_quad], _, _) = random_fold(&mut rng);
        let quads = [a_quad, b_quad];
        let (a, b) = (a_quad[0], a_quad[1]);
        let pieces: Vec<ConvexPolygon> = quads
            .iter()
            .flat_map(|&q| cut(q, rng.random_range(0..2)))
            .collect();
        if pieces.len() != 4 {
            continue;
        }
        let refs: Vec<&ConvexPolygon> = pieces.iter().collect();
        // Each end of the shared edge seen past from each light corner,
        // the region on each side of that corner.
        for (v, l) in [a, b]
            .into_iter()
            .flat_map(|v| light_corners.iter().map(move |&l| (v, l)))
        {
            for (cx, cz, r) in cornered_past(&mut rng, v, l) {
                let region = floor(cx, cz, r);
                if !sees_none(&region, false, &source, &refs, &[]) {
                    continue;
                }
                proven += 1;
                assert_segments_meet(&mut rng, (cx, cz, r), &pieces);
                beyond_pairs += usize::from(!proven_by_two(&region, &source, &refs));
            }
        }
    }
    // (Hinges alone prove 24 of these, 4 beyond any two pieces.)
    assert!(
        proven >= 30 && beyond_pairs >= 12,
        "proven {proven}, beyond pairs {beyond_pairs}"
    );
}

/// Random fans of triangles about a hub, closed or with one triangle left
/// out (open), under a tilted light, over floor squares cornered where a
/// light corner is seen exactly past the hub: whatever they are proven to
/// hide is hidden, every sampled segment to the tilted light meeting one of
/// the triangles; and the fans prove regions that no two of the triangles
/// hide together.
#[test]
fn proven_dark_regions_under_fans_and_a_tilted_light_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(24);
    let rise = 1300;
    let source = AreaSource::from_grid_points(&[
        g(-500, 10_000, -500),
        g(500, 10_000 + rise, -500),
        g(500, 10_000 + rise, 500),
        g(-500, 10_000, 500),
    ])
    .unwrap();
    let light_corners: Vec<GridPoint> = source.vertices().collect();
    let (mut proven, mut beyond_pairs) = (0, 0);
    for _ in 0..300 {
        let (hub, size) = (
            g(
                rng.random_range(-1000..1000),
                rng.random_range(3000..7000),
                rng.random_range(-1000..1000),
            ),
            rng.random_range(800.0..2500.0),
        );
        let n = rng.random_range(3..8);
        let rim: Vec<GridPoint> = (0..n)
            .map(|i| {
                let angle =
                    std::f64::consts::TAU * (i as f64 + rng.random_range(0.0..0.8)) / n as f64;
                let reach = size * rng.random_range(0.4..1.0);
                g(
                    i64::from(hub.x) + (reach * angle.cos()).round() as i64,
                    i64::from(hub.y) + (size * rng.random_range(-0.5..0.5)).round() as i64,
                    i64::from(hub.z) + (reach * angle.sin()).round() as i64,
                )
            })
            .collect();
        let open = rng.random_bool(0.5);
        let fan: Vec<ConvexPolygon> = (0..n - usize::from(open))
            .filter_map(|i| {
                ConvexPolygon::from_grid_points(&[hub, rim[(i + 1) % n], rim[i]], 0).ok()
            })
            .collect();
        let refs: Vec<&ConvexPolygon> = fan.iter().collect();
        for &l in &light_corners {
            for (cx, cz, r) in cornered_past(&mut rng, hub, l) {
                let region = floor(cx, cz, r);
                if !sees_none(&region, false, &source, &refs, &[]) {
                    continue;
                }
                proven += 1;
                for _ in 0..256 {
                    let (k, l) = segment_to_light(&mut rng, (cx, cz, r), rise);
                    let through = fan.iter().any(|p| {
                        let c = p.vertices_f64();
                        segment_meets_triangle(k, l, [c[0], c[1], c[2]])
                    });
                    assert!(through, "segment {k:?} -> {l:?} passes the fan {fan:?}");
                }
                beyond_pairs += usize::from(!proven_by_two(&region, &source, &refs));
            }
        }
    }
    // (Hinges alone prove 84 of these, 2 beyond any two triangles.)
    assert!(
        proven >= 1200 && beyond_pairs >= 1100,
        "proven {proven}, beyond pairs {beyond_pairs}"
    );
}
