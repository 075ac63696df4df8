//! Generators and independent oracles shared by the kernel's tests.

use bsp_core::{ConvexPolygon, GridPoint, Plane};
use proptest::prelude::*;

pub fn gp(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).expect("test point within the grid")
}

/// 2D convex hull (counter-clockwise, no collinear points), exact.
pub fn hull_2d(mut pts: Vec<(i64, i64)>) -> Vec<(i64, i64)> {
    pts.sort();
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: (i64, i64), a: (i64, i64), b: (i64, i64)| {
        i128::from(a.0 - o.0) * i128::from(b.1 - o.1)
            - i128::from(a.1 - o.1) * i128::from(b.0 - o.0)
    };
    let mut lower: Vec<(i64, i64)> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<(i64, i64)> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// A convex polygon in 3D: a 2D convex hull mapped by `o + a u + b v`
/// (affine, so planar and convex exactly).
pub fn planar_convex(
    origin: [i64; 3],
    u: [i64; 3],
    v: [i64; 3],
    pts2d: Vec<(i64, i64)>,
    source: u32,
) -> Option<ConvexPolygon> {
    let hull = hull_2d(pts2d);
    let pts: Vec<GridPoint> = hull
        .iter()
        .map(|&(a, b)| {
            GridPoint::new(
                origin[0] + a * u[0] + b * v[0],
                origin[1] + a * u[1] + b * v[1],
                origin[2] + a * u[2] + b * v[2],
            )
        })
        .collect::<Result<_, _>>()
        .ok()?;
    ConvexPolygon::from_grid_points(&pts, source).ok()
}

/// Strategy: a random convex polygon with coordinates of magnitude below
/// `scale`.
pub fn convex_polygon(scale: i64) -> impl Strategy<Value = ConvexPolygon> {
    let c = scale / 4;
    let axis = -8_i64..=8;
    (
        prop::array::uniform3(-c..=c),
        prop::array::uniform3(axis.clone()),
        prop::array::uniform3(axis),
        prop::collection::vec(
            (
                -(c / 8).max(1)..=(c / 8).max(1),
                -(c / 8).max(1)..=(c / 8).max(1),
            ),
            3..9,
        ),
    )
        .prop_filter_map("degenerate polygon", |(o, u, v, pts)| {
            planar_convex(o, u, v, pts, 7)
        })
}

/// Strategy: a grid point with coordinates of magnitude at most `scale`.
pub fn grid_point(scale: i64) -> impl Strategy<Value = GridPoint> {
    prop::array::uniform3(-scale..=scale).prop_map(|[x, y, z]| gp(x, y, z))
}

/// Strategy: a plane through three grid points.
pub fn plane(scale: i64) -> impl Strategy<Value = Plane> {
    (grid_point(scale), grid_point(scale), grid_point(scale))
        .prop_filter_map("collinear", |(a, b, c)| Plane::through(a, b, c))
}

/// Exact orientation of four `f64` points (Shewchuk, via `robust`): positive
/// when `d` is below the plane of `a`, `b`, `c` seen counter-clockwise.
pub fn orient(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let p = |v: [f64; 3]| robust::Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// Whether the open segment `pq` crosses the interior of triangle `abc`,
/// decided exactly on the `f64` inputs. Touching cases count as no crossing.
pub fn segment_crosses_triangle(
    p: [f64; 3],
    q: [f64; 3],
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
) -> bool {
    let sp = orient(a, b, c, p);
    let sq = orient(a, b, c, q);
    if sp == 0.0 || sq == 0.0 || (sp > 0.0) == (sq > 0.0) {
        return false;
    }
    let s1 = orient(p, q, a, b);
    let s2 = orient(p, q, b, c);
    let s3 = orient(p, q, c, a);
    (s1 > 0.0 && s2 > 0.0 && s3 > 0.0) || (s1 < 0.0 && s2 < 0.0 && s3 < 0.0)
}

/// Whether the segment `pq` crosses the interior of a convex polygon (given
/// by its vertices), exactly on the `f64` inputs, fan by fan. A crossing
/// through a fan diagonal is missed, which only weakens the oracle.
pub fn segment_crosses_polygon(p: [f64; 3], q: [f64; 3], poly: &[[f64; 3]]) -> bool {
    (1..poly.len() - 1).any(|i| segment_crosses_triangle(p, q, poly[0], poly[i], poly[i + 1]))
}
