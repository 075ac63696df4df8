//! Tests of the general shadow volumes against independent oracles.

use super::*;
use crate::LightSource;
use bsp_core::predicates::{Side, orient3d_f64};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

fn g(x: i32, y: i32, z: i32) -> GridPoint {
    GridPoint { x, y, z }
}

/// A planar polygon as a model polygon of one piece.
fn flat(corners: &[GridPoint]) -> ModelPolygon {
    ModelPolygon {
        boundary: corners.to_vec(),
        pieces: vec![ConvexPolygon::from_grid_points(corners, 0).unwrap()],
    }
}

/// The faces of the box `[lo, hi]`, outward and counter-clockwise; `open`
/// leaves out the top (+y) face.
fn cuboid(lo: [i32; 3], hi: [i32; 3], open: bool) -> Model {
    let c = |i: usize| {
        g(
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        )
    };
    let mut faces = vec![
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // -y
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
    ];
    if !open {
        faces.push([2, 6, 7, 3]); // +y
    }
    Model {
        polygons: faces.iter().map(|f| flat(&f.map(c))).collect(),
    }
}

/// A non-planar quad, triangulated along its first diagonal.
fn bent(corners: [GridPoint; 4]) -> ModelPolygon {
    let [a, b, c, d] = corners;
    ModelPolygon {
        boundary: corners.to_vec(),
        pieces: vec![
            ConvexPolygon::from_grid_points(&[a, b, c], 0).unwrap(),
            ConvexPolygon::from_grid_points(&[a, c, d], 0).unwrap(),
        ],
    }
}

fn scene_models() -> Vec<Model> {
    vec![
        cuboid([-6, 2, -6], [-1, 6, -1], false),
        cuboid([1, 1, -2], [7, 5, 5], true),
        Model {
            polygons: vec![bent([g(-5, 7, 2), g(0, 9, 2), g(0, 7, 7), g(-5, 9, 7)])],
        },
    ]
}

fn lights() -> Vec<Light> {
    vec![
        Light::point(g(0, 20, 0)),
        Light::point(g(3, 3, 1)),   // inside the open box
        Light::point(g(-30, 4, 3)), // from the side: the bent quad is twisted
        Light::directional([1, -3, 2]),
        Light {
            range: Some(25.0),
            ..Light::point(g(2, 18, -3))
        },
    ]
}

fn random_point(rng: &mut Pcg64) -> [f64; 3] {
    [0, 1, 2].map(|_| rng.random_range(-35.0..35.0))
}

/// The model pieces as crossing polygons: entering a frustum through its
/// own piece adds 1.
fn piece_polygons(v: &BergeronVolumes) -> Vec<ShadowPolygon> {
    v.pieces
        .iter()
        .filter_map(|p| {
            let c = &p.vertices;
            let light_side = orient3d_f64(c[0], c[1], c[2], v.apex.beside(c[0]));
            (light_side != Side::On).then(|| ShadowPolygon {
                vertices: c.clone(),
                closed: true,
                weight: if light_side == Side::Back { 1 } else { -1 },
                counter: p.counter,
            })
        })
        .collect()
}

/// Along any segment, the counts at its start plus every increment it
/// crosses (shadow polygons and model pieces) are the counts at its end:
/// the increments and their signs are right.
#[test]
fn counts_follow_any_segment() {
    let mut rng = Pcg64::seed_from_u64(7);
    for light in lights() {
        let v = BergeronVolumes::build(&scene_models(), &light, None).unwrap();
        let pieces = piece_polygons(&v);
        for round in 0..800 {
            let (mut e, p) = (random_point(&mut rng), random_point(&mut rng));
            // Every other eye at a small integer point: often on a shadow
            // polygon's plane or in a model's plane, where the perturbation
            // decides.
            if round % 2 == 1 {
                e = e.map(|c| (c / 3.0).round());
            }
            let mut counts = v.eye_counts(e);
            for polygon in v.shadow_polygons().iter().chain(&pieces) {
                counts[polygon.counter as usize] += polygon.crossing(e, p);
            }
            assert_eq!(counts, v.eye_counts(p), "{light:?} from {e:?} to {p:?}");
        }
    }
}

