//! The light as the shadow polygons see it: a point, or a direction.
//!
//! Every decision about a shadow polygon is an orientation of four explicit
//! points. For a point light the fourth is the light itself; for a
//! directional light travelling along `d` it is `a - d` for the edge or
//! vertex `a` in question, which gives exactly the sign the light at
//! infinity gives (`det[a - X + d, .., ..]` reduces to `det[d, .., ..]`).

use bsp_core::GridPoint;

use crate::LightSource;

/// The apex of a light's shadow volumes, in grid units (exact in `f64`:
/// grid coordinates and directions are below `2^25`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Apex {
    /// A point light.
    Point([f64; 3]),
    /// A directional light travelling along this vector.
    Direction([f64; 3]),
}

impl Apex {
    pub(crate) fn of(source: &LightSource) -> Self {
        match *source {
            LightSource::Point(p) => Apex::Point(p.to_f64()),
            LightSource::Directional(d) => Apex::Direction(d.map(f64::from)),
        }
    }

    /// The point standing for the light in an orientation with `a`: the
    /// light itself, or `a - d`.
    #[inline]
    pub(crate) fn beside(&self, a: [f64; 3]) -> [f64; 3] {
        match *self {
            Apex::Point(l) => l,
            Apex::Direction(d) => [a[0] - d[0], a[1] - d[1], a[2] - d[2]],
        }
    }

    /// `v` pushed away from the light by the ratio `m`: `L + m (v - L)`, or
    /// `v + m d`. Exact when `m` is an integer below `2^26` and `v` a grid
    /// point (every product and sum stays below `2^53`).
    pub(crate) fn far(&self, v: [f64; 3], m: f64) -> [f64; 3] {
        match *self {
            Apex::Point(l) => [0, 1, 2].map(|i| l[i] + m * (v[i] - l[i])),
            Apex::Direction(d) => [0, 1, 2].map(|i| v[i] + m * d[i]),
        }
    }
}

/// A grid point as exact `f64` coordinates.
#[inline]
pub(crate) fn f(p: GridPoint) -> [f64; 3] {
    p.to_f64()
}
