//! Integration tests of `area-shadow`, one binary.

mod figure4;
mod oracle;
mod random;
mod volumes;
