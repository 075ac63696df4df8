//! Scene BSP build on random triangle soups of 10k and 100k triangles.
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use bsp_core::{BuildOptions, ConvexPolygon, GridPoint, SceneBsp, Viewpoint};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use std::hint::black_box;

/// `n` random triangles spread uniformly over the grid, each about as wide
/// as the mean spacing between triangle centres (corners within half a
/// spacing of the centre), so that planes cut neighbours but the soup is not
/// a tangle of overlapping triangles.
pub fn triangle_soup(n: usize, seed: u64) -> Vec<ConvexPolygon> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let half = 1_i64 << 23;
    let size = (half as f64 / (n as f64).cbrt()) as i64;
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let c: [i64; 3] = std::array::from_fn(|_| rng.random_range(-half..half));
        let mut corner = || {
            let p: [i64; 3] = std::array::from_fn(|k| c[k] + rng.random_range(-size..=size));
            GridPoint::new(p[0], p[1], p[2]).expect("within the grid")
        };
        let (a, b, d) = (corner(), corner(), corner());
        if let Ok(t) = ConvexPolygon::from_grid_points(&[a, b, d], out.len() as u32) {
            out.push(t);
        }
    }
    out
}

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("scene_bsp_build");
    group.sample_size(10);
    for n in [10_000, 100_000] {
        let soup = triangle_soup(n, 42);
        let bsp = SceneBsp::build(soup.clone(), &BuildOptions::default());
        eprintln!(
            "scene_bsp {n} triangles: {} fragments, {} nodes, depth {}",
            bsp.polygons().len(),
            bsp.nodes().len(),
            bsp.depth()
        );
        group.bench_with_input(BenchmarkId::from_parameter(n), &soup, |b, soup| {
            b.iter_batched(
                || soup.clone(),
                |s| black_box(SceneBsp::build(s, &BuildOptions::default())),
                criterion::BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

fn traverse(c: &mut Criterion) {
    let soup = triangle_soup(100_000, 42);
    let bsp = SceneBsp::build(soup, &BuildOptions::default());
    let eye = Viewpoint::Point(GridPoint {
        x: 12_345,
        y: -1 << 22,
        z: 777,
    });
    c.bench_function("scene_bsp_front_to_back_100k", |b| {
        b.iter(|| black_box(bsp.front_to_back(eye).count()))
    });
}

criterion_group!(benches, build, traverse);
criterion_main!(benches);
