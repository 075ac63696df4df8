//! Batch results are identical whatever the thread count.

use crate::{rect_light, unit};
use illum::{
    Receiver, Sidedness::OneSided, VisiblePart, area_irradiance_batch, evaluate_batch,
    visible_irradiance,
};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

#[test]
fn same_bits_for_any_thread_count() {
    let mut rng = Pcg64::seed_from_u64(3);
    let light = rect_light(-1.0, 1.0, -1.0, 1.0, 5.0, 2.0);
    let occ: Vec<Vec<[f64; 3]>> = (0..5)
        .map(|_| {
            let c: [f64; 3] = [
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(1.0..4.0),
            ];
            (0..3)
                .map(|_| {
                    [
                        c[0] + rng.random_range(-0.5..0.5),
                        c[1] + rng.random_range(-0.5..0.5),
                        c[2],
                    ]
                })
                .collect()
        })
        .collect();
    let receivers: Vec<Receiver> = (0..3000)
        .map(|_| Receiver {
            position: [
                rng.random_range(-2.0..2.0),
                rng.random_range(-2.0..2.0),
                0.0,
            ],
            normal: unit([
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                1.0,
            ]),
        })
        .collect();
    let mut scratch = VisiblePart::new();
    let serial: Vec<f64> = receivers
        .iter()
        .map(|r| visible_irradiance(&light, &occ, r.position, r.normal, OneSided, &mut scratch))
        .collect();
    for threads in [1, 2, 3, 7] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = vec![0.0; receivers.len()];
        pool.install(|| area_irradiance_batch(&light, &occ, &receivers, OneSided, &mut out))
            .unwrap();
        assert!(
            out.iter()
                .zip(&serial)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
        let mut out2 = vec![0.0; receivers.len()];
        pool.install(|| {
            evaluate_batch(&receivers, &mut out2, |r| {
                light.irradiance(r.position, r.normal, OneSided)
            })
        })
        .unwrap();
        for (r, e) in receivers.iter().zip(&out2) {
            assert_eq!(
                e.to_bits(),
                light.irradiance(r.position, r.normal, OneSided).to_bits()
            );
        }
    }
}
