//! Every class of bad input gives one clear message and exit code 2.

use crate::{TRIANGLE, folder, umbra};

/// Runs `umbra check scene.toml` (and `umbra shadow`, which validates the
/// same way) on the files, expecting failure with `expected` in the message.
fn fails_with(files: &[(&str, &str)], expected: &str) {
    let dir = folder(files);
    for command in ["check", "shadow"] {
        let run = umbra(dir.path(), &[command, "scene.toml"]);
        assert_eq!(run.code, 2, "{command}: {}", run.stderr);
        assert!(
            run.stderr.contains(expected),
            "{command}: {} / {expected}",
            run.stderr
        );
        assert_eq!(
            run.stderr.trim_end().lines().count(),
            1,
            "one line: {}",
            run.stderr
        );
        assert!(!run.stderr.contains("panicked"), "{}", run.stderr);
        assert!(run.stdout.is_empty());
    }
    // Nothing was written next to the scene.
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert!(
        names
            .iter()
            .all(|n| !n.ends_with(".ply") && !n.contains(".part")),
        "{names:?}"
    );
}

#[test]
fn missing_scene_file() {
    fails_with(&[], "scene.toml: cannot read");
}

#[test]
fn missing_mesh_file() {
    fails_with(
        &[(
            "scene.toml",
            "[[object]]\nname = \"a\"\nmesh = \"meshes/none.obj\"\n",
        )],
        "none.obj: cannot read",
    );
}

#[test]
fn malformed_obj_names_file_and_line() {
    fails_with(
        &[
            ("scene.toml", "[[object]]\nname = \"a\"\nmesh = \"m.obj\"\n"),
            ("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 x\n"),
        ],
        "m.obj:5: face vertex `x` is not an index",
    );
}

#[test]
fn obj_index_out_of_range() {
    fails_with(
        &[
            ("scene.toml", "[[object]]\nname = \"a\"\nmesh = \"m.obj\"\n"),
            ("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n"),
        ],
        "m.obj:5: face vertex 4 does not exist",
    );
}

#[test]
fn nan_in_obj() {
    fails_with(
        &[
            ("scene.toml", "[[object]]\nname = \"a\"\nmesh = \"m.obj\"\n"),
            ("m.obj", "v 0 0 0\nv 1 NaN 0\nv 0 1 0\nf 1 2 3\n"),
        ],
        "m.obj:2: vertex coordinate `NaN` is not finite",
    );
}

#[test]
fn nan_in_scene() {
    fails_with(
        &[(
            "scene.toml",
            "[[object]]\nname = \"a\"\npolygons = [[[0,0,0],[1,nan,0],[0,1,0]]]\n",
        )],
        "scene.toml: object[0].polygons[0]: NaN is not a finite number",
    );
    fails_with(
        &[(
            "scene.toml",
            &format!("{TRIANGLE}[[light]]\ntype = \"point\"\nposition = [0, inf, 0]\n"),
        )],
        "light[0].position: inf is not a finite number",
    );
}

#[test]
fn malformed_toml_names_the_line() {
    fails_with(
        &[("scene.toml", &format!("{TRIANGLE}\n[[light]\n"))],
        "scene.toml:5:",
    );
}

#[test]
fn unknown_field_names_line_and_field() {
    fails_with(
        &[("scene.toml", &format!("{TRIANGLE}shiny = true\n"))],
        "scene.toml:4:1: unknown field `shiny`",
    );
    fails_with(
        &[(
            "scene.toml",
            &format!("{TRIANGLE}[[light]]\ntype = \"spot\"\nposition = [0,1,0]\n"),
        )],
        "scene.toml:5:",
    );
}

#[test]
fn empty_scene() {
    fails_with(
        &[("scene.toml", "ambient = 0.1\n")],
        "the scene has no polygons",
    );
    fails_with(
        &[
            ("scene.toml", "[[object]]\nname = \"a\"\nmesh = \"m.obj\"\n"),
            ("m.obj", "v 0 0 0\n"),
        ],
        "the scene has no polygons",
    );
}

#[test]
fn degenerate_and_non_convex_area_lights() {
    let light = |v: &str| format!("{TRIANGLE}[[light]]\ntype = \"area\"\nvertices = {v}\n");
    fails_with(
        &[("scene.toml", &light("[[0,2,0],[1,2,0],[2,2,0]]"))],
        "light[0].vertices: the polygon encloses no area",
    );
    fails_with(
        &[("scene.toml", &light("[[0,2,0],[1,2,0]]"))],
        "light[0].vertices: an area light needs at least 3 vertices",
    );
    fails_with(
        &[(
            "scene.toml",
            &light("[[0,2,0],[2,2,0],[1,2,-0.2],[1,2,-2]]"),
        )],
        "light[0].vertices: not convex at vertex 2 (reflex)",
    );
}

#[test]
fn more_than_32_lights() {
    let lights = "[[light]]\ntype = \"point\"\nposition = [0, 2, 0]\n".repeat(33);
    fails_with(
        &[("scene.toml", &format!("{TRIANGLE}{lights}"))],
        "scene.toml: light: 33 lights; at most 32",
    );
}

