//! Fuzz target `area`: small random scenes under an area light, checked by
//! [`umbra_fuzz::area::check_area`].
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::area::run(data);
});
