//! Shared scene generators for umbra's criterion benchmarks and paper-table
//! harness.
