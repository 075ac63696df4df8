//! Writes the solids a `csg` input decodes to as OBJ files
//! (`DIR/s0.obj`, `DIR/s1.obj`, ...) and prints the case and the chain's
//! operations, so that a failure libFuzzer reports can be run with `umbra
//! csg` itself.
//!
//! `cargo run --example csg_case -- FILE DIR`

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [file, dir] = args.as_slice() else {
        eprintln!("usage: csg_case FILE DIR");
        return ExitCode::FAILURE;
    };
    let Some(case) = std::fs::read(file)
        .ok()
        .and_then(|data| umbra_fuzz::csg::decode(&data))
    else {
        eprintln!("csg_case: {file}: unreadable, or too short to decode");
        return ExitCode::FAILURE;
    };
    let dir = std::path::Path::new(dir);
    for (i, solid) in case.solids.iter().enumerate() {
        let path = dir.join(format!("s{i}.obj"));
        if let Err(e) =
            std::fs::create_dir_all(dir).and_then(|()| std::fs::write(&path, solid.obj_text()))
        {
            eprintln!("csg_case: {}: {e}", path.display());
            return ExitCode::FAILURE;
        }
    }
    println!(
        "{case:?}\nops (0 union, 1 intersection, 2 difference): {:?}",
        case.ops
    );
    ExitCode::SUCCESS
}
