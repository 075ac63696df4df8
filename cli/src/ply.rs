//! The shadow output in PLY (FORMATS.md §2), and a reader for it.
//!
//! Header, in this order:
//!
//! ```text
//! ply
//! format binary_little_endian 1.0      (or: format ascii 1.0)
//! comment written by umbra
//! element vertex N
//! property double x
//! property double y
//! property double z
//! property float irradiance
//! element face M
//! property list uchar uint vertex_indices
//! property uint source
//! property uint lit_mask
//! property uint umbra_mask
//! end_header
//! ```

use std::io::Write;
use std::path::Path;

use crate::atomic::Outputs;
use crate::error::{Error, Result};
use crate::mesh::{OutputFace, OutputMesh};

/// How the PLY body is encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PlyEncoding {
    /// `binary_little_endian` (the default).
    #[default]
    BinaryLittleEndian,
    /// `ascii`, one element per line.
    Ascii,
}

/// Writes `mesh` as PLY to `w`. The mesh must pass [`OutputMesh::check`].
pub fn write_ply(
    mesh: &OutputMesh,
    encoding: PlyEncoding,
    w: &mut dyn Write,
) -> std::io::Result<()> {
    let format = match encoding {
        PlyEncoding::BinaryLittleEndian => "binary_little_endian",
        PlyEncoding::Ascii => "ascii",
    };
    write!(
        w,
        "ply\nformat {format} 1.0\ncomment written by umbra {}\n\
         element vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
         property float irradiance\nelement face {}\n\
         property list uchar uint vertex_indices\nproperty uint source\n\
         property uint lit_mask\nproperty uint umbra_mask\nend_header\n",
        env!("CARGO_PKG_VERSION"),
        mesh.vertices.len(),
        mesh.faces.len()
    )?;
    match encoding {
        PlyEncoding::Ascii => {
            for (p, e) in &mesh.vertices {
                writeln!(
                    w,
                    "{:?} {:?} {:?} {:?}",
                    p[0],
                    p[1],
                    p[2],
                    unsigned_zero(*e)
                )?;
            }
            for f in &mesh.faces {
                write!(w, "{}", f.vertices.len())?;
                for v in &f.vertices {
                    write!(w, " {v}")?;
                }
                writeln!(w, " {} {} {}", f.source, f.lit_mask, f.umbra_mask)?;
            }
        }
        PlyEncoding::BinaryLittleEndian => {
            let mut buf = Vec::with_capacity(28);
            for (p, e) in &mesh.vertices {
                buf.clear();
                for c in p {
                    buf.extend_from_slice(&c.to_le_bytes());
                }
                buf.extend_from_slice(&unsigned_zero(*e).to_le_bytes());
                w.write_all(&buf)?;
            }
            for f in &mesh.faces {
                buf.clear();
                let count = u8::try_from(f.vertices.len()).map_err(|_| {
                    std::io::Error::new(
                        std::io::ErrorKind::InvalidData,
                        "a PLY face holds at most 255 vertices",
                    )
                })?;
                buf.push(count);
                for v in &f.vertices {
                    buf.extend_from_slice(&v.to_le_bytes());
                }
                for x in [f.source, f.lit_mask, f.umbra_mask] {
                    buf.extend_from_slice(&x.to_le_bytes());
                }
                w.write_all(&buf)?;
            }
        }
    }
    Ok(())
}

/// `e` with a negative zero made positive: a sum of light that came to
/// nothing may round to -0, which reads as "-0" in ASCII and means no
/// less light than 0.
fn unsigned_zero(e: f32) -> f32 {
    e + 0.0
}

/// Writes `mesh` as PLY to `path`, atomically (see
/// [`write_atomic`](crate::write_atomic)).
pub fn save_ply(path: &Path, mesh: &OutputMesh, encoding: PlyEncoding) -> Result<()> {
    let mut outputs = Outputs::default();
    stage_ply(&mut outputs, path, mesh, encoding)?;
    outputs.commit()
}

/// [`save_ply`] as one of a run's [`Outputs`], written when they are.
pub fn stage_ply(
    outputs: &mut Outputs,
    path: &Path,
    mesh: &OutputMesh,
    encoding: PlyEncoding,
) -> Result<()> {
    mesh.check().map_err(|message| Error::Output {
        path: path.to_path_buf(),
        message,
    })?;
    outputs.stage(path, |w| write_ply(mesh, encoding, w))
}

