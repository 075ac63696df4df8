//! Area-light soft shadows through `umbra shadow`'s pipeline, illumination
//! included: the `room` demo (151 polygons, two quad lights; the 1992
//! paper's plate 6 took 484 s) and a hall of boxes (about 10k polygons,
//! is timed once by `paper-tables`), two quad lights.
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use umbra::{ShadowOptions, shadow_scene_with};
use umbra_benches::rooms;

fn room(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let scene = rooms::demo_room(dir.path());
    for (name, grid) in [
        ("area_room_2_lights", None),
        ("area_room_2_lights_grid40", Some(40)),
    ] {
        let options = ShadowOptions {
            grid,
            adaptive: None,
        };
        c.bench_function(name, |b| {
            b.iter(|| black_box(shadow_scene_with(&scene, &options).unwrap()))
        });
    }
}

fn hall(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let scene = rooms::box_hall(dir.path(), 200, 7);
    let mut group = c.benchmark_group("area_hall");
    group.sample_size(10);
    group.bench_function("hall_1205_polygons_2_lights", |b| {
        b.iter(|| black_box(shadow_scene_with(&scene, &ShadowOptions::default()).unwrap()))
    });
    group.finish();
}

criterion_group!(benches, room, hall);
criterion_main!(benches);
