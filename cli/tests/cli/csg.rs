//! `umbra csg` end to end: closed outputs whose volumes satisfy
//! inclusion-exclusion, and a clear error for an open mesh.

use crate::{folder, umbra};

/// An axis-aligned cube as OBJ, faces outward.
fn cube(lo: [f64; 3], hi: [f64; 3]) -> String {
    let mut s = String::new();
    for i in 0..8 {
        let x = if i & 1 == 0 { lo[0] } else { hi[0] };
        let y = if i & 2 == 0 { lo[1] } else { hi[1] };
        let z = if i & 4 == 0 { lo[2] } else { hi[2] };
        s += &format!("v {x} {y} {z}\n");
    }
    // Corner index = x + 2y + 4z, 1-based in OBJ.
    for f in [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [3, 7, 8, 4],
        [1, 5, 7, 3],
        [2, 4, 8, 6],
    ] {
        s += &format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    s
}

/// Volume and closedness of an OBJ written by `umbra csg`.
fn read(path: &std::path::Path) -> (f64, bool) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut v: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<Vec<usize>> = Vec::new();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => v.push([0, 1, 2].map(|_| it.next().unwrap().parse().unwrap())),
            Some("f") => faces.push(it.map(|i| i.parse::<usize>().unwrap() - 1).collect()),
            _ => {}
        }
    }
    let mut volume = 0.0;
    let mut edges = std::collections::HashMap::new();
    for f in &faces {
        for k in 1..f.len() - 1 {
            let (a, b, c) = (v[f[0]], v[f[k]], v[f[k + 1]]);
            volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0;
        }
        for k in 0..f.len() {
            *edges.entry((f[k], f[(k + 1) % f.len()])).or_insert(0_i32) += 1;
        }
    }
    let closed = edges
        .iter()
        .all(|(&(a, b), &n)| edges.get(&(b, a)) == Some(&n));
    (volume, closed)
}

