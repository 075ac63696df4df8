//! Fragments tile their input polygon, not its snapped copy: a thin needle,
//! a speck and turned polygons (snapped to the grid, a needle 150 grid steps
//! wide misses its area by 6e-4) keep their area to rounding, lie in their
//! input plane and have their corners where the input has them, in
//! `shadow`, `dm` and after `update` moves one.

use crate::vectors::{newell, norm};
use crate::{folder, umbra};
use proptest::prelude::*;
use umbra::{LightKind, OutputMesh, Scene, dm_scene, load_ply, shadow_scene};

/// An object's polygons, turned by `turn` degrees about x, y and z and
/// moved to `at`, as scene-file text.
fn object(name: &str, polygons: &[Vec<[f64; 3]>], turn: [f64; 3], at: [f64; 3]) -> String {
    let polygons: Vec<String> = polygons
        .iter()
        .map(|p| {
            let corners: Vec<String> = p
                .iter()
                .map(|c| format!("[{:?}, {:?}, {:?}]", c[0], c[1], c[2]))
                .collect();
            format!("[{}]", corners.join(", "))
        })
        .collect();
    format!(
        "[[object]]\nname = \"{name}\"\npolygons = [{}]\nrotate_deg = [{:?}, {:?}, {:?}]\n\
         translate = [{:?}, {:?}, {:?}]\ntwo_sided = true\n\n",
        polygons.join(", "),
        turn[0],
        turn[1],
        turn[2],
        at[0],
        at[1],
        at[2]
    )
}

/// A regular polygon of `n` corners and radius `r` about the origin in
/// the plane y = 0, facing up.
fn regular_polygon(n: u32, r: f64) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let a = f64::from(i) * std::f64::consts::TAU / f64::from(n);
            [r * a.cos(), 0.0, -r * a.sin()]
        })
        .collect()
}

/// A floor, a needle of width `width`, a speck of size `speck`, a turned
/// plate, dart (a concave quad), L and 24-gon over it; `light` is the
/// light's table.
fn scene(width: f64, speck: f64, turn: f64, light: &str) -> Scene {
    let floor = vec![vec![
        [-3.0, 0.0, -3.0],
        [-3.0, 0.0, 3.0],
        [3.0, 0.0, 3.0],
        [3.0, 0.0, -3.0],
    ]];
    let needle = vec![vec![
        [-1.0, 0.0, -width],
        [-1.0, 0.0, width],
        [1.0, 0.0, width],
        [1.0, 0.0, -width],
    ]];
    let speck = vec![vec![[0.0, 0.0, 0.0], [speck, 0.0, 0.0], [0.0, 0.0, -speck]]];
    let plate = vec![vec![
        [-0.5, 0.0, -0.4],
        [-0.5, 0.0, 0.4],
        [0.5, 0.0, 0.4],
        [0.5, 0.0, -0.4],
    ]];
    let dart = vec![vec![
        [0.0, 0.0, 0.0],
        [0.6, 0.0, 0.5],
        [0.0, 0.0, -0.5],
        [-0.6, 0.0, 0.5],
    ]];
    let l = vec![vec![
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.4],
        [0.2, 0.0, 0.4],
        [0.2, 0.0, 0.2],
        [0.4, 0.0, 0.2],
        [0.4, 0.0, 0.0],
    ]];
    let disc = vec![regular_polygon(24, 0.1)];
    let text = [
        object("floor", &floor, [0.0; 3], [0.0; 3]),
        object(
            "needle",
            &needle,
            [-37.6 + turn, -131.7, 131.8],
            [-0.37, 0.72, -0.08],
        ),
        object(
            "speck",
            &speck,
            [0.0, 39.7 + turn, 0.0],
            [0.91, 0.44, -0.93],
        ),
        object("plate", &plate, [21.0, 33.0 + turn, 7.0], [0.3, 1.1, 0.2]),
        object("dart", &dart, [-13.0 + turn, 71.0, 5.0], [-0.8, 0.9, 0.7]),
        object("l", &l, [7.0, 11.0 + turn, -23.0], [1.2, 0.3, -1.1]),
        object("disc", &disc, [31.0 + turn, -5.0, 17.0], [-1.3, 0.5, 1.2]),
        light.to_string(),
    ]
    .concat();
    Scene::from_toml_str(&text, "frames.toml").unwrap()
}

