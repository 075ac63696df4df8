//! Integration tests of `area-shadow`, one binary.

mod coincident;
mod cores;
mod culled;
mod figure4;
mod flat_unions;
mod groups;
mod joint;
mod kernel;
mod oracle;
mod pieces;
mod random;
mod volumes;
