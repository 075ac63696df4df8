//! Area-light scenes for the benchmarks: the `room` demo (the 1992 paper's
//! plate 6 analogue, 151 polygons, two quad lights) and a large room full
//! of boxes (about 10k polygons, two quad lights).

use std::fmt::Write as _;
use std::path::Path;
use umbra::{Scene, write_demo};

/// The `room` demo, written into `dir` and loaded.
pub fn demo_room(dir: &Path) -> Scene {
    let path = write_demo("room", dir).expect("demo written");
    Scene::load(&path).expect("demo loads")
}

/// A 40 x 8 x 40 hall with `boxes` boxes of random size and turn on its
/// floor and two 2 x 2 ceiling lights: `6 * boxes + 5` polygons. Written
/// into `dir` and loaded; the same `seed` gives the same scene.
pub fn box_hall(dir: &Path, boxes: usize, seed: u64) -> Scene {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1_u64 << 53) as f64
    };
    let mut obj = String::from("# hall: floor, four walls, facing inward\n");
    for v in [
        [-20.0, 0.0, -20.0],
        [20.0, 0.0, -20.0],
        [20.0, 0.0, 20.0],
        [-20.0, 0.0, 20.0],
        [-20.0, 8.0, -20.0],
        [20.0, 8.0, -20.0],
        [20.0, 8.0, 20.0],
        [-20.0, 8.0, 20.0],
    ] {
        let _ = writeln!(obj, "v {} {} {}", v[0], v[1], v[2]);
    }
    obj.push_str("f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
    let box_obj = "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n\
                   v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n\
                   f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let mut toml = String::from("[[object]]\nname = \"hall\"\nmesh = \"hall.obj\"\n\n");
    for k in 0..boxes {
        let (sx, sy, sz) = (0.2 + 0.5 * next(), 0.2 + 1.5 * next(), 0.2 + 0.5 * next());
        let (x, z) = (-19.0 + 38.0 * next(), -19.0 + 38.0 * next());
        let turn = 90.0 * next();
        let _ = writeln!(
            toml,
            "[[object]]\nname = \"box{k}\"\nmesh = \"box.obj\"\nscale = [{sx}, {sy}, {sz}]\nrotate_deg = [0.0, {turn}, 0.0]\ntranslate = [{x}, {}, {z}]\n",
            sy / 2.0
        );
    }
    for (x, z) in [(-6.0, -4.0), (6.0, 5.0)] {
        let _ = writeln!(
            toml,
            "[[light]]\ntype = \"area\"\nvertices = [[{}, 7.9, {}], [{}, 7.9, {}], [{}, 7.9, {}], [{}, 7.9, {}]]\nintensity = 3.0\n",
            x - 1.0,
            z - 1.0,
            x + 1.0,
            z - 1.0,
            x + 1.0,
            z + 1.0,
            x - 1.0,
            z + 1.0
        );
    }
    std::fs::write(dir.join("hall.obj"), obj).expect("hall written");
    std::fs::write(dir.join("box.obj"), box_obj).expect("box written");
    let path = dir.join("hall.toml");
    std::fs::write(&path, toml).expect("scene written");
    Scene::load(&path).expect("hall loads")
}
