//! Fuzz target `dm_update`: discontinuity meshes through moves, removals
//! and re-additions, checked by [`umbra_fuzz::dm_update::check_dm_update`].
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::dm_update::run(data);
});