#[test]
fn duplicate_object_names() {
    fails_with(
        &[("scene.toml", &format!("{TRIANGLE}{TRIANGLE}"))],
        "object[1].name: `t` is already the name of object[0]",
    );
}

#[test]
fn mesh_and_polygons_together() {
    fails_with(
        &[("scene.toml", &format!("{TRIANGLE}mesh = \"m.obj\"\n"))],
        "object[0]: has both `mesh` and `polygons`",
    );
}

#[test]
fn usage_errors_exit_2() {
    let dir = folder(&[]);
    let run = umbra(dir.path(), &["shadow"]);
    assert_eq!(run.code, 2);
    let run = umbra(dir.path(), &["frobnicate"]);
    assert_eq!(run.code, 2);
}

#[test]
fn an_output_that_cannot_be_written_leaves_no_other() {
    let scene = format!(
        "{TRIANGLE}\n[[light]]\ntype = \"area\"\nvertices = [[0, 0, 5], [0, 1, 5], [1, 0, 5]]\n"
    );
    let dir = folder(&[("scene.toml", scene.as_str())]);
    std::fs::create_dir(dir.path().join("taken")).unwrap();
    // The statistics' folder is missing, or their name a folder's: the PLY
    // written before them must not stay behind, whichever command.
    for args in [
        &["dm", "scene.toml", "-o", "out.ply", "--stats", "taken"][..],
        &["shadow", "scene.toml", "-o", "out.ply", "--obj", "taken"],
        &[
            "shadow",
            "scene.toml",
            "-o",
            "out.ply",
            "--stats",
            "no/s.json",
        ][..],
        &["shadow", "scene.toml", "-o", "out.ply", "--obj", "no/o.obj"],
        &["dm", "scene.toml", "-o", "out.ply", "--stats", "no/s.json"],
        &["dm", "scene.toml", "-o", "out.ply", "--obj", "taken"],
        &["update", "scene.toml", "--move", "t", "--by", "0,1,0"]
            .iter()
            .chain(&["-o", "out.ply", "--obj", "no/o.obj"])
            .copied()
            .collect::<Vec<_>>(),
        &["update", "scene.toml", "--move", "t", "--by", "0,1,0"]
            .iter()
            .chain(&["-o", "out.ply", "--stats", "no/s.json"])
            .copied()
            .collect::<Vec<_>>(),
    ] {
        let run = umbra(dir.path(), args);
        assert_eq!(run.code, 2, "{args:?}: {}", run.stderr);
        assert!(
            run.stderr.contains("no/") || run.stderr.contains("taken"),
            "{}",
            run.stderr
        );
        let mut names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["scene.toml", "taken"], "{args:?}");
    }
}

#[test]
fn zero_image_size_names_the_field() {
    let camera = |width: u32, height: u32| {
        format!(
            "{TRIANGLE}[camera]\neye = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n\
             up = [0.0, 1.0, 0.0]\nfov_deg = 60.0\nwidth = {width}\nheight = {height}\n"
        )
    };
    fails_with(
        &[("scene.toml", &camera(0, 120))],
        "camera.width: image size must be positive",
    );
    fails_with(
        &[("scene.toml", &camera(160, 0))],
        "camera.height: image size must be positive",
    );
}

/// Every vector is three numbers: four were read as three, the last
/// dropped without a word (an inline polygon's vertex, a translation, a
/// light's position, a camera's eye); two were refused already.
#[test]
fn vectors_of_other_than_three_numbers_name_the_line() {
    for (scene, line) in [
        (
            "[[object]]\nname = \"y\"\npolygons = [[[0,0,0],[1,0,0],[0,1,0,5]]]\n".to_string(),
            "scene.toml:3:",
        ),
        (
            "[[object]]\nname = \"y\"\npolygons = [[[0,0,0],[1,0,0],[0,1]]]\n".to_string(),
            "scene.toml:3:",
        ),
        (
            format!("{TRIANGLE}translate = [1, 2, 3, 4]\n"),
            "scene.toml:4:",
        ),
        (format!("{TRIANGLE}scale = [1, 2, 3, 4]\n"), "scene.toml:4:"),
        (
            format!("{TRIANGLE}[[light]]\ntype = \"point\"\nposition = [0, 5, 0, 1]\n"),
            "scene.toml:6:",
        ),
        (
            format!("{TRIANGLE}[camera]\neye = [0, 2, 8, 1]\n"),
            "scene.toml:5:",
        ),
    ] {
        fails_with(&[("scene.toml", &scene)], line);
    }
}

#[test]
fn a_mesh_that_is_a_device_is_refused() {
    // `/dev/zero` reads for ever; it was read until memory ran out.
    fails_with(
        &[(
            "scene.toml",
            "[[object]]\nname = \"z\"\nmesh = \"/dev/zero\"\n",
        )],
        "/dev/zero: cannot read: not a regular file",
    );
}
