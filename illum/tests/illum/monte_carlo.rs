//! The visible-part contour integral against Monte Carlo integration of
//! `E = L * integral over the light of cos(t) cos(t') / r^2 dA`, with an
//! exact occlusion test (segment against occluder triangles).

use crate::{cross, dot, sub, unit};
use illum::{AreaLight, Sidedness::OneSided, Vec3, VisiblePart, visible_irradiance};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Whether the open segment from `p` to `x` crosses triangle `t`
/// (Möller–Trumbore, both sides).
fn blocks(t: &[Vec3; 3], p: Vec3, x: Vec3) -> bool {
    let d = sub(x, p);
    let e1 = sub(t[1], t[0]);
    let e2 = sub(t[2], t[0]);
    let h = cross(d, e2);
    let det = dot(e1, h);
    if det == 0.0 {
        return false;
    }
    let inv = 1.0 / det;
    let s = sub(p, t[0]);
    let u = dot(s, h) * inv;
    if !(0.0..=1.0).contains(&u) {
        return false;
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return false;
    }
    let tt = dot(e2, q) * inv;
    tt > 0.0 && tt < 1.0
}

struct Estimate {
    mean: f64,
    std_error: f64,
}

/// Uniform samples over the light rectangle `[-a, a]^2` at `y = h`.
fn monte_carlo(
    a: f64,
    h: f64,
    occ: &[[Vec3; 3]],
    p: Vec3,
    n: Vec3,
    samples: usize,
    rng: &mut Pcg64,
) -> Estimate {
    let area = 4.0 * a * a;
    let (mut s1, mut s2) = (0.0, 0.0);
    for _ in 0..samples {
        let x = [rng.random_range(-a..a), h, rng.random_range(-a..a)];
        let d = sub(x, p);
        let r2 = dot(d, d);
        let r = r2.sqrt();
        let cos_r = dot(n, d) / r;
        let cos_l = (p[1] - h) / -r; // light normal is -y; d points to it.
        let mut f = 0.0;
        if cos_r > 0.0 && cos_l > 0.0 && !occ.iter().any(|t| blocks(t, p, x)) {
            f = area * cos_r * cos_l / r2;
        }
        s1 += f;
        s2 += f * f;
    }
    let m = s1 / samples as f64;
    let var = (s2 / samples as f64 - m * m).max(0.0);
    Estimate {
        mean: m,
        std_error: (var / samples as f64).sqrt(),
    }
}

#[test]
fn visible_part_matches_monte_carlo() {
    let mut rng = Pcg64::seed_from_u64(1992);
    let (a, h) = (2.0, 10.0);
    // Counter-clockwise seen from below: emits -y.
    let light = AreaLight::new(&[[-a, h, -a], [a, h, -a], [a, h, a], [-a, h, a]], 1.0).unwrap();
    assert_eq!(light.normal(), [0.0, -1.0, 0.0]);
    let mut scratch = VisiblePart::new();
    let samples = 500_000;
    let (mut partial, mut clipped, mut checked) = (0, 0, 0);
    let mut worst_z = 0.0_f64;
    for case in 0..24 {
        let count = 1 + case % 3;
        let occ: Vec<[Vec3; 3]> = (0..count)
            .map(|_| {
                let c = [
                    rng.random_range(-1.5..1.5),
                    rng.random_range(3.0..8.0),
                    rng.random_range(-1.5..1.5),
                ];
                std::array::from_fn(|_| {
                    [
                        c[0] + rng.random_range(-1.5..1.5),
                        c[1] + rng.random_range(-0.5..0.5),
                        c[2] + rng.random_range(-1.5..1.5),
                    ]
                })
            })
            .collect();
        let p = [
            rng.random_range(-3.0..3.0),
            rng.random_range(0.0..1.0),
            rng.random_range(-3.0..3.0),
        ];
        // Normals up to ~80 degrees from +y: some cut the light.
        let n = unit([
            rng.random_range(-4.0..4.0),
            1.0,
            rng.random_range(-4.0..4.0),
        ]);
        let full = light.irradiance(p, n, OneSided);
        let e = visible_irradiance(&light, &occ, p, n, OneSided, &mut scratch);
        let mc = monte_carlo(a, h, &occ, p, n, samples, &mut rng);
        let diff = (e - mc.mean).abs();
        worst_z = f64::max(worst_z, diff / mc.std_error.max(f64::MIN_POSITIVE));
        assert!(
            diff <= 4.0 * mc.std_error,
            "case {case}: contour {e}, Monte Carlo {} +- {}",
            mc.mean,
            mc.std_error
        );
        if e > 0.1 * full {
            assert!(diff <= 0.01 * e, "case {case}: {e} vs {}", mc.mean);
            checked += 1;
        }
        if e < 0.999 * full && e > 0.0 {
            partial += 1;
        }
        if light.vertices().iter().any(|v| dot(sub(*v, p), n) < 0.0) {
            clipped += 1;
        }
    }
    println!(
        "{partial} partly occluded, {clipped} clipped, {checked} checked to 1 %, \
         worst |difference| {worst_z:.2} standard errors"
    );
    // The cases exercise what they should.
    assert!(partial >= 8, "{partial} partly occluded cases");
    assert!(clipped >= 4, "{clipped} cases cut by the horizon");
    assert!(checked >= 16, "{checked} cases checked to 1 %");
}
