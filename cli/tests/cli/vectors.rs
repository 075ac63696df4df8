//! The few `f64` vector operations and sample points the tests' oracles
//! share.

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| a[k] - b[k])
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub fn norm(v: [f64; 3]) -> f64 {
    dot(v, v).sqrt()
}

/// Newell's normal of a polygon: twice its vector area (taken relative to
/// its first corner, so that it keeps its digits far from the origin).
pub fn newell(points: &[[f64; 3]]) -> [f64; 3] {
    let mut n = [0.0; 3];
    let o = points.first().copied().unwrap_or_default();
    for (i, a) in points.iter().enumerate() {
        let (a, b) = (sub(*a, o), sub(points[(i + 1) % points.len()], o));
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// Points inside a convex polygon: its centre, and halfway from it to
/// each corner.
pub fn inner_points(corners: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let n = corners.len() as f64;
    let centre: [f64; 3] = std::array::from_fn(|k| corners.iter().map(|c| c[k]).sum::<f64>() / n);
    corners
        .iter()
        .map(|c| std::array::from_fn(|k| 0.5 * (c[k] + centre[k])))
        .chain([centre])
        .collect()
}
