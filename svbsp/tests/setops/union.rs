//! Union with a convex polyhedron by insertion, against merging.

use crate::common::*;
use bsp_core::BspSolid;
use rand::SeedableRng;
use svbsp::{SetOp, merge, union_with_convex};

#[test]
fn insertion_matches_merge_on_overlapping_polyhedra() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
    for case in 0..12 {
        let a = Solid::from_faces(random_star(&mut rng, [0, 0, 0], 3, 300.0, 900.0));
        // Some polyhedra inside A, some overlapping it, some around it.
        let r = [200, 500, 1100][case % 3];
        let p = random_convex(&mut rng, [100, -50, 30], r, 8);
        let p_solid = Solid::from_faces(convex_faces(&p));
        let inserted = union_with_convex(&a.tree, &p);
        inserted.check_invariants().unwrap();
        let merged = merge(&a.tree, &p_solid.tree, SetOp::Union);
        let points = random_points(&mut rng, 500, 1300);
        let n = check_pointwise(
            &inserted,
            &a.tree,
            &p_solid.tree,
            SetOp::Union,
            points.iter().copied(),
        );
        check_pointwise(
            &merged,
            &a.tree,
            &p_solid.tree,
            SetOp::Union,
            points.iter().copied(),
        );
        assert!(n > 400);
    }
}

#[test]
fn overlapping_volumes_accumulate() {
    // Penumbra-like use: many overlapping convex volumes inserted in turn.
    let mut rng = rand_pcg::Pcg64::seed_from_u64(4);
    let mut solid = BspSolid::empty();
    let mut parts: Vec<BspSolid> = Vec::new();
    for _ in 0..10 {
        let c: [i64; 3] = std::array::from_fn(|_| rand::Rng::random_range(&mut rng, -300..300));
        let p = random_convex(&mut rng, c, 250, 6);
        solid = union_with_convex(&solid, &p);
        parts.push(Solid::from_faces(convex_faces(&p)).tree);
    }
    for p in random_points(&mut rng, 2000, 600) {
        let classes: Vec<_> = parts.iter().map(|t| t.classify_point(p)).collect();
        if classes.contains(&bsp_core::PointClass::On) {
            continue;
        }
        let inside = classes.contains(&bsp_core::PointClass::In);
        let got = solid.classify_point(p);
        assert_eq!(got == bsp_core::PointClass::In, inside, "at {p:?}");
        assert_ne!(got, bsp_core::PointClass::On, "at {p:?}");
    }
}

#[test]
fn cells_inside_the_polyhedron_become_in() {
    // A solid with many small cells, all swallowed by a big cube: no face of
    // the cube reaches them, yet they must become In.
    let a = Solid::from_faces(box_faces([0, 0, 0], [4, 4, 4]));
    let b = Solid::from_faces(box_faces([10, 10, 10], [14, 14, 14]));
    let ab = merge(&a.tree, &b.tree, SetOp::Union);
    let cube = svbsp::ConvexPolyhedron::from_faces(box_faces([-20, -20, -20], [30, 30, 30]));
    let all = union_with_convex(&ab, &cube);
    for p in random_points(&mut rand_pcg::Pcg64::seed_from_u64(5), 500, 19) {
        assert_eq!(all.classify_point(p), bsp_core::PointClass::In);
    }
}

#[test]
fn unbounded_polyhedra_are_closed_by_the_box() {
    // The wedge x < 0, y < x: unbounded, so closed by the grid's box.
    let g = |x, y, z| gp(x, y, z);
    let planes = [
        bsp_core::Plane::with_normal_through([1, 0, 0], g(0, 0, 0)).unwrap(),
        bsp_core::Plane::with_normal_through([-1, 1, 0], g(0, 0, 0)).unwrap(),
    ];
    let wedge = svbsp::ConvexPolyhedron::from_planes(&planes).unwrap();
    assert_eq!(wedge.input_planes().len(), 2);
    let a = Solid::from_faces(box_faces([-5, -5, -5], [5, 5, 5]));
    let u = union_with_convex(&a.tree, &wedge);
    let far = 1 << 23;
    for (p, inside) in [
        (g(-far, -far - 7, far), true),
        (g(-3, -1, 0), true),
        (g(3, 4, 0), true),
        (g(6, 0, 0), false),
        (g(-far, 0, 0), false),
        (g(-3, -4, -far), true),
    ] {
        let want = if inside {
            bsp_core::PointClass::In
        } else {
            bsp_core::PointClass::Out
        };
        assert_eq!(u.classify_point(p), want, "at {p:?}");
    }
}

#[test]
fn a_box_cut_by_planes_is_their_region_within_the_box() {
    let g = |x, y, z| gp(x, y, z);
    assert!(svbsp::ConvexPolyhedron::axis_box(g(0, 0, 0), g(4, 0, 4)).is_none());
    let cube = svbsp::ConvexPolyhedron::axis_box(g(-4, -4, -4), g(4, 4, 4)).unwrap();
    assert_eq!(cube.volume(), 512.0);
    assert!(
        cube.input_planes().is_empty(),
        "the box's faces are sections"
    );
    // The wedge x < 0, y < x inside the cube: half of the quarter x < 0,
    // y < 0, an eighth of the cube.
    let planes = [
        bsp_core::Plane::with_normal_through([1, 0, 0], g(0, 0, 0)).unwrap(),
        bsp_core::Plane::with_normal_through([-1, 1, 0], g(0, 0, 0)).unwrap(),
    ];
    let wedge = cube.clone().cut_by(&planes).unwrap();
    assert_eq!(wedge.volume(), 64.0);
    assert_eq!(wedge.input_planes(), planes.to_vec());
    // Planes that leave nothing of the cube.
    let away = [bsp_core::Plane::with_normal_through([-1, 0, 0], g(4, 0, 0)).unwrap()];
    assert!(cube.cut_by(&away).is_none());
}
