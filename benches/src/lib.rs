//! Scene generators shared by umbra's criterion benchmarks and the
//! paper-table harness (`cargo run --release -p umbra-benches --bin paper-tables`).
//!
//! [`random`] makes deterministic kernel inputs (grid points, planes,
//! implicit-point queries, quads, triangle soups); [`scene`] and [`tetra`]
//! build the scenes of the papers; [`output_change`] weighs what a move
//! must rewrite; [`closed_meshes`] puts dense closed meshes on the grid (a
//! bumpy sphere far from convex, a torus with no kernel).

pub mod closed_meshes;
pub mod dm_table;
pub mod illum_scene;
pub mod output_change;
pub mod random;
pub mod rooms;
pub mod scene;
pub mod tetra;