const POINT: &str = "[[light]]\ntype = \"point\"\nposition = [0.4, 3.2, -0.2]\n";
const AREA: &str = "[[light]]\ntype = \"area\"\n\
                    vertices = [[1.15, 3.1, -0.15], [0.97, 3.17, 0.24], [0.66, 3.26, -0.1]]\n";

/// Checks every input polygon of `scene` against its fragments in `mesh`:
/// areas add up to its area (relative 1e-9, and the rounding of its
/// outline's coordinates), corners lie in its plane
/// (as far as its own corners, and 1e-12 of its size), and each of its
/// corners is an output vertex.
pub(crate) fn assert_on_input(scene: &Scene, mesh: &OutputMesh, what: &str) {
    for (source, (_, polygon)) in scene.input_polygons().enumerate() {
        let input = &polygon.vertices;
        let normal = newell(input);
        let area = norm(normal) / 2.0;
        let unit = normal.map(|x| x / (2.0 * area));
        let size = (0..input.len())
            .map(|i| norm([0, 1, 2].map(|a| input[i][a] - input[(i + 1) % input.len()][a])))
            .fold(0.0, f64::max);
        let offset: f64 = (0..3).map(|a| unit[a] * input[0][a]).sum();
        let faces: Vec<Vec<[f64; 3]>> = mesh
            .faces
            .iter()
            .filter(|f| f.source as usize == source)
            .map(|f| {
                f.vertices
                    .iter()
                    .map(|&v| mesh.vertices[v as usize].0)
                    .collect()
            })
            .collect();
        let sum: f64 = faces.iter().map(|f| norm(newell(f)) / 2.0).sum();
        // Each written coordinate is rounded to f64: far from the origin
        // the outline moves by that much along the polygon's perimeter.
        let far = input.iter().flatten().fold(0.0_f64, |m, c| m.max(c.abs()));
        let perimeter: f64 = (0..input.len())
            .map(|i| norm([0, 1, 2].map(|a| input[i][a] - input[(i + 1) % input.len()][a])))
            .sum();
        let rounding = 4.0 * f64::EPSILON * far * perimeter;
        assert!(
            (sum - area).abs() <= 1e-9 * area + rounding,
            "{what}: polygon {source}: fragments add up to {sum:e}, the polygon is {area:e}"
        );
        // No farther off than its own corners are, as rounded (a needle
        // 2e-6 wide has a plane known to 1e-11 over its length).
        let off = |p: &[f64; 3]| ((0..3).map(|a| unit[a] * p[a]).sum::<f64>() - offset).abs();
        let corners_off = input.iter().map(off).fold(0.0, f64::max);
        for p in faces.iter().flatten() {
            let off = off(p);
            assert!(
                off <= corners_off + 1e-12 * size.max(1.0),
                "{what}: polygon {source}: {p:?} is {off:e} off its plane"
            );
        }
        for corner in input {
            assert!(
                faces.iter().flatten().any(|p| p == corner),
                "{what}: polygon {source}: no fragment has its corner {corner:?}"
            );
        }
    }
}

#[test]
fn thin_and_small_polygons_keep_their_area() {
    for (light, name) in [(POINT, "point"), (AREA, "area")] {
        let scene = scene(1.78e-5, 1.02e-4, 0.0, light);
        let shadow = shadow_scene(&scene).unwrap();
        assert_on_input(&scene, &shadow.mesh, &format!("shadow, {name} light"));
    }
    let scene = scene(1.78e-5, 1.02e-4, 0.0, AREA);
    let dm = dm_scene(&scene).unwrap();
    assert_on_input(&scene, &dm.mesh().unwrap(), "dm");
}

/// `scene` with everything moved by `by`.
fn shifted(mut scene: Scene, by: [f64; 3]) -> Scene {
    let shift = |p: &mut [f64; 3]| *p = [0, 1, 2].map(|c| p[c] + by[c]);
    for object in &mut scene.objects {
        object
            .polygons
            .iter_mut()
            .flat_map(|p| &mut p.vertices)
            .for_each(shift);
    }
    for light in &mut scene.lights {
        match &mut light.kind {
            LightKind::Point { position } => shift(position),
            LightKind::Area { vertices } => vertices.iter_mut().for_each(shift),
            LightKind::Directional { .. } => {}
        }
    }
    scene
}

