//! `umbra shadow` with area lights end to end: classes against the exact
//! geometry of a square under a square light, irradiance against direct
//! quadrature over the light with an occlusion test, a conforming mesh
//! (no T-vertex), gridding and adaptive subdivision, stats.

use crate::{folder, umbra};
use umbra::{OutputMesh, load_ply};

/// Floor 20 x 20 at y = 0, a 4 x 4 square at y = 5, a 2 x 2 light at
/// y = 10 facing down: umbra |x|, |z| <= 3, penumbra out to 5.
const SQUARE_UNDER_LIGHT: &str = r#"
[[object]]
name = "floor"
polygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]

[[object]]
name = "square"
polygons = [[[-2, 5, 2], [2, 5, 2], [2, 5, -2], [-2, 5, -2]]]

[[light]]
type = "area"
vertices = [[-1, 10, -1], [1, 10, -1], [1, 10, 1], [-1, 10, 1]]
intensity = 2.0
"#;

/// Irradiance at floor point `p` (normal +y) from the light of
/// [`SQUARE_UNDER_LIGHT`] by midpoint quadrature over the light, each
/// sample blocked when its ray crosses the square.
fn quadrature(p: [f64; 3]) -> f64 {
    light_quadrature(p, |p, d| {
        // Where the ray crosses y = 5.
        let t = (5.0 - p[1]) / d[1];
        let c = [p[0] + t * d[0], p[2] + t * d[2]];
        (0.0..1.0).contains(&t) && c[0].abs() < 2.0 && c[1].abs() < 2.0
    })
}

/// Irradiance at floor point `p` (normal +y) from the 2 x 2 light of
/// radiance 2 at y = 10 facing down, by midpoint quadrature over it: the
/// samples whose ray (from `p`, along `d` to the sample) is `blocked`
/// count nothing.
fn light_quadrature(p: [f64; 3], blocked: impl Fn([f64; 3], [f64; 3]) -> bool) -> f64 {
    let n = 400;
    let h = 2.0 / f64::from(n);
    let mut e = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = [
                -1.0 + (f64::from(i) + 0.5) * h,
                10.0,
                -1.0 + (f64::from(j) + 0.5) * h,
            ];
            let d = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
            if blocked(p, d) {
                continue;
            }
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            // cos at the floor (normal +y) and at the light (normal -y).
            let cos = d[1] / r2.sqrt();
            // Radiance 2: E = L * integral of cos * cos' / r^2 over the light.
            e += 2.0 * cos * cos / r2 * h * h;
        }
    }
    e
}

pub(crate) fn face_points(mesh: &OutputMesh, f: usize) -> Vec<[f64; 3]> {
    mesh.faces[f]
        .vertices
        .iter()
        .map(|&i| mesh.vertices[i as usize].0)
        .collect()
}

pub(crate) fn area(v: &[[f64; 3]]) -> f64 {
    // Floor faces: the xz-plane area.
    let mut a = 0.0;
    for i in 0..v.len() {
        let (p, q) = (v[i], v[(i + 1) % v.len()]);
        a += p[0] * q[2] - q[0] * p[2];
    }
    0.5 * a.abs()
}

/// No vertex of the mesh lies strictly inside an edge of a face.
fn assert_no_t_vertices(mesh: &OutputMesh) {
    for (f, face) in mesh.faces.iter().enumerate() {
        let pts = face_points(mesh, f);
        for k in 0..pts.len() {
            let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
            let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let len2 = d.iter().map(|x| x * x).sum::<f64>();
            for (v, (p, _)) in mesh.vertices.iter().enumerate() {
                if face.vertices.contains(&(v as u32)) {
                    continue;
                }
                let w = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
                let t = (0..3).map(|i| w[i] * d[i]).sum::<f64>() / len2;
                if t <= 1e-9 || t >= 1.0 - 1e-9 {
                    continue;
                }
                let off = (0..3).map(|i| (w[i] - t * d[i]).powi(2)).sum::<f64>();
                assert!(
                    off > 1e-14 * len2,
                    "face {f} edge {k}: vertex {v} at {p:?} inside it"
                );
            }
        }
    }
}

