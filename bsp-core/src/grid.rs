//! The integer grid: the only place where input coordinates are rounded.

use crate::Error;

/// Bits of magnitude of a snapped coordinate.
pub const GRID_BITS: u32 = 24;

/// Largest magnitude of any grid coordinate the kernel accepts, `2^24`.
///
/// [`Grid::snap`] maps its box into `±(GRID_LIMIT - 1)`, which leaves one
/// unit of room for the helper points that build edge planes
/// (`p + e_k`, see [`ConvexPolygon`](crate::ConvexPolygon)).
pub const GRID_LIMIT: i32 = 1 << GRID_BITS;

/// A point with integer coordinates on the grid, `|x|, |y|, |z| <= GRID_LIMIT`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct GridPoint {
    /// x coordinate in grid units.
    pub x: i32,
    /// y coordinate in grid units.
    pub y: i32,
    /// z coordinate in grid units.
    pub z: i32,
}

impl GridPoint {
    /// A grid point; returns an error if a coordinate exceeds [`GRID_LIMIT`].
    pub fn new(x: i64, y: i64, z: i64) -> Result<Self, Error> {
        let check = |v: i64| {
            if v.abs() > i64::from(GRID_LIMIT) {
                Err(Error::CoordinateRange { value: v })
            } else {
                Ok(v as i32)
            }
        };
        Ok(Self {
            x: check(x)?,
            y: check(y)?,
            z: check(z)?,
        })
    }

    /// The coordinates as an array.
    pub fn to_array(self) -> [i32; 3] {
        [self.x, self.y, self.z]
    }

    /// The coordinates as `i64`, the width difference arithmetic needs.
    pub fn to_i64(self) -> [i64; 3] {
        [i64::from(self.x), i64::from(self.y), i64::from(self.z)]
    }

    /// The coordinates as `f64` (exact).
    pub fn to_f64(self) -> [f64; 3] {
        [f64::from(self.x), f64::from(self.y), f64::from(self.z)]
    }
}

/// A uniform integer grid laid over an axis-aligned box.
///
/// The box's centre maps near the origin and its largest half-extent to at
/// most `GRID_LIMIT - 1`, so every point of the box snaps to a
/// [`GridPoint`] with at most 24 bits of magnitude. The scale is a power of
/// two (at most one bit of resolution given up), so binary fractions of
/// the scene's units snap exactly. Callers include in the box everything that
/// will seed planes: scene vertices and light vertices (with some margin if
/// lights may move).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    center: [f64; 3],
    /// Grid units per world unit.
    scale: f64,
}

impl Grid {
    /// A grid over the box `[min, max]`.
    ///
    /// Errors: a non-finite bound, `min > max` on an axis, or a box that is a
    /// single point.
    pub fn new(min: [f64; 3], max: [f64; 3]) -> Result<Self, Error> {
        for axis in 0..3 {
            check_finite(axis, min[axis])?;
            check_finite(axis, max[axis])?;
            if min[axis] > max[axis] {
                return Err(Error::EmptyBox);
            }
        }
        let half_extent = (0..3)
            .map(|a| 0.5 * (max[a] - min[a]))
            .fold(0.0_f64, f64::max);
        if half_extent <= 0.0 || !half_extent.is_finite() {
            return Err(Error::DegenerateBox);
        }
        // A power-of-two scale and a centre on the grid keep binary
        // fractions exact: inputs built on a binary lattice (1/16 steps, say)
        // snap without rounding, so their coplanar contacts survive.
        let mut scale = f64::from(GRID_LIMIT - 1) / half_extent;
        if !scale.is_finite() || scale <= 0.0 {
            return Err(Error::DegenerateBox);
        }
        scale = 2f64.powi(scale.log2().floor() as i32);
        let center = [0, 1, 2].map(|a| (0.5 * (min[a] + max[a]) * scale).round() / scale);
        // The centre moved by at most half a step: make sure the box still
        // fits.
        if (0..3).any(|a| {
            ((max[a] - center[a]) * scale).abs() > f64::from(GRID_LIMIT - 1)
                || ((min[a] - center[a]) * scale).abs() > f64::from(GRID_LIMIT - 1)
        }) {
            scale *= 0.5;
        }
        if !scale.is_finite() || scale <= 0.0 || !center.iter().all(|c| c.is_finite()) {
            return Err(Error::DegenerateBox);
        }
        Ok(Self { center, scale })
    }

