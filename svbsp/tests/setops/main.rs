//! Integration tests of the BSP set operations (merge, union with a convex
//! polyhedron, CSG boundary), as one binary.

mod common;
mod csg;
mod merge;
mod union;
