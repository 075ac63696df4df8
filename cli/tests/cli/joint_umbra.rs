//! Joint umbrae: two panels at different heights, each hiding only part of
//! a square light from a strip of the floor, together all of it. No one
//! shadow volume bounds such a strip; both commands prove its faces dark
//! and mark them umbra, and a sampling oracle checks every umbra face.

use crate::area::{face_points, floor_classes};
use crate::vectors::inner_points;
use crate::{folder, umbra};
use umbra::{OutputMesh, load_ply};

/// A 20 x 20 floor, a 2 x 2 light at y = 10 above the origin, and the
/// panels: `high` over x <= `a` at y = 6, `low` over x >= `b` at y = 3,
/// both |z| <= 6 (either may be left out).
fn panels(a: Option<f64>, b: Option<f64>) -> String {
    let mut scene = String::from(
        "[[object]]\nname = \"floor\"\npolygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]\n\n",
    );
    if let Some(a) = a {
        scene += &format!(
            "[[object]]\nname = \"high\"\npolygons = [[[-6, 6, 6], [{a}, 6, 6], [{a}, 6, -6], [-6, 6, -6]]]\n\n"
        );
    }
    if let Some(b) = b {
        scene += &format!(
            "[[object]]\nname = \"low\"\npolygons = [[[{b}, 3, 6], [6, 3, 6], [6, 3, -6], [{b}, 3, -6]]]\n\n"
        );
    }
    scene
        + "[[light]]\ntype = \"area\"\nvertices = [[-1, 10, -1], [1, 10, -1], [1, 10, 1], [-1, 10, 1]]\n"
}

/// Whether the segment from `p` to `l` crosses the panel at height `y`
/// over `x` in `[x0, x1]`, |z| <= 6.
fn crosses(p: [f64; 3], l: [f64; 3], y: f64, [x0, x1]: [f64; 2]) -> bool {
    let t = (y - p[1]) / (l[1] - p[1]);
    let x = p[0] + t * (l[0] - p[0]);
    let z = p[2] + t * (l[2] - p[2]);
    (x0..=x1).contains(&x) && z.abs() <= 6.0
}

