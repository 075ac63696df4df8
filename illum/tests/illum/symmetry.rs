//! Invariance under relabelling, rigid motions and mirroring, and
//! reciprocity of form factors (with and without an occluder).

use crate::{assert_rel, unit};
use illum::{AreaLight, Sidedness::OneSided, Vec3, VisiblePart, visible_irradiance};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

fn hexagon() -> Vec<Vec3> {
    // A tilted convex hexagon, counter-clockwise seen from below.
    let mut v: Vec<Vec3> = (0..6)
        .map(|i| {
            let t = i as f64 * std::f64::consts::PI / 3.0 + 0.1;
            let (x, y) = (1.3 * t.cos(), 0.8 * t.sin());
            [x, y, 2.0 + 0.3 * x - 0.2 * y]
        })
        .collect();
    v.reverse();
    v
}

fn rotation(rng: &mut Pcg64) -> [[f64; 3]; 3] {
    let q: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
    let l = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|c| c / l);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

fn apply(m: &[[f64; 3]; 3], v: Vec3) -> Vec3 {
    std::array::from_fn(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

fn occluder() -> Vec<Vec3> {
    vec![[-0.4, -0.5, 1.0], [0.6, -0.2, 1.1], [0.1, 0.7, 0.9]]
}

fn setup() -> (Vec3, Vec3) {
    ([0.3, -0.2, 0.0], unit([0.4, 0.1, 1.0]))
}

#[test]
fn starting_vertex_does_not_matter() {
    let (p, n) = setup();
    let base = AreaLight::new(&hexagon(), 1.0)
        .unwrap()
        .irradiance(p, n, OneSided);
    for k in 1..6 {
        let mut v = hexagon();
        v.rotate_left(k);
        let e = AreaLight::new(&v, 1.0).unwrap().irradiance(p, n, OneSided);
        assert_rel(e, base, 1e-14);
    }
}

#[test]
fn rigid_motions_and_mirrors() {
    let mut rng = Pcg64::seed_from_u64(7);
    let (p, n) = setup();
    let light = AreaLight::new(&hexagon(), 1.0).unwrap();
    let mut scratch = VisiblePart::new();
    let base = light.irradiance(p, n, OneSided);
    let base_vis = visible_irradiance(&light, &[occluder()], p, n, OneSided, &mut scratch);
    assert!(base_vis < base && base_vis > 0.0);
    for _ in 0..20 {
        let r = rotation(&mut rng);
        let t: Vec3 = std::array::from_fn(|_| rng.random_range(-1e3..1e3));
        let f = |v: Vec3| {
            let w = apply(&r, v);
            [w[0] + t[0], w[1] + t[1], w[2] + t[2]]
        };
        let l2 = AreaLight::new(&hexagon().into_iter().map(f).collect::<Vec<_>>(), 1.0).unwrap();
        let occ2: Vec<Vec3> = occluder().into_iter().map(f).collect();
        let (p2, n2) = (f(p), apply(&r, n));
        assert_rel(l2.irradiance(p2, n2, OneSided), base, 1e-10);
        let vis2 = visible_irradiance(&l2, &[occ2], p2, n2, OneSided, &mut scratch);
        assert_rel(vis2, base_vis, 1e-9);
    }
    // Mirror x -> -x: orientation flips, so the light's order is reversed;
    // the occluder blocks whichever side faces the light, so its order is
    // kept as mirrored.
    let m = |v: Vec3| [-v[0], v[1], v[2]];
    let mut mirrored: Vec<Vec3> = hexagon().into_iter().map(m).collect();
    mirrored.reverse();
    let lm = AreaLight::new(&mirrored, 1.0).unwrap();
    assert_rel(lm.irradiance(m(p), m(n), OneSided), base, 1e-14);
    let occ_m: Vec<Vec3> = occluder().into_iter().map(m).collect();
    let vis_m = visible_irradiance(&lm, &[occ_m], m(p), m(n), OneSided, &mut scratch);
    assert_rel(vis_m, base_vis, 1e-13);
}

/// Midpoint-rule integral of `f` over the parallelogram `o + u e1 + v e2`.
fn integrate(o: Vec3, e1: Vec3, e2: Vec3, k: usize, mut f: impl FnMut(Vec3) -> f64) -> f64 {
    let cr = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let area = (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]).sqrt();
    let mut sum = 0.0;
    for i in 0..k {
        for j in 0..k {
            let (u, v) = ((i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64);
            sum += f(std::array::from_fn(|c| o[c] + u * e1[c] + v * e2[c]));
        }
    }
    sum * area / (k * k) as f64
}

fn corners(o: Vec3, e1: Vec3, e2: Vec3) -> Vec<Vec3> {
    vec![
        o,
        std::array::from_fn(|c| o[c] + e1[c]),
        std::array::from_fn(|c| o[c] + e1[c] + e2[c]),
        std::array::from_fn(|c| o[c] + e2[c]),
    ]
}

#[test]
fn reciprocity() {
    // P: unit square at z = 0 facing +z. Q: a tilted rectangle above it,
    // facing down. With unit radiance, A_P F_PQ = A_Q F_QP reads
    // integral over P of E_Q = integral over Q of E_P, with or without an
    // occluder between them (visibility is symmetric).
    let (po, pe1, pe2) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let (qo, qe1, qe2) = ([0.5, -0.3, 1.5], [0.0, 1.2, 0.2], [0.8, 0.0, 0.3]);
    let p_light = AreaLight::new(&corners(po, pe1, pe2), 1.0).unwrap();
    let q_light = AreaLight::new(&corners(qo, qe1, qe2), 1.0).unwrap();
    let n_p = p_light.normal();
    let n_q = q_light.normal();
    assert!(n_p[2] > 0.0 && n_q[2] < 0.0);
    let k = 120;
    let pq = integrate(po, pe1, pe2, k, |x| q_light.irradiance(x, n_p, OneSided));
    let qp = integrate(qo, qe1, qe2, k, |y| p_light.irradiance(y, n_q, OneSided));
    assert!(pq > 0.05);
    assert_rel(pq, qp, 2e-5);

    let occ = [[0.4, 0.1, 0.7], [0.9, 0.3, 0.8], [0.5, 0.8, 0.75]];
    let mut s = VisiblePart::new();
    let pq_v = integrate(po, pe1, pe2, k, |x| {
        visible_irradiance(&q_light, &[occ], x, n_p, OneSided, &mut s)
    });
    let qp_v = integrate(qo, qe1, qe2, k, |y| {
        visible_irradiance(&p_light, &[occ], y, n_q, OneSided, &mut s)
    });
    assert!(pq_v < 0.95 * pq);
    // Visibility has kinks: the midpoint rule converges more slowly.
    assert_rel(pq_v, qp_v, 2e-3);
}
