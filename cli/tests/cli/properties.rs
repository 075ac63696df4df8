//! Property tests: decomposition tiles random concave faces exactly, and no
//! input text makes the readers panic.

use std::path::Path;

use proptest::prelude::*;
use umbra::bsp_core::GridPoint;
use umbra::{ObjMesh, Scene, convex_pieces, read_ply};

/// A star-shaped (so simple, usually concave) polygon around the origin in
/// a plane given by its normal's dominant axis and integer slopes.
fn star(radii: &[u16], slopes: (i32, i32), axis: usize, flip: bool) -> Vec<GridPoint> {
    let n = radii.len();
    let mut pts: Vec<GridPoint> = radii
        .iter()
        .enumerate()
        .map(|(i, &r)| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            let r = 100.0 + f64::from(r);
            let (u, v) = ((r * t.cos()).round() as i32, (r * t.sin()).round() as i32);
            // The third coordinate makes the plane w = a u + b v.
            let w = slopes.0 * u + slopes.1 * v;
            let mut c = [0; 3];
            c[axis] = w;
            c[(axis + 1) % 3] = u;
            c[(axis + 2) % 3] = v;
            GridPoint {
                x: c[0],
                y: c[1],
                z: c[2],
            }
        })
        .collect();
    if flip {
        pts.reverse();
    }
    pts
}

fn vector_area(pts: &[GridPoint]) -> [f64; 3] {
    let mut a = [0.0; 3];
    for i in 0..pts.len() {
        let (p, q) = (pts[i].to_f64(), pts[(i + 1) % pts.len()].to_f64());
        a[0] += 0.5 * (p[1] * q[2] - p[2] * q[1]);
        a[1] += 0.5 * (p[2] * q[0] - p[0] * q[2]);
        a[2] += 0.5 * (p[0] * q[1] - p[1] * q[0]);
    }
    a
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn pieces_tile_planar_faces_and_face_the_same_way(
        radii in prop::collection::vec(0u16..2000, 3..24),
        slopes in (-3i32..=3, -3i32..=3),
        axis in 0usize..3,
        flip in any::<bool>(),
    ) {
        let pts = star(&radii, slopes, axis, flip);
        let area = vector_area(&pts);
        let size = (area[0] * area[0] + area[1] * area[1] + area[2] * area[2]).sqrt();
        let pieces = convex_pieces(&pts);
        if size == 0.0 {
            prop_assert!(pieces.is_empty());
        } else {
            let total: f64 = pieces.iter().map(|p| p.area()).sum();
            prop_assert!((total - size).abs() <= 1e-9 * size, "{} vs {}", total, size);
            for p in &pieces {
                prop_assert!(p.check_invariants().is_ok());
                // Same front as the face, and corners only at its vertices.
                let n = p.support().normal().map(|c| c as f64);
                prop_assert!(n[0] * area[0] + n[1] * area[1] + n[2] * area[2] > 0.0);
                for k in 0..p.len() {
                    let g = p.vertex_grid_point(k);
                    prop_assert!(g.is_some_and(|g| pts.contains(&g)));
                }
            }
        }
    }

    #[test]
    fn non_planar_faces_give_triangles_on_their_vertices(
        coords in prop::collection::vec((-50i32..50, -50i32..50, -50i32..50), 4..10),
    ) {
        let pts: Vec<GridPoint> = coords.iter().map(|&(x, y, z)| GridPoint { x, y, z }).collect();
        for p in convex_pieces(&pts) {
            prop_assert!(p.check_invariants().is_ok());
            for k in 0..p.len() {
                prop_assert!(p.vertex_grid_point(k).is_some_and(|g| pts.contains(&g)));
            }
        }
    }

    #[test]
    fn readers_never_panic(text in "[ -~\n]{0,200}") {
        let _ = ObjMesh::parse(&text, Path::new("fuzz.obj"));
        let _ = Scene::from_toml_str(&text, "fuzz.toml");
        let _ = read_ply(text.as_bytes());
    }

    #[test]
    fn obj_like_text_never_panics(
        lines in prop::collection::vec(
            prop_oneof![
                "v( -?[0-9]{1,3}(\\.[0-9])?){2,4}",
                "f( -?[0-9]{1,2}(/[0-9]?(/[0-9])?)?){0,5}",
                "(o|g) [a-z]{0,3}",
                "(vt|vn|s|#)[ 0-9.]{0,6}",
            ],
            0..20,
        ),
    ) {
        let text = lines.join("\n");
        match ObjMesh::parse(&text, Path::new("f.obj")) {
            Ok(mesh) => prop_assert!(mesh.faces.iter().all(|f| f.vertices.len() >= 3)),
            Err(e) => prop_assert!(e.to_string().starts_with("f.obj:")),
        }
    }

    #[test]
    fn ply_headers_with_garbage_bodies_never_panic(body in prop::collection::vec(any::<u8>(), 0..200), n in 0usize..5, m in 0usize..5) {
        let header = format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {n}\nproperty double x\nproperty double y\nproperty double z\nproperty float irradiance\nelement face {m}\nproperty list uchar uint vertex_indices\nproperty uint source\nproperty uint lit_mask\nproperty uint umbra_mask\nend_header\n"
        );
        let mut bytes = header.into_bytes();
        bytes.extend(body);
        let _ = read_ply(&bytes);
    }
}
