//! Convex polygon splitting: random convex quads cut by random planes
//! through their centres (every split makes two parts), and the same for a
//! fragment whose vertices are implicit (a quad already cut twice).
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use bsp_core::{ConvexPolygon, Plane, Split};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use umbra_benches::random;

/// Splits per measured batch.
const BATCH: usize = 1024;

/// Vertices of the parts, so that the splits cannot be optimised away.
fn split_all(cases: &[(ConvexPolygon, Plane)]) -> usize {
    let mut acc = 0;
    for (polygon, plane) in cases {
        match polygon.split(plane) {
            Split::Both(back, front) => acc += back.len() + front.len(),
            Split::Back | Split::Front => acc += 1,
            Split::Coplanar(_) => {}
        }
    }
    acc
}

/// Fragments with implicit vertices: the front part of a quad cut through
/// its centre (two new, implicit vertices), cut again by another random
/// plane through the centre. The centre lies on the fragment's closing
/// edge, so most of these cuts make two parts and some only touch.
fn fragment_cuts(n: usize, seed: u64) -> Vec<(ConvexPolygon, Plane)> {
    let mut rng = random::rng(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let (quad, centre) = random::quad(&mut rng, 20);
        let first = random::plane_through(&mut rng, centre, &quad);
        let Split::Both(_, fragment) = quad.split(&first) else {
            continue;
        };
        let second = random::plane_through(&mut rng, centre, &quad);
        out.push((fragment, second));
    }
    out
}

fn split(c: &mut Criterion) {
    let mut group = c.benchmark_group("split");
    group.throughput(Throughput::Elements(BATCH as u64));

    let quads = random::quad_cuts(BATCH, 4);
    let both = quads
        .iter()
        .filter(|(q, p)| matches!(q.split(p), Split::Both(..)))
        .count();
    println!("split/quad: {both} of {BATCH} random cuts make two parts");
    group.bench_function("quad", |b| b.iter(|| split_all(black_box(&quads))));

    let fragments = fragment_cuts(BATCH, 5);
    group.bench_function("fragment", |b| b.iter(|| split_all(black_box(&fragments))));
    group.finish();
}

criterion_group!(benches, split);
criterion_main!(benches);
