//! Fuzz target `shadows`: small random scenes under a point or directional
//! light in small cones, checked by [`umbra_fuzz::shadows::check_shadows`].
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::shadows::run(data);
});
