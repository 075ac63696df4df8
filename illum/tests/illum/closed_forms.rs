//! Closed forms derived independently of the contour sum.

use crate::{assert_rel, rect_light};
use illum::{Sidedness::OneSided, contour_integral};
use std::f64::consts::PI;

/// Form factor from a differential element to a parallel rectangle
/// `X * Y` (in units of the height) with one corner straight above it.
fn corner_form_factor(x: f64, y: f64) -> f64 {
    let sx = (1.0 + x * x).sqrt();
    let sy = (1.0 + y * y).sqrt();
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

#[test]
fn square_on_axis() {
    // E = L pi F with F four corner rectangles of a x a at height h,
    // which simplifies to 4 L s atan(s), s = a / sqrt(a^2 + h^2).
    for &(a, h, l) in &[
        (1.0, 1.0, 1.0),
        (0.3, 2.0, 3.5),
        (5.0, 0.01, 0.7),
        (1e-3, 10.0, 2.0),
    ] {
        let light = rect_light(-a, a, -a, a, h, l);
        let e = light.irradiance([0.0; 3], [0.0, 0.0, 1.0], OneSided);
        let via_corners = l * PI * 4.0 * corner_form_factor(a / h, a / h);
        let s = a / (a * a + h * h).sqrt();
        let closed = l * 4.0 * s * s.atan();
        assert_rel(via_corners, closed, 1e-14);
        assert_rel(e, closed, 1e-13);
    }
}

#[test]
fn parallel_rectangle_above_a_corner() {
    for &(a, b, h) in &[(1.0, 2.0, 1.0), (0.5, 3.0, 0.2), (10.0, 0.1, 4.0)] {
        let light = rect_light(0.0, a, 0.0, b, h, 1.0);
        let e = light.irradiance([0.0; 3], [0.0, 0.0, 1.0], OneSided);
        assert_rel(e, PI * corner_form_factor(a / h, b / h), 1e-13);
        // Same from the opposite corner.
        let e2 = light.irradiance([a, b, 0.0], [0.0, 0.0, 1.0], OneSided);
        assert_rel(e2, e, 1e-13);
    }
}

#[test]
fn rectangle_off_corner_by_superposition() {
    // p below (0, 0); rectangle [1, 3] x [2, 5] at h = 1.5 as
    // F(3,5) - F(1,5) - F(3,2) + F(1,2).
    let h = 1.5;
    let f = |x: f64, y: f64| corner_form_factor(x / h, y / h);
    let want = PI * (f(3.0, 5.0) - f(1.0, 5.0) - f(3.0, 2.0) + f(1.0, 2.0));
    let light = rect_light(1.0, 3.0, 2.0, 5.0, h, 1.0);
    let e = light.irradiance([0.0; 3], [0.0, 0.0, 1.0], OneSided);
    assert_rel(e, want, 1e-12);
}

#[test]
fn point_on_the_light_plane_gets_nothing() {
    let light = rect_light(-1.0, 1.0, -1.0, 1.0, 2.0, 1.0);
    for p in [
        [0.0, 0.0, 2.0],
        [5.0, 0.0, 2.0],
        [1.0, 3.0, 2.0],
        [0.5, 0.5, 2.0],
    ] {
        for n in [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]] {
            assert_eq!(light.irradiance(p, n, OneSided), 0.0);
        }
    }
    // Behind it too.
    assert_eq!(
        light.irradiance([0.0, 0.0, 3.0], [0.0, 0.0, -1.0], OneSided),
        0.0
    );
}

#[test]
fn light_half_below_the_horizon() {
    // Light [-a, a] x [-b, b] at z = h, receiver at the origin facing +x:
    // only x > 0 counts. By hand, edge by edge (x = 0: angle 2 atan(b/h),
    // plane normal +-x; y = +-b: planes contain x, cosine 0; x = a: angle
    // 2 atan(b / sqrt(a^2 + h^2)), cosine h / sqrt(a^2 + h^2)):
    // E / L = atan(b/h) - h / sqrt(a^2+h^2) * atan(b / sqrt(a^2+h^2)).
    for &(a, b, h) in &[(1.0, 1.0, 1.0), (2.0, 0.5, 0.3), (0.1, 4.0, 2.0)] {
        let light = rect_light(-a, a, -b, b, h, 1.0);
        let e = light.irradiance([0.0; 3], [1.0, 0.0, 0.0], OneSided);
        let r = (a * a + h * h).sqrt();
        let want = (b / h).atan() - h / r * (b / r).atan();
        assert_rel(e, want, 1e-13);
        // Facing -x sees the other half, the same by symmetry.
        let e2 = light.irradiance([0.0; 3], [-1.0, 0.0, 0.0], OneSided);
        assert_rel(e2, want, 1e-13);
        // Equal to the contour integral of the half above the horizon.
        let half = crate::rect_down(0.0, a, -b, b, h);
        assert_rel(
            contour_integral(&half, [0.0; 3], [1.0, 0.0, 0.0]),
            want,
            1e-13,
        );
    }
}

#[test]
fn two_sided_receiver_takes_both_sides() {
    let light = rect_light(-1.0, 1.0, -1.0, 1.0, 2.0, 1.0);
    let p = [0.2, -0.1, 0.0];
    let up = [0.0, 0.0, 1.0];
    let down = [0.0, 0.0, -1.0];
    let one = light.irradiance(p, up, OneSided);
    assert_eq!(light.irradiance(p, down, OneSided), 0.0);
    assert_eq!(light.irradiance(p, down, illum::Sidedness::TwoSided), one);
    // Edge-on receiver: both halves add up.
    let x = [1.0, 0.0, 0.0];
    let sum = light.irradiance(p, x, OneSided) + light.irradiance(p, [-1.0, 0.0, 0.0], OneSided);
    assert_rel(
        light.irradiance(p, x, illum::Sidedness::TwoSided),
        sum,
        1e-15,
    );
}

#[test]
fn far_light_is_a_point_light() {
    // A light of area A, radiance L at distance d: intensity L A.
    let (a, l) = (0.5, 2.0);
    for d in [1e3, 1e6, 1e9] {
        let light = rect_light(-a, a, -a, a, d, l);
        let e = light.irradiance([0.0; 3], [0.0, 0.0, 1.0], OneSided);
        let area = 4.0 * a * a;
        assert_rel(e, l * area / (d * d), 1e-6);
    }
}

#[test]
fn near_the_plane_is_continuous() {
    // Under the middle, approaching the light plane: E -> pi L (a full
    // hemisphere), monotonically.
    let light = rect_light(-1.0, 1.0, -1.0, 1.0, 1.0, 1.0);
    let mut last = 0.0;
    for k in 1..=15 {
        let h = 10f64.powi(-k);
        let e = light.irradiance([0.0, 0.0, 1.0 - h], [0.0, 0.0, 1.0], OneSided);
        assert!(e >= last && e <= PI * (1.0 + 1e-15), "{h}: {e}");
        last = e;
    }
    assert_rel(last, PI, 1e-12);
    // Beside it, E -> 0.
    let e = light.irradiance([3.0, 0.0, 1.0 - 1e-12], [0.0, 0.0, 1.0], OneSided);
    assert!((0.0..1e-20).contains(&e), "{e}");
}
