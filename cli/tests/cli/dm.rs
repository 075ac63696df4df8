//! `umbra dm` and `umbra update` end to end: cells partition every input
//! polygon, classes have the exact areas of a square under a square light,
//! vertex irradiance matches `umbra shadow` where both have a vertex, the
//! stats carry the contract's fields and the update arrays, and moving an
//! object step by step ends where a scene built at the final place does.

use crate::{Run, folder, umbra};
use std::path::Path;
use umbra::{OutputMesh, load_ply};

/// Floor 20 x 20 at y = 0, a 4 x 4 square at y = 5, a 2 x 2 light at
/// y = 10 facing down: umbra |x|, |z| <= 3, penumbra out to 5.
fn scene(square_x: f64) -> String {
    floor_and_square(square_x) + AREA_LIGHT
}

/// The floor 20 x 20 at y = 0 and a 4 x 4 square at y = 5, moved by
/// `square_x` along x.
pub(crate) fn floor_and_square(square_x: f64) -> String {
    format!(
        r#"
[[object]]
name = "floor"
polygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]

[[object]]
name = "square"
polygons = [[[-2, 5, 2], [2, 5, 2], [2, 5, -2], [-2, 5, -2]]]
translate = [{square_x}, 0, 0]
"#
    )
}

/// A 2 x 2 area light at y = 10 over the origin, facing down.
pub(crate) const AREA_LIGHT: &str = r#"
[[light]]
type = "area"
vertices = [[-1, 10, -1], [1, 10, -1], [1, 10, 1], [-1, 10, 1]]
intensity = 2.0
"#;

fn area(points: &[[f64; 3]]) -> f64 {
    let mut n = [0.0; 3];
    for i in 1..points.len() - 1 {
        let (a, b, c) = (points[0], points[i], points[i + 1]);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        n[0] += u[1] * v[2] - u[2] * v[1];
        n[1] += u[2] * v[0] - u[0] * v[2];
        n[2] += u[0] * v[1] - u[1] * v[0];
    }
    0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}

/// Area per (source, class) with class 0 lit, 1 penumbra, 2 umbra.
fn class_areas(mesh: &OutputMesh, source: u32) -> [f64; 3] {
    let mut out = [0.0; 3];
    for f in mesh.faces.iter().filter(|f| f.source == source) {
        let pts: Vec<[f64; 3]> = f
            .vertices
            .iter()
            .map(|&v| mesh.vertices[v as usize].0)
            .collect();
        let class = if f.lit_mask & 1 != 0 {
            0
        } else if f.umbra_mask & 1 != 0 {
            2
        } else {
            1
        };
        out[class] += area(&pts);
    }
    out
}

/// The floor's (source 0) and the square's (source 1) class areas agree.
fn assert_same_areas(a: &OutputMesh, b: &OutputMesh) {
    for source in [0, 1] {
        let (x, y) = (class_areas(a, source), class_areas(b, source));
        for c in 0..3 {
            assert!(
                (x[c] - y[c]).abs() < 1e-9,
                "source {source}: {x:?} vs {y:?}"
            );
        }
    }
}

/// `umbra update scene.toml` moving the square `steps` times by `by`
/// (`DX,DY,DZ`) into `out`, with `more` options.
fn update_square(dir: &Path, by: &str, steps: &str, out: &str, more: &[&str]) -> Run {
    let mut args = vec![
        "update",
        "scene.toml",
        "--move",
        "square",
        "--by",
        by,
        "--steps",
        steps,
        "-o",
        out,
    ];
    args.extend_from_slice(more);
    umbra(dir, &args)
}

