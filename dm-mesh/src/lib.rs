//! Discontinuity meshes kept as 2D BSP trees in a winged-edge structure.
//!
//! This crate will hold Chrysanthou & Slater's DM-trees: one 2D BSP per
//! receiver, built by merging single-occluder trees, with occluder lists per
//! cell, the shadow overlap cube, and deletion / addition of objects so that a
//! moving object costs a fraction of a rebuild.
//!
//! It is not implemented yet: see the project's open issues.

pub use bsp_core;
