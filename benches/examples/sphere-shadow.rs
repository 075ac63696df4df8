//! One point light over a closed sphere-like mesh on a floor, as the
//! `svbsp` bench's `svbsp_sphere` scene but of any size: prints the phases,
//! the tree and fragment counts. `-- N` gives `8 N^2` triangles (112: about
//! 100k; 354: about 1M). For callgrind or `/usr/bin/time -v` (peak memory).
//! `-- N CONE_PIECES CANDIDATES SAMPLE` tries other [`ShadowOptions`].

use bsp_core::GridPoint;
use std::time::Instant;
use svbsp::{Light, PieceFlags, ShadowOptions, compute_shadows_with};
use umbra_benches::scene;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    let arg = |i: usize, default: usize| {
        std::env::args()
            .nth(i)
            .map_or(default, |s| s.parse().expect("a positive integer"))
    };
    let n = arg(1, 112);
    let mut options = ShadowOptions::default();
    options.cone_pieces = arg(2, options.cone_pieces);
    options.bsp.candidates = arg(3, options.bsp.candidates);
    options.bsp.sample = arg(4, options.bsp.sample);
    let mut triangles = scene::sphere_mesh(n, [0.0, 1.5, 0.0], 1.0);
    triangles.extend(scene::floor(0.0, 6.0));
    let (grid, pieces) = scene::pieces(&triangles, &[[1.0, 6.0, 0.5]]);
    let light: GridPoint = grid.snap([1.0, 6.0, 0.5]).expect("light inside the grid");
    // Only the pieces are the input: the peak memory is the pipeline's.
    drop(triangles);
    let mut flags = vec![
        PieceFlags {
            closed_surface: true,
            ..PieceFlags::default()
        };
        pieces.len()
    ];
    for f in flags.iter_mut().rev().take(2) {
        f.closed_surface = false;
    }
    let floor_sources = [pieces.len() as u32 - 2, pieces.len() as u32 - 1];
    let start = Instant::now();
    let out = compute_shadows_with(&pieces, &flags, &[Light::point(light)], &options)
        .expect("valid scene");
    let total = start.elapsed().as_secs_f64();
    let floor = out
        .fragments
        .iter()
        .filter(|f| floor_sources.contains(&f.polygon.source()))
        .count();
    let s = &out.lights[0];
    println!(
        "{} pieces: total {:.3} s (scene BSP {:.3}, SVBSP {:.3}); {} cones, {} scene nodes, {} SVBSP nodes, {} fragments ({} on the floor), {} planes spared, {} whole-piece volumes",
        pieces.len(),
        total,
        out.bsp_seconds,
        out.shadow_seconds,
        s.cones,
        out.scene_nodes,
        s.tree_nodes,
        out.fragments.len(),
        floor,
        s.planes_skipped,
        s.whole_piece_volumes
    );
}
