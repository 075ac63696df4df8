//! Reading Wavefront OBJ faces into polygons, in file order.
//!
//! A hand-written reader rather than `tobj`: the scene contract wants every
//! malformed line reported with its line number, and input polygon numbers
//! that follow the faces exactly as written across `o` / `g` groups. `tobj`
//! reports errors without line numbers and regroups faces into models.
//!
//! Supported: `v x y z [w]` (w ignored), `f` / `fo` with `v`, `v/vt`,
//! `v//vn` and `v/vt/vn` references, negative (relative) indices, `o`, `g`,
//! and line continuations with a trailing `\`. Texture coordinates, normals,
//! materials, smoothing groups, lines, points and curves are ignored.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// One face of an OBJ file: its vertices in the order written.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjFace {
    /// The face's vertices, as written (counter-clockwise seen from the
    /// front, by the OBJ convention).
    pub vertices: Vec<[f64; 3]>,
    /// 1-based line of the `f` statement.
    pub line: usize,
    /// The `o` / `g` name in force for the face, if any.
    pub group: Option<String>,
}

/// The faces of an OBJ file, in file order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ObjMesh {
    /// The faces, in file order across all groups.
    pub faces: Vec<ObjFace>,
}

impl ObjMesh {
    /// Reads an OBJ file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = crate::read::input_text(path)?;
        Self::parse(&text, path)
    }

    /// Parses OBJ text; `path` names the file in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let err = |line: usize, message: String| Error::Obj {
            path: PathBuf::from(path),
            line,
            message,
        };
        let mut positions: Vec<[f64; 3]> = Vec::new();
        // Faces as 0-based position indices, resolved once the file is read
        // so that a face may name a vertex written after it.
        let mut pending: Vec<PendingFace> = Vec::new();
        let mut group: Option<String> = None;

        let mut lines = text.lines().enumerate();
        while let Some((index, first)) = lines.next() {
            let number = index + 1;
            let mut statement = first.to_string();
            while statement.ends_with('\\') {
                statement.pop();
                match lines.next() {
                    Some((_, next)) => {
                        statement.push(' ');
                        statement.push_str(next);
                    }
                    None => break,
                }
            }
            let content = match statement.find('#') {
                Some(at) => &statement[..at],
                None => &statement[..],
            };
            let mut words = content.split_whitespace();
            let Some(keyword) = words.next() else {
                continue;
            };
            match keyword {
                "v" => {
                    let values: Vec<&str> = words.collect();
                    if values.len() < 3 || values.len() > 4 {
                        return Err(err(
                            number,
                            format!(
                                "a vertex needs 3 coordinates (x y z), found {}",
                                values.len()
                            ),
                        ));
                    }
                    let mut p = [0.0; 3];
                    for (axis, word) in values.iter().take(3).enumerate() {
                        let value: f64 = word.parse().map_err(|_| {
                            err(
                                number,
                                format!("vertex coordinate `{word}` is not a number"),
                            )
                        })?;
                        if !value.is_finite() {
                            return Err(err(
                                number,
                                format!("vertex coordinate `{word}` is not finite"),
                            ));
                        }
                        p[axis] = value;
                    }
                    if let Some(word) = values.get(3) {
                        let w: f64 = word.parse().map_err(|_| {
                            err(number, format!("vertex weight `{word}` is not a number"))
                        })?;
                        if !w.is_finite() {
                            return Err(err(
                                number,
                                format!("vertex weight `{word}` is not finite"),
                            ));
                        }
                    }
                    positions.push(p);
                }
                "f" | "fo" => {
                    let mut refs = Vec::new();
                    for word in words {
                        let first = word.split('/').next().unwrap_or("");
                        let value: i64 = first.parse().map_err(|_| {
                            err(number, format!("face vertex `{word}` is not an index"))
                        })?;
                        let resolved = if value > 0 {
                            (value - 1) as usize
                        } else if value < 0 {
                            let back = value.unsigned_abs() as usize;
                            if back > positions.len() {
                                return Err(err(
                                    number,
                                    format!(
                                        "face vertex {value} points before the first vertex ({} written so far)",
                                        positions.len()
                                    ),
                                ));
                            }
                            positions.len() - back
                        } else {
                            return Err(err(
                                number,
                                "face vertex index 0 (OBJ counts from 1)".into(),
                            ));
                        };
                        refs.push((resolved, value.unsigned_abs() as usize));
                    }
                    if refs.len() < 3 {
                        return Err(err(
                            number,
                            format!("a face needs at least 3 vertices, found {}", refs.len()),
                        ));
                    }
                    pending.push(PendingFace {
                        refs,
                        line: number,
                        group: group.clone(),
                    });
                }
                "o" | "g" => {
                    let name: Vec<&str> = words.collect();
                    group = if name.is_empty() {
                        None
                    } else {
                        Some(name.join(" "))
                    };
                }
                // Everything else (vt, vn, vp, s, usemtl, mtllib, l, p, curves)
                // carries nothing a shadow needs.
                _ => {}
            }
        }

        let mut faces = Vec::with_capacity(pending.len());
        for PendingFace { refs, line, group } in pending {
            let mut vertices = Vec::with_capacity(refs.len());
            for (index, written) in refs {
                let p = positions.get(index).ok_or_else(|| {
                    err(
                        line,
                        format!(
                            "face vertex {written} does not exist (the file has {} vertices)",
                            positions.len()
                        ),
                    )
                })?;
                vertices.push(*p);
            }
            faces.push(ObjFace {
                vertices,
                line,
                group,
            });
        }
        Ok(Self { faces })
    }
}

/// A face as read: (0-based position index, index as written) per vertex.
struct PendingFace {
    refs: Vec<(usize, usize)>,
    line: usize,
    group: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ObjMesh> {
        ObjMesh::parse(text, Path::new("t.obj"))
    }

    #[test]
    fn reads_groups_forms_and_negative_indices_in_file_order() {
        let mesh = parse(
            "# comment\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no a\nf 1 2 3\ng b\nf -4//1 -2//1 -1//1\nvt 0 0\nf 1/1 3/1/2 \\\n 4\n",
        )
        .unwrap();
        assert_eq!(mesh.faces.len(), 3);
        assert_eq!(mesh.faces[0].group.as_deref(), Some("a"));
        assert_eq!(mesh.faces[1].group.as_deref(), Some("b"));
        assert_eq!(
            mesh.faces[1].vertices,
            vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]
        );
        assert_eq!(mesh.faces[2].vertices.len(), 3);
        assert_eq!(mesh.faces[2].line, 11);
    }

    #[test]
    fn malformed_lines_name_their_line() {
        let cases = [
            ("v 0 0 0\nv 1 0\n", 2, "3 coordinates"),
            ("v 0 0 0\nv 1 x 0\n", 2, "not a number"),
            ("v 0 0 nan\n", 1, "not finite"),
            ("v 0 0 inf\n", 1, "not finite"),
            ("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "at least 3"),
            ("v 0 0 0\nf 1 0 1\n", 2, "index 0"),
            ("v 0 0 0\n\nf 1 2 7\n", 3, "does not exist"),
            ("v 0 0 0\nf -1 -2 -3\n", 2, "before the first"),
            ("v 0 0 0\nf 1 a 1\n", 2, "not an index"),
        ];
        for (text, line, words) in cases {
            let e = parse(text).unwrap_err();
            let message = e.to_string();
            assert!(message.starts_with(&format!("t.obj:{line}:")), "{message}");
            assert!(message.contains(words), "{message}");
        }
    }
}
