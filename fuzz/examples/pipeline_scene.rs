//! Prints the scene file a `pipeline` input decodes to (its `Debug` form
//! first, as Rust code for a regression test), so that a crash or a slow
//! unit libFuzzer reports can be run with `umbra` itself.
//!
//! `cargo run --example pipeline_scene -- FILE`

use std::process::ExitCode;

fn main() -> ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: pipeline_scene FILE");
        return ExitCode::FAILURE;
    };
    let data = match std::fs::read(&path) {
        Ok(data) => data,
        Err(e) => {
            eprintln!("pipeline_scene: {path}: {e}");
            return ExitCode::FAILURE;
        }
    };
    match umbra_fuzz::pipeline::decode(&data) {
        Some(case) => {
            println!("// {case:?}\n\n{}", case.scene_text());
            ExitCode::SUCCESS
        }
        None => {
            eprintln!("pipeline_scene: {path}: too short to decode");
            ExitCode::FAILURE
        }
    }
}