/// Reads a PLY file written in umbra's layout (either encoding, or big
/// endian) back into an [`OutputMesh`]. Extra elements and properties are
/// skipped; `irradiance` defaults to 0 when absent.
pub fn load_ply(path: &Path) -> Result<OutputMesh> {
    let bytes = crate::read::input_bytes(path)?;
    read_ply(&bytes).map_err(|message| Error::Ply {
        path: path.to_path_buf(),
        message,
    })
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> std::result::Result<Self, String> {
        Ok(match name {
            "char" | "int8" => Self::I8,
            "uchar" | "uint8" => Self::U8,
            "short" | "int16" => Self::I16,
            "ushort" | "uint16" => Self::U16,
            "int" | "int32" => Self::I32,
            "uint" | "uint32" => Self::U32,
            "float" | "float32" => Self::F32,
            "double" | "float64" => Self::F64,
            other => return Err(format!("unknown property type `{other}`")),
        })
    }

    fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }
}

#[derive(Debug)]
struct Property {
    name: String,
    /// `Some(count type)` for a list.
    list: Option<Scalar>,
    value: Scalar,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Format {
    Ascii,
    Little,
    Big,
}

/// A source of scalar values: ASCII tokens or binary bytes.
struct Body<'a> {
    format: Format,
    bytes: &'a [u8],
    at: usize,
}

