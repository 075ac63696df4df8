//! `[f64; 3]` arithmetic for output geometry (cameras, rendering, scene
//! checks): floating point, never a topological decision.

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// `a` divided by its largest component's magnitude (a zero vector as
/// it is): lengths and products of the result neither overflow nor
/// underflow, however large or small `a` is.
pub(crate) fn by_largest(a: [f64; 3]) -> [f64; 3] {
    let largest = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if largest > 0.0 {
        a.map(|x| x / largest)
    } else {
        a
    }
}

pub(crate) fn normalize(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}
