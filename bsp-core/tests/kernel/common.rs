//! Generators and independent oracles shared by the kernel's tests.

use bsp_core::{ConvexPolygon, GridPoint, Plane, Viewpoint};
use ethnum::I256;
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

/// Bits kept after the binary point of a sample point's coordinates.
const SAMPLE_BITS: u32 = 40;

/// A point with rational coordinates `num / den` (`den > 0`), exact.
#[derive(Debug, Clone, Copy)]
pub struct RationalPoint {
    num: [i128; 3],
    den: i128,
}

impl RationalPoint {
    /// The point of `polygon`'s plane at `q` seen along the plane's
    /// dominant axis, the other two coordinates rounded to multiples of
    /// `2^-SAMPLE_BITS`; `None` unless it lies strictly inside `polygon`.
    /// Exact, so a sight line to it cannot graze the polygon's own edges or
    /// leave its plane by rounding. Within `i128` for any grid: the rounded
    /// coordinates are below `2^64`, normals `2^51`, offsets `2^77`.
    pub fn in_polygon(polygon: &ConvexPolygon, q: [f64; 3]) -> Option<Self> {
        let support = polygon.support();
        let n = support.normal().map(i128::from);
        let a = support.dominant_axis();
        let one = 1_i128 << SAMPLE_BITS;
        let mut num = [0_i128; 3];
        // n . num + offset den = 0 with den = |n_a| 2^SAMPLE_BITS.
        let mut rest = support.offset() * one;
        for k in (0..3).filter(|&k| k != a) {
            let c = (q[k] * one as f64).round() as i128;
            num[k] = c * n[a].abs();
            rest += n[k] * c;
        }
        num[a] = -n[a].signum() * rest;
        let p = Self {
            num,
            den: n[a].abs() * one,
        };
        debug_assert_eq!(p.value(support), I256::ZERO);
        polygon
            .edges()
            .all(|e| p.value(e) < I256::ZERO)
            .then_some(p)
    }

    /// `den` times `plane`'s expression at the point (so of the same sign).
    fn value(&self, plane: &Plane) -> I256 {
        let n = plane.normal();
        (0..3).fold(
            I256::from(plane.offset()) * I256::from(self.den),
            |acc, k| acc + I256::from(n[k]) * I256::from(self.num[k]),
        )
    }
}

/// `plane`'s expression at the viewer as a homogeneous point: `(p, 1)` for
/// a point, `(d, 0)` (the point at infinity) for a direction.
fn viewer_value(plane: &Plane, view: Viewpoint) -> I256 {
    let (p, w) = match view {
        Viewpoint::Point(g) => (g.to_i64(), 1),
        Viewpoint::Direction(d) => (d.map(i64::from), 0),
    };
    let n = plane.normal();
    (0..3).fold(I256::from(plane.offset() * w), |acc, k| {
        acc + I256::from(n[k]) * I256::from(p[k])
    })
}

/// Whether the sight line from `s` to `view` (the open segment to a point
/// viewer, the open ray toward one at infinity) crosses the interior of
/// `polygon`, exactly, from its planes: touching its boundary or running in
/// its plane is no crossing. `I256` holds every product (below `2^250`).
pub fn sight_line_crosses(view: Viewpoint, s: &RationalPoint, polygon: &ConvexPolygon) -> bool {
    let support = polygon.support();
    let (ve, vs) = (viewer_value(support, view), s.value(support));
    if ve == I256::ZERO || vs == I256::ZERO || (ve > I256::ZERO) == (vs > I256::ZERO) {
        return false;
    }
    // The crossing is (ve s - vs view) / (ve - vs) homogeneously; an edge
    // plane's expression there is (ve e(s) - vs e(view)) / (ve - vs), and
    // ve - vs has the sign of ve. Inside is strictly behind every edge.
    polygon.edges().all(|e| {
        let at = ve * s.value(e) - vs * viewer_value(e, view);
        at != I256::ZERO && (at < I256::ZERO) == (ve > I256::ZERO)
    })
}
