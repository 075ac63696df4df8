//! Errors of the discontinuity-mesh library.

use thiserror::Error;

/// What [`DmScene`](crate::DmScene) rejects.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum Error {
    /// More lights than mask bits.
    #[error("{0} lights given; at most 32 are supported")]
    TooManyLights(usize),
    /// An area light's radiance must be finite and not negative.
    #[error("light {0}: radiance must be finite and not negative")]
    BadRadiance(usize),
    /// Polygons must have grid-point vertices (every discontinuity plane is
    /// then a plane through three grid points).
    #[error("polygon {0} of the object has vertices that are not grid points")]
    ImplicitInput(usize),
    /// A translation takes the object's polygon off the grid (a
    /// coordinate past [`bsp_core::GRID_LIMIT`]).
    #[error("polygon {0} of the object would leave the grid")]
    OffGrid(usize),
    /// The object handle names no object of the scene (removed already?).
    #[error("no such object (it was removed, or belongs to another scene)")]
    UnknownObject,
    /// The piece handle names no receiver of the scene.
    #[error("no such receiver (its object was moved or removed, or it belongs to another scene)")]
    UnknownPiece,
    /// A receiver normal must be finite and not zero.
    #[error("a receiver normal must be finite and not zero")]
    BadNormal,
    /// The light polygon is not usable for illumination.
    #[error("light {0}: {1}")]
    Light(usize, String),
}