#[test]
fn a_square_under_a_square_light() {
    let dir = folder(&[("scene.toml", SQUARE_UNDER_LIGHT)]);
    let run = umbra(
        dir.path(),
        &[
            "shadow",
            "scene.toml",
            "-o",
            "out.ply",
            "--stats",
            "s.json",
            "--grid",
            "8",
        ],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    let (mut lit, mut pen, mut umb) = (0.0, 0.0, 0.0);
    for (f, face) in mesh.faces.iter().enumerate() {
        if face.source != 0 {
            continue;
        }
        let a = area(&face_points(&mesh, f));
        match (face.lit_mask & 1, face.umbra_mask & 1) {
            (1, 0) => lit += a,
            (0, 1) => umb += a,
            (0, 0) => pen += a,
            _ => panic!("face {f} lit and umbra"),
        }
    }
    assert!((umb - 36.0).abs() < 1e-9, "umbra {umb}");
    assert!((pen - 64.0).abs() < 1e-9, "penumbra {pen}");
    assert!((lit - 300.0).abs() < 1e-9, "lit {lit}");
    assert_no_t_vertices(&mesh);

    // Irradiance at every floor vertex against quadrature; umbra faces are
    // dark, lit faces see the whole light.
    let mut checked = 0;
    for face in mesh.faces.iter().filter(|f| f.source == 0) {
        for &v in &face.vertices {
            let (p, e) = mesh.vertices[v as usize];
            if face.umbra_mask & 1 != 0 {
                assert!(f64::from(e).abs() < 1e-6, "umbra vertex {p:?}: {e}");
                continue;
            }
            if checked % 7 == 0 {
                let truth = quadrature(p);
                assert!(
                    (f64::from(e) - truth).abs() <= 2e-3 * truth + 1e-5,
                    "vertex {p:?}: {e} vs {truth}"
                );
            }
            checked += 1;
        }
    }
    assert!(checked > 50);

    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    let light = &stats["lights"][0];
    for key in [
        "penumbra_nodes",
        "umbra_nodes",
        "lit",
        "penumbra",
        "umbra",
        "lit_vertices",
        "penumbra_vertices",
        "umbra_vertices",
    ] {
        assert!(light[key].as_u64().is_some(), "{key} in {light}");
    }
    assert!(light.get("tree_nodes").is_none());
    assert!(light["penumbra_vertices"].as_u64().unwrap() > 0);
}

#[test]
fn point_and_area_lights_in_one_run() {
    let scene = format!(
        "{SQUARE_UNDER_LIGHT}\n[[light]]\ntype = \"point\"\nposition = [8, 10, 0]\nintensity = 50.0\n"
    );
    let dir = folder(&[("scene.toml", scene.as_str())]);
    let run = umbra(dir.path(), &["shadow", "scene.toml", "-o", "out.ply"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    // The point light (bit 1) is lit or umbra everywhere; the area light
    // (bit 0) has all three classes on the floor.
    let mut classes = [false; 3];
    for face in &mesh.faces {
        assert_eq!((face.lit_mask | face.umbra_mask) & 2, 2);
        assert_eq!(face.lit_mask & face.umbra_mask, 0);
        if face.source == 0 {
            classes[match (face.lit_mask & 1, face.umbra_mask & 1) {
                (1, _) => 0,
                (_, 1) => 2,
                _ => 1,
            }] = true;
        }
    }
    assert_eq!(classes, [true; 3]);
    assert_no_t_vertices(&mesh);
}

#[test]
fn adaptive_subdivision_refines_where_light_changes() {
    let dir = folder(&[("scene.toml", SQUARE_UNDER_LIGHT)]);
    let coarse = umbra(dir.path(), &["shadow", "scene.toml", "-o", "a.ply"]);
    assert_eq!(coarse.code, 0, "{}", coarse.stderr);
    let fine = umbra(
        dir.path(),
        &["shadow", "scene.toml", "-o", "b.ply", "--adaptive", "0.2"],
    );
    assert_eq!(fine.code, 0, "{}", fine.stderr);
    let (a, b) = (
        load_ply(&dir.path().join("a.ply")).unwrap(),
        load_ply(&dir.path().join("b.ply")).unwrap(),
    );
    assert!(
        b.faces.len() > 2 * a.faces.len(),
        "{} vs {}",
        b.faces.len(),
        a.faces.len()
    );
    assert_no_t_vertices(&b);
    // Every face with some light left varies by at most the tolerance, or
    // reached the smallest cell (1/1024 of the scene: 0.02 here).
    for (f, face) in b.faces.iter().enumerate() {
        let pts = face_points(&b, f);
        let es: Vec<f64> = face
            .vertices
            .iter()
            .map(|&v| f64::from(b.vertices[v as usize].1))
            .collect();
        let hi = es.iter().copied().fold(0.0, f64::max);
        let lo = es.iter().copied().fold(f64::MAX, f64::min);
        let size = (0..3)
            .map(|i| {
                pts.iter().map(|p| p[i]).fold(f64::MIN, f64::max)
                    - pts.iter().map(|p| p[i]).fold(f64::MAX, f64::min)
            })
            .fold(0.0, f64::max);
        assert!(
            hi - lo <= 0.2 * hi + 1e-6 || size < 0.05,
            "face {f}: {lo}..{hi}, size {size}"
        );
    }
    let bad = umbra(
        dir.path(),
        &["shadow", "scene.toml", "-o", "c.ply", "--adaptive", "-1"],
    );
    assert_eq!(bad.code, 2);
    assert!(!dir.path().join("c.ply").exists());
}

#[test]
fn output_does_not_depend_on_the_thread_count() {
    // The room demo (two quad lights) with a grid: trees, classification,
    // conforming mesh and illumination all run in parallel.
    let dir = folder(&[]);
    let scene = umbra::Scene::load(umbra::write_demo("room", dir.path()).unwrap()).unwrap();
    let options = umbra::ShadowOptions {
        grid: Some(12),
        adaptive: None,
    };
    let run = |threads: usize| {
        let pool = illum::rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| umbra::shadow_scene_with(&scene, &options).unwrap())
    };
    let one = run(1);
    for threads in [2, 3] {
        let many = run(threads);
        assert_eq!(one.mesh, many.mesh, "{threads} threads");
        assert_eq!(
            one.light_irradiance, many.light_irradiance,
            "{threads} threads"
        );
    }
}

/// The floor's areas (lit, penumbra, umbra) for light 0 in a PLY written
/// by `umbra shadow` or `umbra dm`.
pub(crate) fn floor_classes(mesh: &OutputMesh) -> [f64; 3] {
    floor_classes_for(mesh, 0)
}

/// [`floor_classes`] for light `light`.
pub(crate) fn floor_classes_for(mesh: &OutputMesh, light: u32) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (f, face) in mesh.faces.iter().enumerate() {
        if face.source != 0 {
            continue;
        }
        let a = area(&face_points(mesh, f));
        match ((face.lit_mask >> light) & 1, (face.umbra_mask >> light) & 1) {
            (1, 0) => out[0] += a,
            (0, 0) => out[1] += a,
            (0, 1) => out[2] += a,
            _ => panic!("face {f} lit and umbra"),
        }
    }
    out
}

/// [`SQUARE_UNDER_LIGHT`] with the square given as two triangles of an
/// OBJ mesh: together they hide all of the light from the square's umbra,
/// which neither does alone; both commands mark it umbra.
#[test]
fn a_square_in_two_triangles_casts_the_squares_umbra() {
    let scene = SQUARE_UNDER_LIGHT.replace(
        "polygons = [[[-2, 5, 2], [2, 5, 2], [2, 5, -2], [-2, 5, -2]]]",
        "mesh = \"square.obj\"",
    );
    let obj = "v -2 5 2\nv 2 5 2\nv 2 5 -2\nv -2 5 -2\nf 1 2 3\nf 1 3 4\n";
    let dir = folder(&[("scene.toml", scene.as_str()), ("square.obj", obj)]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let [lit, pen, umb] = floor_classes(&mesh);
        assert!((umb - 36.0).abs() < 1e-9, "{command}: umbra {umb}");
        assert!((pen - 64.0).abs() < 1e-9, "{command}: penumbra {pen}");
        assert!((lit - 300.0).abs() < 1e-9, "{command}: lit {lit}");
    }
}

/// A UV sphere of triangles (its quads' halves meet at slight creases once
/// rounded to the grid) over the floor: the floor right under it sees none
/// of the light, and both commands say so.
#[test]
fn a_triangulated_sphere_has_an_umbra_under_it() {
    let mut obj = String::new();
    let (rings, segments) = (8, 16);
    for i in 0..=rings {
        for j in 0..segments {
            let t = std::f64::consts::PI * f64::from(i) / f64::from(rings);
            let f = 2.0 * std::f64::consts::PI * f64::from(j) / f64::from(segments);
            obj += &format!(
                "v {} {} {}\n",
                t.sin() * f.cos(),
                3.0 + t.cos(),
                t.sin() * f.sin()
            );
        }
    }
    let at = |i: u32, j: u32| i * segments + j % segments + 1;
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            // Counter-clockwise seen from outside; the poles' slivers are
            // degenerate and dropped, the surface stays closed.
            if i > 0 {
                obj += &format!("f {a} {b} {c}\n");
            }
            if i + 1 < rings {
                obj += &format!("f {a} {c} {d}\n");
            }
        }
    }
    let scene = r#"
