//! Joint-umbra proofs (`area_shadow::dark::sees_none`) as the commands
//! make them: of 2000 seeded cases of 3 to 7 panels over a patch of
//! floor, those whose corners see none of the light (sampled in floating
//! point), under a level square light and under the same light tilted
//! (halved in its plane's lattice), timed as a batch; proofs that succeed
//! and proofs that fail both count. Then the floor under a 1,280-triangle
//! bumpy sphere: finding its body (a core of its kernel), and the proofs
//! of the floor squares whose corners see none of the light, with the
//! core's shell among the blockers. Last, finding the cores of a
//! 1,024-triangle torus (local kernels: it has no kernel).
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use area_shadow::dark::sees_none;
use area_shadow::{AreaSource, convex_groups, section_unions};
use bsp_core::{ConvexPolygon, GridPoint};
use criterion::{Criterion, criterion_group, criterion_main};
use rand::Rng;
use std::hint::black_box;
use umbra_benches::closed_meshes::{bumpy_sphere, torus};
use umbra_benches::random::rng;

fn g(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).unwrap()
}

/// One case: a floor square, facing up, and the panels over it.
struct Case {
    region: ConvexPolygon,
    panels: Vec<ConvexPolygon>,
}

fn cases(n: usize) -> Vec<Case> {
    let mut rng = rng(8);
    (0..n)
        .map(|_| {
            let panels = (0..rng.random_range(3..8))
                .map(|_| {
                    let (x, z) = (rng.random_range(-2500..1500), rng.random_range(-2500..1500));
                    let (w, d) = (rng.random_range(300..2500), rng.random_range(300..2500));
                    let y = rng.random_range(2000..8000);
                    let c = [
                        g(x, y, z),
                        g(x + w, y, z),
                        g(x + w, y, z + d),
                        g(x, y, z + d),
                    ];
                    ConvexPolygon::from_grid_points(&c, 0).unwrap()
                })
                .collect();
            let (cx, cz, r) = (
                rng.random_range(-1000..1000),
                rng.random_range(-1000..1000),
                rng.random_range(5..100),
            );
            let c = [
                g(cx - r, 0, cz - r),
                g(cx - r, 0, cz + r),
                g(cx + r, 0, cz + r),
                g(cx + r, 0, cz - r),
            ];
            Case {
                region: ConvexPolygon::from_grid_points(&c, 1).unwrap(),
                panels,
            }
        })
        .collect()
}

/// Whether the segment from `k` to `l` crosses the panel.
fn crosses(k: [f64; 3], l: [f64; 3], panel: &ConvexPolygon) -> bool {
    let c = panel.vertices_f64();
    let y = c[0][1];
    let t = (y - k[1]) / (l[1] - k[1]);
    if !(0.0..=1.0).contains(&t) {
        return false;
    }
    let (x, z) = (k[0] + t * (l[0] - k[0]), k[2] + t * (l[2] - k[2]));
    let (lo, hi) = (c[0], c[2]);
    (lo[0].min(hi[0])..=lo[0].max(hi[0])).contains(&x)
        && (lo[2].min(hi[2])..=lo[2].max(hi[2])).contains(&z)
}

/// Whether every corner of the case's region sees none of 9 x 9 points of
/// the light (its corners given).
fn corners_dark(case: &Case, light: &[[f64; 3]; 4]) -> bool {
    case.region.vertices_f64().iter().all(|&k| {
        (0..81).all(|s| {
            let (a, b) = ((s % 9) as f64 / 8.0, (s / 9) as f64 / 8.0);
            let l: [f64; 3] = std::array::from_fn(|i| {
                (1.0 - a) * (1.0 - b) * light[0][i]
                    + a * (1.0 - b) * light[1][i]
                    + a * b * light[2][i]
                    + (1.0 - a) * b * light[3][i]
            });
            case.panels.iter().any(|p| crosses(k, l, p))
        })
    })
}

