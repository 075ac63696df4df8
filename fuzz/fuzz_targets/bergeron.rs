//! Fuzz target `bergeron`: Bergeron's shadow volumes of random boxes and
//! bent quads, counted along random segments by
//! [`umbra_fuzz::bergeron::check_bergeron`].
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::bergeron::run(data);
});
