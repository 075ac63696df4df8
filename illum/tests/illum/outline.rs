//! Past many occluders `visible_irradiance` integrates the outlines of the
//! visible part (the light minus the union of the occluders' images): the
//! same irradiance as the convex pieces `VisiblePart::compute` cuts, on
//! meshes whose triangles share edges, overlap and fold, seen from points
//! that see their surfaces from both sides.

use crate::{assert_rel, unit};
use illum::{
    AreaLight,
    Sidedness::{self, OneSided, TwoSided},
    Vec3, VisiblePart, visible_irradiance,
};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// A bumpy height field over `[x0, x0 + 3] x [z0, z0 + 3]` around height
/// `y`, `k x k` cells each cut into two triangles, wound either way; the
/// triangles share their edges, and steep bumps fold the surface as seen
/// from a point off to the side.
fn bumpy_patch(rng: &mut Pcg64, x0: f64, z0: f64, y: f64, k: usize, bump: f64) -> Vec<[Vec3; 3]> {
    let step = 3.0 / k as f64;
    let mut height = || {
        if bump > 0.0 {
            y + rng.random_range(-bump..bump)
        } else {
            y
        }
    };
    let heights: Vec<Vec<f64>> = (0..=k)
        .map(|_| (0..=k).map(|_| height()).collect())
        .collect();
    let at = |i: usize, j: usize| [x0 + i as f64 * step, heights[i][j], z0 + j as f64 * step];
    let mut out = Vec::new();
    for i in 0..k {
        for j in 0..k {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            for mut t in [[a, b, c], [a, c, d]] {
                if rng.random_bool(0.5) {
                    t.reverse();
                }
                out.push(t);
            }
        }
    }
    out
}

/// A 2 x 2 light at height 8 over the origin, emitting down, of radiance
/// `radiance`.
fn ceiling_light(radiance: f64) -> AreaLight {
    let corners = [
        [-1.0, 8.0, -1.0],
        [1.0, 8.0, -1.0],
        [1.0, 8.0, 1.0],
        [-1.0, 8.0, 1.0],
    ];
    AreaLight::new(&corners, radiance).unwrap()
}

/// `visible_irradiance` at `p` checked against the convex pieces (to 1e-9
/// of the unoccluded irradiance) and the whole light: the value, the
/// unoccluded one, and whether it was taken by outlines (some light seen,
/// and no pieces left in the scratch).
fn checked(
    light: &AreaLight,
    occ: &[[Vec3; 3]],
    p: Vec3,
    n: Vec3,
    sided: Sidedness,
    case: usize,
) -> (f64, f64, bool) {
    let mut scratch = VisiblePart::new();
    let e = visible_irradiance(light, occ, p, n, sided, &mut scratch);
    let full = light.irradiance(p, n, sided);
    assert!(
        e.is_finite() && e >= 0.0 && e <= full * (1.0 + 1e-12),
        "case {case}: {e} of {full}"
    );
    let want = by_pieces(light, occ, p, n, sided);
    assert!(
        (e - want).abs() <= 1e-9 * full,
        "case {case}: outlines {e}, pieces {want} (unoccluded {full})"
    );
    (e, full, e > 0.0 && scratch.is_empty())
}

/// The irradiance from the convex pieces of the visible part.
fn by_pieces(light: &AreaLight, occ: &[[Vec3; 3]], p: Vec3, n: Vec3, sided: Sidedness) -> f64 {
    let mut pieces = VisiblePart::new();
    pieces.compute(light, occ, p);
    pieces.irradiance(light, p, n, sided)
}

#[test]
fn outlines_match_convex_pieces() {
    let mut rng = Pcg64::seed_from_u64(2026);
    let light = ceiling_light(1.0);
    let (mut outlined, mut partial, mut holes) = (0, 0, 0);
    for case in 0..60 {
        // A patch across part of the light's view, loose triangles
        // crossing it, and at times a second patch above the first.
        let k = rng.random_range(12..24);
        let bump = if case % 3 == 0 { 0.6 } else { 0.1 };
        let p = [
            rng.random_range(-2.0..2.0),
            rng.random_range(0.0..1.0),
            rng.random_range(-2.0..2.0),
        ];
        // The patch's edge x = x0 + 3 crosses the view of the light at its
        // height (about [-0.5, 0.5] around p.x / 2).
        let x0 = p[0] / 2.0 - 3.0 + rng.random_range(-0.4..0.4);
        let z0 = p[2] / 2.0 - 1.5 + rng.random_range(-1.0..1.0);
        let mut occ = bumpy_patch(&mut rng, x0, z0, 4.0, k, bump);
        for _ in 0..rng.random_range(0..6) {
            let c = [
                rng.random_range(-1.0..1.0),
                rng.random_range(2.0..6.0),
                rng.random_range(-1.0..1.0),
            ];
            occ.push(std::array::from_fn(|_| {
                [
                    c[0] + rng.random_range(-0.5..0.5),
                    c[1] + rng.random_range(-0.3..0.3),
                    c[2] + rng.random_range(-0.5..0.5),
                ]
            }));
        }
        if case % 4 == 1 {
            occ.extend(bumpy_patch(&mut rng, -0.5, -1.5, 5.5, 3, 0.2));
        }
        let n = unit([
            rng.random_range(-3.0..3.0),
            1.0,
            rng.random_range(-3.0..3.0),
        ]);
        let sided = if case % 5 == 4 { TwoSided } else { OneSided };
        let (e, full, by_outlines) = checked(&light, &occ, p, n, sided, case);
        // The outlines were taken, and the cases cover partial shadows,
        // some with holes of light inside the shadow.
        outlined += usize::from(by_outlines);
        if e > 0.01 * full && e < 0.99 * full {
            partial += 1;
        }
        let mut pieces = VisiblePart::new();
        pieces.compute(&light, &occ, p);
        if pieces.len() > 40 {
            holes += 1;
        }
    }
    println!("{outlined} by outlines, {partial} partly shadowed, {holes} past 40 pieces");
    assert!(outlined >= 30, "{outlined} cases by outlines");
    assert!(partial >= 30, "{partial} partly shadowed cases");
    assert!(holes >= 10, "{holes} cases past 40 pieces");
}

