//! CSG boundaries: volumes satisfy inclusion-exclusion, meshes are closed.

use crate::common::*;
use rand::SeedableRng;
use svbsp::{CsgBoundary, SetOp, boundary};

fn csg(a: &Solid, b: &Solid, op: SetOp) -> CsgBoundary {
    let out = boundary(&a.tree, &a.faces, &b.tree, &b.faces, op);
    for p in &out.polygons {
        p.check_invariants().unwrap();
    }
    let open = out.mesh.open_edges();
    assert!(
        open.is_empty(),
        "{op:?}: {} open edges, e.g. {:?}",
        open.len(),
        &open[..open.len().min(4)]
    );
    let v = polygons_volume(&out.polygons);
    let w = out.mesh.volume();
    assert!((v - w).abs() <= 1e-9 * v.abs().max(1.0), "{v} vs {w}");
    out
}

fn check_volumes(a: &Solid, b: &Solid) {
    let (va, vb) = (a.volume(), b.volume());
    let union = csg(a, b, SetOp::Union).mesh.volume();
    let inter = csg(a, b, SetOp::Intersection).mesh.volume();
    let diff = csg(a, b, SetOp::Difference).mesh.volume();
    let scale = va + vb;
    assert!(
        (union + inter - va - vb).abs() <= 1e-9 * scale,
        "union {union} inter {inter} a {va} b {vb}"
    );
    assert!(
        (diff + inter - va).abs() <= 1e-9 * scale,
        "diff {diff} inter {inter} a {va}"
    );
    assert!(inter >= -1e-9 * scale && inter <= va.min(vb) * (1.0 + 1e-9));
}

#[test]
fn random_boxes() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    for _ in 0..80 {
        let a = Solid::from_faces(random_box(&mut rng, 8));
        let b = Solid::from_faces(random_box(&mut rng, 8));
        check_volumes(&a, &b);
    }
}

#[test]
fn random_convex_polyhedra() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(12);
    for _ in 0..20 {
        let a = Solid::from_faces(convex_faces(&random_convex(&mut rng, [0, 0, 0], 500, 10)));
        let c: [i64; 3] = std::array::from_fn(|_| rand::Rng::random_range(&mut rng, -600..600));
        let b = Solid::from_faces(convex_faces(&random_convex(&mut rng, c, 400, 10)));
        check_volumes(&a, &b);
    }
}

#[test]
fn star_meshes() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(13);
    for _ in 0..10 {
        let a = Solid::from_faces(random_star(&mut rng, [0, 0, 0], 3, 300.0, 900.0));
        let c: [i64; 3] = std::array::from_fn(|_| rand::Rng::random_range(&mut rng, -700..700));
        let b = Solid::from_faces(random_star(&mut rng, c, 3, 300.0, 900.0));
        check_volumes(&a, &b);
        // Generic position: every edge is used once in each direction.
        for op in OPS {
            assert!(csg(&a, &b, op).mesh.is_closed_manifold(), "{op:?}");
        }
    }
}

#[test]
fn coplanar_boxes() {
    let a = Solid::from_faces(box_faces([0, 0, 0], [4, 4, 4]));
    for (b, union) in [
        (box_faces([4, 0, 0], [8, 4, 4]), 128.0),
        (box_faces([2, 0, 0], [6, 4, 4]), 96.0),
        (box_faces([0, 0, 0], [4, 4, 4]), 64.0),
        (box_faces([1, 1, 4], [3, 3, 6]), 72.0),
        (box_faces([1, 1, 1], [3, 3, 3]), 64.0),
        (box_faces([2, 2, 2], [6, 6, 6]), 120.0),
        (box_faces([4, 4, 0], [8, 8, 4]), 128.0),
    ] {
        let b = Solid::from_faces(b);
        check_volumes(&a, &b);
        assert_eq!(csg(&a, &b, SetOp::Union).mesh.volume(), union);
    }
}

#[test]
fn a_with_itself_and_its_complement() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(14);
    let a = Solid::from_faces(random_star(&mut rng, [0, 0, 0], 3, 300.0, 900.0));
    let va = a.volume();
    let close = |v: f64, want: f64| (v - want).abs() <= 1e-9 * va;
    assert!(close(csg(&a, &a, SetOp::Union).mesh.volume(), va));
    assert!(close(csg(&a, &a, SetOp::Intersection).mesh.volume(), va));
    assert!(csg(&a, &a, SetOp::Difference).polygons.is_empty());
    let comp = a.complement();
    // A ∪ ¬A is all of space and A ∩ ¬A is empty: no boundary at all.
    assert!(csg(&a, &comp, SetOp::Union).polygons.is_empty());
    assert!(csg(&a, &comp, SetOp::Intersection).polygons.is_empty());
    assert!(close(csg(&a, &comp, SetOp::Difference).mesh.volume(), va));
}

#[test]
fn t_junctions_are_removed() {
    // A small box on a big one: the big top face is cut around the small
    // one's footprint, and the small box's bottom is gone; the cut pieces'
    // vertices land inside the neighbouring side faces' edges.
    let a = Solid::from_faces(box_faces([0, 0, 0], [8, 8, 4]));
    let b = Solid::from_faces(box_faces([2, 0, 4], [5, 3, 7]));
    let out = csg(&a, &b, SetOp::Union);
    let longer = out
        .mesh
        .faces
        .iter()
        .zip(&out.mesh.face_polygon)
        .filter(|(f, p)| f.len() > out.polygons[**p as usize].len())
        .count();
    assert!(longer > 0, "some face needed a vertex inserted");
    let mut obj = String::new();
    out.mesh.write_obj(&mut obj).unwrap();
    assert!(obj.lines().filter(|l| l.starts_with("f ")).count() == out.mesh.faces.len());
}
