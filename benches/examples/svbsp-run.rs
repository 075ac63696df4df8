//! One point light's SVBSP pass over a scene, once, for callgrind or
//! `/usr/bin/time` (peak memory): prints the phases, the tree and fragment
//! counts.
//!
//! - `-- sphere N`: the `svbsp` bench's closed sphere-like mesh over a
//!   floor, `8 N^2` triangles (112: about 100k; 354: about 1M).
//! - `-- tetra D`: Haines' tetra of depth `D` over the ground in contact
//!   (4: Tetra256, 5: Tetra1024), Chin & Feiner's Table 1 scene.
//!
//! Then optionally `CONE_PIECES CANDIDATES SAMPLE` try other
//! [`ShadowOptions`]. With `REPEAT=K` in the environment it runs K times
//! and prints the fastest and the median.

use bsp_core::GridPoint;
use std::time::Instant;
use svbsp::{Light, PieceFlags, ShadowOptions, compute_shadows_with};
use umbra_benches::{scene, tetra};

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, default: usize| {
        args.get(i)
            .map_or(default, |s| s.parse().expect("a positive integer"))
    };
    let kind = args.get(1).map_or("sphere", String::as_str);
    let mut options = ShadowOptions::default();
    options.cone_pieces = arg(3, options.cone_pieces);
    options.bsp.candidates = arg(4, options.bsp.candidates);
    options.bsp.sample = arg(5, options.bsp.sample);
    let (triangles, light, closed) = match kind {
        "sphere" => {
            let mut t = scene::sphere_mesh(arg(2, 112), [0.0, 1.5, 0.0], 1.0);
            let closed = t.len();
            t.extend(scene::floor(0.0, 6.0));
            (t, [1.0, 6.0, 0.5], closed)
        }
        "tetra" => {
            let mut t = tetra::tetra_triangles(arg(2, 5) as u32);
            // Each leaf tetrahedron is closed; the ground is not.
            let closed = t.len();
            t.extend(tetra::ground(1.0, 8.0));
            (t, tetra::LIGHT, closed)
        }
        other => panic!("unknown scene {other}: sphere or tetra"),
    };
    let (grid, pieces) = scene::pieces(&triangles, &[light]);
    let light: GridPoint = grid.snap(light).expect("light inside the grid");
    // Only the pieces are the input: the peak memory is the pipeline's.
    drop(triangles);
    // The sphere is closed (its pieces come first); the floor is not.
    let flags: Vec<PieceFlags> = (0..pieces.len())
        .map(|i| PieceFlags {
            closed_surface: i < closed,
            ..PieceFlags::default()
        })
        .collect();
    let repeat: usize = std::env::var("REPEAT").map_or(1, |r| r.parse().expect("REPEAT: a count"));
    let mut times = Vec::with_capacity(repeat.max(1));
    let mut out = None;
    for _ in 0..repeat.max(1) {
        let start = Instant::now();
        let run = compute_shadows_with(&pieces, &flags, &[Light::point(light)], &options)
            .expect("valid scene");
        times.push(start.elapsed().as_secs_f64());
        out = Some(run);
    }
    times.sort_by(f64::total_cmp);
    let (total, median) = (times[0], times[times.len() / 2]);
    let out = out.expect("ran once");
    let s = &out.lights[0];
    println!(
        "{} pieces: total {:.6} s, median {:.6} s (scene BSP {:.6}, SVBSP {:.6}); {} cones, {} scene nodes, {} SVBSP nodes, {} fragments, {} planes spared, {} whole-piece volumes",
        pieces.len(),
        total,
        median,
        out.bsp_seconds,
        out.shadow_seconds,
        s.cones,
        out.scene_nodes,
        s.tree_nodes,
        out.fragments.len(),
        s.planes_skipped,
        s.whole_piece_volumes
    );
}
