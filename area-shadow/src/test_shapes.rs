//! Shapes the unit tests of several modules build.

use bsp_core::{ConvexPolygon, GridPoint, Plane};

/// The six faces of the box from `lo` to `hi`, facing out.
pub(crate) fn cuboid(lo: [i32; 3], hi: [i32; 3]) -> Vec<ConvexPolygon> {
    let g = |x, y, z| GridPoint { x, y, z };
    let ([a, b, c], [d, e, f]) = (lo, hi);
    let faces = [
        [g(a, b, c), g(a, e, c), g(d, e, c), g(d, b, c)],
        [g(a, b, f), g(d, b, f), g(d, e, f), g(a, e, f)],
        [g(a, b, c), g(d, b, c), g(d, b, f), g(a, b, f)],
        [g(a, e, c), g(a, e, f), g(d, e, f), g(d, e, c)],
        [g(a, b, c), g(a, b, f), g(a, e, f), g(a, e, c)],
        [g(d, b, c), g(d, e, c), g(d, e, f), g(d, b, f)],
    ];
    faces
        .iter()
        .map(|f| ConvexPolygon::from_grid_points(f, 0).unwrap())
        .collect()
}

/// A torus about the y axis, its ring of radius `big`, its tube of
/// radius `small`, in `rings` x `segments` quads cut into triangles
/// facing out: the triangles' corners and planes.
pub(crate) fn torus(
    big: f64,
    small: f64,
    rings: u32,
    segments: u32,
) -> (Vec<[GridPoint; 3]>, Vec<Plane>) {
    let at = |i: u32, j: u32| {
        let (u, v) = (
            std::f64::consts::TAU * f64::from(i % rings) / f64::from(rings),
            std::f64::consts::TAU * f64::from(j % segments) / f64::from(segments),
        );
        let r = big + small * v.cos();
        GridPoint::new(
            (r * u.cos()).round() as i64,
            (small * v.sin()).round() as i64,
            (r * u.sin()).round() as i64,
        )
        .expect("a grid point")
    };
    let mut triangles = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    let planes = triangles
        .iter()
        .map(|t| Plane::through(t[0], t[1], t[2]).expect("a triangle"))
        .collect();
    (triangles, planes)
}

/// The winding number of `p` about the triangles, as the sum of the
/// solid angles they subtend over 4 pi (floating point; a method
/// independent of the ray crossings of `groups`' winding numbers).
pub(crate) fn solid_angle_winding(p: [f64; 3], triangles: &[[GridPoint; 3]]) -> f64 {
    let sub = |a: [f64; 3]| [a[0] - p[0], a[1] - p[1], a[2] - p[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let len = |a: [f64; 3]| dot(a, a).sqrt();
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|q| sub(q.to_f64()));
            let (la, lb, lc) = (len(a), len(b), len(c));
            let numerator = dot(a, cross(b, c));
            let denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
            2.0 * numerator.atan2(denominator)
        })
        .sum::<f64>()
        / (4.0 * std::f64::consts::PI)
}
