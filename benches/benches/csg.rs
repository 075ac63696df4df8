//! CSG union of two closed star-shaped meshes of about 10k triangles each:
//! boundary evaluation (each mesh's faces partitioned by the other's tree,
//! welded without T-junctions), with and without building the two
//! (balanced) trees, and the Naylor-Amanatides-Thibault tree merge.
//!
//! The trees are [`balanced_solid`]s: an autopartition of a star-shaped
//! mesh is a chain as deep as the mesh is large, which makes every
//! filtering linear in the mesh (seconds here, not milliseconds).
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use bsp_core::{ConvexPolygon, GridPoint};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Instant;
use svbsp::{BalancedOptions, SetOp, balanced_solid, boundary, merge};

/// The allocator of the `umbra` binary, so the figures are `umbra csg`'s.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A closed star-shaped mesh of `8 m^2` triangles: the octahedron with each
/// face cut into `m * m` triangles, each vertex pushed along its direction to
/// a smooth, bumpy radius around `radius` (a function of the direction, so
/// shared vertices agree and the mesh stays closed and embedded).
fn star_mesh(center: [i64; 3], m: i64, radius: f64, phase: f64) -> Vec<ConvexPolygon> {
    let point = |d: [i64; 3]| {
        let len = ((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) as f64).sqrt();
        let u = d.map(|c| c as f64 / len);
        let bump =
            ((3.0 * u[0] + phase).sin() + (2.0 * u[1] - phase).sin() + (4.0 * u[2]).sin()) / 3.0;
        let r = radius * (1.0 + 0.15 * bump);
        GridPoint::new(
            center[0] + (u[0] * r).round() as i64,
            center[1] + (u[1] * r).round() as i64,
            center[2] + (u[2] * r).round() as i64,
        )
        .expect("within the grid")
    };
    let c = GridPoint::new(center[0], center[1], center[2]).expect("within the grid");
    let mut faces = Vec::new();
    for sx in [1_i64, -1] {
        for sy in [1_i64, -1] {
            for sz in [1_i64, -1] {
                let at = |i: i64, j: i64| point([sx * i, sy * j, sz * (m - i - j)]);
                for i in 0..m {
                    for j in 0..m - i {
                        let mut tris = vec![[at(i, j), at(i + 1, j), at(i, j + 1)]];
                        if i + j + 1 < m {
                            tris.push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                        }
                        for t in tris {
                            let f = ConvexPolygon::from_grid_points(&t, faces.len() as u32)
                                .expect("a proper triangle");
                            let outward = bsp_core::predicates::side_of_point(f.support(), c)
                                == bsp_core::predicates::Side::Back;
                            faces.push(if outward { f } else { f.flipped() });
                        }
                    }
                }
            }
        }
    }
    faces
}

fn operands() -> (Vec<ConvexPolygon>, Vec<ConvexPolygon>) {
    let a = star_mesh([0, 0, 0], 35, 4.0e6, 0.3);
    let b = star_mesh([2_500_000, 1_100_000, -700_000], 35, 3.5e6, 1.7);
    (a, b)
}

fn union(c: &mut Criterion) {
    let (a_faces, b_faces) = operands();
    let options = BalancedOptions::default();
    let t = Instant::now();
    let a = balanced_solid(a_faces.clone(), &options);
    let b = balanced_solid(b_faces.clone(), &options);
    let build = t.elapsed();
    let t = Instant::now();
    let out = boundary(&a, &a_faces, &b, &b_faces, SetOp::Union);
    let eval = t.elapsed();
    let t = Instant::now();
    let merged = merge(&a, &b, SetOp::Union);
    let merging = t.elapsed();
    eprintln!(
        "csg union: {} + {} triangles, trees {} + {} nodes ({build:?}); boundary {} pieces, {} mesh vertices, closed {} ({eval:?}); merged tree {} nodes ({merging:?})",
        a_faces.len(),
        b_faces.len(),
        a.nodes().len(),
        b.nodes().len(),
        out.polygons.len(),
        out.mesh.vertices.len(),
        out.mesh.is_closed(),
        merged.nodes().len(),
    );

    let mut group = c.benchmark_group("csg_union_10k");
    group.sample_size(10);
    group.bench_function("boundary", |bench| {
        bench.iter(|| black_box(boundary(&a, &a_faces, &b, &b_faces, SetOp::Union)))
    });
    group.bench_function("balanced_trees_and_boundary", |bench| {
        bench.iter(|| {
            let a = balanced_solid(a_faces.clone(), &options);
            let b = balanced_solid(b_faces.clone(), &options);
            black_box(boundary(&a, &a_faces, &b, &b_faces, SetOp::Union))
        })
    });
    group.bench_function("merge_trees", |bench| {
        bench.iter(|| black_box(merge(&a, &b, SetOp::Union)))
    });
    group.finish();
}

criterion_group!(benches, union);
criterion_main!(benches);
