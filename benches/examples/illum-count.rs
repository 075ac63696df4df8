//! A small driver for instruction counts of the illum hot paths under
//! `valgrind --tool=callgrind` (repeatable, unlike wall-clock time on a
//! shared machine): the same light, receivers and occluders as
//! `benches/illum.rs`.
//!
//! ```text
//! cargo build --release -p umbra-benches --example illum-count
//! valgrind --tool=callgrind target/release/examples/illum-count unoccluded
//! valgrind --tool=callgrind target/release/examples/illum-count visible
//! ```
//!
//! Divide the total instruction count by the printed number of evaluations
//! (setup is a small, fixed part).

use illum::{AreaLight, Receiver, Sidedness::OneSided, Vec3, VisiblePart, visible_irradiance};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::hint::black_box;

const BATCH: usize = 4096;

fn light() -> AreaLight {
    AreaLight::new(
        &[
            [-1.0, 10.0, -1.0],
            [1.0, 10.0, -1.0],
            [1.0, 10.0, 1.0],
            [-1.0, 10.0, 1.0],
        ],
        1.0,
    )
    .unwrap()
}

fn receivers(n: usize, seed: u64) -> Vec<Receiver> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let d: [f64; 3] = [
                rng.random_range(-0.8..0.8),
                1.0,
                rng.random_range(-0.8..0.8),
            ];
            let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            Receiver {
                position: [
                    rng.random_range(-4.0..4.0),
                    rng.random_range(0.0..1.0),
                    rng.random_range(-4.0..4.0),
                ],
                normal: [d[0] / l, d[1] / l, d[2] / l],
            }
        })
        .collect()
}

fn occluders(seed: u64) -> Vec<[Vec3; 3]> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..10)
        .map(|_| {
            let c = [
                rng.random_range(-2.0..2.0),
                rng.random_range(3.0..8.0),
                rng.random_range(-2.0..2.0),
            ];
            std::array::from_fn(|_| {
                [
                    c[0] + rng.random_range(-1.0..1.0),
                    c[1] + rng.random_range(-0.3..0.3),
                    c[2] + rng.random_range(-1.0..1.0),
                ]
            })
        })
        .collect()
}

fn main() {
    let mode = std::env::args().nth(1).unwrap_or_else(|| "visible".into());
    let rounds: usize = std::env::args()
        .nth(2)
        .map(|s| s.parse().expect("rounds"))
        .unwrap_or(10);
    let light = light();
    let rs = receivers(BATCH, 5);
    let occ = occluders(6);
    let mut scratch = VisiblePart::new();
    let mut acc = 0.0;
    for _ in 0..rounds {
        for r in &rs {
            acc += match mode.as_str() {
                "unoccluded" => light.irradiance(black_box(r.position), r.normal, OneSided),
                _ => visible_irradiance(
                    &light,
                    &occ,
                    black_box(r.position),
                    r.normal,
                    OneSided,
                    &mut scratch,
                ),
            };
        }
    }
    println!("{mode}: {} evaluations, sum {acc:.17e}", rounds * BATCH);
    if mode == "stats" {
        let (mut pieces, mut verts, mut n) = (0, 0, 0);
        for r in &rs {
            if light.lights_side_of(r.position) {
                scratch.compute(&light, &occ, r.position);
                pieces += scratch.len();
                verts += scratch.pieces().map(|p| p.len()).sum::<usize>();
                n += 1;
            }
        }
        println!(
            "{n} points, mean pieces {}, mean verts {}",
            pieces as f64 / n as f64,
            verts as f64 / n as f64
        );
    }
}
#[allow(dead_code)]
fn stats() {}
