//! `umbra dm` and `umbra update` with point and directional lights beside
//! an area light: their shadows cut the cells, so every light's classes
//! cover the same areas as `umbra shadow` gives; with point lights alone
//! the output is `umbra shadow`'s.

use crate::area::floor_classes_for;
use crate::dm::{AREA_LIGHT, floor_and_square};
use crate::{folder, umbra};
use umbra::{OutputMesh, load_ply};

/// Floor 20 x 20, a 4 x 4 square at y = 5 (moved by `square_x`), a 2 x 2
/// area light above it, a point light and a directional light.
fn scene(square_x: f64, area_light: bool) -> String {
    let area = if area_light { AREA_LIGHT } else { "" };
    floor_and_square(square_x)
        + area
        + r#"
[[light]]
type = "point"
position = [3, 9, 1]
intensity = 40.0
range = 30.0

[[light]]
type = "directional"
direction = [0.5, -1, 0.25]
intensity = 0.5
"#
}

fn run(dir: &std::path::Path, args: &[&str]) -> OutputMesh {
    let run = umbra(dir, args);
    assert_eq!(run.code, 0, "{args:?}: {}", run.stderr);
    let out = args[args.iter().position(|a| *a == "-o").unwrap() + 1];
    load_ply(&dir.join(out)).unwrap()
}

fn assert_same_areas(a: &OutputMesh, b: &OutputMesh, lights: u32, what: &str) {
    for bit in 0..lights {
        let (x, y) = (floor_classes_for(a, bit), floor_classes_for(b, bit));
        for c in 0..3 {
            assert!(
                (x[c] - y[c]).abs() < 1e-9,
                "{what}, light {bit}: {x:?} vs {y:?}"
            );
        }
    }
}

#[test]
fn point_and_directional_lights_cut_the_cells() {
    let text = scene(0.0, true);
    let dir = folder(&[("scene.toml", text.as_str())]);
    let dm = run(
        dir.path(),
        &["dm", "scene.toml", "-o", "dm.ply", "--stats", "s.json"],
    );
    let shadow = run(dir.path(), &["shadow", "scene.toml", "-o", "shadow.ply"]);
    assert_same_areas(&dm, &shadow, 3, "dm against shadow");
    // Each light casts the square's shadow on the floor.
    for bit in 0..3 {
        assert!(floor_classes_for(&dm, bit)[2] > 10.0, "light {bit}");
    }
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    let lights = stats["lights"].as_array().unwrap();
    assert_eq!(lights.len(), 3);
    assert!(lights[0]["umbra_nodes"].as_u64().is_some());
    assert!(lights[1]["tree_nodes"].as_u64().unwrap() > 0);
    assert!(lights[2]["tree_nodes"].as_u64().unwrap() > 0);
    assert_eq!(
        stats["output_fragments"].as_u64(),
        Some(dm.faces.len() as u64)
    );
    for (bit, light) in lights.iter().enumerate() {
        let count = |f: &dyn Fn(&umbra::OutputFace) -> bool| {
            Some(dm.faces.iter().filter(|x| f(x)).count() as u64)
        };
        assert_eq!(
            light["lit"].as_u64(),
            count(&|f| f.lit_mask & (1 << bit) != 0)
        );
        assert_eq!(
            light["umbra"].as_u64(),
            count(&|f| f.umbra_mask & (1 << bit) != 0)
        );
    }
}

#[test]
fn point_lights_alone_give_the_shadow_output() {
    let text = scene(0.0, false);
    let dir = folder(&[("scene.toml", text.as_str())]);
    let dm = run(dir.path(), &["dm", "scene.toml", "-o", "dm.ply"]);
    let shadow = run(dir.path(), &["shadow", "scene.toml", "-o", "shadow.ply"]);
    assert_eq!(dm.faces, shadow.faces);
    assert_eq!(dm.vertices, shadow.vertices);
}

#[test]
fn update_with_point_lights_ends_where_a_scene_built_there_does() {
    let (text, moved) = (scene(0.0, true), scene(2.0, true));
    let dir = folder(&[
        ("scene.toml", text.as_str()),
        ("moved.toml", moved.as_str()),
    ]);
    let updated = run(
        dir.path(),
        &[
            "update",
            "scene.toml",
            "--move",
            "square",
            "--by",
            "1,0,0",
            "--steps",
            "2",
            "-o",
            "out.ply",
        ],
    );
    let built = run(dir.path(), &["dm", "moved.toml", "-o", "moved.ply"]);
    assert_same_areas(&updated, &built, 3, "update against dm");
}
