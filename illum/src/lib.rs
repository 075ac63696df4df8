//! Direct illumination for umbra.
//!
//! This crate will hold Lambert's contour integral for convex polygonal
//! lights (clipped by the receiver's horizon), the visible part of an area
//! light from a point, point and directional lights with Bergeron's sphere of
//! influence, the 1992 paper's vertex-sharing rules and batch evaluation.
//!
//! It is not implemented yet: see the project's open issues.

pub use bsp_core;
