//! Lights as the SVBSP sees them: a grid point, or a direction.

use bsp_core::predicates::{Side, side_of_direction, side_of_point};
use bsp_core::{GridPoint, Plane, Viewpoint};

/// Where light comes from, exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightSource {
    /// A point light at a grid point.
    Point(GridPoint),
    /// A directional light travelling along this vector (components below
    /// `2^24` in magnitude, not all zero).
    Directional([i32; 3]),
}

impl LightSource {
    /// Which side of `plane` the light is on. A directional light is on the
    /// side its rays come from; it is on the plane when the plane is
    /// parallel to its direction.
    #[inline]
    pub fn side(&self, plane: &Plane) -> Side {
        match *self {
            LightSource::Point(p) => side_of_point(plane, p),
            LightSource::Directional(d) => side_of_direction(plane, d).flipped(),
        }
    }

    /// Whether `plane` contains the light (for a directional light: is
    /// parallel to its rays). Such a plane is its own shadow plane.
    #[inline]
    pub fn lies_in(&self, plane: &Plane) -> bool {
        self.side(plane) == Side::On
    }

    /// The (unoriented) shadow plane of the segment `pq`: through the light
    /// and `p`, `q`. `None` if the light is on the line `pq`.
    ///
    /// Either way it passes through three grid points, or is such a plane's
    /// translate (a directional light's plane holds `p`, `q` and `p + d`,
    /// and `|d| < 2^24`), so its coefficients keep the kernel's bounds.
    pub fn shadow_plane(&self, p: GridPoint, q: GridPoint) -> Option<Plane> {
        match *self {
            LightSource::Point(l) => Plane::through(l, p, q),
            LightSource::Directional(d) => {
                let e = [
                    i64::from(q.x) - i64::from(p.x),
                    i64::from(q.y) - i64::from(p.y),
                    i64::from(q.z) - i64::from(p.z),
                ];
                let d = d.map(i64::from);
                let n = [
                    e[1] * d[2] - e[2] * d[1],
                    e[2] * d[0] - e[0] * d[2],
                    e[0] * d[1] - e[1] * d[0],
                ];
                Plane::with_normal_through(n, p)
            }
        }
    }

    /// The viewpoint for front-to-back order from the light.
    pub fn viewpoint(&self) -> Viewpoint {
        match *self {
            LightSource::Point(p) => Viewpoint::Point(p),
            LightSource::Directional(d) => Viewpoint::Direction(d.map(|c| -c)),
        }
    }
}

/// A light for the shadow pipeline: its source and, for point lights with a
/// sphere of influence (Bergeron), its range in grid units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Where the light comes from.
    pub source: LightSource,
    /// Distance (grid units) beyond which the light reaches nothing. A
    /// polygon wholly beyond it takes no part for this light: it neither
    /// receives nor casts.
    pub range: Option<f64>,
}

impl Light {
    /// A point light without a range.
    pub fn point(p: GridPoint) -> Self {
        Self {
            source: LightSource::Point(p),
            range: None,
        }
    }

    /// A directional light travelling along `d`.
    pub fn directional(d: [i32; 3]) -> Self {
        Self {
            source: LightSource::Directional(d),
            range: None,
        }
    }

    /// Whether every point of a polygon (given by its vertices, grid units)
    /// is at or beyond the range. A convex polygon is wholly beyond a sphere
    /// only if its closest point is: the vertices alone do not tell, so this
    /// measures the distance from the light to the polygon.
    pub fn wholly_beyond_range(&self, vertices: &[[f64; 3]]) -> bool {
        let (LightSource::Point(p), Some(range)) = (self.source, self.range) else {
            return false;
        };
        distance_to_polygon(p.to_f64(), vertices) >= range
    }
}

/// Distance from `x` to a convex planar polygon (f64; it only decides the
/// sphere of influence, never topology).
pub(crate) fn distance_to_polygon(x: [f64; 3], v: &[[f64; 3]]) -> f64 {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let n = (1..v.len() - 1).fold([0.0; 3], |acc, i| {
        let c = cross(sub(v[i], v[0]), sub(v[i + 1], v[0]));
        [acc[0] + c[0], acc[1] + c[1], acc[2] + c[2]]
    });
    let len = dot(n, n).sqrt();
    if len > 0.0 {
        let n = n.map(|c| c / len);
        let h = dot(sub(x, v[0]), n);
        let proj = [x[0] - h * n[0], x[1] - h * n[1], x[2] - h * n[2]];
        let inside = (0..v.len()).all(|i| {
            let e = sub(v[(i + 1) % v.len()], v[i]);
            dot(cross(e, sub(proj, v[i])), n) >= 0.0
        });
        if inside {
            return h.abs();
        }
    }
    // Closest point on the boundary.
    (0..v.len())
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let ab = sub(b, a);
            let t = (dot(sub(x, a), ab) / dot(ab, ab).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
            let c = [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]];
            dot(sub(x, c), sub(x, c)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}
