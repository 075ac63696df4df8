//! Integration tests of dm-mesh, one binary.

mod bodies;
mod classes;
mod common;
mod errors;
mod flat_unions;
mod illumination;
mod joint;
mod oracle;
mod threads;
mod updates;