/// A point is in shadow exactly when the segment to the light (the ray
/// against a directional light) meets a model piece: an oracle in floating
/// point, away from ties.
#[test]
fn shadow_is_occlusion() {
    let mut rng = Pcg64::seed_from_u64(11);
    let models = scene_models();
    let all: Vec<Vec<[f64; 3]>> = models
        .iter()
        .flat_map(|m| m.polygons.iter().flat_map(|p| p.pieces.iter()))
        .map(|p| p.vertices_f64())
        .collect();
    for light in lights() {
        let v = BergeronVolumes::build(&models, &light, None).unwrap();
        let mut shadowed = 0;
        for _ in 0..1500 {
            let mut x = random_point(&mut rng);
            // With a range, points within it.
            if let (Some(range), LightSource::Point(l)) = (light.range, light.source) {
                while distance(x, l.to_f64()) >= range {
                    x = random_point(&mut rng);
                }
            }
            let (to, far) = match light.source {
                LightSource::Point(l) => (l.to_f64(), false),
                LightSource::Directional(d) => (d.map(|c| -f64::from(c)), true),
            };
            let Some(hit) = oracle_occluded(&all, x, to, far) else {
                continue;
            };
            if let Some(range) = light.range
                && distance(x, to) >= range
            {
                continue;
            }
            let ours = is_shadowed(&v.eye_counts(x));
            assert_eq!(ours, hit, "{light:?} at {x:?}");
            shadowed += usize::from(hit);
        }
        assert!(shadowed > 20, "{light:?}: only {shadowed} shadowed points");
    }
}

/// Whether the segment from `x` to `to` (or the ray from `x` along `to`
/// when `far`) crosses a polygon; `None` when it passes within a margin of
/// a polygon's boundary or plane, where floating point could be wrong.
fn oracle_occluded(
    polygons: &[Vec<[f64; 3]>],
    x: [f64; 3],
    to: [f64; 3],
    far: bool,
) -> Option<bool> {
    let dir = if far {
        to
    } else {
        [0, 1, 2].map(|i| to[i] - x[i])
    };
    let t_max = if far { f64::INFINITY } else { 1.0 };
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mut hit = false;
    for v in polygons {
        let n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
        let len = dot(n, n).sqrt();
        let n = n.map(|c| c / len);
        let denom = dot(n, dir);
        let h = dot(n, sub(v[0], x));
        if h.abs() < 1e-6 {
            return None;
        }
        if denom.abs() < 1e-9 {
            continue;
        }
        let t = h / denom;
        if t <= 0.0 || t >= t_max {
            if (t - t_max).abs() < 1e-6 {
                return None;
            }
            continue;
        }
        let q = [0, 1, 2].map(|i| x[i] + t * dir[i]);
        let mut inside = true;
        for i in 0..v.len() {
            let e = sub(v[(i + 1) % v.len()], v[i]);
            let s = dot(cross(e, sub(q, v[i])), n) / dot(e, e).sqrt();
            if s.abs() < 1e-6 {
                return None;
            }
            inside &= s > 0.0;
        }
        hit |= inside;
    }
    Some(hit)
}

#[test]
fn contour_increments_of_closed_and_open_models() {
    let light = Light::point(g(0, 20, 0));
    // A closed box under the light: its contour edges are shared, Nb_C = 2.
    let closed =
        BergeronVolumes::build(&[cuboid([-2, 1, -2], [2, 3, 2], false)], &light, None).unwrap();
    let s = closed.stats();
    assert_eq!((s.shared_edges, s.open_edges), (4, 0));
    assert!(closed.shadow_polygons().iter().all(|p| p.weight.abs() == 2));
    // The open box (no top) under the light: its rim is open, Nb_C = 1.
    let open =
        BergeronVolumes::build(&[cuboid([-2, 1, -2], [2, 3, 2], true)], &light, None).unwrap();
    let s = open.stats();
    assert_eq!((s.shared_edges, s.open_edges), (0, 4));
    // Under a closed box the count is 2 (Type 2), under the open one 1
    // (Type 3: only its bottom lies between), beside them 0 (Type 1).
    assert_eq!(closed.eye_counts([0.5, 0.0, 0.5]), vec![2]);
    assert_eq!(open.eye_counts([0.5, 0.0, 0.5]), vec![1]);
    assert_eq!(open.eye_counts([9.5, 0.0, 0.5]), vec![0]);
    assert_eq!(
        closed.eye_cases([0.5, 0.0, 0.5]),
        vec![EyeCase::InClosedModel { depth: 2 }]
    );
    assert_eq!(
        open.eye_cases([0.5, 0.0, 0.5]),
        vec![EyeCase::InOpenModel { depth: 1 }]
    );
    assert_eq!(open.eye_cases([9.5, 0.0, 0.5]), vec![EyeCase::Outside]);
    // From inside the open box, nothing is in its shadow inside it, and
    // everything below the floor is.
    let inside = Light::point(g(0, 2, 0));
    let v = BergeronVolumes::build(&[cuboid([-2, 1, -2], [2, 3, 2], true)], &inside, None).unwrap();
    assert_eq!(v.eye_counts([0.5, 2.5, 0.5]), vec![0]);
    assert_eq!(v.eye_counts([30.5, -20.0, 0.5]), vec![1]);
}

