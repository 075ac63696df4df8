//! Soft shadows of convex area lights.
//!
//! This crate will hold the penumbra and umbra volumes and BSP trees of
//! Chin & Feiner (1992), the splitting of area lights into sub-lights with a
//! unique front-to-back order, the lit / penumbra / umbra classification,
//! gridding and adaptive subdivision, and T-vertex-free output.
//!
//! It is not implemented yet: see the project's open issues.

pub use bsp_core;
