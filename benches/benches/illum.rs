//! Throughput of direct illumination: unoccluded quad-light irradiance
//! (Lambert's contour integral with the horizon clip), the same through the
//! visible part past 10 occluders, past a dense patch of 2,048 triangles
//! (the visible part's outlines), and the batch on 1 and 2 threads.
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use illum::{Sidedness::OneSided, VisiblePart, area_irradiance_batch, visible_irradiance};
use std::hint::black_box;
use umbra_benches::illum_scene::{BATCH, dense_patch, light, occluders, receivers};

fn bench(c: &mut Criterion) {
    let light = light();
    let rs = receivers(BATCH, 5);
    let occ = occluders(6);

    let mut g = c.benchmark_group("illum");
    g.throughput(Throughput::Elements(BATCH as u64));
    g.bench_function("unoccluded quad light", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for r in &rs {
                acc += light.irradiance(black_box(r.position), r.normal, OneSided);
            }
            acc
        })
    });
    let mut scratch = VisiblePart::new();
    g.bench_function("visible part, 10 occluders", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for r in &rs {
                acc += visible_irradiance(
                    &light,
                    &occ,
                    black_box(r.position),
                    r.normal,
                    OneSided,
                    &mut scratch,
                );
            }
            acc
        })
    });
    // A receiver under the patch sees the light past about 100 of its
    // triangles (the light's view is about a unit wide at its height).
    let patch = dense_patch(32, 3);
    let few = &rs[..BATCH / 16];
    g.throughput(Throughput::Elements(few.len() as u64));
    g.bench_function("visible part, 2048-triangle patch", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for r in few {
                acc += visible_irradiance(
                    &light,
                    &patch,
                    black_box(r.position),
                    r.normal,
                    OneSided,
                    &mut scratch,
                );
            }
            acc
        })
    });
    let big = receivers(16 * BATCH, 7);
    let mut out = vec![0.0; big.len()];
    g.throughput(Throughput::Elements(big.len() as u64));
    for threads in [1, 2] {
        let pool = illum::rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        g.bench_function(format!("batch, 10 occluders, {threads} threads"), |b| {
            b.iter(|| {
                pool.install(|| area_irradiance_batch(&light, &occ, &big, OneSided, &mut out))
                    .unwrap();
                black_box(out[0])
            })
        });
    }
    g.finish();

    // How much of the light the occluders hide on average (context for the
    // occluded figure).
    let full: f64 = rs
        .iter()
        .map(|r| light.irradiance(r.position, r.normal, OneSided))
        .sum();
    let vis: f64 = rs
        .iter()
        .map(|r| visible_irradiance(&light, &occ, r.position, r.normal, OneSided, &mut scratch))
        .sum();
    println!(
        "visible fraction of the irradiance over the batch: {:.3}",
        vis / full
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