#[test]
fn polygons_far_from_the_origin_keep_their_area() {
    // Four thousand times their size away: the planarity of an input
    // polygon is judged relative to its corner, not to the origin.
    let far = [-7944.52, -1601.51, -1501.46];
    for light in [POINT, AREA] {
        let scene = shifted(scene(1.78e-5, 1.02e-4, 0.0, light), far);
        assert_on_input(&scene, &shadow_scene(&scene).unwrap().mesh, "shadow, far");
    }
    let scene = shifted(scene(1.78e-5, 1.02e-4, 0.0, AREA), far);
    assert_on_input(
        &scene,
        &dm_scene(&scene).unwrap().mesh().unwrap(),
        "dm, far",
    );
}

#[test]
fn a_moved_object_keeps_its_area_where_it_went() {
    let at = scene(1.78e-5, 1.02e-4, 0.0, AREA);
    let mut dm = dm_scene(&at).unwrap();
    dm.move_steps(&at, "plate", [0.0123, -0.0456, 0.0789], 3, |_, _, _| {})
        .unwrap();
    // The scene with the plate where three steps took it.
    let mut moved = at.clone();
    let plate = moved
        .objects
        .iter_mut()
        .find(|o| o.name == "plate")
        .unwrap();
    for p in &mut plate.polygons {
        for v in &mut p.vertices {
            *v = [
                v[0] + 3.0 * 0.0123,
                v[1] + 3.0 * -0.0456,
                v[2] + 3.0 * 0.0789,
            ];
        }
    }
    assert_on_input(&moved, &dm.mesh().unwrap(), "update");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn turned_polygons_keep_their_area(
        width in 1e-6_f64..1e-2,
        speck in 1e-5_f64..1e-2,
        turn in -90.0_f64..90.0,
    ) {
        let scene = scene(width, speck, turn, AREA);
        let shadow = shadow_scene(&scene).unwrap();
        assert_on_input(&scene, &shadow.mesh, "shadow");
    }
}

/// Irradiance from a polygon light of radiance `radiance` at `p` on a
/// two-sided receiver of unit normal `n`: Lambert's contour integral,
/// (1/2) sum of each edge's angle times the cosine between its plane
/// through `p` and the receiver's.
fn polygon_light(vertices: &[[f64; 3]], radiance: f64, p: [f64; 3], n: [f64; 3]) -> f64 {
    let unit = |v: [f64; 3]| v.map(|x| x / norm(v));
    let rel: Vec<[f64; 3]> = vertices
        .iter()
        .map(|v| unit([0, 1, 2].map(|a| v[a] - p[a])))
        .collect();
    let mut sum = 0.0;
    for i in 0..rel.len() {
        let (a, b) = (rel[i], rel[(i + 1) % rel.len()]);
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let angle = (0..3)
            .map(|k| a[k] * b[k])
            .sum::<f64>()
            .clamp(-1.0, 1.0)
            .acos();
        sum += angle * (0..3).map(|k| unit(c)[k] * n[k]).sum::<f64>();
    }
    (radiance * sum / 2.0).abs()
}

