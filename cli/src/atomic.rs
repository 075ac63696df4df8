//! Writing output files all at once: to a temporary file beside the target,
//! then renamed over it, so that a failed run leaves no partial file.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

use crate::error::{Error, Result};

/// Writes `path` through `write`, atomically: the bytes go to a temporary
/// file in the same folder, which replaces `path` only once `write`
/// succeeded and everything is flushed. On any error the temporary file is
/// removed and `path` is left as it was.
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let mut outputs = Outputs::default();
    outputs.stage(path, write)?;
    outputs.commit()
}

/// Output files of one run, written together: each goes to a temporary
/// file beside its target as it is staged, and all of them replace their
/// targets only at [`Outputs::commit`]. A run that fails on any file (the
/// statistics' folder missing, say) leaves none of them written; dropped
/// uncommitted, the temporary files are removed.
#[derive(Default)]
pub struct Outputs {
    staged: Vec<(PathBuf, NamedTempFile)>,
}

impl Outputs {
    /// Writes `path`'s future bytes through `write` to a temporary file.
    pub fn stage(
        &mut self,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<()> {
        let fail = |source| Error::Write {
            path: path.to_path_buf(),
            source,
        };
        // A link is written through (the file it names is replaced, the
        // link stays); a pipe, a device or a socket is refused before a
        // byte is written: renaming over it would replace it with a file.
        // (A folder fails at `commit`.)
        let target = resolve_links(path).map_err(fail)?;
        let path = target.as_path();
        if let Ok(meta) = std::fs::metadata(path)
            && !meta.is_file()
            && !meta.is_dir()
        {
            return Err(fail(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "is not a regular file (a pipe, a device or a socket)",
            )));
        }
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let temp = tempfile::Builder::new()
            .prefix(".umbra-")
            .suffix(".part")
            .tempfile_in(dir)
            .map_err(fail)?;
        let mut out = BufWriter::new(temp);
        write(&mut out).map_err(fail)?;
        let temp = out.into_inner().map_err(|e| fail(e.into_error()))?;
        // A temporary file is private; an output is not: read and
        // written by its owner, read by the rest, like files made the
        // usual way.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let permissions = std::fs::Permissions::from_mode(0o644);
            std::fs::set_permissions(temp.path(), permissions).map_err(fail)?;
        }
        temp.as_file().sync_all().map_err(fail)?;
        self.staged.push((path.to_path_buf(), temp));
        Ok(())
    }

    /// Puts every staged file in place (renames within their folders).
    /// A target that is a folder fails before any file is put in place
    /// (the renames cannot fail otherwise: each temporary file was made in
    /// its target's folder).
    pub fn commit(self) -> Result<()> {
        if let Some((path, _)) = self.staged.iter().find(|(path, _)| path.is_dir()) {
            return Err(Error::Write {
                path: path.clone(),
                source: std::io::Error::new(std::io::ErrorKind::IsADirectory, "is a folder"),
            });
        }
        for (path, temp) in self.staged {
            temp.persist(&path).map_err(|e| Error::Write {
                path,
                source: e.error,
            })?;
        }
        Ok(())
    }
}

/// `path` with symbolic links followed to the file they name (which need
/// not exist yet), at most 40 deep.
fn resolve_links(path: &Path) -> std::io::Result<PathBuf> {
    let mut path = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&path) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = std::fs::read_link(&path)?;
                path = match path.parent() {
                    Some(parent) => parent.join(link),
                    None => link,
                };
            }
            _ => return Ok(path),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failure_leaves_nothing_and_success_replaces() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.txt");
        let e = write_atomic(&target, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("boom"))
        });
        assert!(e.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        write_atomic(&target, |w| w.write_all(b"whole")).unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "whole");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[cfg(unix)]
    #[test]
    fn links_are_written_through_and_special_files_refused() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("real.ply");
        let link = dir.path().join("link.ply");
        std::os::unix::fs::symlink("real.ply", &link).unwrap();
        write_atomic(&link, |w| w.write_all(b"through")).unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "through");
        // A pipe stays a pipe, and nothing is written beside it.
        let pipe = dir.path().join("pipe.ply");
        let made = std::process::Command::new("mkfifo").arg(&pipe).status();
        if made.is_ok_and(|s| s.success()) {
            let e = write_atomic(&pipe, |w| w.write_all(b"x")).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
            assert!(!std::fs::metadata(&pipe).unwrap().is_file());
            assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);
        }
    }

    #[test]
    fn outputs_land_together_or_not_at_all() {
        let dir = tempfile::tempdir().unwrap();
        let (first, second) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        // The second file's folder is missing: the first is not written.
        let mut outputs = Outputs::default();
        outputs.stage(&first, |w| w.write_all(b"a")).unwrap();
        let missing = dir.path().join("no").join("b.txt");
        assert!(outputs.stage(&missing, |w| w.write_all(b"b")).is_err());
        drop(outputs);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        let mut outputs = Outputs::default();
        outputs.stage(&first, |w| w.write_all(b"a")).unwrap();
        outputs.stage(&second, |w| w.write_all(b"b")).unwrap();
        assert!(!first.exists() && !second.exists());
        // A target that is a folder: none is written.
        let mut blocked = Outputs::default();
        blocked.stage(&first, |w| w.write_all(b"a")).unwrap();
        std::fs::create_dir(dir.path().join("folder")).unwrap();
        let folder = dir.path().join("folder");
        blocked.stage(&folder, |w| w.write_all(b"b")).unwrap();
        assert!(blocked.commit().is_err());
        assert!(!first.exists());
        std::fs::remove_dir(&folder).unwrap();
        outputs.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&first).unwrap(), "a");
        assert_eq!(std::fs::read_to_string(&second).unwrap(), "b");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    }
}
