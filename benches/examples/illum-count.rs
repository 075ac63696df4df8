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

use illum::{Sidedness::OneSided, VisiblePart, visible_irradiance};
use std::hint::black_box;
use umbra_benches::illum_scene::{BATCH, light, occluders, receivers};

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