#[test]
fn a_needle_is_lit_along_its_input_normal() {
    // Its snapped copy, 8 grid steps wide, is turned by about a degree.
    let needle = vec![vec![
        [-1.0, 0.0, -8e-7],
        [-1.0, 0.0, 8e-7],
        [1.0, 0.0, 8e-7],
        [1.0, 0.0, -8e-7],
    ]];
    let floor = vec![vec![
        [-3.0, 0.0, -3.0],
        [-3.0, 0.0, 3.0],
        [3.0, 0.0, 3.0],
        [3.0, 0.0, -3.0],
    ]];
    let light = [[0.4, 3.2, -0.2], [0.9, 3.3, -0.1], [0.6, 3.25, 0.4]];
    let text = [
        object("floor", &floor, [0.0; 3], [0.0; 3]),
        object(
            "needle",
            &needle,
            [-37.6, -131.7, 131.8],
            [-0.37, 0.72, -0.08],
        ),
    ]
    .concat();
    let point = format!("{text}{POINT}intensity = 2.0\n");
    let area = format!(
        "{text}[[light]]\ntype = \"area\"\nintensity = 1.5\nvertices = [{}]\n",
        light
            .map(|v| format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2]))
            .join(", ")
    );
    let point = Scene::from_toml_str(&point, "point.toml").unwrap();
    let area = Scene::from_toml_str(&area, "area.toml").unwrap();
    let input = &point.objects[1].polygons[0].vertices;
    let normal = newell(input).map(|x| x / norm(newell(input)));
    let dot = |a: [f64; 3], b: [f64; 3]| (0..3).map(|k| a[k] * b[k]).sum::<f64>();
    let check = |mesh: &OutputMesh, expected: &dyn Fn([f64; 3]) -> f64, what: &str| {
        let mut seen = 0;
        for face in mesh.faces.iter().filter(|f| f.source == 1) {
            for &v in &face.vertices {
                let (p, e) = mesh.vertices[v as usize];
                let want = expected(p);
                assert!(
                    (f64::from(e) - want).abs() <= 1e-5 * want,
                    "{what}: {e} at {p:?}, expected {want}"
                );
                seen += 1;
            }
        }
        assert!(seen >= 4, "{what}: the needle has {seen} vertices");
    };
    let at_point = |p: [f64; 3]| {
        let d = [0.4 - p[0], 3.2 - p[1], -0.2 - p[2]];
        2.0 * dot(d, normal).abs() / norm(d).powi(3)
    };
    check(
        &shadow_scene(&point).unwrap().mesh,
        &at_point,
        "shadow, point light",
    );
    let at_area = |p: [f64; 3]| polygon_light(&light, 1.5, p, normal);
    check(
        &shadow_scene(&area).unwrap().mesh,
        &at_area,
        "shadow, area light",
    );
    check(&dm_scene(&area).unwrap().mesh().unwrap(), &at_area, "dm");
}

/// A needle 20000 long and 11 wide through a floor, on a grid step of
/// about 0.005 (a scene of the black-box checker): a projective map of its
/// corners moved its crossing with the floor 0.84 below the floor.
const THROUGH: &str = r#"
[[object]]
name = "floor"
polygons = [ [[-3,0,-3],[-3,0,3],[3,0,3],[3,0,-3]] ]
scale = 10000

[[object]]
name = "needle"
polygons = [ [[-1,0,-0.00057255634840135486],[-1,0,0.00057255634840135486],[1,0,0.00057255634840135486],[1,0,-0.00057255634840135486]] ]
translate = [893.80848091161533,5364.0814253179051,645.44196669858775]
rotate_deg = [-53.122099641553504,174.90421022807379,66.576474738094021]
scale = 10000

[[light]]
type = "area"
vertices = [[5961.9517855497461,29557.543766465315,7479.3455652460143], [-536.11016904326675,30917.289566644609,2994.6058877579262], [11646.604715402349,28756.45924665036,-1598.9130317194658]]
intensity = 0.60288143072733047

[[light]]
type = "point"
position = [19897.126921999967,37440.209473241339,11510.905011656929]
"#;

#[test]
fn a_needle_through_the_floor_meets_it_on_the_floor() {
    let scene = Scene::from_toml_str(THROUGH, "through.toml").unwrap();
    let step = umbra::Pieces::from_scene(&scene).unwrap().grid.cell_size();
    let corners = &scene.objects[1].polygons[0].vertices;
    for mesh in [
        shadow_scene(&scene).unwrap().mesh,
        dm_scene(&scene).unwrap().mesh().unwrap(),
    ] {
        let crossing: Vec<[f64; 3]> = mesh
            .faces
            .iter()
            .filter(|f| f.source == 1)
            .flat_map(|f| f.vertices.iter().map(|&v| mesh.vertices[v as usize].0))
            .filter(|p| !corners.contains(p) && p[1].abs() < 1000.0 * step)
            .collect();
        assert!(!crossing.is_empty());
        for p in crossing {
            assert!(
                p[1].abs() <= step,
                "{p:?} is {} grid steps off the floor",
                p[1] / step
            );
        }
        assert_on_input(&scene, &mesh, "through");
    }
}

