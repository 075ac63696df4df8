//! Typed errors for bad input at the crate's boundary.

use thiserror::Error;

/// What is wrong with an input to this crate.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IllumError {
    /// An area light needs at least three vertices.
    #[error("area light has {count} vertices; at least 3 are needed")]
    TooFewVertices {
        /// How many vertices were given.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {index} of the area light has a non-finite coordinate")]
    NonFinite {
        /// Index of the offending vertex.
        index: usize,
    },
    /// The light polygon has (almost) no area.
    #[error("area light is degenerate: its area is zero or negligible for its size")]
    Degenerate,
    /// A vertex lies off the plane of the light polygon.
    #[error("vertex {index} of the area light lies {distance} off the light's plane")]
    NonPlanar {
        /// Index of the offending vertex.
        index: usize,
        /// Its distance to the plane.
        distance: f64,
    },
    /// The light polygon is not convex (or not simple).
    #[error("area light is not convex: vertex {index} lies on the outer side of edge {edge}")]
    NonConvex {
        /// Edge (from vertex `edge` to the next) that sees a vertex outside.
        edge: usize,
        /// The vertex outside.
        index: usize,
    },
    /// A radiance, intensity or irradiance that is negative or not finite.
    #[error("light strength {value} must be finite and non-negative")]
    BadStrength {
        /// The value given.
        value: f64,
    },
    /// A position or direction that is not finite, or a zero direction.
    #[error("light position or direction {value:?} is not finite or is zero")]
    BadVector {
        /// The value given.
        value: [f64; 3],
    },
    /// Falloff parameters out of range.
    #[error(
        "sphere of influence needs 0 <= falloff_start <= range, range > 0 and a positive \
         finite exponent; got start {start}, range {range}, exponent {exponent}"
    )]
    BadFalloff {
        /// `falloff_start`.
        start: f64,
        /// `range`.
        range: f64,
        /// `falloff_exponent`.
        exponent: f64,
    },
    /// The output slice of a batch does not match its input.
    #[error("batch of {receivers} receivers given an output of length {output}")]
    LengthMismatch {
        /// Number of receivers.
        receivers: usize,
        /// Length of the output slice.
        output: usize,
    },
    /// A vertex-sharing query with no fragments around the vertex.
    #[error("no fragments around the vertex")]
    NoFragments,
}