#[test]
fn cube_operations_satisfy_inclusion_exclusion() {
    let dir = folder(&[
        ("a.obj", &cube([0.0; 3], [2.0; 3])),
        ("b.obj", &cube([1.0, 0.5, 1.5], [3.0, 1.5, 2.5])),
    ]);
    let mut volume = std::collections::HashMap::new();
    for (op, name) in [("--union", "u"), ("--intersect", "i"), ("--subtract", "d")] {
        let out = format!("{name}.obj");
        let run = umbra(dir.path(), &["csg", "a.obj", op, "b.obj", "-o", &out]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let (v, closed) = read(&dir.path().join(&out));
        assert!(closed, "{op} output is not closed");
        volume.insert(name, v);
    }
    let (a, b) = (8.0, 2.0);
    assert!(
        (volume["u"] + volume["i"] - (a + b)).abs() < 1e-9 * (a + b),
        "{volume:?}"
    );
    assert!(
        (volume["d"] + volume["i"] - a).abs() < 1e-9 * a,
        "{volume:?}"
    );
    assert!((volume["i"] - 0.5).abs() < 1e-9, "{volume:?}");
}

#[test]
fn an_open_mesh_is_refused() {
    let dir = folder(&[
        ("a.obj", &cube([0.0; 3], [2.0; 3])),
        ("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
    ]);
    refused(
        dir.path(),
        &["a.obj", "--union", "open.obj"],
        &["open.obj", "not closed"],
    );
}

/// Runs `umbra csg ARGS -o out.obj` in `dir`, expecting exit code 2, a
/// message holding each of `words`, and no output file.
fn refused(dir: &std::path::Path, args: &[&str], words: &[&str]) {
    let mut all = vec!["csg"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", "out.obj"]);
    let run = umbra(dir, &all);
    assert_eq!(run.code, 2, "{args:?}: {}", run.stderr);
    assert!(
        words.iter().all(|w| run.stderr.contains(w)),
        "{args:?}: {}",
        run.stderr
    );
    assert!(!dir.join("out.obj").exists());
}

/// A slab thinner than a grid step (1e-8 across a unit cube, snapped to a
/// step of about 1e-7) collapses to a doubled sheet that still closes up:
/// it is refused by name, where the set operations once took the sheet
/// for a solid (an intersection with a cube beside it gave the cube).
#[test]
fn a_mesh_thinner_than_the_grid_is_refused() {
    for (a, b) in [
        (
            cube([0.0; 3], [1.0; 3]),
            cube([0.5, -1.0, -1.0], [0.500_000_01, 2.0, 2.0]),
        ),
        (
            cube([5.0; 3], [6.0; 3]),
            cube([0.5, 0.0, 0.0], [0.500_000_001, 1.0, 1.0]),
        ),
    ] {
        let dir = folder(&[("a.obj", &a), ("thin.obj", &b)]);
        for op in ["--union", "--intersect", "--subtract"] {
            refused(
                dir.path(),
                &["a.obj", op, "thin.obj"],
                &["thin.obj", "encloses no volume"],
            );
        }
    }
}

/// A cube wound inwards encloses a negative volume, and so does a flat
/// tetrahedron (its four corners in the plane x = y) turned by 45 degrees
/// about each axis, which snapping left a hair thick and inside out: each
/// refused by name and reason. The set operations worked on such a mesh's
/// outside (an intersection with a cube gave most of the cube).
#[test]
fn a_mesh_wound_inwards_is_refused() {
    let inward: String = cube([0.0; 3], [1.0; 3])
        .lines()
        .map(|line| match line.strip_prefix("f ") {
            Some(corners) => {
                let mut c: Vec<&str> = corners.split(' ').collect();
                c.reverse();
                format!("f {}\n", c.join(" "))
            }
            None => format!("{line}\n"),
        })
        .collect();
    let flat = "v -3.4445436482630054 -2.9445436482630054 -0.9822330470336318\n\
                v -3.621320343559643 -3.621320343559642 -0.8786796564403581\n\
                v -3.1945436482630063 -3.6945436482630054 -0.6286796564403578\n\
                v -3.017766952966369 -3.017766952966369 -0.7322330470336316\n\
                f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n";
    // The cube beside it, turned as the tetrahedron was: the grid, which
    // encloses both, decides how the tetrahedron snaps.
    let turned = "v -3.017766952966369 -3.017766952966369 -0.7322330470336316\n\
                  v -2.017766952966369 -2.017766952966369 -2.1464466094067265\n\
                  v -0.31066017177982125 -2.3106601717798214 -1.1464466094067263\n\
                  v -1.3106601717798214 -3.3106601717798214 0.2677669529663686\n\
                  v -3.3106601717798214 -1.3106601717798214 0.26776695296636843\n\
                  v -1.603553390593274 -1.603553390593274 1.2677669529663687\n\
                  v -0.6035533905932737 -0.6035533905932737 -0.14644660940672632\n\
                  v -2.3106601717798214 -0.3106601717798212 -1.1464466094067265\n\
                  f 1 2 3 4\nf 5 6 7 8\nf 1 4 6 5\nf 2 8 7 3\nf 1 5 8 2\nf 4 3 7 6\n";
    let dir = folder(&[
        ("a.obj", &cube([-4.0; 3], [0.0; 3])),
        ("turned.obj", turned),
        ("inward.obj", &inward),
        ("flat.obj", flat),
    ]);
    for (a, b) in [("a.obj", "inward.obj"), ("turned.obj", "flat.obj")] {
        for op in ["--union", "--intersect", "--subtract"] {
            refused(
                dir.path(),
                &[a, op, b],
                &[b, "negative volume", "wound inwards"],
            );
        }
    }
}

/// A unit cube whose top is two quads, its front and back faces carrying
/// their shared corner in line with their own: every edge pairs, and the
/// mesh is closed (it was refused: the convex pieces drop the in-line
/// corner, and their edges no longer paired).
#[test]
fn a_face_split_along_its_neighbours_is_closed() {
    let split = "v 0 0 0\nv 0 0 1\nv 0 1 1\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 1 1 1\nv 1 0 1\n\
                 v 0.5 1 0\nv 0.5 1 1\n\
                 f 1 2 3 4\nf 5 6 7 8\nf 1 5 8 2\nf 4 3 10 9\nf 9 10 7 6\nf 1 4 9 6 5\nf 2 8 7 10 3\n";
    let dir = folder(&[("split.obj", split), ("b.obj", &cube([0.5; 3], [1.5; 3]))]);
    volumes_are(
        dir.path(),
        "split.obj",
        "b.obj",
        [
            ("--union", 1.875),
            ("--intersect", 0.125),
            ("--subtract", 0.875),
        ],
    );
}

/// A unit cube beside one 1e9 away snaps to nothing (the grid's step is
/// 32): refused by name and reason (it was "not closed, 0 edges without a
/// match").
#[test]
fn a_mesh_lost_to_the_grid_is_refused_so() {
    let dir = folder(&[
        ("a.obj", &cube([0.0; 3], [1.0; 3])),
        ("far.obj", &cube([1e9, 0.0, 0.0], [1e9 + 1.0, 1.0, 1.0])),
    ]);
    refused(
        dir.path(),
        &["a.obj", "--union", "far.obj"],
        &["a.obj", "encloses no volume once snapped"],
    );
}

/// Two cubes apart intersect in nothing: the result is an empty OBJ file,
/// and read back it is the empty solid (it was refused: "has no faces").
/// With a cube of volume 8: the union and the cube minus it are the cube,
/// the intersection and it minus the cube are empty; two empty solids give
/// the empty one. A file of vertices only is read so too; both with a
/// warning that names the file.
#[test]
fn an_empty_result_read_back_is_the_empty_solid() {
    let dir = folder(&[
        ("a.obj", &cube([0.0; 3], [2.0; 3])),
        ("far.obj", &cube([5.0; 3], [6.0; 3])),
        ("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"),
    ]);
    let run = umbra(
        dir.path(),
        &["csg", "a.obj", "--intersect", "far.obj", "-o", "empty.obj"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("0 vertices, 0 faces"), "{}", run.stdout);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("empty.obj")).unwrap(),
        ""
    );
    for empty in ["empty.obj", "points.obj"] {
        for (a, op, b, volume) in [
            ("a.obj", "--union", empty, 8.0),
            (empty, "--union", "a.obj", 8.0),
            ("a.obj", "--subtract", empty, 8.0),
            ("a.obj", "--intersect", empty, 0.0),
            (empty, "--intersect", "a.obj", 0.0),
            (empty, "--subtract", "a.obj", 0.0),
            (empty, "--union", empty, 0.0),
        ] {
            let run = umbra(dir.path(), &["csg", a, op, b, "-o", "out.obj"]);
            assert_eq!(run.code, 0, "{a} {op} {b}: {}", run.stderr);
            let warning = format!("{empty} has no faces: read as the empty solid");
            assert!(
                run.stderr.contains(&warning),
                "{a} {op} {b}: {}",
                run.stderr
            );
            let (found, closed) = read(&dir.path().join("out.obj"));
            assert!(closed, "{a} {op} {b}: not closed");
            assert!(
                (found - volume).abs() < 1e-9,
                "{a} {op} {b}: {found} vs {volume}"
            );
        }
    }
}

/// A unit cube with a two-sided sheet inside (a quad and its reverse at
/// x = 0.5): the sheet bounds no volume and takes no part (its faces
/// split the solid as a wall: the intersection with a box was 0.2656 of
/// volume, open, instead of 0.4219).
#[test]
fn a_two_sided_sheet_inside_a_solid_takes_no_part() {
    let sheet = "v 0.5 0 0\nv 0.5 0 1\nv 0.5 1 1\nv 0.5 1 0\nf 9 10 11 12\nf 12 11 10 9\n";
    let with_sheet = cube([0.0; 3], [1.0; 3]) + sheet;
    // (The sheet's corners are vertices 9-12, after the cube's eight.)
    let dir = folder(&[
        ("a.obj", &with_sheet),
        ("b.obj", &cube([0.25; 3], [1.5; 3])),
    ]);
    let b = 1.25_f64.powi(3);
    let i = 0.75_f64.powi(3);
    volumes_are(
        dir.path(),
        "a.obj",
        "b.obj",
        [
            ("--union", 1.0 + b - i),
            ("--intersect", i),
            ("--subtract", 1.0 - i),
        ],
    );
}

/// A cube whose every face is written twice, the same way round, is the
/// cube: its intersection with a box was 0.1875 of volume and open, the
/// doubled faces kept as walls.
#[test]
fn faces_written_twice_count_once() {
    let twice = {
        let once = cube([0.0; 3], [1.0; 3]);
        let faces: String = once
            .lines()
            .filter(|l| l.starts_with("f "))
            .map(|l| format!("{l}\n"))
            .collect();
        once + &faces
    };
    let dir = folder(&[("a.obj", &twice), ("b.obj", &cube([0.5; 3], [1.5; 3]))]);
    volumes_are(
        dir.path(),
        "a.obj",
        "b.obj",
        [
            ("--union", 1.875),
            ("--intersect", 0.125),
            ("--subtract", 0.875),
        ],
    );
}

/// Runs `umbra csg A OP B -o out.obj` in `dir` for each operation, and
/// checks that each output is closed with the volume expected.
fn volumes_are(dir: &std::path::Path, a: &str, b: &str, expected: [(&str, f64); 3]) {
    for (op, volume) in expected {
        let run = umbra(dir, &["csg", a, op, b, "-o", "out.obj"]);
        assert_eq!(run.code, 0, "{op}: {}", run.stderr);
        let (found, closed) = read(&dir.join("out.obj"));
        assert!(closed, "{op} output is not closed");
        assert!((found - volume).abs() < 1e-9, "{op}: {found} vs {volume}");
    }
}

/// A tetrahedron and a turned cube near (1e6, -1e6, 1e6): exact corners a
/// hair apart round to one `f64` position there, and three faces of the
/// union were quads with two corners at each of two places (no area).
/// Vertices at one position are one now: every face has three corners
/// apart or more and some area, and the surface is closed.
#[test]
fn far_from_the_origin_no_face_is_flat() {
    let tetrahedron = "v 999998.8705519061 -1000002.3415546853 1000001.314375259\n\
        v 999999.849150214 -1000002.2022225816 999999.892077148\n\
        v 1000000.3742545167 -1000000.7357832222 999998.2877638754\n\
        v 999998.9858401774 -1000001.722300221 1000000.0481870727\n\
        f 2 3 1\nf 4 2 1\nf 3 4 1\nf 4 3 2\n";
    let cube = "v 1000000.0 -1000000.0 1000000.0\n\
        v 1000000.0000030152 -999999.1033398103 999999.5572805583\n\
        v 999998.3525445461 -999999.6053644832 999998.5404955168\n\
        v 999998.3525415309 -1000000.5020246729 999998.9832149586\n\
        v 1000001.133966751 -1000000.7293649595 999998.5227910902\n\
        v 999999.486508282 -1000001.2313896324 999997.5060060488\n\
        v 999999.4865112972 -1000000.3347294426 999997.063286607\n\
        v 1000001.1339697663 -999999.8327047697 999998.0800716485\n\
        f 1 2 3 4\nf 5 6 7 8\nf 1 5 8 2\nf 4 3 7 6\nf 1 4 6 5\nf 2 8 7 3\n";
    let dir = folder(&[("a.obj", tetrahedron), ("b.obj", cube)]);
    let run = umbra(
        dir.path(),
        &["csg", "a.obj", "--union", "b.obj", "-o", "out.obj"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let (_, closed) = read(&dir.path().join("out.obj"));
    assert!(closed);
    let text = std::fs::read_to_string(dir.path().join("out.obj")).unwrap();
    let v: Vec<[f64; 3]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    for face in text.lines().filter_map(|l| l.strip_prefix("f ")) {
        let corners: Vec<[f64; 3]> = face
            .split_whitespace()
            .map(|i| v[i.parse::<usize>().unwrap() - 1])
            .collect();
        let mut apart = corners.clone();
        apart.sort_by(|a, b| a.partial_cmp(b).unwrap());
        apart.dedup();
        assert!(apart.len() >= 3, "face {face}: {corners:?}");
        // Twice its area, from the fan of cross products.
        let n = (1..corners.len() - 1).fold([0.0; 3], |n, k| {
            let (a, b, c) = (corners[0], corners[k], corners[k + 1]);
            let (u, w) = (
                [0, 1, 2].map(|i| b[i] - a[i]),
                [0, 1, 2].map(|i| c[i] - a[i]),
            );
            [
                n[0] + u[1] * w[2] - u[2] * w[1],
                n[1] + u[2] * w[0] - u[0] * w[2],
                n[2] + u[0] * w[1] - u[1] * w[0],
            ]
        });
        assert!(
            n.iter().map(|x| x * x).sum::<f64>().sqrt() > 1e-3,
            "face {face}"
        );
    }
}

/// A turned cube as OBJ: corners 0-3 one face's, 4-7 the opposite face's.
fn turned_cube(corners: [[f64; 3]; 8]) -> String {
    let mut s = String::new();
    for [x, y, z] in corners {
        s += &format!("v {x:?} {y:?} {z:?}\n");
    }
    s + "f 1 2 3 4\nf 5 6 7 8\nf 1 5 8 2\nf 4 3 7 6\nf 1 4 6 5\nf 2 8 7 3\n"
}

/// Three turned cubes intersected, the result fed back in (an adversarial
/// sweep's chain): it has corners 2.7e-9 apart, and snapped to a step of
/// 1.2e-7 its surface folds, which the solid's BSP takes for walls (`A -
/// A` was written open, of volume -0.17). With a tetrahedron apart, and
/// with itself, every operation is closed with the right volume.
#[test]
fn a_surface_that_snapping_folds_gives_no_open_output() {
    let half = |c: [[f64; 3]; 4]| -> [[f64; 3]; 8] {
        // The opposite face's corners mirror these through the centre.
        let m = |p: [f64; 3]| p.map(|x| -x);
        [c[0], c[1], c[2], c[3], m(c[2]), m(c[1]), m(c[0]), m(c[3])]
    };
    let cubes = [
        half([
            [-1.2804257960403733, 0.9014085336406722, -0.7402516033850581],
            [
                -0.24867354808946118,
                -0.5710881566995175,
                -1.616174428630198,
            ],
            [
                -0.42391504876961006,
                -1.6789035634832157,
                0.03973482037230697,
            ],
            [
                -1.4556672967205224,
                -0.20640687314302608,
                0.9156576456174468,
            ],
        ]),
        half([
            [
                -0.33182086746196976,
                1.2534935214935239,
                -1.1483243894869388,
            ],
            [1.0728118746129724, 1.3320724842781557, 0.27323538994504837],
            [1.63839142773744, -0.5313459370258864, -0.18260620121604765],
            [0.2337586856624978, -0.6099248998105182, -1.6041659806480348],
        ]),
        half([
            [
                -1.2669738496334348,
                -1.1545228592299797,
                -0.24870511024196285,
            ],
            [
                -0.45364581345859584,
                -0.6957449719344475,
                1.5199159220033929,
            ],
            [-0.5572424849154685, 1.2486478230811737, 1.0631836280341602],
            [-1.3705705210903074, 0.7898699357856416, -0.7054374042111954],
        ]),
    ];
    // A tetrahedron 1.22 away from their intersection.
    let tetrahedron = "v -3.27267602979005 0.458923972317024 -1.84052632714059\n\
                       v -0.7582986125516564 1.7409073019143988 -1.6549867186576204\n\
                       v -3.835876623865679 1.4408506838190531 -0.992808789235617\n\
                       v -2.9157451457744985 2.504774597312929 0.7454155833128795\n\
                       f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    let dir = folder(&[
        ("m0.obj", &turned_cube(cubes[0])),
        ("m1.obj", &turned_cube(cubes[1])),
        ("m2.obj", &turned_cube(cubes[2])),
        ("b.obj", tetrahedron),
    ]);
    for args in [
        ["m0.obj", "--intersect", "m1.obj", "-o", "m01.obj"],
        ["m01.obj", "--intersect", "m2.obj", "-o", "a.obj"],
    ] {
        let run = umbra(dir.path(), &[&["csg"], &args[..]].concat());
        assert_eq!(run.code, 0, "{args:?}: {}", run.stderr);
    }
    let (whole, closed) = read(&dir.path().join("a.obj"));
    assert!(closed && whole > 1.0, "{whole}");
    // With the tetrahedron apart: the folds' cells labelled by winding
    // number (their last planes' sides put the tetrahedron inside, and
    // the union came out open), each result closed and right.
    let (tetra, _) = read(&dir.path().join("b.obj"));
    for (op, expected) in [
        ("--union", whole + tetra),
        ("--intersect", 0.0),
        ("--subtract", whole),
    ] {
        let run = umbra(dir.path(), &["csg", "a.obj", op, "b.obj", "-o", "ab.obj"]);
        assert_eq!(run.code, 0, "{op}: {}", run.stderr);
        let (volume, closed) = read(&dir.path().join("ab.obj"));
        assert!(closed && (volume - expected).abs() < 1e-6, "{op}: {volume}");
    }
    for (op, expected) in [
        ("--union", whole),
        ("--intersect", whole),
        ("--subtract", 0.0),
    ] {
        let out = dir.path().join("out.obj");
        let _ = std::fs::remove_file(&out);
        let run = umbra(dir.path(), &["csg", "a.obj", op, "a.obj", "-o", "out.obj"]);
        assert_eq!(run.code, 0, "{op}: {}", run.stderr);
        let (volume, closed) = read(&out);
        assert!(closed && (volume - expected).abs() < 1e-6, "{op}: {volume}");
    }
}