    /// A grid over the bounding box of `points`, grown by `margin` (a
    /// fraction of the largest extent) on every side.
    pub fn enclosing<'a>(
        points: impl IntoIterator<Item = &'a [f64; 3]>,
        margin: f64,
    ) -> Result<Self, Error> {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for p in points {
            for axis in 0..3 {
                check_finite(axis, p[axis])?;
                min[axis] = min[axis].min(p[axis]);
                max[axis] = max[axis].max(p[axis]);
            }
        }
        if min[0] > max[0] {
            return Err(Error::EmptyBox);
        }
        let extent = (0..3).map(|a| max[a] - min[a]).fold(0.0_f64, f64::max);
        let grow = extent * margin.max(0.0);
        Self::new(min.map(|v| v - grow), max.map(|v| v + grow))
    }

    /// World length of one grid step.
    pub fn cell_size(&self) -> f64 {
        1.0 / self.scale
    }

    /// Grid units per world unit.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Snaps a world point to the nearest grid point.
    ///
    /// Errors: a non-finite coordinate, or a point outside the grid's box.
    pub fn snap(&self, p: [f64; 3]) -> Result<GridPoint, Error> {
        let mut g = [0_i32; 3];
        for axis in 0..3 {
            check_finite(axis, p[axis])?;
            let v = ((p[axis] - self.center[axis]) * self.scale).round();
            // Points of the box land within ±(GRID_LIMIT - 1); allow for the
            // rounding of the line above, nothing more.
            if v.abs() > f64::from(GRID_LIMIT - 1) {
                return Err(Error::OutsideGrid {
                    x: p[0],
                    y: p[1],
                    z: p[2],
                });
            }
            g[axis] = v as i32;
        }
        Ok(GridPoint {
            x: g[0],
            y: g[1],
            z: g[2],
        })
    }

    /// Snaps a point and also returns how far it moved (world units).
    pub fn snap_with_distance(&self, p: [f64; 3]) -> Result<(GridPoint, f64), Error> {
        let g = self.snap(p)?;
        let w = self.to_world(g);
        let d = ((w[0] - p[0]).powi(2) + (w[1] - p[1]).powi(2) + (w[2] - p[2]).powi(2)).sqrt();
        Ok((g, d))
    }

    /// Snaps many points; returns them with the largest snap distance.
    pub fn snap_all(&self, points: &[[f64; 3]]) -> Result<(Vec<GridPoint>, f64), Error> {
        let mut largest = 0.0_f64;
        let mut out = Vec::with_capacity(points.len());
        for &p in points {
            let (g, d) = self.snap_with_distance(p)?;
            largest = largest.max(d);
            out.push(g);
        }
        Ok((out, largest))
    }

    /// World coordinates of a grid point.
    pub fn to_world(&self, g: GridPoint) -> [f64; 3] {
        self.grid_to_world(g.to_f64())
    }

    /// World coordinates of a point given in (fractional) grid units, such
    /// as an implicit vertex turned into `f64`.
    pub fn grid_to_world(&self, p: [f64; 3]) -> [f64; 3] {
        [
            p[0] / self.scale + self.center[0],
            p[1] / self.scale + self.center[1],
            p[2] / self.scale + self.center[2],
        ]
    }

    /// Grid units (fractional) of a world point, without rounding.
    pub fn world_to_grid(&self, p: [f64; 3]) -> [f64; 3] {
        [
            (p[0] - self.center[0]) * self.scale,
            (p[1] - self.center[1]) * self.scale,
            (p[2] - self.center[2]) * self.scale,
        ]
    }
}

fn check_finite(axis: usize, value: f64) -> Result<(), Error> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::NonFinite { axis, value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_corners_reach_the_limit_and_round_trip() {
        let grid = Grid::new([-1.0, 0.0, 2.0], [3.0, 1.0, 2.5]).unwrap();
        let lo = grid.snap([-1.0, 0.0, 2.0]).unwrap();
        let hi = grid.snap([3.0, 1.0, 2.5]).unwrap();
        // At least 23 of the 24 bits are used.
        assert!(hi.x > (GRID_LIMIT - 1) / 2 && hi.x < GRID_LIMIT);
        assert!(lo.x < -(GRID_LIMIT - 1) / 2 && lo.x > -GRID_LIMIT);
        // Binary fractions snap exactly.
        for v in [0.0625, 1.5, -0.75, 2.9375] {
            let (_, d) = grid.snap_with_distance([v, 0.5, 2.25]).unwrap();
            assert_eq!(d, 0.0);
        }
        let w = grid.to_world(hi);
        assert!((w[0] - 3.0).abs() < 1e-12);
        let (_, d) = grid.snap_with_distance([0.123456789, 0.5, 2.2]).unwrap();
        assert!(d <= grid.cell_size() * 3f64.sqrt() / 2.0 + 1e-15);
    }

    #[test]
    fn bad_boxes_and_points_are_typed_errors() {
        assert_eq!(
            Grid::new([1.0, 0.0, 0.0], [0.0, 1.0, 1.0]),
            Err(Error::EmptyBox)
        );
        assert_eq!(Grid::new([1.0; 3], [1.0; 3]), Err(Error::DegenerateBox));
        assert!(matches!(
            Grid::new([f64::NAN, 0.0, 0.0], [1.0; 3]),
            Err(Error::NonFinite { axis: 0, .. })
        ));
        let grid = Grid::new([0.0; 3], [1.0; 3]).unwrap();
        for corner in [[0.0; 3], [1.0; 3], [0.0, 1.0, 0.0]] {
            assert!(grid.snap(corner).is_ok());
        }
        assert!(matches!(
            grid.snap([0.5, f64::INFINITY, 0.5]),
            Err(Error::NonFinite { axis: 1, .. })
        ));
        assert!(matches!(
            grid.snap([2.0, 0.5, 0.5]),
            Err(Error::OutsideGrid { .. })
        ));
        assert_eq!(
            Grid::enclosing(std::iter::empty::<&[f64; 3]>(), 0.1),
            Err(Error::EmptyBox)
        );
    }

    #[test]
    fn grid_point_range_is_checked() {
        assert!(GridPoint::new(1 << 24, 0, 0).is_ok());
        assert!(GridPoint::new((1 << 24) + 1, 0, 0).is_err());
    }
}
