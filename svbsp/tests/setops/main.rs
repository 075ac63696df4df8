//! Integration tests of the BSP set operations (merge, union with a convex
//! polyhedron, CSG boundary), as one binary.

mod balanced;
mod common;
mod csg;
mod merge;
mod union;