impl Body<'_> {
    fn next(&mut self, t: Scalar) -> std::result::Result<f64, String> {
        if self.format == Format::Ascii {
            while self.at < self.bytes.len() && self.bytes[self.at].is_ascii_whitespace() {
                self.at += 1;
            }
            let start = self.at;
            while self.at < self.bytes.len() && !self.bytes[self.at].is_ascii_whitespace() {
                self.at += 1;
            }
            if start == self.at {
                return Err("the body ends early".into());
            }
            let word = std::str::from_utf8(&self.bytes[start..self.at])
                .map_err(|_| "the body is not text".to_string())?;
            return word
                .parse::<f64>()
                .map_err(|_| format!("`{word}` is not a number"));
        }
        let n = t.size();
        let raw = self
            .bytes
            .get(self.at..self.at + n)
            .ok_or("the body ends early")?;
        self.at += n;
        let mut b = [0_u8; 8];
        b[..n].copy_from_slice(raw);
        if self.format == Format::Big {
            b[..n].reverse();
        }
        Ok(match t {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
            Scalar::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
            Scalar::I32 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }
}

fn as_u32(v: f64, what: &str) -> std::result::Result<u32, String> {
    if v >= 0.0 && v <= f64::from(u32::MAX) && v.fract() == 0.0 {
        Ok(v as u32)
    } else {
        Err(format!("{what} {v} is not an unsigned integer"))
    }
}

/// Parses PLY bytes (see [`load_ply`]).
pub fn read_ply(bytes: &[u8]) -> std::result::Result<OutputMesh, String> {
    let end = bytes
        .windows(10)
        .position(|w| w == b"end_header")
        .ok_or("no end_header")?;
    let mut body_start = end + 10;
    if bytes.get(body_start) == Some(&b'\r') {
        body_start += 1;
    }
    if bytes.get(body_start) != Some(&b'\n') {
        return Err("end_header is not followed by a newline".into());
    }
    body_start += 1;
    let header = std::str::from_utf8(&bytes[..end]).map_err(|_| "the header is not text")?;
    let mut lines = header.lines();
    if lines.next().map(str::trim) != Some("ply") {
        return Err("not a PLY file (no `ply` magic line)".into());
    }
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    for line in lines {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, "1.0"] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Little,
                    "binary_big_endian" => Format::Big,
                    other => return Err(format!("unknown format `{other}`")),
                });
            }
            ["element", name, count] => elements.push(Element {
                name: (*name).to_string(),
                count: count
                    .parse()
                    .map_err(|_| format!("bad element count `{count}`"))?,
                properties: Vec::new(),
            }),
            ["property", "list", count, value, name] => elements
                .last_mut()
                .ok_or("a property before any element")?
                .properties
                .push(Property {
                    name: (*name).to_string(),
                    list: Some(Scalar::parse(count)?),
                    value: Scalar::parse(value)?,
                }),
            ["property", value, name] => elements
                .last_mut()
                .ok_or("a property before any element")?
                .properties
                .push(Property {
                    name: (*name).to_string(),
                    list: None,
                    value: Scalar::parse(value)?,
                }),
            _ => return Err(format!("unreadable header line `{line}`")),
        }
    }
    let mut body = Body {
        format: format.ok_or("no format line")?,
        bytes: &bytes[body_start..],
        at: 0,
    };
    let mut mesh = OutputMesh::default();
    for element in &elements {
        let find = |name: &str| element.properties.iter().position(|p| p.name == name);
        for _ in 0..element.count {
            let mut scalars = vec![0.0; element.properties.len()];
            let mut lists = vec![Vec::new(); element.properties.len()];
            for (k, p) in element.properties.iter().enumerate() {
                match p.list {
                    None => scalars[k] = body.next(p.value)?,
                    Some(count_type) => {
                        let n = as_u32(body.next(count_type)?, "list length")?;
                        for _ in 0..n {
                            lists[k].push(body.next(p.value)?);
                        }
                    }
                }
            }
            match element.name.as_str() {
                "vertex" => {
                    let get = |name: &str| {
                        find(name)
                            .map(|k| scalars[k])
                            .ok_or(format!("vertex has no `{name}` property"))
                    };
                    let e = find("irradiance").map_or(0.0, |k| scalars[k]);
                    mesh.vertices
                        .push(([get("x")?, get("y")?, get("z")?], e as f32));
                }
                "face" => {
                    let list = find("vertex_indices")
                        .or_else(|| find("vertex_index"))
                        .ok_or("face has no `vertex_indices` property")?;
                    let get = |name: &str| {
                        find(name)
                            .ok_or(format!("face has no `{name}` property"))
                            .and_then(|k| as_u32(scalars[k], name))
                    };
                    mesh.faces.push(OutputFace {
                        vertices: lists[list]
                            .iter()
                            .map(|&v| as_u32(v, "vertex index"))
                            .collect::<std::result::Result<_, _>>()?,
                        source: get("source")?,
                        lit_mask: get("lit_mask")?,
                        umbra_mask: get("umbra_mask")?,
                    });
                }
                _ => {}
            }
        }
    }
    mesh.check()?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn sample() -> OutputMesh {
        OutputMesh {
            vertices: vec![
                ([0.0, 0.0, 0.0], 0.0),
                ([1.0, 0.0, -0.1], 0.5),
                ([1.0, 1.0 / 3.0, 1e-300], 1.25e-7),
                ([-2.5, 1e12, 0.0], 3.0),
            ],
            faces: vec![
                OutputFace {
                    vertices: vec![0, 1, 2],
                    source: 0,
                    lit_mask: 1,
                    umbra_mask: 0,
                },
                OutputFace {
                    vertices: vec![0, 2, 3, 1],
                    source: 7,
                    lit_mask: 0,
                    umbra_mask: u32::MAX,
                },
            ],
        }
    }

    #[test]
    fn round_trips_in_both_encodings() {
        for enc in [PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian] {
            let mut out = Vec::new();
            write_ply(&sample(), enc, &mut out).unwrap();
            assert_eq!(read_ply(&out).unwrap(), sample());
        }
    }

    #[test]
    fn no_light_is_written_as_plus_zero() {
        let mut mesh = sample();
        mesh.vertices[0].1 = -0.0;
        let mut ascii = Vec::new();
        write_ply(&mesh, PlyEncoding::Ascii, &mut ascii).unwrap();
        assert!(!String::from_utf8(ascii).unwrap().contains("-0.0"));
        let mut binary = Vec::new();
        write_ply(&mesh, PlyEncoding::BinaryLittleEndian, &mut binary).unwrap();
        let read = read_ply(&binary).unwrap();
        assert!(read.vertices[0].1.is_sign_positive());
    }

    #[test]
    fn binary_body_has_the_exact_size() {
        let mut out = Vec::new();
        write_ply(&sample(), PlyEncoding::BinaryLittleEndian, &mut out).unwrap();
        let end = out.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        assert_eq!(out.len() - end, 4 * 28 + (1 + 12 + 12) + (1 + 16 + 12));
    }
}
