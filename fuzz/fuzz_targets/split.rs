//! Fuzz target `split`: a random convex polygon cut by a random plane.
//!
//! The input bytes are decoded by [`umbra_fuzz::split::SplitCase`]; every
//! check lives in [`umbra_fuzz::split::check_split`], which the stable test
//! suite also runs over the committed seed corpus.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::split::run(data);
});