#[test]
fn an_eye_on_a_shadow_polygon() {
    // The square's shadow volume under the light; the plane through the
    // light and its edge x = 2 is 5x + 2y = 20, and (3, 2.5, 0) lies on the
    // volume's side there.
    let square = [g(-2, 5, 2), g(2, 5, 2), g(2, 5, -2), g(-2, 5, -2)];
    let model = Model {
        polygons: vec![flat(&square)],
    };
    let v = BergeronVolumes::build(&[model], &Light::point(g(0, 10, 0)), None).unwrap();
    let eye = [3.0, 2.5, 0.0];
    let start = v.eye_counts(eye);
    // Perturbed along +x, the eye is just outside.
    assert_eq!(start, vec![0]);
    assert!(v.in_shadow(eye, &start, [0.5, 0.0, 1.0]));
    assert!(v.in_shadow(eye, &start, [3.9, 0.0, -0.5]));
    assert!(!v.in_shadow(eye, &start, [4.1, 0.0, -0.5]));
    assert!(!v.in_shadow(eye, &start, [6.0, 0.0, 0.0]));
    // On the side x = -2 the same perturbation puts it inside.
    let eye = [-3.0, 2.5, 0.0];
    let start = v.eye_counts(eye);
    assert_eq!(start, vec![1]);
    assert!(v.in_shadow(eye, &start, [0.5, 0.0, 1.0]));
    assert!(!v.in_shadow(eye, &start, [-6.0, 0.0, 0.0]));
}

#[test]
fn twisted_polygons_count_apart() {
    let quad = [g(-5, 7, 2), g(0, 9, 2), g(0, 7, 7), g(-5, 9, 7)];
    let model = Model {
        polygons: vec![bent(quad)],
    };
    // From above the quad is not twisted; from the side along z it is.
    let above = BergeronVolumes::build(
        std::slice::from_ref(&model),
        &Light::point(g(-2, 30, 4)),
        None,
    )
    .unwrap();
    assert_eq!((above.stats().twisted_polygons, above.counters()), (0, 1));
    let side = BergeronVolumes::build(&[model], &Light::directional([0, 0, 1]), None).unwrap();
    assert_eq!((side.stats().twisted_polygons, side.counters()), (1, 2));
    assert!(side.shadow_polygons().iter().all(|p| p.counter == 1));
    // Behind it along +z, in the left lobe of its bow-tie outline.
    let counts = side.eye_counts([-4.0, 8.0, 20.0]);
    assert_eq!(counts[0], 0);
    assert!(counts[1] > 0);
}

#[test]
fn a_range_truncates_and_leaves_far_models_out() {
    let near = cuboid([-2, 10, -2], [2, 12, 2], false);
    let far = cuboid([30, 0, 30], [35, 5, 35], false);
    let light = Light {
        range: Some(20.0),
        ..Light::point(g(0, 16, 0))
    };
    let v = BergeronVolumes::build(&[near, far], &light, None).unwrap();
    assert_eq!(v.stats().models_beyond_range, 1);
    assert_eq!(
        v.eye_cases([0.5, 0.0, 0.5]),
        vec![EyeCase::InClosedModel { depth: 2 }, EyeCase::Outside]
    );
    assert_eq!(v.stats().caps, 6);
    // Inside the range under the box: shadow (closed: 2); far beyond the
    // truncation: out of every volume.
    assert_eq!(v.eye_counts([0.5, 0.0, 0.5]), vec![2]);
    assert_eq!(v.eye_counts([0.5, -39.0, 0.5]), vec![0]);
    assert!(v.shadow_polygons().iter().all(|p| p.closed));
    // Without the range the volumes are unbounded.
    let unbounded = BergeronVolumes::build(
        &[cuboid([-2, 10, -2], [2, 12, 2], false)],
        &Light::point(g(0, 16, 0)),
        None,
    )
    .unwrap();
    assert_eq!(unbounded.stats().caps, 0);
    assert!(unbounded.shadow_polygons().iter().all(|p| !p.closed));
    assert_eq!(unbounded.eye_counts([0.5, -1e9, 0.5]), vec![2]);
    let eye = [0.5, -1e9, 0.5];
    assert!(unbounded.in_shadow(eye, &[2], [0.5, 0.0, 0.7]));
    assert!(!unbounded.in_shadow(eye, &[2], [1e9, 0.0, 0.7]));
    // An eye beyond the caps sees the floor's shadow right.
    let eye = [0.5, -39.0, 0.5];
    let start = v.eye_counts(eye);
    assert!(v.in_shadow(eye, &start, [0.5, 0.0, 0.7]));
    assert!(!v.in_shadow(eye, &start, [12.5, 0.0, 0.7]));
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}
