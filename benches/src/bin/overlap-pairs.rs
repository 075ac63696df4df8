//! The two overlap structures of `dm-mesh` side by side (the uniform grid
//! of boxes and the paper's shadow overlap cube) on the benchmark scenes:
//! occluder / receiver pairs each gives, those that really shadow, the time
//! of a build and of one move of an object (both with illumination).
//!
//! `overlap-pairs [HALL_BOXES]`: office, cubes and a hall of
//! `HALL_BOXES` boxes (1665 by default: about 10k polygons; outer
//! discontinuities only, as `paper-tables dm` times it).

use std::time::Instant;

use bsp_core::ConvexPolygon;
use umbra::{DmOptions, OverlapKind, Scene, dm_scene_with};
use umbra_benches::dm_table::demo;
use umbra_benches::rooms::box_hall;

/// The allocator of the `umbra` binary, so the figures are the command's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn row(name: &str, scene: &Scene, object: &str, kind: OverlapKind, runs: usize) {
    // The hall as paper-tables times it: outer discontinuities only.
    let options = DmOptions {
        overlap: kind,
        internal_discontinuities: name != "hall",
        ..DmOptions::default()
    };
    let mut builds = Vec::new();
    let mut run = None;
    for _ in 0..runs {
        let start = Instant::now();
        let built = dm_scene_with(scene, options).expect("the scene builds");
        builds.push(start.elapsed().as_secs_f64());
        run = Some(built);
    }
    let mut run = run.expect("built");
    let figures = run.dm.overlap_figures();
    let index = scene
        .objects
        .iter()
        .position(|o| o.name == object)
        .expect("object");
    let (id, ks) = run.objects[index].clone();
    let step = (0.05 * run.pieces.grid.scale()).round() as i64;
    let here: Vec<ConvexPolygon> = ks.iter().map(|&k| run.pieces.polygons[k].clone()).collect();
    let there: Vec<ConvexPolygon> = here
        .iter()
        .map(|p| p.translated([step, 0, 0]).expect("on the grid"))
        .collect();
    let mut moves = Vec::new();
    for m in 0..5 {
        let to = if m % 2 == 0 { &there } else { &here };
        let start = Instant::now();
        run.dm.move_object(id, to.clone()).expect("moves");
        run.dm.illuminate();
        moves.push(start.elapsed().as_secs_f64());
    }
    println!(
        "{:<8} {:<5} {:>10} {:>10} {:>8.1}% {:>11.2} {:>9.2}",
        name,
        format!("{kind:?}").to_lowercase(),
        figures.candidates,
        figures.shadowing,
        100.0 * figures.shadowing as f64 / figures.candidates.max(1) as f64,
        1e3 * median(builds),
        1e3 * median(moves),
    );
}

fn main() {
    let boxes = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1665);
    let dir = std::env::temp_dir().join(format!("umbra-overlap-{}", std::process::id()));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "overlap structures ({cores} cores): pairs after the box test, pairs that shadow, build and move (with illumination) in ms"
    );
    println!(
        "{:<8} {:<5} {:>10} {:>10} {:>9} {:>11} {:>9}",
        "scene", "kind", "pairs", "shadowing", "useful", "build ms", "move ms"
    );
    let scenes = [
        ("office", demo(&dir, "office"), "monitor_1", 5),
        ("cubes", demo(&dir, "cubes"), "cube_1", 5),
        ("hall", box_hall(&dir, boxes, 7), "box0", 1),
    ];
    for (name, scene, object, runs) in &scenes {
        for kind in [OverlapKind::Grid, OverlapKind::Cube] {
            row(name, scene, object, kind, *runs);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
