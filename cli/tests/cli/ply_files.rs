//! PLY and OBJ files written through the atomic writer and read back.

use umbra::{OutputFace, OutputMesh, PlyEncoding, load_ply, save_obj, save_ply};

use crate::folder;

fn mesh() -> OutputMesh {
    OutputMesh {
        vertices: vec![
            ([0.0, 0.0, 0.0], 0.0),
            ([1.0, 0.0, 0.0], 0.75),
            ([1.0, 1.0, 0.1], 1.0 / 3.0),
            ([0.0, 1.0, -1e-9], 2.5),
        ],
        faces: vec![
            OutputFace {
                vertices: vec![0, 1, 2, 3],
                source: 5,
                lit_mask: 0b101,
                umbra_mask: 0b010,
            },
            OutputFace {
                vertices: vec![0, 2, 3],
                source: 6,
                lit_mask: 0,
                umbra_mask: u32::MAX,
            },
        ],
    }
}

const HEADER_TAIL: &str = "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n\
property float irradiance\nelement face 2\nproperty list uchar uint vertex_indices\n\
property uint source\nproperty uint lit_mask\nproperty uint umbra_mask\nend_header\n";

#[test]
fn both_encodings_round_trip_with_the_contract_header() {
    let dir = folder(&[]);
    for (encoding, format) in [
        (PlyEncoding::BinaryLittleEndian, "binary_little_endian"),
        (PlyEncoding::Ascii, "ascii"),
    ] {
        let path = dir.path().join(format!("{format}.ply"));
        save_ply(&path, &mesh(), encoding).unwrap();
        assert_eq!(load_ply(&path).unwrap(), mesh());
        let bytes = std::fs::read(&path).unwrap();
        let end = bytes
            .windows(11)
            .position(|w| w == b"end_header\n")
            .unwrap()
            + 11;
        let header = std::str::from_utf8(&bytes[..end]).unwrap();
        assert!(
            header.starts_with(&format!("ply\nformat {format} 1.0\n")),
            "{header}"
        );
        assert!(header.ends_with(HEADER_TAIL), "{header}");
        if encoding == PlyEncoding::BinaryLittleEndian {
            let body = &bytes[end..];
            assert_eq!(body.len(), 4 * 28 + (1 + 16 + 12) + (1 + 12 + 12));
            // First face: count 4, indices 0 1 2 3, then source 5.
            let face = &body[4 * 28..];
            assert_eq!(face[0], 4);
            assert_eq!(&face[1 + 16..1 + 20], &5u32.to_le_bytes());
        }
    }
}

#[test]
fn unwritable_output_leaves_nothing() {
    let dir = folder(&[]);
    let mut bad = mesh();
    bad.faces[0].vertices.push(9);
    let path = dir.path().join("bad.ply");
    let e = save_ply(&path, &bad, PlyEncoding::Ascii)
        .unwrap_err()
        .to_string();
    assert!(e.contains("bad.ply: face 0 names vertex 9"), "{e}");
    let missing = dir.path().join("no/such/folder/out.ply");
    assert!(save_ply(&missing, &mesh(), PlyEncoding::Ascii).is_err());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn obj_output_reads_back() {
    let dir = folder(&[]);
    let path = dir.path().join("out.obj");
    save_obj(&path, &mesh()).unwrap();
    let back = umbra::ObjMesh::load(&path).unwrap();
    assert_eq!(back.faces.len(), 2);
    assert_eq!(back.faces[0].vertices[2], [1.0, 1.0, 0.1]);
    assert_eq!(
        back.faces[1].group.as_deref(),
        Some("source_6_lit_0_umbra_4294967295")
    );
}
