//! The `umbra` command: exact object-space shadows from scene files.
//!
//! Run `umbra --help` for the commands. Errors print one message on stderr
//! and exit with status 2.

mod cli;

use std::process::ExitCode;

use clap::Parser;

/// Millions of small polygons are made and dropped per run; mimalloc's
/// thread-local free lists serve them far faster than the system allocator.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    // A panic is a bug; report it in one line instead of a backtrace dump,
    // and exit with the same status as any other error.
    std::panic::set_hook(Box::new(|info| {
        eprintln!("umbra: internal error (a bug, please report it): {info}");
    }));
    let args = cli::Cli::parse();
    match std::panic::catch_unwind(|| cli::run(args)) {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            eprintln!("umbra: error: {e}");
            ExitCode::from(2)
        }
        Err(_) => ExitCode::from(2),
    }
}
