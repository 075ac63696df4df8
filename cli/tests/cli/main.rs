//! Integration tests of the `umbra` library and command, as one binary.

mod area;
mod closed_mesh;
mod closed_parts;
mod commands;
mod csg;
mod cup_and_panel;
mod decimal;
mod decomposition;
mod demos;
mod dm;
mod dm_lights;
mod errors;
mod input_frames;
mod inward_surfaces;
mod joint_umbra;
mod joints;
mod open_box;
mod order;
mod ply_files;
mod properties;
mod render;
mod ring_mesh;
mod shadow;
mod t_junctions;
mod tilted_light;
mod vectors;
mod volumes;

use std::path::Path;
use std::process::Command;

/// What a run of the `umbra` binary gave.
pub struct Run {
    /// Exit status.
    pub code: i32,
    /// Standard output.
    pub stdout: String,
    /// Standard error.
    pub stderr: String,
}

/// Runs the built `umbra` binary in `dir`.
pub fn umbra(dir: &Path, args: &[&str]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_umbra"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the umbra binary runs");
    Run {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// A fresh folder with the given files written into it.
pub fn folder(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

/// A one-triangle object, to append lights or more objects to.
pub const TRIANGLE: &str = "[[object]]\nname = \"t\"\npolygons = [[[0,0,0],[1,0,0],[0,1,0]]]\n";
