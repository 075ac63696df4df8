//! The commands: `demo` writes scenes and runs them, `check` summarises,
//! the discontinuity-mesh commands refuse what they cannot do.

use crate::{TRIANGLE, folder, umbra};

#[test]
fn demo_writes_the_scene_and_prints_its_path() {
    let dir = folder(&[]);
    let run = umbra(dir.path(), &["demo", "tetra", "-o", "out"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        run.stdout.lines().next(),
        Some("wrote the `tetra` scene: out/tetra.toml")
    );
    assert!(dir.path().join("out/tetra.toml").is_file());
    assert!(dir.path().join("out/tetra.ply").is_file());
    assert!(dir.path().join("out/tetra.json").is_file());
    assert!(dir.path().join("out/meshes/tetra.obj").is_file());
    let run = umbra(dir.path(), &["check", "out/tetra.toml"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("input polygons 257"), "{}", run.stdout);

    let run = umbra(dir.path(), &["demo"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(dir.path().join("room/room.toml").is_file());

    let run = umbra(dir.path(), &["demo", "nowhere"]);
    assert_eq!(run.code, 2);
    assert!(run.stderr.contains(
        "unknown demo scene `nowhere` (known: room, room1, tetra, window, office, cubes, meshes)"
    ));
}

#[test]
fn dm_commands_refuse_bad_input_with_exit_2_and_write_nothing() {
    // A point light given a direction: not a field of its kind.
    let scene = format!(
        "{TRIANGLE}[[light]]\ntype = \"point\"\nposition = [0, 3, 0]\ndirection = [0, -1, 0]\n"
    );
    let valid = format!("{TRIANGLE}[[light]]\ntype = \"point\"\nposition = [0, 3, 0]\n");
    let dir = folder(&[
        ("scene.toml", scene.as_str()),
        ("valid.toml", valid.as_str()),
        ("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    ]);
    let runs: [&[&str]; 2] = [
        &["dm", "scene.toml", "-o", "out.ply"],
        &[
            "update",
            "scene.toml",
            "--move",
            "t",
            "--by",
            "-1,0,0.5",
            "--steps",
            "3",
            "-o",
            "out.ply",
        ],
    ];
    for args in runs {
        let run = umbra(dir.path(), args);
        assert_eq!(run.code, 2, "{args:?}");
        assert!(
            run.stderr
                .contains("light[0].direction: not a field of a point light"),
            "{}",
            run.stderr
        );
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);
    let run = umbra(
        dir.path(),
        &[
            "update",
            "valid.toml",
            "--move",
            "nobody",
            "--by",
            "1,0,0",
            "-o",
            "o.ply",
        ],
    );
    assert!(
        run.stderr
            .contains("valid.toml: --move: no object is named `nobody`"),
        "{}",
        run.stderr
    );
    let run = umbra(dir.path(), &["csg", "a.obj", "a.obj", "-o", "out.obj"]);
    assert_eq!(run.code, 2, "an operation is required");
}

#[test]
fn help_documents_every_option() {
    let dir = folder(&[]);
    let expected: [(&str, &[&str]); 7] = [
        (
            "shadow",
            &["--output", "--obj", "--stats", "--grid", "--ascii"],
        ),
        (
            "render",
            &[
                "--output",
                "--view",
                "shaded",
                "classes",
                "fragments",
                "--method",
                "volumes",
                "--order",
                "zbuffer",
                "bsp",
            ],
        ),
        ("dm", &["--output", "--obj", "--stats", "--ascii"]),
        (
            "update",
            &[
                "--move", "--by", "--steps", "--output", "--obj", "--stats", "--ascii",
            ],
        ),
        ("csg", &["--union", "--intersect", "--subtract", "--output"]),
        ("demo", &["--output", "room", "room1", "tetra", "window"]),
        ("check", &["SCENE"]),
    ];
    for (command, options) in expected {
        let run = umbra(dir.path(), &[command, "--help"]);
        assert_eq!(run.code, 0);
        for option in options {
            assert!(
                run.stdout.contains(option),
                "{command} --help lacks {option}"
            );
        }
    }
}

#[test]
fn check_lists_dropped_faces_with_their_line() {
    let dir = folder(&[
        ("scene.toml", "[[object]]\nname = \"m\"\nmesh = \"m.obj\"\n"),
        (
            "m.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n",
        ),
    ]);
    let run = umbra(dir.path(), &["check", "scene.toml"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("input polygons 2"), "{}", run.stdout);
    assert!(run.stdout.contains("dropped        1"), "{}", run.stdout);
    assert!(
        run.stdout.contains("dropped input polygon 1 (m.obj:6)"),
        "{}",
        run.stdout
    );
}

/// Commands that write geometry warn on stderr about the input polygons
/// their output leaves out (here a face in line, no area), name them with
/// their line, and list them in the statistics; a run that drops nothing
/// stays quiet and lists none.
#[test]
fn dropped_faces_are_warned_about_and_listed_in_the_statistics() {
    let light = "[[light]]\ntype = \"area\"\nintensity = 1.0\n\
                 vertices = [[0,3,0],[0.5,3,0],[0.5,3,0.5]]\n";
    let dir = folder(&[
        (
            "scene.toml",
            &format!("[[object]]\nname = \"m\"\nmesh = \"m.obj\"\n{light}"),
        ),
        (
            "whole.toml",
            &format!("[[object]]\nname = \"m\"\npolygons = [[[0,0,0],[1,0,0],[0,1,0]]]\n{light}"),
        ),
        (
            "m.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n",
        ),
    ]);
    let runs: [&[&str]; 3] = [
        &["shadow", "-o", "out.ply", "--stats", "s.json"],
        &["dm", "-o", "out.ply", "--stats", "s.json"],
        &[
            "update", "--move", "m", "--by", "0,0.1,0", "-o", "out.ply", "--stats", "s.json",
        ],
    ];
    for args in runs {
        for (scene, dropped) in [("scene.toml", vec![1]), ("whole.toml", vec![])] {
            let mut all = vec![args[0], scene];
            all.extend(&args[1..]);
            let run = umbra(dir.path(), &all);
            assert_eq!(run.code, 0, "{all:?}: {}", run.stderr);
            if dropped.is_empty() {
                assert_eq!(run.stderr, "", "{all:?}");
            } else {
                assert!(
                    run.stderr
                        .starts_with("umbra: warning: 1 input polygon left out")
                        && run.stderr.contains(": 1 (m.obj:6)\n"),
                    "{all:?}: {}",
                    run.stderr
                );
            }
            let stats: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap())
                    .unwrap();
            assert_eq!(
                stats["dropped_polygons"],
                serde_json::json!(dropped),
                "{all:?}"
            );
        }
    }
}

/// A corner 1e17 units out makes the grid step 5e9: the other object's
/// unit triangle snaps to nothing, and is dropped. The run ends (it once
/// walked the buckets around that triangle's edges for ever, their count
/// wrapped) with both polygons dropped, for every command that loads.
#[test]
fn a_far_corner_drops_small_polygons_and_ends() {
    let dir = folder(&[(
        "scene.toml",
        "[[object]]\nname = \"a\"\npolygons = [[[0,0,0],[1,0,0],[0,0,-1]]]\n\
         [[object]]\nname = \"b\"\npolygons = [[[-1e17,0,0],[1,0,0],[0,0,-1]]]\n",
    )]);
    let run = umbra(dir.path(), &["check", "scene.toml"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("dropped        2"), "{}", run.stdout);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert!(
            !run.stderr.contains("panicked"),
            "{command}: {}",
            run.stderr
        );
        assert_eq!(run.code, 0, "{command}: {}", run.stderr);
    }
}