/// A needle bent into two triangles by the grid, under a box that moves (a
/// scene of the black-box checker): after the move, the needle's two
/// triangles' cells meet along their diagonal with a vertex on one side
/// only, so its map must be affine on each triangle (a bilinear map missed
/// 4.7e-6 of its area).
const BENT_NEEDLE: &str = r#"
[[object]]
name = "floor"
polygons = [ [[-3,0,-3],[-3,0,3],[3,0,3],[3,0,-3]] ]

[[object]]
name = "needle"
polygons = [ [[-1,0,-0.00062582326367966519],[-1,0,0.00062582326367966519],[1,0,0.00062582326367966519],[1,0,-0.00062582326367966519]] ]
translate = [-0.5299560973074644,0.77224463647653707,0.88061698133879296]
rotate_deg = [76.748867319582132,71.614754203646953,-39.088044184316402]

[[object]]
name = "speck"
polygons = [ [[0,0,0],[0.0026008481638306875,0,0],[0,0,-0.0026008481638306875]] ]
translate = [-0.22992840779934975,0.95361928104743776,0.98041759869723544]
rotate_deg = [0,6.1959963128255477,0]

[[object]]
name = "box"
polygons = [ [[-1,-1,-1],[-1,-1,1],[-1,1,1],[-1,1,-1]], [[1,-1,-1],[1,1,-1],[1,1,1],[1,-1,1]], [[-1,-1,-1],[1,-1,-1],[1,-1,1],[-1,-1,1]], [[-1,1,-1],[-1,1,1],[1,1,1],[1,1,-1]], [[-1,-1,-1],[-1,1,-1],[1,1,-1],[1,-1,-1]], [[-1,-1,1],[1,-1,1],[1,1,1],[-1,1,1]] ]
translate = [-0.15097181839551777,1.5446086693065608,-0.13214565853256821]
rotate_deg = [-154.1632991421919,40.000001249473939,95.072988887954409]
scale = [0.22197488962374173,0.38564782984232204,0.31496949547616443]

[[light]]
type = "area"
vertices = [[0.38664051523198234,2.8083613114817516,0.2755824300996042], [0.21210036758643147,2.8400485788522642,0.038305658262100944], [0.37842305022455414,2.8102181300304534,-0.26795498937852341], [0.77826909377009179,2.7378867539588261,-0.10297164563627469], [0.77150022509742455,2.7389540702527042,0.12348207702628929]]
intensity = 1.529033894126286
"#;

#[test]
fn a_bent_needle_keeps_its_area_when_a_box_moves_over_it() {
    let dir = folder(&[("needle.toml", BENT_NEEDLE)]);
    let args = [
        "update",
        "needle.toml",
        "--move",
        "box",
        "--by=0.0625,0.0625,0.5",
        "-o",
        "out.ply",
    ];
    let run = umbra(dir.path(), &args);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    let mut moved = Scene::from_toml_str(BENT_NEEDLE, "needle.toml").unwrap();
    let by = [0.0625, 0.0625, 0.5];
    let the_box = moved.objects.iter_mut().find(|o| o.name == "box").unwrap();
    for p in the_box.polygons.iter_mut().flat_map(|p| &mut p.vertices) {
        *p = [0, 1, 2].map(|c| p[c] + by[c]);
    }
    assert_on_input(&moved, &mesh, "update");
}

#[test]
fn a_turned_400_gon_keeps_its_area() {
    let disc = vec![regular_polygon(400, 2.0)];
    let square = vec![vec![
        [-0.3, 0.0, -0.3],
        [-0.3, 0.0, 0.3],
        [0.3, 0.0, 0.3],
        [0.3, 0.0, -0.3],
    ]];
    let text = [
        object("disc", &disc, [13.0, 27.0, 41.0], [0.0; 3]),
        object("square", &square, [13.0, 27.0, 41.0], [0.1, 1.0, 0.2]),
        POINT.to_string(),
    ]
    .concat();
    let scene = Scene::from_toml_str(&text, "disc.toml").unwrap();
    assert_on_input(&scene, &shadow_scene(&scene).unwrap().mesh, "shadow");
    assert_on_input(&scene, &dm_scene(&scene).unwrap().mesh().unwrap(), "dm");
}
