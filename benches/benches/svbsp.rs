//! SVBSP shadows of one point light: Haines' tetra scenes (Chin & Feiner
//! 1989, Table 1) on one thread, and a closed sphere-like mesh over a floor
//! on all.
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use bsp_core::{BuildOptions, ConvexPolygon, GridPoint};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use svbsp::{Light, PieceFlags, compute_shadows};
use umbra_benches::{scene, tetra};

fn prepare(triangles: &[[[f64; 3]; 3]], light: [f64; 3]) -> (Vec<ConvexPolygon>, Light) {
    let (grid, pieces) = scene::pieces(triangles, &[light]);
    let light: GridPoint = grid.snap(light).expect("light inside the grid");
    (pieces, Light::point(light))
}

/// The allocator of the `umbra` binary, so the figures are the command's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The tetra scenes on one thread, as Chin & Feiner's Table 1 and the
/// speed goal count them.
fn tetras(c: &mut Criterion) {
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");
    for (name, depth) in [("svbsp_tetra256", 4), ("svbsp_tetra1024", 5)] {
        let mut triangles = tetra::tetra_triangles(depth);
        let closed = triangles.len();
        triangles.extend(tetra::ground(1.0, 8.0));
        let (pieces, light) = prepare(&triangles, tetra::LIGHT);
        let flags = tetra::flags(closed, pieces.len());
        c.bench_function(name, |b| {
            one.install(|| {
                b.iter(|| {
                    black_box(
                        compute_shadows(&pieces, &flags, &[light], &BuildOptions::default())
                            .unwrap(),
                    )
                })
            })
        });
    }
}

fn sphere(c: &mut Criterion) {
    // 8 * 112^2 = 100 352 triangles.
    let mut triangles = scene::sphere_mesh(112, [0.0, 1.5, 0.0], 1.0);
    triangles.extend(scene::floor(0.0, 6.0));
    let (pieces, light) = prepare(&triangles, [1.0, 6.0, 0.5]);
    // The sphere is closed; the floor (the last two pieces) is not.
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
    let out = compute_shadows(&pieces, &flags, &[light], &BuildOptions::default()).unwrap();
    eprintln!(
        "sphere 100k: {} pieces, {} fragments, {} SVBSP nodes, {} scene nodes",
        pieces.len(),
        out.fragments.len(),
        out.lights[0].tree_nodes,
        out.scene_nodes
    );
    let mut group = c.benchmark_group("svbsp_sphere");
    group.sample_size(10);
    group.bench_function("100k", |b| {
        b.iter(|| {
            black_box(compute_shadows(&pieces, &flags, &[light], &BuildOptions::default()).unwrap())
        })
    });
    group.finish();
}

criterion_group!(benches, tetras, sphere);
criterion_main!(benches);
