//! Balanced solids classify like autopartitions, and the set operations
//! work on them.

use crate::common::*;
use bsp_core::PointClass;
use rand::SeedableRng;
use svbsp::{BalancedOptions, SetOp, balanced_solid, boundary, merge};

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