[[object]]
name = "floor"
polygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]

[[object]]
name = "ball"
mesh = "ball.obj"

[[light]]
type = "area"
vertices = [[-0.5, 8, -0.5], [0.5, 8, -0.5], [0.5, 8, 0.5], [-0.5, 8, 0.5]]
intensity = 1.0
"#;
    let dir = folder(&[("scene.toml", scene), ("ball.obj", obj.as_str())]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        // The floor face holding the point under the sphere's centre.
        let under = mesh.faces.iter().enumerate().find(|(f, face)| {
            face.source == 0 && contains_xz(&face_points(&mesh, *f), [0.01, 0.02])
        });
        let (_, face) = under.expect("a floor face under the sphere");
        assert_eq!(
            face.umbra_mask & 1,
            1,
            "{command}: not umbra under the sphere"
        );
        let [_, _, umb] = floor_classes(&mesh);
        // The sphere hides all of the light from a disc of radius about
        // 0.75 (a cone from the light's corners past the sphere).
        assert!(umb > 1.0, "{command}: umbra {umb}");
    }
}

/// Whether the convex polygon `v` (on the floor) holds the point `p` of
/// the xz-plane.
fn contains_xz(v: &[[f64; 3]], p: [f64; 2]) -> bool {
    let n = v.len();
    let side = |i: usize| {
        let (a, b) = (v[i], v[(i + 1) % n]);
        (b[0] - a[0]) * (p[1] - a[2]) - (b[2] - a[2]) * (p[0] - a[0])
    };
    (0..n).all(|i| side(i) > 0.0) || (0..n).all(|i| side(i) < 0.0)
}

