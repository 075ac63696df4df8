//! Bergeron's general shadow volumes: building them for Haines' tetra
//! scene, and `umbra render` of the `tetra` demo by counting shadow
//! polygons along eye rays beside drawing the fragments.
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use bsp_core::GridPoint;
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use svbsp::Light;
use svbsp::bergeron::{BergeronVolumes, Model, ModelPolygon};
use umbra::{Method, Order, RenderOptions, Scene, View, render_scene_with, write_demo};
use umbra_benches::{scene, tetra};

fn build(c: &mut Criterion) {
    for (name, depth) in [
        ("bergeron_build_tetra256", 4),
        ("bergeron_build_tetra1024", 5),
    ] {
        let triangles = tetra::tetra_triangles(depth);
        let (grid, pieces) = scene::pieces(&triangles, &[tetra::LIGHT]);
        let light: GridPoint = grid.snap(tetra::LIGHT).expect("light inside the grid");
        let model = Model {
            polygons: pieces
                .into_iter()
                .map(|p| ModelPolygon {
                    boundary: (0..p.len())
                        .filter_map(|i| p.vertex_grid_point(i))
                        .collect(),
                    pieces: vec![p],
                })
                .collect(),
        };
        let models = [model];
        let light = Light::point(light);
        c.bench_function(name, |b| {
            b.iter(|| black_box(BergeronVolumes::build(&models, &light, None).unwrap()))
        });
    }
}

fn render(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mut scene = Scene::load(write_demo("tetra", dir.path()).expect("the demo")).expect("loads");
    let camera = scene.camera.as_mut().expect("a camera");
    (camera.width, camera.height) = (160, 160);
    let mut group = c.benchmark_group("render_tetra_160");
    group.sample_size(10);
    for (name, method) in [
        ("fragments", Method::Fragments),
        ("volumes", Method::Volumes),
    ] {
        let options = RenderOptions {
            view: View::Classes,
            method,
            order: Order::ZBuffer,
        };
        group.bench_function(name, |b| {
            b.iter(|| black_box(render_scene_with(&scene, &options).unwrap()))
        });
    }
    group.finish();
}

criterion_group!(benches, build, render);
criterion_main!(benches);
