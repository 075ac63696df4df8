//! The shadow output as Wavefront OBJ: the same vertices and faces as the
//! PLY, for tools that read only OBJ.
//!
//! OBJ has no per-face integers, so each face's `source`, `lit_mask` and
//! `umbra_mask` are kept by grouping: consecutive faces with the same three
//! values share a `g source_S_lit_L_umbra_U` line. Irradiance is not written
//! (the PLY has it).

use std::io::Write;
use std::path::Path;

use crate::atomic::Outputs;
use crate::error::{Error, Result};
use crate::mesh::OutputMesh;

/// Writes `mesh` as OBJ to `w` (1-based indices, vertices in full
/// precision).
pub fn write_obj(mesh: &OutputMesh, w: &mut dyn Write) -> std::io::Result<()> {
    writeln!(w, "# written by umbra {}", env!("CARGO_PKG_VERSION"))?;
    writeln!(
        w,
        "# {} vertices, {} faces; groups name source, lit_mask, umbra_mask",
        mesh.vertices.len(),
        mesh.faces.len()
    )?;
    for (p, _) in &mesh.vertices {
        writeln!(w, "v {:?} {:?} {:?}", p[0], p[1], p[2])?;
    }
    let mut current = None;
    for f in &mesh.faces {
        let key = (f.source, f.lit_mask, f.umbra_mask);
        if current != Some(key) {
            writeln!(w, "g source_{}_lit_{}_umbra_{}", key.0, key.1, key.2)?;
            current = Some(key);
        }
        write!(w, "f")?;
        for v in &f.vertices {
            write!(w, " {}", u64::from(*v) + 1)?;
        }
        writeln!(w)?;
    }
    Ok(())
}

/// Writes `mesh` as OBJ to `path`, atomically.
pub fn save_obj(path: &Path, mesh: &OutputMesh) -> Result<()> {
    let mut outputs = Outputs::default();
    stage_obj(&mut outputs, path, mesh)?;
    outputs.commit()
}

/// [`save_obj`] as one of a run's [`Outputs`], written when they are.
pub fn stage_obj(outputs: &mut Outputs, path: &Path, mesh: &OutputMesh) -> Result<()> {
    mesh.check().map_err(|message| Error::Output {
        path: path.to_path_buf(),
        message,
    })?;
    outputs.stage(path, |w| write_obj(mesh, w))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::OutputFace;
    use crate::obj::ObjMesh;

    #[test]
    fn reads_back_with_the_obj_reader() {
        let mesh = OutputMesh {
            vertices: vec![
                ([0.0, 0.0, 0.0], 1.0),
                ([1.0, 0.0, 0.0], 1.0),
                ([0.1, 0.7, 0.0], 1.0),
            ],
            faces: vec![OutputFace {
                vertices: vec![0, 1, 2],
                source: 3,
                lit_mask: 1,
                umbra_mask: 2,
            }],
        };
        let mut out = Vec::new();
        write_obj(&mesh, &mut out).unwrap();
        let back = ObjMesh::parse(std::str::from_utf8(&out).unwrap(), Path::new("o.obj")).unwrap();
        assert_eq!(back.faces.len(), 1);
        assert_eq!(back.faces[0].vertices[2], [0.1, 0.7, 0.0]);
        assert_eq!(
            back.faces[0].group.as_deref(),
            Some("source_3_lit_1_umbra_2")
        );
    }
}
