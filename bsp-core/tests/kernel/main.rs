//! Integration tests of the exact kernel, as one binary.

mod chord;
mod common;
mod planar_snap;
mod scene_bsp;
mod solid;
mod split;
mod translate;
mod winged_edge;
