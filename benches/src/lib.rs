//! Scene generators shared by umbra's criterion benchmarks and the
//! paper-table harness (`cargo run --release -p umbra-benches --bin paper-tables`).

pub mod scene;
pub mod tetra;
