//! Fuzz targets of umbra, as library code.
//!
//! Each module holds one target: a decoder from fuzzer bytes to a case that
//! prints as Rust code (its `Debug` output), and one checking function that
//! panics on no input but returns every violated invariant as an error. The
//! `fuzz_targets/*.rs` binaries are one-line wrappers, so a stable
//! `cargo test` replays the same code over the committed seed corpus
//! (`corpus/<target>/`) on every CI run, and a crash found by libFuzzer is
//! pasted as a case into a named regression test.
//!
//! ```text
//! cargo +nightly fuzz run split -- -max_total_time=60    # fuzz (nightly)
//! cargo test --manifest-path fuzz/Cargo.toml             # replay the corpus (stable)
//! ```

pub mod area;
pub mod bergeron;
pub mod csg;
pub mod dm_update;
pub mod merge;
pub mod pipeline;
mod scene;
pub mod shadows;
mod solids;
pub mod split;
mod vector;

/// Every file of a committed corpus directory (`corpus/<target>/`), sorted
/// by name, with its contents. Hidden files are skipped.
pub fn corpus_files(target: &str) -> std::io::Result<Vec<(String, Vec<u8>)>> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(target);
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') || !entry.file_type()?.is_file() {
            continue;
        }
        files.push((name, std::fs::read(entry.path())?));
    }
    files.sort();
    Ok(files)
}

/// Deterministic pseudo-random bytes (splitmix64), for tests that feed a
/// target many inputs without a fuzzer.
pub fn pseudo_random_bytes(seed: u64, len: usize) -> Vec<u8> {
    let mut state = seed;
    (0..len)
        .map(|_| {
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            (z ^ (z >> 31)) as u8
        })
        .collect()
}
