//! Closed surfaces wound inwards: a box whose faces all face its inside
//! sees none of any light outside it, even when the same object holds a
//! larger box wound outwards (so that the object as a whole encloses a
//! positive volume): every face in umbra, every corner dark. Skipping the
//! faces turned away from a light, as an outward closed surface allows,
//! would light the inside box's far faces; under an area light the shadow
//! passes alone leave faces the grid bends in penumbra.

use crate::t_junctions::box_faces;
use crate::{folder, umbra};
use umbra::load_ply;

/// The faces of the cube `centre ± half`, counter-clockwise seen from
/// outside, or reversed (`inward`).
fn cube(centre: [f64; 3], half: f64, inward: bool) -> Vec<String> {
    box_faces(false)
        .into_iter()
        .map(|face| {
            let mut corners: Vec<[f64; 3]> = face
                .iter()
                .map(|p| std::array::from_fn(|k| centre[k] + half * p[k]))
                .collect();
            if inward {
                corners.reverse();
            }
            format!("{corners:?}")
        })
        .collect()
}

fn scene(light: &str) -> String {
    let mut boxes = cube([-2.0, 2.0, 0.0], 1.0, false);
    boxes.extend(cube([2.0, 2.0, 0.5], 0.75, true));
    format!(
        r#"
[[object]]
name = "floor"
polygons = [[[-8, 0, 8], [8, 0, 8], [8, 0, -8], [-8, 0, -8]]]

[[object]]
name = "boxes"
polygons = [{}]
rotate_deg = [10, 20, 5]

{light}
"#,
        boxes.join(", ")
    )
}

const POINT: &str = "[[light]]\ntype = \"point\"\nposition = [0.5, 9, 0.3]\nintensity = 50";
const DIRECTIONAL: &str =
    "[[light]]\ntype = \"directional\"\ndirection = [0.2, -1, 0.1]\nintensity = 1";
const AREA: &str = "[[light]]\ntype = \"area\"\nvertices = [[-0.5, 9, -0.5], [0.5, 9, -0.5], [0.5, 9, 0.5], [-0.5, 9, 0.5]]\nintensity = 20";

#[test]
fn an_inward_box_sees_none_of_any_light() {
    for (light, commands) in [
        (POINT, &["shadow"][..]),
        (DIRECTIONAL, &["shadow"][..]),
        (AREA, &["shadow", "dm"][..]),
    ] {
        let dir = folder(&[("scene.toml", &scene(light))]);
        for command in commands {
            let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
            assert_eq!(run.code, 0, "{}", run.stderr);
            let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
            mesh.check().unwrap();
            // Sources: the floor 0, the outward box 1-6, the inward box 7-12.
            let inside: Vec<_> = mesh.faces.iter().filter(|f| f.source >= 7).collect();
            assert!(!inside.is_empty());
            for face in inside {
                assert_eq!(
                    (face.lit_mask, face.umbra_mask),
                    (0, 1),
                    "{command} {light}: face of {}",
                    face.source
                );
                for &v in &face.vertices {
                    assert_eq!(mesh.vertices[v as usize].1, 0.0, "{command} {light}");
                }
            }
            // The outward box's top is lit: faces towards a light still cast
            // and receive.
            assert!(
                mesh.faces
                    .iter()
                    .any(|f| (1..=6).contains(&f.source) && f.lit_mask == 1),
                "{command} {light}"
            );
        }
    }
}

/// An inward box that casts no shadow blocks nothing: its faces towards a
/// light (the bottom, facing up into it) see all of it.
#[test]
fn an_inward_box_that_casts_nothing_is_lit_inside() {
    for (light, commands) in [(POINT, &["shadow"][..]), (AREA, &["shadow", "dm"][..])] {
        let text = format!(
            "[[object]]\nname = \"box\"\npolygons = [{}]\ncasts_shadows = false\nrotate_deg = [10, 20, 5]\n\n{light}\n",
            cube([0.0, 2.0, 0.0], 1.0, true).join(", ")
        );
        let dir = folder(&[("scene.toml", &text)]);
        for command in commands {
            let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
            assert_eq!(run.code, 0, "{}", run.stderr);
            let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
            assert!(
                mesh.faces.iter().any(|f| f.lit_mask == 1),
                "{command} {light}"
            );
        }
    }
}
