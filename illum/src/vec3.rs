//! Plain `[f64; 3]` vector arithmetic used by every module of the crate.

/// A point or vector in 3D: `[x, y, z]`.
pub type Vec3 = [f64; 3];

#[inline(always)]
pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
pub(crate) fn scale(a: Vec3, k: f64) -> Vec3 {
    [a[0] * k, a[1] * k, a[2] * k]
}

#[inline(always)]
pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
pub(crate) fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// `a + t (b - a)`.
#[inline(always)]
pub(crate) fn lerp(a: Vec3, b: Vec3, t: f64) -> Vec3 {
    add(a, scale(sub(b, a), t))
}

/// Twice the vector area of a polygon (Newell's normal, as a fan from the
/// first vertex): exact direction for a planar polygon, length twice its
/// area. Zero for fewer than three vertices.
pub(crate) fn area_normal(poly: &[Vec3]) -> Vec3 {
    let Some(&o) = poly.first() else {
        return [0.0; 3];
    };
    let mut acc = [0.0; 3];
    for w in poly.windows(2).skip(1) {
        acc = add(acc, cross(sub(w[0], o), sub(w[1], o)));
    }
    acc
}
