//! A cup turned so the grid bends it (its solid moved in, no convex body
//! of its pieces) and a panel beside it, under a wide area light: from a
//! strip of the floor the cup hides part of the light and the panel the
//! rest. The proofs take the cup as the shell its walls and the cap over
//! its hole close around the body inside; a ray oracle checks both ways.

use crate::area::{area, face_points};
use crate::open_box::crosses;
use crate::vectors::inner_points;
use crate::{folder, umbra};
use umbra::{OutputMesh, load_ply};

const SCENE: &str = r#"
[[object]]
name = "floor"
polygons = [[[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]]

[[object]]
name = "cup"
polygons = [
  [[-1, -1, -1], [-1, -1, 1], [-1, 1, 1], [-1, 1, -1]],
  [[1, -1, -1], [1, 1, -1], [1, 1, 1], [1, -1, 1]],
  [[-1, -1, -1], [1, -1, -1], [1, -1, 1], [-1, -1, 1]],
  [[-1, -1, -1], [-1, 1, -1], [1, 1, -1], [1, -1, -1]],
  [[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]],
]
translate = [0, 1.3, 0]
rotate_deg = [15.3, -39.6, -30.4]
scale = [0.6, 0.5, 0.55]

[[object]]
name = "panel"
polygons = [[[-1.76, 2, -0.43], [-1.76, 2, 1.91], [0.58, 2, 1.91], [0.58, 2, -0.43]]]

[[light]]
type = "area"
vertices = [[-1.5, 3.2, -0.5], [1.5, 3.2, -0.5], [1.5, 3.2, 0.5], [-1.5, 3.2, 0.5]]
"#;

/// Per floor face, whether every segment from points inside it (its
/// centre, and halfway to each corner) to 31 x 11 points of the light
/// crosses a face of another polygon (`None`: one too close to a border
/// to tell).
fn floor_faces_dark(mesh: &OutputMesh) -> Vec<(usize, Option<bool>)> {
    let faces: Vec<Vec<[f64; 3]>> = (0..mesh.faces.len())
        .map(|f| face_points(mesh, f))
        .collect();
    let light: Vec<[f64; 3]> = (0..31 * 11)
        .map(|k| {
            [
                -1.5 + 0.1 * (k % 31) as f64,
                3.2,
                -0.5 + 0.1 * (k / 31) as f64,
            ]
        })
        .collect();
    let occluders: Vec<&Vec<[f64; 3]>> = mesh
        .faces
        .iter()
        .zip(&faces)
        .filter(|(face, _)| face.source != 0)
        .map(|(_, q)| q)
        .collect();
    (0..mesh.faces.len())
        .filter(|&f| mesh.faces[f].source == 0)
        .map(|f| {
            let mut dark = Some(true);
            for p in inner_points(&faces[f]) {
                for &l in &light {
                    let hits: Vec<Option<bool>> =
                        occluders.iter().map(|q| crosses(p, l, q)).collect();
                    if hits.contains(&Some(true)) {
                        continue;
                    }
                    if hits.contains(&None) {
                        dark = None;
                    } else {
                        return (f, Some(false));
                    }
                }
            }
            (f, dark)
        })
        .collect()
}

/// No umbra face sees the light, and the strip is umbra: before the cup
/// blocked as a shell, `shadow` gave 4.37 of umbra on the floor and left
/// 0.47 of penumbra that this oracle finds dark; now 4.82 and 0.02
/// (`dm`: 4.88 and 0.15, its faces smaller; the oracle's grid of the
/// light misses slivers of it, so some of those see a little).
#[test]
fn a_bent_cup_and_a_panel_hide_a_strip_together() {
    let dir = folder(&[("scene.toml", SCENE)]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let (mut umbra_area, mut dark_penumbra) = (0.0, 0.0);
        for (f, dark) in floor_faces_dark(&mesh) {
            let face = &mesh.faces[f];
            let size = area(&face_points(&mesh, f));
            if face.umbra_mask & 1 != 0 {
                assert_ne!(
                    dark,
                    Some(false),
                    "{command}: umbra face {f} sees the light"
                );
                umbra_area += size;
            } else if face.lit_mask & 1 == 0 && dark == Some(true) {
                dark_penumbra += size;
            }
        }
        assert!(umbra_area > 4.5, "{command}: umbra {umbra_area}");
        assert!(
            dark_penumbra < 0.2,
            "{command}: {dark_penumbra} of penumbra sees nothing"
        );
    }
}
