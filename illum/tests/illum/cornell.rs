//! The Cornell box light, unoccluded, against reference values.
//!
//! The light's corners are listed in the order that makes its
//! counter-clockwise normal point down (-y), into the box:
//! (343, 548.8, 227) -> (343, 548.8, 332) -> (213, 548.8, 332) ->
//! (213, 548.8, 227); the first two edges are +z then -x, and
//! (+z) x (-x) = -y.

use crate::unit;
use illum::{AreaLight, Sidedness::OneSided};

fn light() -> AreaLight {
    AreaLight::new(
        &[
            [343.0, 548.8, 227.0],
            [343.0, 548.8, 332.0],
            [213.0, 548.8, 332.0],
            [213.0, 548.8, 227.0],
        ],
        1.0,
    )
    .unwrap()
}

/// Agreement to 7 significant digits: `e` rounded to 7 digits is the
/// reference (itself given rounded to 7 digits).
#[track_caller]
fn assert_7_digits(e: f64, want: f64) {
    assert_eq!(
        format!("{e:.6e}"),
        format!("{want:.6e}"),
        "{e:.12e} vs {want:.12e}"
    );
}

/// Agreement with a value computed independently in 30-digit arithmetic
/// (mpmath: the same contour formula, and for the tall block also an adaptive
/// double quadrature of cos cos' / r^2 over the light split at the horizon
/// line; both give 0.00276567852258151...).
#[track_caller]
fn assert_reference(e: f64, precise: f64) {
    let rel = ((e - precise) / precise).abs();
    assert!(rel < 1e-12, "{e:.15e} vs {precise:.15e} (relative {rel:e})");
}

#[test]
fn light_points_down() {
    assert_eq!(light().normal(), [0.0, -1.0, 0.0]);
}

#[test]
fn floor_centre() {
    let e = light().irradiance([278.0, 0.0, 279.6], [0.0, 1.0, 0.0], OneSided);
    assert_7_digits(e, 0.044632472);
    assert_reference(e, 0.044_632_471_779_722_22);
}

#[test]
fn back_wall() {
    let e = light().irradiance([278.0, 274.4, 559.2], [0.0, 0.0, -1.0], OneSided);
    assert_7_digits(e, 0.043652624);
    assert_reference(e, 0.043_652_624_453_716_23);
}

#[test]
fn tall_block_face_needs_the_horizon_clip() {
    // Outward normal of the tall block's face through (265, y, 296) and
    // (423, y, 247): perpendicular to (158, 0, -49), towards -z.
    let n = unit([-49.0, 0.0, -158.0]);
    assert!((n[0] + 0.2962).abs() < 1e-4 && (n[2] + 0.9551).abs() < 1e-4);
    let p = [344.0, 100.0, 271.5];
    let l = light();
    // The face's tangent plane cuts the light.
    let above = l
        .vertices()
        .iter()
        .filter(|v| (0..3).map(|k| (v[k] - p[k]) * n[k]).sum::<f64>() > 0.0)
        .count();
    assert!(above > 0 && above < 4, "{above}");
    let e = l.irradiance(p, n, OneSided);
    assert_7_digits(e, 0.002765679);
    assert_reference(e, 0.002_765_678_522_581_511);
    // With the rounded normal (-0.2962, 0, -0.9551) the value differs in
    // the 5th digit (0.0027655998...): the exact normal matters.
    let rounded = l.irradiance(p, [-0.2962, 0.0, -0.9551], OneSided);
    assert!((rounded - 0.002_765_599_8).abs() < 1e-10, "{rounded}");
}
