//! The one error type of the `umbra` library: every message names the file
//! and the line or field that is wrong.

use std::path::PathBuf;

use thiserror::Error;

/// Everything that can go wrong between a scene file and an output file.
///
/// Each variant's message is complete on its own (the command prints it as
/// is): it names the file, and the line or the field path (like
/// `light[2].vertices`) where the problem is.
#[derive(Debug, Error)]
pub enum Error {
    /// A file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// An output file could not be written (nothing is left behind).
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The scene file is not valid TOML, or does not match the scene format
    /// (unknown field, wrong type, missing field).
    #[error("{}:{line}:{column}: {message}", path.display())]
    Toml {
        /// The scene file.
        path: PathBuf,
        /// 1-based line of the problem.
        line: usize,
        /// 1-based column of the problem.
        column: usize,
        /// What the TOML reader said.
        message: String,
    },
    /// A field of the scene has a value the format does not allow.
    #[error("{}: {field}: {message}", path.display())]
    Field {
        /// The scene file.
        path: PathBuf,
        /// The field path, like `object[1].scale` or `light[2].vertices`.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// An OBJ file is malformed.
    #[error("{}:{line}: {message}", path.display())]
    Obj {
        /// The OBJ file.
        path: PathBuf,
        /// 1-based line of the problem.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A PLY file could not be parsed (reader used by tests and tools).
    #[error("{}: {message}", path.display())]
    Ply {
        /// The PLY file, or `<memory>`.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The scene has no polygons at all.
    #[error("{}: the scene has no polygons (add an [[object]] with a mesh or polygons)", path.display())]
    EmptyScene {
        /// The scene file.
        path: PathBuf,
    },
    /// The scene's points cannot be laid on a grid (for example, all
    /// coincide).
    #[error("{}: cannot lay the grid over the scene: {source}", path.display())]
    Grid {
        /// The scene file.
        path: PathBuf,
        /// The kernel's reason.
        source: bsp_core::Error,
    },
    /// Output that the chosen format cannot hold (for example, a face with
    /// more than 255 vertices in PLY).
    #[error("{}: {message}", path.display())]
    Output {
        /// The output file.
        path: PathBuf,
        /// What cannot be written.
        message: String,
    },
    /// A set operation whose result would not be a closed surface (the
    /// inputs' snapped surfaces fold or cross themselves).
    #[error("{} and {}: {message}", a.display(), b.display())]
    Csg {
        /// The first mesh.
        a: PathBuf,
        /// The second mesh.
        b: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// A demo scene name that does not exist.
    #[error("unknown demo scene `{name}` (known: {known})")]
    UnknownDemo {
        /// The name asked for.
        name: String,
        /// The names that exist, comma-separated.
        known: String,
    },
    /// The discontinuity meshes could not be built or updated.
    #[error("discontinuity meshes: {0}")]
    Dm(String),
    /// A command that is parsed but not implemented yet.
    #[error("`umbra {command}` is not implemented yet: {reason}")]
    NotImplemented {
        /// The command.
        command: &'static str,
        /// What it waits for.
        reason: &'static str,
    },
}

/// `Result` with [`enum@Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