/// Whether the segment from `p` to `l` meets the box `[lo, hi]`.
fn meets_box(p: [f64; 3], l: [f64; 3], lo: [f64; 3], hi: [f64; 3]) -> bool {
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for k in 0..3 {
        let d = l[k] - p[k];
        if d == 0.0 {
            if p[k] < lo[k] || p[k] > hi[k] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[k] - p[k]) / d, (hi[k] - p[k]) / d);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

/// Checks that from points inside every umbra floor face (its centre, and
/// halfway from it to each corner) `hidden` holds for each of 21 x 21
/// points of the light.
fn assert_umbra_sees_nothing(
    mesh: &OutputMesh,
    hidden: impl Fn([f64; 3], [f64; 3]) -> bool,
    what: &str,
) {
    let light: Vec<[f64; 3]> = (0..21 * 21)
        .map(|k| {
            [
                -1.0 + 0.1 * (k % 21) as f64,
                10.0,
                -1.0 + 0.1 * (k / 21) as f64,
            ]
        })
        .collect();
    for (f, face) in mesh.faces.iter().enumerate() {
        if face.source != 0 || face.umbra_mask & 1 == 0 {
            continue;
        }
        for p in inner_points(&face_points(mesh, f)) {
            for &l in &light {
                assert!(
                    hidden(p, l),
                    "{what}: umbra face {f} sees the light from {p:?} at {l:?}"
                );
            }
        }
    }
}

/// Whether the panels of [`panels`] hide `l` from `p`.
fn panels_hide(a: f64, b: f64) -> impl Fn([f64; 3], [f64; 3]) -> bool {
    move |p, l| crosses(p, l, 6.0, [-6.0, a]) || crosses(p, l, 3.0, [b, 6.0])
}

/// Runs `command` (with `args`) on the scene and returns the output mesh,
/// checking that the statistics count each class as the mesh has it
/// (proofs turn faces umbra after the volumes or DM-trees classed them).
fn run(scene: &str, command: &str, args: &[&str]) -> OutputMesh {
    let dir = folder(&[("scene.toml", scene)]);
    let mut all = vec![command, "scene.toml", "-o", "out.ply", "--stats", "s.json"];
    all.extend_from_slice(args);
    let run = umbra(dir.path(), &all);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    let count = |class: fn(&umbra::OutputFace) -> bool| {
        mesh.faces.iter().filter(|f| class(f)).count() as u64
    };
    let light = &stats["lights"][0];
    assert_eq!(
        light["lit"].as_u64(),
        Some(count(|f| f.lit_mask & 1 != 0)),
        "{command}"
    );
    assert_eq!(
        light["umbra"].as_u64(),
        Some(count(|f| f.umbra_mask & 1 != 0)),
        "{command}"
    );
    assert_eq!(
        light["penumbra"].as_u64(),
        Some(count(|f| (f.lit_mask | f.umbra_mask) & 1 == 0)),
        "{command}"
    );
    mesh
}

/// High panel to x = 0.2, low from x = -0.6: from the strip -1 <= x <=
/// -3/7 between their umbrae the high panel hides the light's part x <=
/// 0.6 and the low one its part x >= 1/3, together all of it. The strip is
/// bounded by volume planes (and DM edges); where both panels span every
/// ray's z (|z| <= 57/7, the low panel's umbra in z) it sees nothing: 4/7
/// x 114/7 more umbra than the panels give one by one.
#[test]
fn two_panels_hide_a_strip_neither_hides_alone() {
    let (a, b) = (0.2, -0.6);
    let strip = 4.0 / 7.0 * 114.0 / 7.0;
    for command in ["shadow", "dm"] {
        let both = run(&panels(Some(a), Some(b)), command, &[]);
        let [_, _, joint] = floor_classes(&both);
        let [_, _, high] = floor_classes(&run(&panels(Some(a), None), command, &[]));
        let [_, _, low] = floor_classes(&run(&panels(None, Some(b)), command, &[]));
        assert!(
            joint >= high + low + strip - 1e-6,
            "{command}: umbra {joint} with both panels, {high} + {low} one by one, strip {strip}"
        );
        assert_umbra_sees_nothing(&both, panels_hide(a, b), command);
    }
}

/// High panel to x = 0.2, low from x = -0.2: the joint umbra -0.6 <= x <
/// 1/7 ends along a plane that no volume has, across a fragment. Gridded,
/// `shadow` proves the cells inside it (all but those it crosses).
#[test]
fn gridded_cells_follow_a_joint_umbra_across_a_fragment() {
    let (a, b) = (0.2, -0.2);
    let strip = (1.0 / 7.0 + 0.6) * 114.0 / 7.0;
    let both = run(&panels(Some(a), Some(b)), "shadow", &["--grid", "40"]);
    let [_, _, joint] = floor_classes(&both);
    let [_, _, high] = floor_classes(&run(&panels(Some(a), None), "shadow", &["--grid", "40"]));
    let [_, _, low] = floor_classes(&run(&panels(None, Some(b)), "shadow", &["--grid", "40"]));
    // Penumbra cells are 0.25 wide: the column the boundary crosses, and
    // the cells past |z| = 57/7, may stay penumbra.
    let lost = 0.25 * 114.0 / 7.0;
    assert!(
        joint >= high + low + strip - lost,
        "umbra {joint} with both panels, {high} + {low} one by one, strip {strip}"
    );
    assert_umbra_sees_nothing(&both, panels_hide(a, b), "gridded shadow");
}

/// The panels of [`two_panels_hide_a_strip_neither_hides_alone`] as slabs
/// 0.2 thick (each a closed convex body, one object; the high slab's
/// bottom is the high panel, the low slab's top the low panel). Between
/// their umbrae (x = -1 from the high slab's bottom edge, x = -4/9 from the
/// low slab's bottom edge) and where the low slab's bottom spans every
/// ray's z (|z| <= 5.72 / 0.72), the floor sees nothing: both commands
/// prove that strip past the bodies (a DM cell lists a body as one
/// occluder of its object; `shadow` gridded, as its fragment runs on to
/// the floor's edge).
#[test]
fn two_slabs_hide_a_strip_as_bodies() {
    let (a, b) = (0.2, -0.6);
    let high = ([-6.0, 6.0, -6.0], [a, 6.2, 6.0]);
    let low = ([b, 2.8, -6.0], [6.0, 3.0, 6.0]);
    let scene = |boxes: &[([f64; 3], [f64; 3])]| {
        crate::joints::boxes_under_a_side_light(boxes).replace(
            "vertices = [[2, 10, -1], [4, 10, -1], [4, 10, 1], [2, 10, 1]]",
            "vertices = [[-1, 10, -1], [1, 10, -1], [1, 10, 1], [-1, 10, 1]]",
        )
    };
    let strip = (1.0 - 4.0 / 9.0) * 2.0 * 5.72 / 0.72;
    let hidden = |p, l| meets_box(p, l, high.0, high.1) || meets_box(p, l, low.0, low.1);
    for (command, args) in [("shadow", &["--grid", "40"][..]), ("dm", &[][..])] {
        let both = run(&scene(&[high, low]), command, args);
        let [_, _, joint] = floor_classes(&both);
        let [_, _, by_high] = floor_classes(&run(&scene(&[high]), command, args));
        let [_, _, by_low] = floor_classes(&run(&scene(&[low]), command, args));
        assert!(
            joint >= by_high + by_low + strip - 1e-6,
            "{command}: umbra {joint} under both slabs, {by_high} + {by_low} one by one, strip {strip}"
        );
        assert_umbra_sees_nothing(&both, hidden, command);
    }
}

/// [`two_panels_hide_a_strip_neither_hides_alone`] with the light tilted:
/// its edge x = 1 raised to y = 10.25. Light corners at heights 10 and
/// 10.25 bound the strip: the high panel's umbra ends at x = (0.2 - t) /
/// (1 - t), t = 6 / 10.25 (the far corner); the low panel's starts at x =
/// -3/7 (the near corner); both span every ray's z for |z| <= (6 - t') /
/// (1 - t'), t' = 3 / 10.25. The proofs halve the tilted light in its
/// plane's lattice; both commands add the whole strip.
#[test]
fn two_panels_hide_a_strip_from_a_tilted_light() {
    let (a, b) = (0.2, -0.6);
    let tilt = |scene: String| {
        scene.replace(
            "vertices = [[-1, 10, -1], [1, 10, -1], [1, 10, 1], [-1, 10, 1]]",
            "vertices = [[-1, 10, -1], [1, 10.25, -1], [1, 10.25, 1], [-1, 10, 1]]",
        )
    };
    let t = 6.0 / 10.25;
    let t_low = 3.0 / 10.25;
    let strip = (-3.0 / 7.0 - (0.2 - t) / (1.0 - t)) * 2.0 * (6.0 - t_low) / (1.0 - t_low);
    for command in ["shadow", "dm"] {
        let both = run(&tilt(panels(Some(a), Some(b))), command, &[]);
        let [_, _, joint] = floor_classes(&both);
        let [_, _, high] = floor_classes(&run(&tilt(panels(Some(a), None)), command, &[]));
        let [_, _, low] = floor_classes(&run(&tilt(panels(None, Some(b))), command, &[]));
        assert!(
            joint >= high + low + strip - 1e-6,
            "{command}: umbra {joint} with both panels, {high} + {low} one by one, strip {strip}"
        );
        let hidden = |p: [f64; 3], l: [f64; 3]| {
            // The oracle's light samples lie in the plane y = 10: lift
            // them onto the tilted light.
            let l = [l[0], 10.0 + 0.125 * (l[0] + 1.0), l[2]];
            panels_hide(a, b)(p, l)
        };
        assert_umbra_sees_nothing(&both, hidden, command);
    }
}
