//! Scene files written in decimals come back to the last bit: the grid
//! takes a decimal step when that holds more of the input exactly, so
//! fragments lie in their input polygon's plane and add up to its area to
//! rounding, and `umbra update` moves by exactly the decimal step asked
//! (and any step to where the scene file puts the object).

use crate::area::floor_classes;
use crate::joints::boxes_under_a_side_light;
use crate::vectors::{newell, norm};
use crate::{folder, umbra};
use umbra::{OutputMesh, load_ply};

/// A floor, a 0.6 x 0.25 x 0.6 box just under a unit light (a black-box
/// check's scene; on a power-of-two grid its face areas came out 1.3e-6
/// too large) and a panel moved by a decimal `translate`.
const DECIMAL_SCENE: &str = r#"
[[object]]
name = "floor"
polygons = [[[-4.0, 0.0, -4.0], [-4.0, 0.0, 4.0], [4.0, 0.0, 4.0], [4.0, 0.0, -4.0]]]
casts_shadows = false

[[object]]
name = "box"
polygons = [
  [[-0.3, 3.7, -0.3], [-0.3, 3.95, -0.3], [0.3, 3.95, -0.3], [0.3, 3.7, -0.3]],
  [[-0.3, 3.7, 0.3], [0.3, 3.7, 0.3], [0.3, 3.95, 0.3], [-0.3, 3.95, 0.3]],
  [[-0.3, 3.7, -0.3], [0.3, 3.7, -0.3], [0.3, 3.7, 0.3], [-0.3, 3.7, 0.3]],
  [[-0.3, 3.95, -0.3], [-0.3, 3.95, 0.3], [0.3, 3.95, 0.3], [0.3, 3.95, -0.3]],
  [[-0.3, 3.7, -0.3], [-0.3, 3.7, 0.3], [-0.3, 3.95, 0.3], [-0.3, 3.95, -0.3]],
  [[0.3, 3.7, -0.3], [0.3, 3.95, -0.3], [0.3, 3.95, 0.3], [0.3, 3.7, 0.3]],
]

[[object]]
name = "panel"
polygons = [[[-1.3, 2.1, -0.7], [-1.3, 2.1, 0.9], [0.35, 2.1, 0.9], [0.35, 2.1, -0.7]]]
translate = [0.1, 0.2, -0.3]

[[light]]
type = "area"
vertices = [[-0.5, 4.0, -0.5], [0.5, 4.0, -0.5], [0.5, 4.0, 0.5], [-0.5, 4.0, 0.5]]
intensity = 5.0
"#;

/// The input polygons of [`DECIMAL_SCENE`] as the scene file gives them,
/// transforms applied in `f64`.
fn input_polygons() -> Vec<Vec<[f64; 3]>> {
    let table: toml::Table = DECIMAL_SCENE.parse().unwrap();
    let mut out = Vec::new();
    for object in table["object"].as_array().unwrap() {
        let t = object
            .get("translate")
            .map(|t| {
                t.as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_float().unwrap())
                    .collect()
            })
            .unwrap_or_else(|| vec![0.0; 3]);
        for polygon in object["polygons"].as_array().unwrap() {
            let points = polygon.as_array().unwrap().iter().map(|p| {
                let c: Vec<f64> = p
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_float().unwrap())
                    .collect();
                [c[0] + t[0], c[1] + t[1], c[2] + t[2]]
            });
            out.push(points.collect());
        }
    }
    out
}

#[test]
fn decimal_fragments_lie_in_their_polygons_and_add_up_to_them() {
    let inputs = input_polygons();
    assert_eq!(inputs.len(), 8);
    let dir = folder(&[("scene.toml", DECIMAL_SCENE)]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh: OutputMesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let mut sums = vec![0.0; inputs.len()];
        for face in &mesh.faces {
            let source = face.source as usize;
            let polygon = &inputs[source];
            let n = newell(polygon);
            let unit = n.map(|c| c / norm(n));
            let points: Vec<[f64; 3]> = face
                .vertices
                .iter()
                .map(|&v| mesh.vertices[v as usize].0)
                .collect();
            for p in &points {
                let d: f64 = (0..3).map(|a| (p[a] - polygon[0][a]) * unit[a]).sum();
                assert!(
                    d.abs() < 1e-13,
                    "{command}: {p:?} is {d:e} off polygon {source}"
                );
            }
            sums[source] += 0.5 * norm(newell(&points));
        }
        for (source, polygon) in inputs.iter().enumerate() {
            let want = 0.5 * norm(newell(polygon));
            assert!(
                (sums[source] - want).abs() <= 1e-13 * want,
                "{command}: polygon {source} has fragments of area {} for {want}",
                sums[source]
            );
        }
    }
}

