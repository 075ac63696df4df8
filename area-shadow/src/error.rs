//! Errors of the area-light pipeline.

use thiserror::Error;

/// What the area-light pipeline rejects.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum Error {
    /// An area light needs at least three vertices that are grid points
    /// (every plane through its vertices and edges must stay a plane through
    /// three grid points).
    #[error("an area light needs a convex polygon with grid-point vertices")]
    LightNotOnGrid,
    /// Input pieces must have grid-point vertices, so that the planes of
    /// their volumes are planes through grid points.
    #[error("piece {0} has vertices that are not grid points")]
    ImplicitInput(usize),
    /// One flag entry per piece is needed.
    #[error("{pieces} pieces but {flags} flag entries")]
    FlagsLength {
        /// Number of pieces.
        pieces: usize,
        /// Number of flag entries.
        flags: usize,
    },
    /// More lights than mask bits.
    #[error("{0} lights given; at most 32 are supported")]
    TooManyLights(usize),
    /// A light's bit is out of range.
    #[error("light bit {0} is out of range (0..32)")]
    BitOutOfRange(u32),
    /// The point- and directional-light pass failed.
    #[error(transparent)]
    Svbsp(#[from] svbsp::Error),
}
