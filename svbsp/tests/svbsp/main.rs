//! Integration tests of the SVBSP pipeline against an exact occlusion
//! oracle, as one binary.

mod oracle;
mod scenes;
mod shadows;
