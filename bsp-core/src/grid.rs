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
/// [`GridPoint`] with at most 24 bits of magnitude. One grid step is either
/// a power of two of the scene's units ([`Grid::new`]; binary fractions snap
/// exactly) or `1`, `2` or `5` times a power of ten ([`Grid::enclosing`]
/// takes it when more of the input snaps exactly: decimal coordinates such
/// as `0.3` then come back as the very `f64` they were read from). Either
/// way at most about one bit of resolution is given up. Callers include in
/// the box everything that will seed planes: scene vertices and light
/// vertices (with some margin if lights may move).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Grid units per world unit.
    scale: f64,
    step: Step,
}

/// How a grid coordinate maps to a world coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Step {
    /// `world = grid / scale + center`, with a power-of-two `scale` and the
    /// centre on the grid: one rounding, none for binary fractions.
    Binary { center: [f64; 3] },
    /// One step is `mantissa * 10^exponent` world units and grid zero lies
    /// `origin` (an integer) steps from the world origin:
    /// `world = (grid + origin) * mantissa * 10^exponent`, computed as an
    /// exact integer times or over an exact power of ten, so a grid point
    /// comes back as the correctly rounded decimal.
    Decimal {
        mantissa: f64,
        exponent: i32,
        origin: [f64; 3],
    },
}

/// The most input points [`Grid::enclosing`] looks at to choose its step.
const SNAP_SAMPLE: usize = 4096;

/// The powers of ten that `f64` holds exactly.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

impl Grid {
    /// A grid over the box `[min, max]` with a power-of-two step.
    ///
    /// Errors: a non-finite bound, `min > max` on an axis, or a box that is a
    /// single point.
    pub fn new(min: [f64; 3], max: [f64; 3]) -> Result<Self, Error> {
        let half_extent = checked_half_extent(min, max)?;
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
        Ok(Self {
            scale,
            step: Step::Binary { center },
        })
    }

    /// A grid over the box `[min, max]` whose step is `1`, `2` or `5` times a
    /// power of ten (the finest that fits), or `None` when that power is
    /// beyond what `f64` holds exactly (steps below `1e-22` or above
    /// `5e22`).
    ///
    /// Errors: as [`Grid::new`].
    pub fn decimal(min: [f64; 3], max: [f64; 3]) -> Result<Option<Self>, Error> {
        let half_extent = checked_half_extent(min, max)?;
        let finest = half_extent / f64::from(GRID_LIMIT - 1);
        let first = finest.log10().floor() as i32 - 1;
        for exponent in first..first + 4 {
            if exponent.unsigned_abs() as usize >= POW10.len() {
                return Ok(None);
            }
            for mantissa in [1.0, 2.0, 5.0] {
                let scale = step_scale(mantissa, exponent);
                if scale * half_extent > f64::from(GRID_LIMIT - 1) {
                    continue;
                }
                let origin = [0, 1, 2]
                    .map(|a| to_steps(0.5 * (min[a] + max[a]), mantissa, exponent).round());
                let grid = Self {
                    scale,
                    step: Step::Decimal {
                        mantissa,
                        exponent,
                        origin,
                    },
                };
                let fits = (0..3).all(|a| {
                    [min[a], max[a]]
                        .iter()
                        .all(|&v| grid.units(a, v).abs() <= f64::from(GRID_LIMIT - 1))
                });
                // Origins beyond 2^53 steps are not exact integers: the
                // box is then far from the world origin for its size.
                if fits && origin.iter().all(|o| o.abs() < 2f64.powi(52)) {
                    return Ok(Some(grid));
                }
            }
        }
        Ok(None)
    }

