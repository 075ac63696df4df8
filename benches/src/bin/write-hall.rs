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
    const USAGE: &str = "usage: write-hall DIR [BOXES] [SEED]";
    let mut args = std::env::args().skip(1);
    let dir = match args.next() {
        Some(flag) if flag == "-h" || flag == "--help" => {
            println!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        // (An option is no folder name: `--help` made a folder of that name.)
        Some(flag) if flag.starts_with('-') => {
            eprintln!("write-hall: unknown option {flag}\n{USAGE}");
            return ExitCode::FAILURE;
        }
        Some(dir) => PathBuf::from(dir),
        None => {
            eprintln!("{USAGE}");
            return ExitCode::FAILURE;
        }
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
