//! Reading input files: regular files only, so that a path to a device or
//! a pipe (`/dev/zero`, say, which reads for ever) is refused by name.

use std::path::Path;

use crate::error::{Error, Result};

/// The bytes of the regular file at `path`.
pub(crate) fn input_bytes(path: &Path) -> Result<Vec<u8>> {
    let error = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    let metadata = std::fs::metadata(path).map_err(error)?;
    if !metadata.is_file() {
        return Err(error(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file",
        )));
    }
    std::fs::read(path).map_err(error)
}

/// The text (UTF-8) of the regular file at `path`.
pub(crate) fn input_text(path: &Path) -> Result<String> {
    String::from_utf8(input_bytes(path)?).map_err(|_| Error::Read {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "stream did not contain valid UTF-8",
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::{input_bytes, input_text};
    use std::path::Path;

    #[test]
    fn devices_and_folders_are_refused_files_read() {
        for path in ["/dev/zero", "/dev/null", "/"] {
            let Err(e) = input_text(Path::new(path)) else {
                panic!("{path} was read");
            };
            assert!(e.to_string().contains("not a regular file"), "{path}: {e}");
        }
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.txt");
        std::fs::write(&file, "text").unwrap();
        assert_eq!(input_text(&file).unwrap(), "text");
        std::fs::write(&file, [0xff, 0xfe]).unwrap();
        assert!(input_text(&file).is_err());
        assert_eq!(input_bytes(&file).unwrap(), [0xff, 0xfe]);
    }
}
