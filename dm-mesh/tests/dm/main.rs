//! Integration tests of dm-mesh, one binary.

mod bodies;
mod classes;
mod common;
mod illumination;
mod oracle;
mod threads;
mod updates;