fn dark(c: &mut Criterion) {
    let all = cases(2000);
    for (name, rise) in [("dark_level_light", 0), ("dark_tilted_light", 1300)] {
        let y = 10_000;
        let light = AreaSource::from_grid_points(&[
            g(-500, y, -500),
            g(500, y + rise, -500),
            g(500, y + rise, 500),
            g(-500, y, 500),
        ])
        .unwrap();
        let corners = [
            [-500.0, y as f64, -500.0],
            [500.0, (y + rise) as f64, -500.0],
            [500.0, (y + rise) as f64, 500.0],
            [-500.0, y as f64, 500.0],
        ];
        let tried: Vec<&Case> = all
            .iter()
            .filter(|case| corners_dark(case, &corners))
            .collect();
        let prove = || {
            tried
                .iter()
                .filter(|case| {
                    let panels: Vec<&ConvexPolygon> = case.panels.iter().collect();
                    sees_none(&case.region, false, &light, &panels, &[])
                })
                .count()
        };
        eprintln!("{name}: {} cases tried, {} proven", tried.len(), prove());
        c.bench_function(name, |b| b.iter(|| black_box(prove())));
    }
}

/// Whether the segment from `k` to `l` crosses the triangle (floating
/// point, for choosing cases only).
fn crosses_triangle(k: [f64; 3], l: [f64; 3], t: &[[f64; 3]]) -> bool {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (d, e1, e2) = (sub(l, k), sub(t[1], t[0]), sub(t[2], t[0]));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-12 {
        return false;
    }
    let s = sub(k, t[0]);
    let u = dot(s, p) / det;
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    let w = dot(e2, q) / det;
    u >= 0.0 && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&w)
}

fn bumpy(c: &mut Criterion) {
    let faces = bumpy_sphere([0, 9000, 0], 5000.0, 0.03, 3);
    let objects = vec![Some(0); faces.len()];
    c.bench_function("kernel_core_1280_triangles", |b| {
        b.iter(|| black_box(convex_groups(&faces, &objects)))
    });
    let groups = convex_groups(&faces, &objects);
    let shell = groups[0].shell().expect("a core of the kernel");
    let y = 24_000;
    let light = AreaSource::from_grid_points(&[
        g(-2000, y, -2000),
        g(2000, y, -2000),
        g(2000, y, 2000),
        g(-2000, y, 2000),
    ])
    .unwrap();
    let triangles: Vec<&ConvexPolygon> = faces.iter().collect();
    let outlines: Vec<Vec<[f64; 3]>> = faces.iter().map(ConvexPolygon::vertices_f64).collect();
    // Floor squares (300 grid units) on a grid under the sphere whose
    // corners see none of 9 x 9 points of the light.
    let squares: Vec<ConvexPolygon> = (0..24 * 24)
        .map(|k| {
            let (x, z) = (-7200 + 600 * (k % 24), -7200 + 600 * (k / 24));
            let c = [
                g(x, 0, z),
                g(x, 0, z + 300),
                g(x + 300, 0, z + 300),
                g(x + 300, 0, z),
            ];
            ConvexPolygon::from_grid_points(&c, 1).unwrap()
        })
        .filter(|square| {
            square.vertices_f64().iter().all(|&k| {
                (0..81).all(|s| {
                    let l = [
                        -2000.0 + 500.0 * (s % 9) as f64,
                        y as f64,
                        -2000.0 + 500.0 * (s / 9) as f64,
                    ];
                    outlines.iter().any(|t| crosses_triangle(k, l, t))
                })
            })
        })
        .collect();
    let prove = || {
        squares
            .iter()
            .filter(|square| sees_none(square, false, &light, &triangles, &[&shell]))
            .count()
    };
    eprintln!(
        "dark_under_bumpy_sphere: {} squares tried, {} proven",
        squares.len(),
        prove()
    );
    c.bench_function("dark_under_bumpy_sphere", |b| b.iter(|| black_box(prove())));
}

fn ring(c: &mut Criterion) {
    let faces = torus([0, 9000, 0], (5000.0, 2000.0), (32, 16));
    let objects = vec![Some(0); faces.len()];
    let cores = convex_groups(&faces, &objects).len();
    eprintln!("local_cores_1024_triangles: {cores} cores");
    c.bench_function("local_cores_1024_triangles", |b| {
        b.iter(|| black_box(convex_groups(&faces, &objects)))
    });
    let sections = section_unions(&faces, &objects).len();
    eprintln!("sections_1024_triangles: {sections} sections");
    c.bench_function("sections_1024_triangles", |b| {
        b.iter(|| black_box(section_unions(&faces, &objects)))
    });
}

criterion_group!(benches, dark, bumpy, ring);
criterion_main!(benches);
