//! The errors `bsp-core` returns at its boundary.

use thiserror::Error;

/// What can go wrong when input enters the exact kernel.
///
/// Every variant is a property of the caller's data, never of the kernel's
/// arithmetic: once points are on the grid, every decision is exact.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A coordinate is NaN or infinite.
    #[error("coordinate {axis} is not finite ({value})")]
    NonFinite {
        /// 0, 1 or 2 for x, y, z.
        axis: usize,
        /// The offending value.
        value: f64,
    },
    /// The bounding box has `min > max` on some axis (for example, no points).
    #[error("the bounding box is empty")]
    EmptyBox,
    /// The bounding box is a single point, so no grid can be laid over it.
    #[error("the bounding box has zero extent")]
    DegenerateBox,
    /// A point lies outside the box the grid was built for.
    #[error("point ({x}, {y}, {z}) lies outside the grid's bounding box")]
    OutsideGrid {
        /// x of the point.
        x: f64,
        /// y of the point.
        y: f64,
        /// z of the point.
        z: f64,
    },
    /// A grid coordinate exceeds [`GRID_LIMIT`](crate::GRID_LIMIT) in magnitude.
    #[error("grid coordinate {value} exceeds the grid limit 2^24")]
    CoordinateRange {
        /// The offending coordinate.
        value: i64,
    },
    /// A polygon has fewer than three distinct, non-collinear vertices.
    #[error("polygon has fewer than three distinct non-collinear vertices")]
    TooFewVertices,
    /// A polygon's vertices enclose no area.
    #[error("polygon has zero area")]
    ZeroArea,
    /// A polygon's vertices do not lie in one plane.
    #[error("polygon is not planar")]
    NonPlanar,
    /// A polygon is not strictly convex (a reflex vertex or a self-overlap).
    #[error("polygon is not convex")]
    NonConvex,
    /// A polygon corner is a cut's implicit point (three planes meeting,
    /// even where that falls on a grid position) where a grid point is
    /// needed.
    #[error("a polygon corner is not a grid point (it was cut)")]
    ImplicitVertex,
    /// Three planes do not meet in a single point.
    #[error("the planes do not meet in a single point")]
    NoIntersection,
}
