//! A ring (a torus of 192 triangles, no kernel: from no point inside it
//! does every face turn its back) over a floor, under a light over its
//! tube, wider than any triangle casts an umbra under but narrower than
//! the tube: the floor under the tube is a joint umbra of many triangles.
//! A ray oracle checks that every umbra floor face sees none of the
//! light, and that both commands find most of the floor's true umbra
//! (the same oracle on a grid): `umbra shadow` by the umbrae of convex
//! cores and flat sections inside the ring (the triangles alone give
//! none), `umbra dm` those and cells proven dark past them.

use crate::closed_mesh::{floor_umbra, mesh_scene, true_floor_umbra};
use crate::{folder, umbra};

/// The ring's triangles, counter-clockwise seen from outside: 12 x 8
/// quads of a torus about the vertical axis, its ring of radius 1.5 at
/// height 2.5, its tube of radius 0.6.
fn ring() -> Vec<[[f64; 3]; 3]> {
    umbra::shapes::torus([0.0, 2.5, 0.0], (1.5, 0.6), (12, 8))
}

fn scene() -> String {
    mesh_scene(
        4,
        "ring",
        &ring(),
        "[[0.9, 6, -0.6], [2.1, 6, -0.6], [2.1, 6, 0.6], [0.9, 6, 0.6]]",
    )
}

#[test]
fn a_ring_hides_its_joint_umbra() {
    let dir = folder(&[("scene.toml", &scene())]);
    let light: Vec<[f64; 3]> = (0..5 * 5)
        .map(|k| [0.9 + 0.3 * (k % 5) as f64, 6.0, -0.6 + 0.3 * (k / 5) as f64])
        .collect();
    // The light's middle at x = 1.5, 6 high; the ring up to 3.1 high
    // and 2.1 out: its shadow from x = -6 to 3.6, |z| < 4.4.
    let truth = true_floor_umbra(&ring(), &light, [-6.5, 4.5], [-5.0, 5.0]);
    for command in ["shadow", "dm"] {
        let floor = floor_umbra(dir.path(), command, &light);
        let umbra_area = floor.umbra_area;
        // 17.7 in truth; with the sections' umbrae 15.7 found by `umbra
        // shadow` and 15.9 by `umbra dm` (with the cores' alone 7.2 and
        // 12.0; with neither, none and 8.0).
        assert!(
            umbra_area > 0.85 * truth,
            "{command}: floor umbra {umbra_area} of {truth}"
        );
        if command == "shadow" {
            continue;
        }
        // Past the cores, proofs darken the floor right under the tube.
        assert!(
            floor.umbra_at([1.5, 0.0]),
            "the floor under the tube is not umbra (umbra area {umbra_area})"
        );
    }
}

/// The ring and the floor in one object: the ring is a closed part of it,
/// whose faces turned away from the light cast nothing, as when it is an
/// object of its own; both commands write the same output.
#[test]
fn a_ring_in_one_object_with_its_floor_casts_as_an_object_of_its_own() {
    let apart = scene();
    let joined = apart.replace("]]]\n\n[[object]]\nname = \"ring\"\npolygons = [", "]], ");
    assert_ne!(apart, joined);
    let dir = folder(&[("apart.toml", &apart), ("joined.toml", &joined)]);
    for command in ["shadow", "dm"] {
        let mut outputs = Vec::new();
        for scene in ["apart", "joined"] {
            let (out, stats) = (format!("{scene}.ply"), format!("{scene}.json"));
            let args = [
                command,
                &format!("{scene}.toml"),
                "-o",
                &out,
                "--stats",
                &stats,
            ];
            let run = umbra(dir.path(), &args);
            assert_eq!(run.code, 0, "{command} {scene}: {}", run.stderr);
            outputs.push(std::fs::read(dir.path().join(out)).unwrap());
        }
        assert!(outputs[0] == outputs[1], "{command}: the outputs differ");
    }
}
