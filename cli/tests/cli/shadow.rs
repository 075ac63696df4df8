//! `umbra shadow` end to end: the PLY it writes partitions every input
//! polygon, its classes agree with the scene's geometry, and its
//! irradiance follows FORMATS.md.

use crate::vectors::{cross, dot, sub};
use crate::{folder, umbra};
use umbra::{OutputMesh, load_ply};

/// Area of a face of the mesh (world units).
fn face_area(mesh: &OutputMesh, face: usize) -> f64 {
    let v: Vec<[f64; 3]> = mesh.faces[face]
        .vertices
        .iter()
        .map(|&i| mesh.vertices[i as usize].0)
        .collect();
    polygon_area(&v)
}

/// Area of a planar polygon (world units).
fn polygon_area(v: &[[f64; 3]]) -> f64 {
    let mut n = [0.0; 3];
    for i in 1..v.len() - 1 {
        let a = [v[i][0] - v[0][0], v[i][1] - v[0][1], v[i][2] - v[0][2]];
        let b = [
            v[i + 1][0] - v[0][0],
            v[i + 1][1] - v[0][1],
            v[i + 1][2] - v[0][2],
        ];
        n[0] += a[1] * b[2] - a[2] * b[1];
        n[1] += a[2] * b[0] - a[0] * b[2];
        n[2] += a[0] * b[1] - a[1] * b[0];
    }
    0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}

const FLOOR_AND_SQUARE: &str = r#"
[[object]]
name = "floor"
polygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]

[[object]]
name = "square"
polygons = [[[-2, 5, 2], [2, 5, 2], [2, 5, -2], [-2, 5, -2]]]

[[light]]
type = "point"
position = [0, 10, 0]
intensity = 100.0
"#;