    /// A grid over the bounding box of `points`, grown by `margin` (a
    /// fraction of the largest extent) on every side.
    ///
    /// Its step is a power of two ([`Grid::new`]) unless a decimal step
    /// ([`Grid::decimal`]) snaps strictly more of the points' coordinates
    /// exactly (of at most 4096 points, evenly spread over the list): scene files written in decimals then keep their vertices,
    /// planes and areas to the last bit, and binary input keeps its grid.
    pub fn enclosing<'a>(
        points: impl IntoIterator<Item = &'a [f64; 3]>,
        margin: f64,
    ) -> Result<Self, Error> {
        Self::fitted(points, margin, &[])
    }

    /// [`Grid::enclosing`], with `lengths` (displacements the caller will
    /// move things by, such as `umbra update`'s step) counted among the
    /// values the chosen step should hold exactly: a dyadic scene moved by
    /// `0.1` takes the decimal grid, on which the moves are exact.
    pub fn fitted<'a>(
        points: impl IntoIterator<Item = &'a [f64; 3]>,
        margin: f64,
        lengths: &[f64],
    ) -> Result<Self, Error> {
        let points: Vec<&[f64; 3]> = points.into_iter().collect();
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for p in &points {
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
        let (min, max) = (min.map(|v| v - grow), max.map(|v| v + grow));
        let binary = Self::new(min, max)?;
        // At most SNAP_SAMPLE points, evenly spread, decide: a million
        // triangles' corners would cost more than the rest of the choice.
        let stride = points.len().div_ceil(SNAP_SAMPLE).max(1);
        let sample: Vec<&[f64; 3]> = points.iter().step_by(stride).copied().collect();
        let exact = |grid: &Self| -> usize {
            let coordinates: usize = sample
                .iter()
                .map(|p| (0..3).filter(|&a| grid.holds(a, p[a])).count())
                .sum();
            coordinates + lengths.iter().filter(|&&l| grid.holds_length(l)).count()
        };
        let on_binary = exact(&binary);
        if on_binary == 3 * sample.len() + lengths.len() {
            return Ok(binary);
        }
        Ok(match Self::decimal(min, max)? {
            Some(decimal) if exact(&decimal) > on_binary => decimal,
            _ => binary,
        })
    }

    /// World length of one grid step.
    pub fn cell_size(&self) -> f64 {
        1.0 / self.scale
    }

    /// Grid units per world unit.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Whether the step is decimal (see [`Grid::decimal`]).
    pub fn is_decimal(&self) -> bool {
        matches!(self.step, Step::Decimal { .. })
    }

    /// A world length (a displacement along one axis) in grid units, not
    /// rounded: decimal lengths such as `0.1` on a decimal grid come out
    /// whole.
    pub fn length_to_units(&self, length: f64) -> f64 {
        match self.step {
            Step::Binary { .. } => length * self.scale,
            Step::Decimal {
                mantissa, exponent, ..
            } => to_steps(length, mantissa, exponent),
        }
    }

    /// Snaps a world point to the nearest grid point.
    ///
    /// Errors: a non-finite coordinate, or a point outside the grid's box.
    pub fn snap(&self, p: [f64; 3]) -> Result<GridPoint, Error> {
        let mut g = [0_i32; 3];
        for axis in 0..3 {
            check_finite(axis, p[axis])?;
            let v = self.units(axis, p[axis]).round();
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
        [0, 1, 2].map(|a| self.world(a, p[a]))
    }

    /// Grid units (fractional) of a world point, without rounding.
    pub fn world_to_grid(&self, p: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|a| self.units(a, p[a]))
    }

    /// Grid units of world coordinate `v` on `axis`, not rounded.
    fn units(&self, axis: usize, v: f64) -> f64 {
        match self.step {
            Step::Binary { center } => (v - center[axis]) * self.scale,
            Step::Decimal {
                mantissa,
                exponent,
                origin,
            } => to_steps(v, mantissa, exponent) - origin[axis],
        }
    }

    /// World coordinate of grid coordinate `g` on `axis`.
    fn world(&self, axis: usize, g: f64) -> f64 {
        match self.step {
            Step::Binary { center } => g / self.scale + center[axis],
            Step::Decimal {
                mantissa,
                exponent,
                origin,
            } => {
                // One rounding: `(g + origin) * mantissa` is an exact
                // integer for grid points.
                times_pow10((g + origin[axis]) * mantissa, exponent)
            }
        }
    }

    /// Whether the world length `length` is a whole number of steps,
    /// exactly.
    fn holds_length(&self, length: f64) -> bool {
        let units = self.length_to_units(length).round();
        let back = match self.step {
            Step::Binary { .. } => units / self.scale,
            Step::Decimal {
                mantissa, exponent, ..
            } => times_pow10(units * mantissa, exponent),
        };
        units.abs() <= f64::from(GRID_LIMIT) && back == length
    }

    /// Whether world coordinate `v` on `axis` is a grid point exactly.
    fn holds(&self, axis: usize, v: f64) -> bool {
        let g = self.units(axis, v).round();
        g.abs() <= f64::from(GRID_LIMIT - 1) && self.world(axis, g) == v
    }
}

/// `n * 10^exponent` in one rounding: a product or a quotient by an exact
/// power of ten.
fn times_pow10(n: f64, exponent: i32) -> f64 {
    if exponent < 0 {
        n / POW10[exponent.unsigned_abs() as usize]
    } else {
        n * POW10[exponent as usize]
    }
}