/// Floor 20 x 20 at y = 0, the light of [`SQUARE_UNDER_LIGHT`], and a
/// closed box [0.5, 1.5] x [9, 10] x [-0.5, 0.5] whose top face lies in
/// the light's plane over part of the light: that part shines into the
/// box, and no ray from it gets out.
const BOX_IN_THE_LIGHT: &str = r#"
[[object]]
name = "floor"
polygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]

[[object]]
name = "box"
polygons = [
  [[0.5, 9, -0.5], [1.5, 9, -0.5], [1.5, 9, 0.5], [0.5, 9, 0.5]],
  [[0.5, 10, -0.5], [0.5, 10, 0.5], [1.5, 10, 0.5], [1.5, 10, -0.5]],
  [[0.5, 9, -0.5], [0.5, 9, 0.5], [0.5, 10, 0.5], [0.5, 10, -0.5]],
  [[1.5, 9, -0.5], [1.5, 10, -0.5], [1.5, 10, 0.5], [1.5, 9, 0.5]],
  [[0.5, 9, -0.5], [0.5, 10, -0.5], [1.5, 10, -0.5], [1.5, 9, -0.5]],
  [[0.5, 9, 0.5], [1.5, 9, 0.5], [1.5, 10, 0.5], [0.5, 10, 0.5]],
]

[[light]]
type = "area"
vertices = [[-1, 10, -1], [1, 10, -1], [1, 10, 1], [-1, 10, 1]]
intensity = 2.0
"#;