#[test]
fn a_square_casts_its_projection() {
    let dir = folder(&[("scene.toml", FLOOR_AND_SQUARE)]);
    let run = umbra(
        dir.path(),
        &[
            "shadow",
            "scene.toml",
            "-o",
            "out.ply",
            "--stats",
            "s.json",
            "--ascii",
        ],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    mesh.check().unwrap();
    // The floor (source 0) partitions into 400 units of area; its umbra is
    // the square projected from the light: [-4, 4]^2.
    let area = |source: u32, umbra: bool| -> f64 {
        (0..mesh.faces.len())
            .filter(|&f| mesh.faces[f].source == source && (mesh.faces[f].umbra_mask == 1) == umbra)
            .map(|f| face_area(&mesh, f))
            .sum()
    };
    assert!((area(0, true) + area(0, false) - 400.0).abs() < 1e-9);
    assert!(
        (area(0, true) - 64.0).abs() < 1e-9,
        "umbra area {}",
        area(0, true)
    );
    // The square faces up, towards the light: lit.
    assert!((area(1, false) - 16.0).abs() < 1e-9);
    for face in &mesh.faces {
        assert_eq!(
            face.lit_mask ^ face.umbra_mask,
            1,
            "a point light leaves no penumbra"
        );
        for &v in &face.vertices {
            let (p, e) = mesh.vertices[v as usize];
            if face.umbra_mask == 1 {
                assert_eq!(e, 0.0);
            } else {
                // intensity * cos / r^2 with the light straight above.
                let d = [-p[0], 10.0 - p[1], -p[2]];
                let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                let expected = 100.0 * (d[1] / r2.sqrt()) / r2;
                assert!(
                    (f64::from(e) - expected).abs() <= 1e-6 * expected,
                    "{e} vs {expected}"
                );
            }
        }
    }
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(stats["input_polygons"], 2);
    assert_eq!(
        stats["output_fragments"].as_u64().unwrap() as usize,
        mesh.faces.len()
    );
    assert_eq!(stats["lights"][0]["front_facing_polygons"], 2);
    for key in ["bsp", "shadow", "grid", "illum", "total"] {
        assert!(stats["seconds"][key].is_number(), "{key}");
    }
}

#[test]
fn demo_scenes_partition_every_input_polygon() {
    let dir = folder(&[]);
    for name in ["tetra", "window", "room"] {
        let run = umbra(dir.path(), &["demo", name, "-o", name]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join(format!("{name}/{name}.ply"))).unwrap();
        mesh.check().unwrap();
        let scene = umbra::Scene::load(dir.path().join(format!("{name}/{name}.toml"))).unwrap();
        let mut area = vec![0.0; scene.polygon_count()];
        for (f, face) in mesh.faces.iter().enumerate() {
            area[face.source as usize] += face_area(&mesh, f);
            // Per light: lit or umbra, never both; only area lights
            // have neither (penumbra).
            assert_eq!(face.lit_mask & face.umbra_mask, 0);
            for (i, light) in scene.lights.iter().enumerate() {
                let point_like = !matches!(light.kind, umbra::LightKind::Area { .. });
                let classified = (face.lit_mask | face.umbra_mask) & (1 << i) != 0;
                assert!(classified || !point_like, "{name} face {f} light {i}");
            }
        }
        for (i, (_, polygon)) in scene.input_polygons().enumerate() {
            let expected = polygon_area(&polygon.vertices);
            // Snapping moves vertices by less than a grid cell.
            assert!(
                (area[i] - expected).abs() <= 1e-5 * expected.max(1.0),
                "{name} polygon {i}: {} vs {expected}",
                area[i]
            );
        }
    }
}

/// A random scene with the degenerate features real scenes have: boxes
/// standing on the floor (coplanar contact), boxes touching each other,
/// coplanar overlapping quads, two-sided and non-casting objects, lights on
/// a polygon's plane or at a vertex, directional lights parallel to walls,
/// lights with a range.
fn degenerate_scene(seed: u64) -> String {
    let mut state = seed;
    let mut next = |m: i64| {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) as i64).rem_euclid(m)
    };
    let mut s = String::from("ambient = 0.1\n");
    s += "[[object]]\nname = \"floor\"\npolygons = [[[-8,0,8],[8,0,8],[8,0,-8],[-8,0,-8]]]\n";
    let boxes = 1 + next(3);
    for b in 0..boxes {
        let (x, z) = (next(8) - 4, next(8) - 4);
        let (w, h, d) = (1 + next(3), 1 + next(3), 1 + next(3));
        let y = if next(2) == 0 { 0 } else { next(3) };
        let (x1, y1, z1) = (x + w, y + h, z + d);
        let two_sided = next(4) == 0;
        let casts = next(5) != 0;
        s += &format!(
            "[[object]]\nname = \"box{b}\"\ntwo_sided = {two_sided}\ncasts_shadows = {casts}\npolygons = [\n\
             [[{x},{y},{z}],[{x},{y1},{z}],[{x1},{y1},{z}],[{x1},{y},{z}]],\n\
             [[{x},{y},{z1}],[{x1},{y},{z1}],[{x1},{y1},{z1}],[{x},{y1},{z1}]],\n\
             [[{x},{y},{z}],[{x1},{y},{z}],[{x1},{y},{z1}],[{x},{y},{z1}]],\n\
             [[{x},{y1},{z}],[{x},{y1},{z1}],[{x1},{y1},{z1}],[{x1},{y1},{z}]],\n\
             [[{x},{y},{z}],[{x},{y},{z1}],[{x},{y1},{z1}],[{x},{y1},{z}]],\n\
             [[{x1},{y},{z}],[{x1},{y1},{z}],[{x1},{y1},{z1}],[{x1},{y},{z1}]]]\n"
        );
    }
    // Two coplanar overlapping quads floating above the floor.
    let h = 3 + next(3);
    s += &format!(
        "[[object]]\nname = \"sheets\"\npolygons = [[[-2,{h},-2],[2,{h},-2],[2,{h},2],[-2,{h},2]], [[0,{h},0],[3,{h},0],[3,{h},3],[0,{h},3]]]\n"
    );
    let lights = 1 + next(3);
    for _ in 0..lights {
        match next(4) {
            // On the sheets' plane, or at one of their vertices.
            0 => {
                s += &format!(
                    "[[light]]\ntype = \"point\"\nposition = [{}, {h}, {}]\n",
                    next(9) - 4,
                    next(9) - 4
                )
            }
            1 => {
                s += &format!(
                    "[[light]]\ntype = \"point\"\nposition = [2, {h}, 2]\nrange = {}\n",
                    3 + next(8)
                )
            }
            // Parallel to the box walls.
            2 => s += "[[light]]\ntype = \"directional\"\ndirection = [0, -1, 0]\n",
            _ => {
                s += &format!(
                    "[[light]]\ntype = \"point\"\nposition = [{}, {}, {}]\n",
                    next(13) - 6,
                    6 + next(6),
                    next(13) - 6
                )
            }
        }
    }
    s
}

