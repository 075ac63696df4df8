//! Discontinuity meshes (`umbra dm`): building and illuminating the
//! `office` and `cubes` demos, and one incremental move (delete, add,
//! re-illuminate) of a desk (19 % of the office) and of a cube, back and
//! forth so that the scene stays the same.
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use bsp_core::ConvexPolygon;
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use umbra::dm_scene;
use umbra_benches::dm_table::demo;

fn build(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    for name in ["office", "cubes"] {
        let scene = demo(dir.path(), name);
        c.bench_function(&format!("dm_build_illuminate_{name}"), |b| {
            b.iter(|| black_box(dm_scene(&scene).unwrap()))
        });
    }
}

fn moves(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    for (name, object) in [
        ("office", "desk_1"),
        ("office", "monitor_1"),
        ("cubes", "cube_1"),
    ] {
        let scene = demo(dir.path(), name);
        let mut run = dm_scene(&scene).unwrap();
        let index = scene.objects.iter().position(|o| o.name == object).unwrap();
        let (id, ks) = run.objects[index].clone();
        let step = (0.05 * run.pieces.grid.scale()).round() as i64;
        let here: Vec<ConvexPolygon> = ks.iter().map(|&k| run.pieces.polygons[k].clone()).collect();
        let there: Vec<ConvexPolygon> = here
            .iter()
            .map(|p| p.translated([step, 0, 0]).expect("on the grid"))
            .collect();
        let mut flip = false;
        c.bench_function(&format!("dm_move_{name}_{object}"), |b| {
            b.iter(|| {
                flip = !flip;
                let to = if flip { &there } else { &here };
                run.dm.move_object(id, to.clone()).unwrap();
                black_box(run.dm.illuminate())
            })
        });
    }
}

criterion_group!(benches, build, moves);
criterion_main!(benches);
