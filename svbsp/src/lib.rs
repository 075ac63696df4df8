//! Shadow Volume BSP trees and BSP set operations.
//!
//! This crate will hold, on top of [`bsp_core`]:
//! - Thibault-Naylor union of a BSP solid with a convex polyhedron's boundary
//!   and Naylor-Amanatides-Thibault merging of two BSP trees (union,
//!   intersection, difference);
//! - Shadow Volume BSP trees (Chin & Feiner 1989) for point and directional
//!   lights, pipelined over many lights with lit / umbra bits;
//! - Bergeron's general shadow volumes (open models, twisted polygons, the eye
//!   in shadow, lights with a sphere of influence).
//!
//! It is not implemented yet: see the project's open issues.

pub use bsp_core;
