//! The illumination benchmark's scene: a 2 x 2 quad light ten units above
//! random receivers, and ten random triangles between them (or a dense
//! bumpy patch of triangles). Shared by the
//! `illum` criterion bench and the `illum-count` callgrind driver, so both
//! measure the same evaluations.

use illum::{AreaLight, Receiver, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Receivers per measured batch.
pub const BATCH: usize = 4096;

/// The light: a Cornell-box-like quad at y = 10, emitting -y.
pub fn light() -> AreaLight {
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

/// `n` receivers under the light, tilted up to about 40 degrees.
pub fn receivers(n: usize, seed: u64) -> Vec<Receiver> {
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

/// Ten triangles between the receivers and the light.
pub fn occluders(seed: u64) -> Vec<[Vec3; 3]> {
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

/// A bumpy patch over `[-2, 2]^2` around height 5, `k x k` cells of two
/// triangles each, sharing their edges: what a dense mesh puts between the
/// receivers and the light.
pub fn dense_patch(k: usize, seed: u64) -> Vec<[Vec3; 3]> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let step = 4.0 / k as f64;
    let heights: Vec<Vec<f64>> = (0..=k)
        .map(|_| (0..=k).map(|_| 5.0 + rng.random_range(-0.1..0.1)).collect())
        .collect();
    let at = |i: usize, j: usize| {
        [
            -2.0 + i as f64 * step,
            heights[i][j],
            -2.0 + j as f64 * step,
        ]
    };
    let mut out = Vec::with_capacity(2 * k * k);
    for i in 0..k {
        for j in 0..k {
            out.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            out.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    out
}