/// World length `v` in decimal steps of `mantissa * 10^exponent`.
fn to_steps(v: f64, mantissa: f64, exponent: i32) -> f64 {
    let v = if exponent < 0 {
        v * POW10[exponent.unsigned_abs() as usize]
    } else {
        v / POW10[exponent as usize]
    };
    v / mantissa
}

/// Grid units per world unit for a decimal step.
fn step_scale(mantissa: f64, exponent: i32) -> f64 {
    if exponent < 0 {
        POW10[exponent.unsigned_abs() as usize] / mantissa
    } else {
        1.0 / (mantissa * POW10[exponent as usize])
    }
}

/// Half the largest extent of a valid, non-degenerate box.
fn checked_half_extent(min: [f64; 3], max: [f64; 3]) -> Result<f64, Error> {
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
    Ok(half_extent)
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
    fn decimal_input_takes_a_decimal_grid_and_comes_back_bit_for_bit() {
        let points = [
            [-4.0, 0.0, -4.0],
            [4.0, 3.95, 4.0],
            [-0.3, 3.7, 0.3],
            [0.1, 0.2, 0.7],
            [1.0 / 3.0, 0.0, 0.0],
        ];
        let grid = Grid::enclosing(points.iter(), 0.01).unwrap();
        assert!(grid.is_decimal());
        // The finest step that fits the box, one of 1, 2, 5 times 10^k.
        let binary = Grid::new([-4.08, -0.0795, -4.08], [4.08, 4.0295, 4.08]).unwrap();
        assert!(grid.cell_size() >= binary.cell_size());
        assert!(grid.cell_size() <= 2.5 * binary.cell_size());
        for p in &points[..4] {
            let (g, d) = grid.snap_with_distance(*p).unwrap();
            assert_eq!(d, 0.0, "{p:?}");
            assert_eq!(grid.to_world(g), *p);
        }
        // What no grid holds still snaps to the nearest point.
        let (_, d) = grid.snap_with_distance(points[4]).unwrap();
        assert!(d > 0.0 && d <= 0.5 * grid.cell_size());
        assert_eq!(grid.length_to_units(0.1), (0.1 * grid.scale()).round());
        assert_eq!(grid.length_to_units(0.1).fract(), 0.0);
    }

    #[test]
    fn binary_input_keeps_the_power_of_two_grid() {
        // 2^-12 needs 12 decimals: only the binary grid holds these.
        let points = [
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.000244140625, 0.5, 0.75],
        ];
        let grid = Grid::enclosing(points.iter(), 0.0).unwrap();
        assert!(!grid.is_decimal());
        for p in &points {
            assert_eq!(grid.snap_with_distance(*p).unwrap().1, 0.0);
        }
        // Ties (both grids hold everything) keep the binary one too.
        let halves = [[0.0; 3], [2.0, 0.5, 1.25]];
        assert!(!Grid::enclosing(halves.iter(), 0.1).unwrap().is_decimal());
    }

    #[test]
    fn lengths_to_move_by_count_towards_the_step() {
        let halves = [[0.0; 3], [2.0, 0.5, 1.25]];
        let grid = Grid::fitted(halves.iter(), 0.1, &[-0.1, 0.05]).unwrap();
        assert!(grid.is_decimal());
        assert_eq!(grid.length_to_units(-0.1).fract(), 0.0);
        for p in &halves {
            assert_eq!(grid.snap_with_distance(*p).unwrap().1, 0.0);
        }
        // Dyadic steps keep the binary grid.
        assert!(
            !Grid::fitted(halves.iter(), 0.1, &[0.25])
                .unwrap()
                .is_decimal()
        );
    }

    #[test]
    fn decimal_grids_far_from_the_origin_and_of_any_size() {
        for (lo, hi) in [
            ([1000.0, 1000.0, 1000.0], [1000.5, 1000.1, 1000.2]),
            ([-3e9, 0.0, 0.0], [2e9, 1.0, 1.0]),
            ([1e-9, 0.0, 0.0], [3e-9, 1e-9, 1e-9]),
        ] {
            let grid = Grid::decimal(lo, hi).unwrap().unwrap();
            for p in [lo, hi] {
                let g = grid.snap(p).unwrap();
                let back = grid.to_world(g);
                for a in 0..3 {
                    assert!((back[a] - p[a]).abs() <= 0.5 * grid.cell_size() * (1.0 + 1e-9));
                }
            }
        }
        assert_eq!(Grid::decimal([0.0; 3], [1e-30; 3]).unwrap(), None);
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
