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
            let (lv, vv) = (l.to_f64(), v.to_f64());
            let t = lv[1] / (lv[1] - vv[1]);
            let k = [lv[0] + (vv[0] - lv[0]) * t, lv[2] + (vv[2] - lv[2]) * t];
            let r = rng.random_range(5..60);
            for (sx, sz) in [(r, r), (r, -r), (-r, r), (-r, -r)] {
                let (cx, cz) = (k[0].round() as i64 + sx, k[1].round() as i64 + sz);
                let region = floor(cx, cz, r);
                if !sees_none(&region, false, &source, &refs, &[]) {
                    continue;
                }
                proven += 1;
                assert_segments_meet(&mut rng, (cx, cz, r), &pieces);
                let by_two = (0..4).any(|i| {
                    (i + 1..4).any(|j| sees_none(&region, false, &source, &[refs[i], refs[j]], &[]))
                });
                beyond_pairs += usize::from(!by_two);
            }
        }
    }
    // (Hinges alone prove 24 of these, 4 beyond any two pieces.)
    assert!(
        proven >= 30 && beyond_pairs >= 12,
        "proven {proven}, beyond pairs {beyond_pairs}"
    );
}
