//! Merged trees classify points like the Boolean of the operands.

use crate::common::*;
use bsp_core::{BspSolid, PointClass};
use rand::SeedableRng;
use svbsp::{SetOp, merge};

#[test]
fn random_boxes_merge_pointwise() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(1);
    for _ in 0..60 {
        let a = Solid::from_faces(random_box(&mut rng, 12));
        let b = Solid::from_faces(random_box(&mut rng, 12));
        let points = random_points(&mut rng, 300, 14);
        for op in OPS {
            let r = merge(&a.tree, &b.tree, op);
            r.check_invariants().unwrap();
            check_pointwise(&r, &a.tree, &b.tree, op, points.iter().copied());
        }
    }
}

#[test]
fn star_meshes_and_convex_polyhedra_merge_pointwise() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(2);
    for case in 0..12 {
        let a = Solid::from_faces(random_star(&mut rng, [0, 0, 0], 3, 300.0, 900.0));
        let b = if case % 2 == 0 {
            Solid::from_faces(random_star(&mut rng, [250, -120, 80], 3, 300.0, 900.0))
        } else {
            Solid::from_faces(convex_faces(&random_convex(
                &mut rng,
                [300, 100, -50],
                600,
                10,
            )))
        };
        let points = random_points(&mut rng, 400, 1200);
        for op in OPS {
            let r = merge(&a.tree, &b.tree, op);
            r.check_invariants().unwrap();
            let n = check_pointwise(&r, &a.tree, &b.tree, op, points.iter().copied());
            assert!(n > 300);
        }
    }
}

#[test]
fn coplanar_operands() {
    let a = Solid::from_faces(box_faces([0, 0, 0], [4, 4, 4]));
    // Face to face, overlapping with shared face planes, and equal.
    for b in [
        box_faces([4, 0, 0], [8, 4, 4]),
        box_faces([2, 0, 0], [6, 4, 4]),
        box_faces([0, 0, 0], [4, 4, 4]),
        box_faces([1, 1, 4], [3, 3, 6]),
    ] {
        let b = Solid::from_faces(b);
        let points: Vec<_> = (-1..10)
            .flat_map(|x| (-1..6).flat_map(move |y| (-1..8).map(move |z| gp(x, y, z))))
            .collect();
        for op in OPS {
            let r = merge(&a.tree, &b.tree, op);
            check_pointwise(&r, &a.tree, &b.tree, op, points.iter().copied());
        }
    }
    let comp = a.tree.complement();
    assert_eq!(merge(&a.tree, &comp, SetOp::Union), BspSolid::full());
    assert_eq!(
        merge(&a.tree, &comp, SetOp::Intersection),
        BspSolid::empty()
    );
    assert_eq!(
        merge(&a.tree, &a.tree, SetOp::Difference),
        BspSolid::empty()
    );
    let same = merge(&a.tree, &comp, SetOp::Difference);
    assert_eq!(same.classify_point(gp(1, 1, 1)), PointClass::In);
    assert_eq!(same.classify_point(gp(5, 1, 1)), PointClass::Out);
}

#[test]
fn deep_trees_merge_without_recursion() {
    // Two chains of 3000 nested slabs each: trees thousands of nodes deep.
    let chain = |offset: i64| {
        let mut nodes = Vec::new();
        let n = 3000_i64;
        for k in 0..n {
            let plane =
                bsp_core::Plane::with_normal_through([1, 0, 0], gp(4 * k + offset, 0, 0)).unwrap();
            let id = nodes.len() as u32;
            nodes.push(bsp_core::SolidNode {
                plane,
                front: if k + 1 == n {
                    bsp_core::SolidChild::Leaf(bsp_core::Region::Out)
                } else {
                    bsp_core::SolidChild::Node(id + 1)
                },
                back: bsp_core::SolidChild::Leaf(if k % 2 == 0 {
                    bsp_core::Region::Out
                } else {
                    bsp_core::Region::In
                }),
            });
        }
        BspSolid::from_nodes(nodes, bsp_core::SolidChild::Node(0)).unwrap()
    };
    let (a, b) = (chain(0), chain(2));
    let handle = std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(move || {
            let r = merge(&a, &b, SetOp::Union);
            let points: Vec<_> = (-2..12004).map(|x| gp(2 * x + 1, 3, -7)).collect();
            check_pointwise(&r, &a, &b, SetOp::Union, points)
        })
        .unwrap();
    assert!(handle.join().unwrap() > 1000);
}