#[test]
fn dm_cells_have_the_exact_shadow_areas_and_stats() {
    let text = scene(0.0);
    let dir = folder(&[("scene.toml", text.as_str())]);
    let run = umbra(
        dir.path(),
        &["dm", "scene.toml", "-o", "out.ply", "--stats", "s.json"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    let floor = class_areas(&mesh, 0);
    assert!((floor[2] - 36.0).abs() < 1e-9, "{floor:?}");
    assert!((floor[1] - (100.0 - 36.0)).abs() < 1e-9, "{floor:?}");
    assert!((floor[0] - (400.0 - 100.0)).abs() < 1e-9, "{floor:?}");
    let square = class_areas(&mesh, 1);
    assert!((square.iter().sum::<f64>() - 16.0).abs() < 1e-9);
    // Vertex irradiance against `umbra shadow` at the points both have.
    let run = umbra(dir.path(), &["shadow", "scene.toml", "-o", "shadow.ply"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let shadow = load_ply(&dir.path().join("shadow.ply")).unwrap();
    let mut matched = 0;
    for (p, e) in &mesh.vertices {
        if let Some((_, f)) = shadow.vertices.iter().find(|(q, _)| q == p) {
            assert!(
                (e - f).abs() <= 1e-5 * e.abs().max(f.abs()) + 1e-7,
                "{p:?}: {e} vs {f}"
            );
            matched += 1;
        }
    }
    assert!(matched >= 8, "{matched}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    for key in [
        "input_polygons",
        "output_fragments",
        "seconds",
        "lights",
        "dm",
    ] {
        assert!(json.get(key).is_some(), "{key}");
    }
    assert_eq!(json["output_fragments"], json["dm"]["cells"]);
    assert!(json["dm"]["tree_nodes"].as_u64().unwrap() >= 8);
    // The run's total counts every phase, the output (with its joint
    // umbra proofs) included.
    let seconds = |v: &serde_json::Value| v.as_f64().unwrap();
    let phases = ["build_seconds", "illum_seconds", "output_seconds"]
        .map(|key| seconds(&json["dm"][key]))
        .iter()
        .sum::<f64>();
    assert!(seconds(&json["seconds"]["total"]) >= phases);
    // Per light, the contract's fields for an area light: the floor's
    // umbra is the square's four umbra planes, its penumbra at least the
    // four outer ones.
    let light = &json["lights"][0];
    for key in [
        "front_facing_polygons",
        "front_facing_edges",
        "penumbra_nodes",
        "umbra_nodes",
        "lit",
        "penumbra",
        "umbra",
    ] {
        assert!(light.get(key).is_some(), "lights[0].{key}");
    }
    assert_eq!(light["umbra_nodes"].as_u64(), Some(4));
    let penumbra_nodes = light["penumbra_nodes"].as_u64().unwrap();
    assert!(penumbra_nodes >= 4, "{penumbra_nodes}");
    assert!(penumbra_nodes + 4 <= json["dm"]["tree_nodes"].as_u64().unwrap());
    // One occluder: every cell vertex lies on the penumbra's outer
    // boundary (unoccluded) or in the umbra's closure (dark), so no vertex
    // needs a visibility computation.
    assert_eq!(json["dm"]["comparisons_per_vertex"].as_f64(), Some(0.0));
    assert_eq!(json["dm"]["visibility_vertices"].as_u64(), Some(0));
}

#[test]
fn update_ends_where_a_scene_built_there_does() {
    let text = scene(0.0);
    let moved = scene(3.0);
    let dir = folder(&[
        ("scene.toml", text.as_str()),
        ("moved.toml", moved.as_str()),
    ]);
    let args = [
        "update",
        "scene.toml",
        "--move",
        "square",
        "--by",
        "1,0,0",
        "--steps",
        "3",
        "-o",
        "out.ply",
        "--stats",
        "s.json",
    ];
    let run = umbra(dir.path(), &args);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        run.stdout
            .lines()
            .filter(|l| l.starts_with("step "))
            .count(),
        3
    );
    let run = umbra(dir.path(), &["dm", "moved.toml", "-o", "moved.ply"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let a = load_ply(&dir.path().join("out.ply")).unwrap();
    let b = load_ply(&dir.path().join("moved.ply")).unwrap();
    assert_same_areas(&a, &b);
    // The umbra moved with the square: [0, 6] x [-3, 3].
    assert!((class_areas(&a, 0)[2] - 36.0).abs() < 1e-9);
    // Collapsing instead of the paper's deletion, through the shadow
    // overlap cube instead of the grid: the same regions.
    let mut other = args.to_vec();
    other[9] = "alt.ply";
    other.truncate(10);
    other.extend(["--deletion", "collapse", "--overlap", "cube"]);
    let run = umbra(dir.path(), &other);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let c = load_ply(&dir.path().join("alt.ply")).unwrap();
    assert_same_areas(&a, &c);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(
        json["update"]["update_seconds"].as_array().unwrap().len(),
        3
    );
    assert_eq!(
        json["update"]["rebuild_seconds"].as_array().unwrap().len(),
        3
    );
    // Each step changed the floor's cells and made the square anew.
    let changed = json["update"]["changed_receivers"].as_array().unwrap();
    assert_eq!(changed.len(), 3);
    assert!(changed.iter().all(|n| n.as_u64() == Some(2)), "{changed:?}");
}

#[test]
fn update_carries_an_object_off_the_scene_box() {
    // The square ends 30 to the right, beyond the floor's edge (the box of
    // the scene is [-10, 10] along x): the grid grows to hold its way, and
    // the end state is what a scene built there gives, the floor all lit.
    let text = scene(0.0);
    let far = scene(30.0);
    let dir = folder(&[("scene.toml", text.as_str()), ("far.toml", far.as_str())]);
    let run = update_square(dir.path(), "10,0,0", "3", "out.ply", &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr.contains("leaves the scene's box: the grid grew"),
        "{}",
        run.stderr
    );
    let run = umbra(dir.path(), &["dm", "far.toml", "-o", "far.ply"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let a = load_ply(&dir.path().join("out.ply")).unwrap();
    let b = load_ply(&dir.path().join("far.ply")).unwrap();
    assert_eq!(class_areas(&a, 0), [400.0, 0.0, 0.0]);
    assert_same_areas(&a, &b);
    // A move within the box keeps the scene's grid: no warning.
    let run = update_square(dir.path(), "2,0,0", "3", "near.ply", &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(!run.stderr.contains("warning"), "{}", run.stderr);
    // A way so long that the scene no longer holds on the grid is an
    // error naming `--by`, and nothing is written.
    for by in ["1e30,0,0", "1e308,0,0"] {
        let run = update_square(dir.path(), by, "2", "gone.ply", &[]);
        assert_eq!(run.code, 2, "{by}: {}", run.stderr);
        assert!(run.stderr.contains("--by: 2 steps of"), "{}", run.stderr);
        assert!(!dir.path().join("gone.ply").exists());
    }
}

/// `path`'s OBJ has the PLY `mesh`'s faces in order: the same corners, and
/// a group naming each face's source and masks.
fn assert_obj_is_ply(path: &Path, mesh: &OutputMesh) {
    let obj = umbra::ObjMesh::load(path).unwrap();
    assert_eq!(obj.faces.len(), mesh.faces.len());
    for (o, p) in obj.faces.iter().zip(&mesh.faces) {
        let corners: Vec<[f64; 3]> = p
            .vertices
            .iter()
            .map(|&v| mesh.vertices[v as usize].0)
            .collect();
        assert_eq!(o.vertices, corners);
        let group = format!(
            "source_{}_lit_{}_umbra_{}",
            p.source, p.lit_mask, p.umbra_mask
        );
        assert_eq!(o.group.as_deref(), Some(group.as_str()));
    }
}

#[test]
fn dm_and_update_write_the_cells_as_obj_too() {
    let text = scene(0.0);
    let dir = folder(&[("scene.toml", text.as_str())]);
    let run = umbra(
        dir.path(),
        &["dm", "scene.toml", "-o", "dm.ply", "--obj", "dm.obj"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("dm.ply")).unwrap();
    assert!(mesh.faces.len() > 9, "penumbra and umbra cells");
    assert_obj_is_ply(&dir.path().join("dm.obj"), &mesh);

    let run = update_square(dir.path(), "1,0,0", "1", "up.ply", &["--obj", "up.obj"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let moved = load_ply(&dir.path().join("up.ply")).unwrap();
    assert_obj_is_ply(&dir.path().join("up.obj"), &moved);
    // The moved shadow's umbra is still 6 x 6, now over x in [-2, 4].
    assert!((class_areas(&moved, 0)[2] - 36.0).abs() < 1e-9);
    assert_ne!(moved.vertices, mesh.vertices);
}
