//! Fuzz target `pipeline`: scene files through `umbra shadow`, `dm` and
//! `update`, checked by [`umbra_fuzz::pipeline::check_pipeline`].
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::pipeline::run(data);
});
