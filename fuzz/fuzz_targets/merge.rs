//! Fuzz target `merge`: two random solids (unions of boxes) merged by a
//! random set operation, checked pointwise by [`umbra_fuzz::merge::check_merge`].
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::merge::run(data);
});