#[test]
fn a_patch_over_the_whole_view_leaves_only_its_gap() {
    // A flat patch of 2 x 64 triangles over all of the light's view (32 of
    // them cut it) hides all of it; with one triangle taken out, the light
    // seen is what that triangle alone hides (a hole in the union).
    let light = ceiling_light(2.0);
    let mut rng = Pcg64::seed_from_u64(7);
    let patch = bumpy_patch(&mut rng, -1.5, -1.5, 4.0, 8, 0.0);
    let (p, up) = ([0.1, 0.0, 0.05], [0.0, 1.0, 0.0]);
    let mut scratch = VisiblePart::new();
    assert_eq!(
        visible_irradiance(&light, &patch, p, up, OneSided, &mut scratch),
        0.0
    );
    // The first triangle of the cell over [-0.375, 0]^2.
    let mut holed = patch.clone();
    let taken = holed.remove(2 * (3 * 8 + 3));
    let e = visible_irradiance(&light, &holed, p, up, OneSided, &mut scratch);
    assert!(scratch.is_empty(), "taken by outlines");
    let through = light.irradiance(p, up, OneSided) - by_pieces(&light, &[taken], p, up, OneSided);
    assert!(through > 0.0);
    assert_rel(e, through, 1e-12);
}

#[test]
fn wild_occluders_agree_and_stay_finite() {
    // Soups of 24 to 60 triangles of every size: specks, sheets wider than
    // the whole view, triangles through the light's plane or behind the
    // point, repeated ones, fans about a shared corner, tilted lights.
    let mut rng = Pcg64::seed_from_u64(1986);
    let mut outlined = 0;
    for case in 0..300 {
        let tilt = rng.random_range(-0.4..0.4);
        let light = AreaLight::new(
            &[
                [-1.0, 8.0 - tilt, -1.0],
                [1.0, 8.0 + tilt, -1.0],
                [1.0, 8.0 + tilt, 1.0],
                [-1.0, 8.0 - tilt, 1.0],
            ],
            1.0,
        )
        .unwrap();
        let p = [
            rng.random_range(-3.0..3.0),
            rng.random_range(-1.0..2.0),
            rng.random_range(-3.0..3.0),
        ];
        let mut occ: Vec<[Vec3; 3]> = Vec::new();
        let count = rng.random_range(24..60);
        while occ.len() < count {
            // About the segment from p to the light's centre (some past
            // either end), where they cut the view.
            let t = rng.random_range(-0.1..1.1);
            let c = [
                p[0] * (1.0 - t) + rng.random_range(-0.5..0.5),
                p[1] * (1.0 - t) + 8.0 * t,
                p[2] * (1.0 - t) + rng.random_range(-0.5..0.5),
            ];
            // One sheet wider than the view in every fourth case.
            let size = if occ.is_empty() && case % 4 == 0 {
                20.0
            } else if rng.random_bool(0.15) {
                1e-6
            } else {
                rng.random_range(0.02..0.3)
            };
            let kind = rng.random_range(0..8);
            let mut corner = || {
                [
                    c[0] + size * rng.random_range(-1.0..1.0),
                    c[1] + size * rng.random_range(-0.5..0.5),
                    c[2] + size * rng.random_range(-1.0..1.0),
                ]
            };
            let t = [corner(), corner(), corner()];
            match kind {
                // The same triangle twice, the other way round.
                0 => occ.extend([t, [t[2], t[1], t[0]]]),
                // A fan of three about the first corner.
                1 => {
                    let (d, e) = (corner(), corner());
                    occ.extend([t, [t[0], t[2], d], [t[0], d, e]]);
                }
                _ => occ.push(t),
            }
        }
        let n = unit([
            rng.random_range(-2.0..2.0),
            1.0,
            rng.random_range(-2.0..2.0),
        ]);
        let sided = if case % 3 == 0 { TwoSided } else { OneSided };
        let (_, _, by_outlines) = checked(&light, &occ, p, n, sided, case);
        outlined += usize::from(by_outlines);
    }
    println!("{outlined} by outlines");
    assert!(outlined >= 50, "{outlined} cases by outlines");
}