/// Irradiance at floor point `p` from the light of [`BOX_IN_THE_LIGHT`]
/// by midpoint quadrature, each sample blocked when its ray runs through
/// the box (slab test).
fn quadrature_past_the_box(p: [f64; 3]) -> f64 {
    let (lo, hi) = ([0.5, 9.0, -0.5], [1.5, 10.0, 0.5]);
    light_quadrature(p, |p, d| {
        let (mut enter, mut exit) = (0.0_f64, 1.0_f64);
        for k in 0..3 {
            let (a, b) = ((lo[k] - p[k]) / d[k], (hi[k] - p[k]) / d[k]);
            enter = enter.max(a.min(b));
            exit = exit.min(a.max(b));
        }
        enter < exit
    })
}

#[test]
fn a_box_the_light_shines_into_hides_that_light() {
    let dir = folder(&[("scene.toml", BOX_IN_THE_LIGHT)]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let mut checked = 0;
        for face in mesh.faces.iter().filter(|f| f.source == 0) {
            for &v in &face.vertices {
                let (p, e) = mesh.vertices[v as usize];
                let truth = quadrature_past_the_box(p);
                assert!(
                    (f64::from(e) - truth).abs() <= 2e-3 * truth + 1e-6,
                    "{command}: vertex {p:?}: {e} vs {truth}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 4, "{command}: {checked}");
    }
}

/// Floor 8 x 8 at y = 0, an L-shaped polygon at y = 1.5 (the bar
/// x in [-1, -0.5], z in [-1, 1] and the bar z in [0.5, 1], x in
/// [-0.5, 1]), a 1 x 1 light at y = 4 facing down.
const CONCAVE_OCCLUDER: &str = r#"
[[object]]
name = "floor"
polygons = [[[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]]]

[[object]]
name = "ell"
polygons = [[[-1, 1.5, -1], [-1, 1.5, 1], [1, 1.5, 1], [1, 1.5, 0.5], [-0.5, 1.5, 0.5], [-0.5, 1.5, -1]]]

[[light]]
type = "area"
vertices = [[-0.5, 4, -0.5], [0.5, 4, -0.5], [0.5, 4, 0.5], [-0.5, 4, 0.5]]
"#;

#[test]
fn a_concave_occluder_hides_the_light_where_its_pieces_do_together() {
    // From floor point p the light seen through the L's plane is the
    // square of half-side 0.1875 about 0.625 p; it lies in the L where it
    // lies in one of the bars (an axis-aligned square cannot round the
    // corner): centres in two 0.125-wide strips of length 1.625 that
    // overlap in a 0.125 square, 0.390625 in all, which is 1.0 on the
    // floor (scaled by 1 / 0.625^2). The convex pieces the L is cut into
    // each hide all of the light from less.
    // The same L as two quads, one's edge running past the other's
    // corner (a T-junction).
    let two_quads = CONCAVE_OCCLUDER.replace(
        "polygons = [[[-1, 1.5, -1], [-1, 1.5, 1], [1, 1.5, 1], [1, 1.5, 0.5], [-0.5, 1.5, 0.5], [-0.5, 1.5, -1]]]",
        "polygons = [[[-1, 1.5, -1], [-1, 1.5, 1], [-0.5, 1.5, 1], [-0.5, 1.5, -1]], \
         [[-0.5, 1.5, 0.5], [-0.5, 1.5, 1], [1, 1.5, 1], [1, 1.5, 0.5]]]",
    );
    assert_ne!(two_quads, CONCAVE_OCCLUDER);
    let dir = folder(&[
        ("scene.toml", CONCAVE_OCCLUDER),
        ("quads.toml", two_quads.as_str()),
    ]);
    for scene in ["scene.toml", "quads.toml"] {
        for command in ["shadow", "dm"] {
            let run = umbra(dir.path(), &[command, scene, "-o", "out.ply"]);
            assert_eq!(run.code, 0, "{}", run.stderr);
            let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
            let classes = floor_classes(&mesh);
            let all: f64 = classes.iter().sum();
            assert!(
                (classes[2] - 1.0).abs() < 1e-9,
                "{command} {scene}: {classes:?}"
            );
            assert!((all - 64.0).abs() < 1e-9, "{command} {scene}: {classes:?}");
        }
    }
}

/// [`CONCAVE_OCCLUDER`]'s L turned by a fraction of a degree: the grid
/// bends it, so its pieces (triangles sharing edges) are no flat union,
/// and where they hide the light only together no single piece hides it.
/// Gridded, the floor's cells there are proven dark across the seams
/// (hinges): umbra 0.48 of the flat L's 1.0 (0.0098 before; the rest of
/// the joint umbra lies in cells its curved edge or a corner of three
/// pieces crosses, left penumbra), and not above the flat L's by more
/// than the turn could add (2 %), with every umbra corner dark.
#[test]
fn a_bent_concave_occluder_casts_its_joint_umbra_on_gridded_cells() {
    let scene = CONCAVE_OCCLUDER.replace(
        "name = \"ell\"\n",
        "name = \"ell\"\nrotate_deg = [0.3, 0, 0.2]\n",
    );
    assert_ne!(scene, CONCAVE_OCCLUDER);
    let dir = folder(&[("scene.toml", scene.as_str())]);
    let run = umbra(
        dir.path(),
        &["shadow", "scene.toml", "--grid", "32", "-o", "out.ply"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    let classes = floor_classes(&mesh);
    assert!((0.45..=1.02).contains(&classes[2]), "{classes:?}");
    for face in mesh
        .faces
        .iter()
        .filter(|f| f.source == 0 && f.umbra_mask & 1 != 0)
    {
        for &v in &face.vertices {
            assert!(mesh.vertices[v as usize].1 < 1e-9, "{face:?}");
        }
    }
}

/// [`BOX_IN_THE_LIGHT`] with the box under all of the light: its top face
/// is the light, which shines into it, and no light gets out.
#[test]
fn a_box_that_holds_the_light_in_leaves_the_floor_in_umbra() {
    let scene = BOX_IN_THE_LIGHT
        .replace("0.5, ", "-1, ")
        .replace("1.5, ", "1, ")
        .replace(", -0.5]", ", -1]")
        .replace(", 0.5]", ", 1]");
    assert!(
        scene.contains("[[-1, 9, -1], [1, 9, -1], [1, 9, 1], [-1, 9, 1]]"),
        "{scene}"
    );
    let dir = folder(&[("scene.toml", scene.as_str())]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let classes = floor_classes(&mesh);
        assert!((classes[2] - 400.0).abs() < 1e-9, "{command}: {classes:?}");
        for face in mesh.faces.iter().filter(|f| f.source == 0) {
            for &v in &face.vertices {
                assert_eq!(mesh.vertices[v as usize].1, 0.0, "{command}");
            }
        }
    }
}

/// Runs both commands on each scene file `(name, text)` and checks that
/// the floor's class areas agree with the first's, whose umbra is
/// `umbra_area`.
pub(crate) fn shade_the_floor_alike(scenes: &[(&str, &str)], umbra_area: f64) {
    let dir = folder(scenes);
    for command in ["shadow", "dm"] {
        let classes = |name: &str| {
            let run = umbra(dir.path(), &[command, name, "-o", "out.ply"]);
            assert_eq!(run.code, 0, "{}", run.stderr);
            floor_classes(&load_ply(&dir.path().join("out.ply")).unwrap())
        };
        let want = classes(scenes[0].0);
        assert!((want[2] - umbra_area).abs() < 1e-9, "{command}: {want:?}");
        for (name, _) in &scenes[1..] {
            let got = classes(name);
            for k in 0..3 {
                assert!(
                    (got[k] - want[k]).abs() < 1e-9,
                    "{command} {name}: {got:?} vs {want:?}"
                );
            }
        }
    }
}

/// A box one face short under a light off to its side, open towards the
/// light or away from it: from the floor it hides what the closed box
/// does, in both commands (open at the top, its bottom alone would leave
/// a third of the umbra penumbra).
#[test]
fn an_open_box_shades_the_floor_as_the_closed_one() {
    let faces = [
        "[[-1, 4, -1], [1, 4, -1], [1, 4, 1], [-1, 4, 1]]",
        "[[-1, 5, -1], [-1, 5, 1], [1, 5, 1], [1, 5, -1]]",
        "[[-1, 4, -1], [-1, 4, 1], [-1, 5, 1], [-1, 5, -1]]",
        "[[1, 4, -1], [1, 5, -1], [1, 5, 1], [1, 4, 1]]",
        "[[-1, 4, -1], [-1, 5, -1], [1, 5, -1], [1, 4, -1]]",
        "[[-1, 4, 1], [1, 4, 1], [1, 5, 1], [-1, 5, 1]]",
    ];
    let scene = |skip: Option<usize>| -> String {
        let kept: Vec<&str> = (0..6)
            .filter(|&k| Some(k) != skip)
            .map(|k| faces[k])
            .collect();
        format!(
            "[[object]]\nname = \"floor\"\npolygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]\n\n\
             [[object]]\nname = \"box\"\npolygons = [{}]\n\n\
             [[light]]\ntype = \"area\"\nvertices = [[2, 10, -1], [4, 10, -1], [4, 10, 1], [2, 10, 1]]\n",
            kept.join(", ")
        )
    };
    let (closed, top_open, side_open) = (scene(None), scene(Some(1)), scene(Some(5)));
    shade_the_floor_alike(
        &[
            ("closed.toml", closed.as_str()),
            ("top.toml", top_open.as_str()),
            ("side.toml", side_open.as_str()),
        ],
        6.0,
    );
}

/// Two faces of a turned cube (a black-box check's scene): the grid bends
/// each quad into two triangles, and a DM vertex on one's common edge saw
/// the other triangle, whose plane holds it, hide the whole light
/// (irradiance 0 where nine tenths of the light is seen). Every vertex of
/// both faces, in both commands, against quadrature over the light with
/// the faces as occluders.
#[test]
fn a_vertex_on_a_bent_quads_diagonal_sees_past_the_other_triangle() {
    let faces = [
        [
            [-1.4426075818377362, 0.7403187587841277, -0.9262881186186737],
            [-1.563631949824405, 1.1610647992544156, -0.35923366314232585],
            [-1.03177424859841, 1.5938059030600273, -0.5668087252699244],
            [-0.9107498806117413, 1.1730598625897393, -1.1338631807462722],
        ],
        [
            [-1.563631949824405, 1.1610647992544156, -0.35923366314232585],
            [-1.0991910260315043, 0.7751466859204459, 0.02623581917854656],
            [
                -0.5673333248055095,
                1.2078877897260574,
                -0.18133924294905202,
            ],
            [-1.03177424859841, 1.5938059030600273, -0.5668087252699244],
        ],
    ];
    let polygon = |f: &[[f64; 3]; 4]| {
        let v: Vec<String> = f
            .iter()
            .map(|p| format!("[{}, {}, {}]", p[0], p[1], p[2]))
            .collect();
        format!("[{}]", v.join(", "))
    };
    let scene = format!(
        "[[object]]\nname = \"floor\"\npolygons = [[[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]]]\ncasts_shadows = false\n\n\
         [[object]]\nname = \"c\"\npolygons = [{}, {}]\n\n\
         [[light]]\ntype = \"area\"\nvertices = [[-0.5, 4, -0.5], [0.5, 4, -0.5], [0.5, 4, 0.5], [-0.5, 4, 0.5]]\nintensity = 5.0\n",
        polygon(&faces[0]),
        polygon(&faces[1])
    );
    // Each quad in both triangulations: the grid's bend is far below what
    // the quadrature resolves.
    let triangles: Vec<[[f64; 3]; 3]> = faces
        .iter()
        .flat_map(|f| {
            [
                [f[0], f[1], f[2]],
                [f[0], f[2], f[3]],
                [f[1], f[2], f[3]],
                [f[1], f[3], f[0]],
            ]
        })
        .collect();
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // Whether the segment p + t d, t in (1e-5, 1), crosses the triangle
    // (the output is on the grid: a vertex is a rounding error off its own
    // face, whose crossing at the start counts nothing).
    let crosses = |p: [f64; 3], d: [f64; 3], t: &[[f64; 3]; 3]| {
        let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
        let h = cross(d, e2);
        let det = dot(e1, h);
        if det.abs() < 1e-18 {
            return false;
        }
        let s = sub(p, t[0]);
        let u = dot(s, h) / det;
        let q = cross(s, e1);
        let v = dot(d, q) / det;
        let k = dot(e2, q) / det;
        u > 0.0 && v > 0.0 && u + v < 1.0 && k > 1e-5 && k < 1.0
    };
    let quadrature = |p: [f64; 3], normal: [f64; 3]| {
        let n = 256;
        let h = 1.0 / f64::from(n);
        let mut e = 0.0;
        for i in 0..n {
            for j in 0..n {
                let x = [
                    -0.5 + (f64::from(i) + 0.5) * h,
                    4.0,
                    -0.5 + (f64::from(j) + 0.5) * h,
                ];
                let d = sub(x, p);
                let r2 = dot(d, d);
                let cos = dot(d, normal) / r2.sqrt();
                if cos <= 0.0 || triangles.iter().any(|t| crosses(p, d, t)) {
                    continue;
                }
                e += 5.0 * cos * (d[1] / r2.sqrt()) / r2 * h * h;
            }
        }
        e
    };
    let dir = folder(&[("scene.toml", scene.as_str())]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let mut checked = 0;
        for (f, face) in mesh.faces.iter().enumerate() {
            if face.source == 0 {
                continue;
            }
            let points = face_points(&mesh, f);
            let normal = cross(sub(points[1], points[0]), sub(points[2], points[0]));
            let length = dot(normal, normal).sqrt();
            let normal = normal.map(|c| c / length);
            for &v in &face.vertices {
                let (p, got) = mesh.vertices[v as usize];
                let want = quadrature(p, normal);
                assert!(
                    (f64::from(got) - want).abs() <= 0.02 * want + 2e-4,
                    "{command}: {p:?} has {got}, quadrature {want}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 6, "{command}: {checked} vertices");
    }
}

/// A two-sided upright panel in the plane x = 0 under a 2 x 2 light that
/// this plane cuts in half: the panel takes each half on its own side, so
/// it sees all of the light where nothing else hides any (lit, not
/// penumbra). A small square at y = 7 over x in [0.5, 1.5] hides part of
/// the light's x > 0 half exactly from the panel's points with y <= 4
/// (the plane through the square's edge x = 0.5 and the light's edge
/// x = 1): penumbra 12 below, lit 4 above, in both commands, and the
/// floor, shaded by the panel's volumes on both of its sides, alike.
#[test]
fn a_two_sided_panel_cutting_the_light_sees_all_of_it() {
    let scene = "[[object]]\nname = \"floor\"\npolygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]\n\n\
                 [[object]]\nname = \"panel\"\ntwo_sided = true\npolygons = [[[0, 1, -2], [0, 1, 2], [0, 5, 2], [0, 5, -2]]]\n\n\
                 [[object]]\nname = \"square\"\npolygons = [[[0.5, 7, -0.5], [0.5, 7, 0.5], [1.5, 7, 0.5], [1.5, 7, -0.5]]]\n\n\
                 [[light]]\ntype = \"area\"\nvertices = [[-1, 10, -1], [1, 10, -1], [1, 10, 1], [-1, 10, 1]]\n";
    let dir = folder(&[("scene.toml", scene)]);
    let mut floors = Vec::new();
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let mut panel = [0.0; 3];
        for (f, face) in mesh.faces.iter().enumerate() {
            if face.source != 1 {
                continue;
            }
            let class = match (face.lit_mask & 1, face.umbra_mask & 1) {
                (1, 0) => 0,
                (0, 0) => 1,
                _ => 2,
            };
            // The panel's faces: the yz-plane area.
            let v = face_points(&mesh, f);
            let twice: f64 = (0..v.len())
                .map(|i| {
                    let (p, q) = (v[i], v[(i + 1) % v.len()]);
                    p[1] * q[2] - q[1] * p[2]
                })
                .sum();
            panel[class] += 0.5 * twice.abs();
        }
        for (got, want) in panel.iter().zip([4.0, 12.0, 0.0]) {
            assert!((got - want).abs() < 1e-9, "{command}: {panel:?}");
        }
        floors.push(floor_classes(&mesh));
    }
    for k in 0..3 {
        assert!(
            (floors[0][k] - floors[1][k]).abs() < 1e-9,
            "floor: shadow {:?}, dm {:?}",
            floors[0],
            floors[1]
        );
    }
}
