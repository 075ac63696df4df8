//! Writes the benchmarks' hall of boxes (two quad lights) into a folder, so
//! that `umbra shadow` and profilers can run on exactly the scene the
//! paper-table harness times.
//!
//! `write-hall DIR [BOXES] [SEED]`: `6 * BOXES + 5` polygons (1665 boxes,
//! about 10k polygons, by default).

use std::path::PathBuf;
use std::process::ExitCode;

use umbra_benches::rooms;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let Some(dir) = args.next().map(PathBuf::from) else {
        eprintln!("usage: write-hall DIR [BOXES] [SEED]");
        return ExitCode::FAILURE;
    };
    let parse = |arg: Option<String>, default: u64| match arg {
        None => Ok(default),
        Some(text) => text
            .parse::<u64>()
            .map_err(|_| format!("not a whole number: {text}")),
    };
    let (boxes, seed) = match (parse(args.next(), 1665), parse(args.next(), 7)) {
        (Ok(b), Ok(s)) => (b, s),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("write-hall: {e}");
            return ExitCode::FAILURE;
        }
    };
    if let Err(e) = std::fs::create_dir_all(&dir) {
        eprintln!("write-hall: {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    let Ok(boxes) = usize::try_from(boxes) else {
        eprintln!("write-hall: too many boxes");
        return ExitCode::FAILURE;
    };
    let scene = rooms::box_hall(&dir, boxes, seed);
    println!("{}", scene.path.display());
    ExitCode::SUCCESS
}