/// A box and a second one `[-1, 4, lo]..[1, 5, lo + 1]` beside it along z.
fn two_boxes(lo: f64) -> String {
    boxes_under_a_side_light(&[
        ([-1.0, 4.0, -1.0], [1.0, 5.0, 0.0]),
        ([-1.0, 4.0, lo], [1.0, 5.0, lo + 1.0]),
    ])
}

/// `umbra update` of [`two_boxes`]`(start)` moving the second box by
/// `by` along z in `steps` steps, and `umbra dm` of `two_boxes(end)`:
/// the two meshes written.
fn moved_and_built(start: f64, by: f64, steps: u32, end: f64) -> (OutputMesh, OutputMesh) {
    let (start, end) = (two_boxes(start), two_boxes(end));
    let dir = folder(&[("start.toml", &start), ("end.toml", &end)]);
    let (by, steps) = (format!("0,0,{by}"), steps.to_string());
    let args = [
        "update",
        "start.toml",
        "--move",
        "box1",
        "--by",
        &by,
        "--steps",
        &steps,
        "-o",
        "moved.ply",
    ];
    let run = umbra(dir.path(), &args);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let run = umbra(dir.path(), &["dm", "end.toml", "-o", "built.ply"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let load = |name: &str| load_ply(&dir.path().join(name)).unwrap();
    (load("moved.ply"), load("built.ply"))
}

/// Moved to touch the first box, the second ends where the scene file
/// with the boxes touching puts it: one joint body, the floor shaded as
/// under one 2 x 2 box (umbra 6).
fn assert_moved_into_contact(start: f64, by: f64, steps: u32) {
    let (moved, built) = moved_and_built(start, by, steps, 0.0);
    let (moved, built) = (floor_classes(&moved), floor_classes(&built));
    assert!((built[2] - 6.0).abs() < 1e-9, "{built:?}");
    for k in 0..3 {
        assert!((moved[k] - built[k]).abs() < 1e-9, "{moved:?} vs {built:?}");
    }
}

/// Two boxes 0.3 apart; `update` moves the second by -0.1 three times
/// into contact. On a power-of-two grid three snapped steps of 0.1
/// overshot 0.3 by a grid step and the boxes overlapped instead.
#[test]
fn update_by_decimal_steps_closes_a_decimal_gap() {
    assert_moved_into_contact(0.3, -0.1, 3);
}

/// Steps that no grid holds (a third) still end where the scene file puts
/// the object: step `s` goes `s * by` from the start, rounded once. Three
/// rounded thirds of the gap fell one grid step short of the first box.
#[test]
fn update_steps_round_the_whole_way_once() {
    assert_moved_into_contact(1.0, -1.0 / 3.0, 3);
}

/// A scene on a binary lattice moved by a decimal step: the step counts
/// towards the grid's choice, so `update` takes the decimal grid and ends
/// exactly where the scene file with the final position puts the box (on
/// the binary grid it ended up to half a grid step off, 1e-7).
#[test]
fn update_of_a_dyadic_scene_by_a_decimal_step_is_exact() {
    let (moved, built) = moved_and_built(0.5, -0.1, 2, 0.3);
    let (a, b) = (floor_classes(&moved), floor_classes(&built));
    for k in 0..3 {
        assert!((a[k] - b[k]).abs() < 1e-12 * 400.0, "{a:?} vs {b:?}");
    }
    // The moved box's corners are the scene file's, bit for bit.
    let corners = |mesh: &OutputMesh| -> Vec<[f64; 3]> {
        let mut out: Vec<[f64; 3]> = mesh
            .vertices
            .iter()
            .map(|v| v.0)
            .filter(|p| p[2] == 0.3 || p[2] == 1.3)
            .collect();
        out.sort_by(|p, q| p.partial_cmp(q).unwrap());
        out.dedup();
        out
    };
    assert!(!corners(&moved).is_empty());
    assert_eq!(corners(&moved), corners(&built));
}
