//! The `umbra` library: scene files, OBJ input, PLY / OBJ / PNG / JSON output
//! and the shadow pipeline behind the `umbra` command.
//!
//! It is not implemented yet: see the project's open issues. The kernel it
//! will stand on is [`bsp_core`].

pub use bsp_core;
