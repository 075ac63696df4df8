//! Errors of the shadow pipeline.

use thiserror::Error;

/// What the shadow pipeline rejects.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum Error {
    /// More lights than mask bits.
    #[error("{0} lights given; at most 32 are supported")]
    TooManyLights(usize),
    /// One flag entry per piece is needed.
    #[error("{pieces} pieces but {flags} flag entries")]
    FlagsLength {
        /// Number of pieces.
        pieces: usize,
        /// Number of flag entries.
        flags: usize,
    },
    /// Input pieces must have grid-point vertices, so that shadow planes
    /// can be built through their edges.
    #[error("piece {0} has vertices that are not grid points")]
    ImplicitInput(usize),
}
