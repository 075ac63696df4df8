//! Integration tests of `illum`, compiled as one binary.

mod batch;
mod closed_forms;
mod cornell;
mod errors;
mod monte_carlo;
mod occluder_index;
mod outline;
mod silhouette;
mod symmetry;

use illum::{AreaLight, Vec3};

/// A rectangle `[x0, x1] x [y0, y1]` in the plane `z = h`, counter-clockwise
/// seen from below (it emits towards -z).
pub fn rect_down(x0: f64, x1: f64, y0: f64, y1: f64, h: f64) -> Vec<Vec3> {
    vec![[x0, y0, h], [x0, y1, h], [x1, y1, h], [x1, y0, h]]
}

/// `rect_down` as a light of radiance `l`.
pub fn rect_light(x0: f64, x1: f64, y0: f64, y1: f64, h: f64, l: f64) -> AreaLight {
    AreaLight::new(&rect_down(x0, x1, y0, y1, h), l).unwrap()
}

/// `|a - b| <= tol * |b|`.
#[track_caller]
pub fn assert_rel(a: f64, b: f64, tol: f64) {
    assert!(
        (a - b).abs() <= tol * b.abs(),
        "{a} vs {b}: relative error {:e}",
        (a - b).abs() / b.abs()
    );
}

/// `v / |v|`.
pub fn unit(v: Vec3) -> Vec3 {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

/// `a - b`.
pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a . b`.
pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a x b`.
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
