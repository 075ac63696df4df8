//! Balanced solids classify like autopartitions, and the set operations
//! work on them.

use crate::common::*;
use bsp_core::PointClass;
use bsp_core::{ConvexPolygon, Plane, Region, Side};
use rand::SeedableRng;
use svbsp::{BalancedOptions, SetOp, balanced_solid, balanced_solid_labelled, boundary, merge};

#[test]
fn balanced_trees_classify_like_autopartitions() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(21);
    for case in 0..8 {
        let faces = if case % 2 == 0 {
            random_star(&mut rng, [0, 0, 0], 5, 300.0, 900.0)
        } else {
            convex_faces(&random_convex(&mut rng, [10, -20, 30], 700, 14))
        };
        let reference = Solid::from_faces(faces.clone());
        for leaf_faces in [1, 4, 12] {
            let options = BalancedOptions {
                leaf_faces,
                ..Default::default()
            };
            let tree = balanced_solid(faces.clone(), &options);
            tree.check_invariants().unwrap();
            let mut compared = 0;
            for p in random_points(&mut rng, 400, 1000) {
                let want = reference.tree.classify_point(p);
                if want == PointClass::On {
                    continue;
                }
                assert_eq!(tree.classify_point(p), want, "leaf {leaf_faces} at {p:?}");
                compared += 1;
            }
            assert!(compared > 300);
        }
    }
}

#[test]
fn set_operations_on_balanced_trees() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(22);
    let options = BalancedOptions::default();
    for _ in 0..4 {
        let a_faces = random_star(&mut rng, [0, 0, 0], 6, 300.0, 900.0);
        let b_faces = random_star(&mut rng, [300, 200, -100], 6, 300.0, 900.0);
        let (a, b) = (
            balanced_solid(a_faces.clone(), &options),
            balanced_solid(b_faces.clone(), &options),
        );
        let (va, vb) = (polygons_volume(&a_faces), polygons_volume(&b_faces));
        let points = random_points(&mut rng, 500, 1200);
        let mut volumes = Vec::new();
        for op in OPS {
            let r = merge(&a, &b, op);
            check_pointwise(&r, &a, &b, op, points.iter().copied());
            let out = boundary(&a, &a_faces, &b, &b_faces, op);
            assert!(out.mesh.is_closed_manifold(), "{op:?}");
            volumes.push(out.mesh.volume());
        }
        let (union, inter, diff) = (volumes[0], volumes[1], volumes[2]);
        assert!((union + inter - va - vb).abs() <= 1e-9 * (va + vb));
        assert!((diff + inter - va).abs() <= 1e-9 * (va + vb));
        let _ = SetOp::Union;
    }
}

/// A labelled balanced tree asks about each empty region with the planes
/// that bound it, the axis splits' included: the pieces in the last plane
/// lie within all the others; its answers are the leaves' labels, and
/// answering as the last plane's side does gives the plain tree.
#[test]
fn labels_are_asked_with_each_cell_and_kept() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    let faces = random_star(&mut rng, [0, 0, 0], 5, 300.0, 900.0);
    let options = BalancedOptions {
        leaf_faces: 4,
        ..Default::default()
    };
    let asked = std::cell::Cell::new(0);
    let longest = std::cell::Cell::new(0);
    let axis_bounded = std::cell::Cell::new(0);
    let by_side = |path: &[(Plane, Side)], pieces: &[ConvexPolygon]| {
        let (last, bounds) = path.split_last().expect("a plane above");
        for piece in pieces {
            assert!(piece.support().is_coincident(&last.0) || piece.support().is_opposite(&last.0));
            for (plane, side) in bounds {
                for v in 0..piece.len() {
                    let at = piece.vertex_side(v, plane);
                    assert!(at == *side || at == Side::On, "a piece outside its cell");
                }
            }
        }
        asked.set(asked.get() + 1);
        longest.set(longest.get().max(path.len()));
        // (The star's faces lie in no axis plane: these are the splits'.)
        let axis = |p: &Plane| p.normal().iter().filter(|&&c| c == 0).count() == 2;
        axis_bounded.set(axis_bounded.get() + usize::from(bounds.iter().any(|(p, _)| axis(p))));
        Some(if last.1 == Side::Front {
            Region::Out
        } else {
            Region::In
        })
    };
    let labelled = balanced_solid_labelled(faces.clone(), &options, &by_side);
    let plain = balanced_solid(faces.clone(), &options);
    assert!(
        asked.get() > 50 && longest.get() > 6,
        "{} {}",
        asked.get(),
        longest.get()
    );
    assert!(
        axis_bounded.get() > asked.get() / 2,
        "{}",
        axis_bounded.get()
    );
    for p in random_points(&mut rng, 400, 1000) {
        assert_eq!(labelled.classify_point(p), plain.classify_point(p));
    }
    let inside = |_: &[(Plane, Side)], _: &[ConvexPolygon]| Some(Region::In);
    let full = balanced_solid_labelled(faces, &options, &inside);
    for p in random_points(&mut rng, 100, 1000) {
        assert_ne!(full.classify_point(p), PointClass::Out);
    }
}
