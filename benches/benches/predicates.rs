//! Throughput of the kernel's side predicates: implicit points through the
//! floating-point filter, the exact 256-bit path alone, and grid points.
//!
//! Before measuring, it prints the exact-fallback fraction of a batch of
//! random queries (read from `bsp_core::predicates::exact_fallbacks()`).
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use bsp_core::Side;
use bsp_core::predicates::{
    exact_fallbacks, exact_side_of_implicit, side_of_implicit, side_of_point,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use umbra_benches::random;

/// Queries per measured batch.
const BATCH: usize = 4096;

fn tally(side: Side) -> u32 {
    match side {
        Side::Back => 1,
        Side::On => 1 << 10,
        Side::Front => 1 << 20,
    }
}

/// Prints how many of `n` random implicit-point queries the filter left to
/// the exact path.
fn report_fallbacks(n: usize) {
    let queries = random::random_implicit_queries(n, 11);
    let before = exact_fallbacks();
    let mut acc = 0_u32;
    for q in &queries {
        acc = acc.wrapping_add(tally(side_of_implicit(&q.filter, q.plane_refs(), &q.q)));
    }
    let fell_back = exact_fallbacks() - before;
    black_box(acc);
    println!(
        "exact fallbacks on {n} random implicit-point queries: {fell_back} ({:.4} %)",
        100.0 * fell_back as f64 / n as f64
    );
    let degenerate = random::degenerate_implicit_queries(1000, 12);
    let before = exact_fallbacks();
    for q in &degenerate {
        assert_eq!(side_of_implicit(&q.filter, q.plane_refs(), &q.q), Side::On);
    }
    println!(
        "exact fallbacks on 1000 degenerate queries (point on the plane): {}",
        exact_fallbacks() - before
    );
}

fn predicates(c: &mut Criterion) {
    report_fallbacks(1_000_000);

    let mut group = c.benchmark_group("predicates");
    group.throughput(Throughput::Elements(BATCH as u64));

    let random = random::random_implicit_queries(BATCH, 1);
    group.bench_function("implicit/filtered", |b| {
        b.iter(|| {
            let mut acc = 0_u32;
            for q in black_box(&random) {
                acc = acc.wrapping_add(tally(side_of_implicit(&q.filter, q.plane_refs(), &q.q)));
            }
            acc
        })
    });
    group.bench_function("implicit/filter-only", |b| {
        b.iter(|| {
            let mut decided = 0_u32;
            for q in black_box(&random) {
                decided += u32::from(q.filter.side(&q.q).is_some());
            }
            decided
        })
    });

    let degenerate = random::degenerate_implicit_queries(BATCH, 2);
    group.bench_function("implicit/filter-fails", |b| {
        b.iter(|| {
            let mut acc = 0_u32;
            for q in black_box(&degenerate) {
                acc = acc.wrapping_add(tally(side_of_implicit(&q.filter, q.plane_refs(), &q.q)));
            }
            acc
        })
    });
    group.bench_function("implicit/exact-only", |b| {
        b.iter(|| {
            let mut acc = 0_u32;
            for q in black_box(&random) {
                acc = acc.wrapping_add(tally(exact_side_of_implicit(q.plane_refs(), &q.q)));
            }
            acc
        })
    });

    let grid = random::grid_point_queries(BATCH, 3);
    group.bench_function("grid-point", |b| {
        b.iter(|| {
            let mut acc = 0_u32;
            for (plane, p) in black_box(&grid) {
                acc = acc.wrapping_add(tally(side_of_point(plane, *p)));
            }
            acc
        })
    });
    group.finish();
}

criterion_group!(benches, predicates);
criterion_main!(benches);
