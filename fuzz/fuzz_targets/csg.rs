//! Fuzz target `csg`: chains of `umbra csg` set operations on closed
//! meshes, checked by [`umbra_fuzz::csg::check_csg`].
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    umbra_fuzz::csg::run(data);
});