#[test]
fn degenerate_scenes_partition_and_classify_consistently() {
    for seed in 0..40 {
        let text = degenerate_scene(seed);
        let dir = folder(&[("scene.toml", &text)]);
        let run = umbra(dir.path(), &["shadow", "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "seed {seed}: {}\n{text}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        mesh.check().unwrap();
        let scene = umbra::Scene::load(dir.path().join("scene.toml")).unwrap();
        let all = (1_u32 << scene.lights.len()) - 1;
        let mut area = vec![0.0; scene.polygon_count()];
        for (f, face) in mesh.faces.iter().enumerate() {
            area[face.source as usize] += face_area(&mesh, f);
            assert_eq!(face.lit_mask & face.umbra_mask, 0, "seed {seed}");
            assert_eq!(
                face.lit_mask | face.umbra_mask,
                all,
                "seed {seed}: a point light leaves no penumbra"
            );
            for &v in &face.vertices {
                let (p, e) = mesh.vertices[v as usize];
                assert!(
                    p.iter().all(|c| c.is_finite()) && e.is_finite() && e >= 0.0,
                    "seed {seed}"
                );
                if face.lit_mask == 0 {
                    assert_eq!(e, 0.0, "seed {seed}: irradiance in umbra");
                }
            }
        }
        for (i, (_, polygon)) in scene.input_polygons().enumerate() {
            let expected = polygon_area(&polygon.vertices);
            // Integer input snaps exactly (power-of-two grid): areas agree to
            // rounding.
            assert!(
                (area[i] - expected).abs() <= 1e-9 * expected,
                "seed {seed} polygon {i}: {} vs {expected}",
                area[i]
            );
        }
    }
}

#[test]
fn svg_draws_one_polygons_fragments() {
    let dir = folder(&[("scene.toml", FLOOR_AND_SQUARE)]);
    let run = umbra(
        dir.path(),
        &["svg", "scene.toml", "--polygon", "0", "-o", "floor.svg"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let svg = std::fs::read_to_string(dir.path().join("floor.svg")).unwrap();
    let run = umbra(dir.path(), &["shadow", "scene.toml", "-o", "out.ply"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    let floor_fragments = mesh.faces.iter().filter(|f| f.source == 0).count();
    assert_eq!(svg.matches("<polygon ").count(), floor_fragments);
    // The square's shadow is drawn in the umbra colour, the rest lit.
    assert!(svg.contains(r##"fill="#555555""##) && svg.contains(r##"fill="#ffe9a0""##));
    assert!(svg.starts_with("<svg ") && svg.trim_end().ends_with("</svg>"));
    let run = umbra(
        dir.path(),
        &["svg", "scene.toml", "--polygon", "7", "-o", "none.svg"],
    );
    assert_eq!(run.code, 2);
    assert!(run.stderr.contains("polygon"), "{}", run.stderr);
    assert!(!dir.path().join("none.svg").exists());
}

/// A polygon of zero area (collinear corners) is dropped and has no
/// fragment: its picture is empty, of finite size (it was `-inf` wide).
#[test]
fn svg_of_a_dropped_polygon_is_empty() {
    let scene = "[[object]]\nname = \"floor\"\npolygons = [[[-5,0,-5],[-5,0,5],[5,0,5],[5,0,-5]]]\n\
                 [[object]]\nname = \"line\"\npolygons = [[[0,1,0],[1,1,0],[2,1,0]]]\n\
                 [[light]]\ntype = \"point\"\nposition = [0.0, 4.0, 0.0]\n";
    let dir = folder(&[("scene.toml", scene)]);
    let run = umbra(
        dir.path(),
        &["svg", "scene.toml", "--polygon", "1", "-o", "line.svg"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let svg = std::fs::read_to_string(dir.path().join("line.svg")).unwrap();
    assert!(!svg.contains("inf") && !svg.contains("NaN"), "{svg}");
    assert!(svg.contains(r#"width="20.0" height="20.0""#), "{svg}");
    assert!(
        svg.contains("0 fragments") && !svg.contains("<polygon "),
        "{svg}"
    );
}

/// Distance from `x` to the convex polygon `v` (counter-clockwise about
/// its normal): to its plane when `x` projects inside, else to its
/// nearest edge.
fn distance_to_polygon(x: [f64; 3], v: &[[f64; 3]]) -> f64 {
    let n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
    let inside =
        (0..v.len()).all(|i| dot(cross(sub(v[(i + 1) % v.len()], v[i]), sub(x, v[i])), n) >= 0.0);
    if inside {
        return dot(sub(x, v[0]), n).abs() / dot(n, n).sqrt();
    }
    (0..v.len())
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let t = (dot(sub(x, a), sub(b, a)) / dot(sub(b, a), sub(b, a))).clamp(0.0, 1.0);
            let p: [f64; 3] = std::array::from_fn(|k| a[k] + t * (b[k] - a[k]));
            dot(sub(x, p), sub(x, p)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// A floor straddling a point light's range, and a panel inside the range
/// whose shadow falls on the floor beyond it: every fragment wholly beyond
/// the range has the umbra bit (it takes no part for the light), also the
/// pieces the shadow and the grid cut from the straddling floor; those
/// within it keep their classes.
#[test]
fn fragments_beyond_a_lights_range_are_umbra() {
    let scene = r#"
[[object]]
name = "floor"
polygons = [[[-4, 0, -1], [-4, 0, 1], [4, 0, 1], [4, 0, -1]]]

[[object]]
name = "panel"
polygons = [[[1.2, 0.5, -0.3], [1.2, 0.5, 0.3], [1.8, 0.5, 0.3], [1.8, 0.5, -0.3]]]

[[light]]
type = "point"
position = [0.0, 1.0, 0.0]
intensity = 1.0
falloff_start = 1.0
range = 2.0
"#;
    let dir = folder(&[("scene.toml", scene)]);
    for grid in [None, Some("16")] {
        let mut args = vec!["shadow", "scene.toml", "-o", "out.ply"];
        args.extend(grid.iter().flat_map(|n| ["--grid", *n]));
        let run = umbra(dir.path(), &args);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let (mut beyond, mut within_lit) = (0, 0);
        for (f, face) in mesh.faces.iter().enumerate() {
            let corners: Vec<[f64; 3]> = face
                .vertices
                .iter()
                .map(|&v| mesh.vertices[v as usize].0)
                .collect();
            let d = distance_to_polygon([0.0, 1.0, 0.0], &corners);
            if d >= 2.0 + 1e-6 {
                beyond += 1;
                assert!(
                    face.umbra_mask & 1 != 0 && face.lit_mask & 1 == 0,
                    "grid {grid:?}: face {f} at {d} from the light is not umbra"
                );
            } else if face.lit_mask & 1 != 0 {
                within_lit += 1;
            }
        }
        assert!(
            beyond >= 2 && within_lit >= 1,
            "grid {grid:?}: {beyond} beyond, {within_lit} lit within"
        );
    }
}

/// The floor's share of each class (lit, penumbra, umbra) under the light,
/// with the scene scaled by `s`: a tilted square between a square light
/// and the floor.
fn class_shares(s: f64) -> [f64; 3] {
    let text = format!(
        "[[object]]\nname = \"floor\"\npolygons = [[[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]]\n\
         scale = {s:e}\n\n[[object]]\nname = \"square\"\n\
         polygons = [[[-0.3, 1, -0.3], [-0.3, 1, 0.3], [0.3, 1, 0.3], [0.3, 1, -0.3]]]\n\
         scale = {s:e}\nrotate_deg = [10, 20, 30]\n\n[[light]]\ntype = \"area\"\n\
         vertices = [[{a:e}, {h:e}, {a:e}], [{b:e}, {h:e}, {a:e}], [{b:e}, {h:e}, {b:e}], [{a:e}, {h:e}, {b:e}]]\n",
        a = -0.2 * s,
        b = 0.2 * s,
        h = 3.0 * s,
    );
    let scene = umbra::Scene::from_toml_str(&text, "scaled.toml").unwrap();
    let mesh = umbra::shadow_scene(&scene).unwrap().mesh;
    let mut shares = [0.0; 3];
    for face in mesh.faces.iter().filter(|f| f.source == 0) {
        // Areas in units of the scale: no square overflows.
        let v: Vec<[f64; 3]> = face
            .vertices
            .iter()
            .map(|&k| mesh.vertices[k as usize].0.map(|x| x / s))
            .collect();
        let class = if face.lit_mask & 1 != 0 {
            0
        } else if face.umbra_mask & 1 != 0 {
            2
        } else {
            1
        };
        shares[class] += polygon_area(&v) / 4.0;
    }
    shares
}

#[test]
fn scenes_1e300_or_a_1e300th_across_shade_as_at_unit_size() {
    // At 1e300 a light's size squared overflows an f64: its checks work
    // relative to its own size.
    let unit = class_shares(1.0);
    assert!(unit[1] > 0.01 && unit[2] > 0.01, "{unit:?}");
    for s in [1e-300, 1e-30, 1e30, 1e300] {
        let scaled = class_shares(s);
        for c in 0..3 {
            assert!(
                (scaled[c] - unit[c]).abs() <= 1e-6,
                "scale {s:e}: {scaled:?} vs {unit:?}"
            );
        }
    }
}

#[test]
fn irradiance_past_the_float_range_is_written_as_the_largest_float() {
    // A unit point light 3e-20 above a floor: 1e38 and more, past f32.
    let text = "[[object]]\nname = \"floor\"\n\
                polygons = [[[-1e-20, 0, -1e-20], [-1e-20, 0, 1e-20], [1e-20, 0, 1e-20], [1e-20, 0, -1e-20]]]\n\n\
                [[light]]\ntype = \"point\"\nposition = [1e-21, 3e-20, 2e-21]\n";
    let scene = umbra::Scene::from_toml_str(text, "tiny.toml").unwrap();
    for mesh in [
        umbra::shadow_scene(&scene).unwrap().mesh,
        umbra::dm_scene(&scene).unwrap().mesh().unwrap(),
    ] {
        assert!(
            mesh.vertices.iter().all(|(_, e)| *e == f32::MAX),
            "{:?}",
            mesh.vertices
        );
    }
}

/// A directional light's direction is any non-zero vector, however small
/// or large its components (its length underflowed to zero for
/// `1e-300`, and `check` passed a scene that `shadow` refused).
#[test]
fn tiny_and_huge_light_directions_shade_like_unit_ones() {
    let scene = |d: &str| {
        format!(
            "[[object]]\nname = \"floor\"\npolygons = [[[-5,0,-5],[-5,0,5],[5,0,5],[5,0,-5]]]\n\
             [[object]]\nname = \"square\"\npolygons = [[[-1,1,-1],[-1,1,1],[1,1,1],[1,1,-1]]]\n\
             [[light]]\ntype = \"directional\"\ndirection = {d}\n"
        )
    };
    let mut outputs = Vec::new();
    for d in [
        "[0.0, -1.0, 0.0]",
        "[0.0, -1e-300, 0.0]",
        "[0.0, -1e300, 0.0]",
    ] {
        let dir = folder(&[("scene.toml", &scene(d))]);
        for command in ["check", "shadow"] {
            let run = umbra(
                dir.path(),
                &[command, "scene.toml", "-o", "out.ply"][..if command == "check" { 2 } else { 4 }],
            );
            assert_eq!(run.code, 0, "{d} {command}: {}", run.stderr);
        }
        outputs.push(std::fs::read(dir.path().join("out.ply")).unwrap());
    }
    assert!(outputs.iter().all(|o| *o == outputs[0]));
}
