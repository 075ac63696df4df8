//! The scene BSP: its polygons tile the input, its order is a visibility
//! order (checked with exact segment tests), and builds are deterministic.

use crate::common::{RationalPoint, convex_polygon, gp, grid_point, sight_line_crosses};
use bsp_core::predicates::side_of_point;
use bsp_core::{
    BuildOptions, ConvexPolygon, GridPoint, Location, SceneBsp, SceneChild, Side, Viewpoint,
};
use proptest::prelude::*;

/// Exact interior sample points of a polygon: near the centroid, and near
/// each vertex moved a tenth of the way to it.
fn samples(polygon: &ConvexPolygon) -> Vec<RationalPoint> {
    let c = polygon.centroid();
    std::iter::once(c)
        .chain(
            polygon
                .vertices_f64()
                .into_iter()
                .map(|v| std::array::from_fn(|k| 0.9 * v[k] + 0.1 * c[k])),
        )
        .filter_map(|q| RationalPoint::in_polygon(polygon, q))
        .collect()
}

/// Fails unless no polygon of `order` hides a point of one before it from
/// `view`. Exact: a sight line that grazes an edge, or runs in a polygon's
/// plane (a viewer in that plane), is no occlusion.
fn check_visibility_order(order: &[&ConvexPolygon], view: Viewpoint) -> Result<(), TestCaseError> {
    for (i, near) in order.iter().enumerate() {
        for s in samples(near) {
            for (j, far) in order.iter().enumerate().skip(i + 1) {
                prop_assert!(
                    !sight_line_crosses(view, &s, far),
                    "polygon {j} (later) hides polygon {i} from the eye"
                );
            }
        }
    }
    Ok(())
}

fn soup() -> impl Strategy<Value = Vec<ConvexPolygon>> {
    prop::collection::vec(convex_polygon(2000), 1..28).prop_map(|v| {
        v.into_iter()
            .enumerate()
            .map(|(i, p)| p.with_source(i as u32))
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn front_to_back_is_a_visibility_order(polygons in soup(), eye in grid_point(1500)) {
        let bsp = SceneBsp::build(polygons, &BuildOptions::default());
        let order: Vec<&ConvexPolygon> = bsp.front_to_back(Viewpoint::Point(eye)).map(|(_, p)| p).collect();
        prop_assert_eq!(order.len(), bsp.polygons().len());
        check_visibility_order(&order, Viewpoint::Point(eye))?;
        let mut reversed: Vec<&ConvexPolygon> = bsp.back_to_front(Viewpoint::Point(eye)).map(|(_, p)| p).collect();
        reversed.reverse();
        // Back-to-front is a visibility order read backwards.
        check_visibility_order(&reversed, Viewpoint::Point(eye))?;
    }

    #[test]
    fn direction_order_is_a_parallel_visibility_order(polygons in soup(), dir in prop::array::uniform3(-20_i32..=20)) {
        prop_assume!(dir != [0, 0, 0]);
        let bsp = SceneBsp::build(polygons, &BuildOptions::default());
        let order: Vec<&ConvexPolygon> = bsp.front_to_back(Viewpoint::Direction(dir)).map(|(_, p)| p).collect();
        check_visibility_order(&order, Viewpoint::Direction(dir))?;
    }

    #[test]
    fn fragments_tile_the_input(polygons in soup()) {
        let areas: Vec<f64> = polygons.iter().map(ConvexPolygon::area).collect();
        let bsp = SceneBsp::build(polygons.clone(), &BuildOptions::default());
        let mut by_source = vec![0.0; polygons.len()];
        for p in bsp.polygons() {
            p.check_invariants().map_err(TestCaseError::fail)?;
            by_source[p.source() as usize] += p.area();
        }
        for (got, want) in by_source.iter().zip(&areas) {
            prop_assert!((got - want).abs() <= 1e-9 * want);
        }
        // Each node's polygons lie in its plane.
        for (i, node) in bsp.nodes().iter().enumerate() {
            for p in bsp.node_polygons(i as u32) {
                prop_assert!(p.support().is_coincident(&node.plane));
            }
        }
        // Deterministic: the same input builds the same tree.
        let again = SceneBsp::build(polygons, &BuildOptions::default());
        prop_assert_eq!(again.polygons(), bsp.polygons());
    }

    #[test]
    fn point_location_is_consistent_with_the_planes(polygons in soup(), p in grid_point(2500)) {
        let bsp = SceneBsp::build(polygons, &BuildOptions::default());
        // Walk down by hand with the exact predicate and compare.
        let mut child = bsp.root();
        let expected = loop {
            match child {
                SceneChild::Leaf(l) => break Location::Leaf(l),
                SceneChild::Node(i) => {
                    let node = &bsp.nodes()[i as usize];
                    match bsp_core::predicates::side_of_point(&node.plane, p) {
                        Side::Front => child = node.front,
                        Side::Back => child = node.back,
                        Side::On => break Location::OnPlane(i),
                    }
                }
            }
        };
        prop_assert_eq!(bsp.locate(p), expected);
        prop_assert_eq!(bsp.leaf_count() as usize, bsp.nodes().len() + 1);
    }
}

#[test]
fn an_empty_scene_is_one_leaf() {
    let bsp = SceneBsp::build(Vec::new(), &BuildOptions::default());
    assert_eq!(bsp.root(), SceneChild::Leaf(0));
    assert_eq!(
        bsp.front_to_back(Viewpoint::Point(GridPoint::default()))
            .count(),
        0
    );
    assert_eq!(bsp.locate(GridPoint::default()), Location::Leaf(0));
}

#[test]
fn a_long_chain_builds_and_traverses_without_recursion() {
    // 3 000 parallel squares stacked along z, with every candidate scored
    // alike: a tree as deep as the input. Built and walked on a thread with
    // a 256 KiB stack, far too small for recursion of that depth.
    let run = || {
        let options = BuildOptions {
            candidates: 1,
            sample: 1,
            split_weight: 1,
            axis_planes: false,
        };
        let squares: Vec<ConvexPolygon> = (0..3_000)
            .map(|z| {
                let g = |x: i32, y: i32| GridPoint { x, y, z };
                ConvexPolygon::from_grid_points(&[g(0, 0), g(4, 0), g(4, 4), g(0, 4)], z as u32)
                    .unwrap()
            })
            .collect();
        let bsp = SceneBsp::build(squares, &options);
        assert_eq!(bsp.polygons().len(), 3_000);
        assert_eq!(bsp.depth(), 3_000);
        let eye = GridPoint { x: 1, y: 1, z: -5 };
        let order: Vec<u32> = bsp
            .front_to_back(Viewpoint::Point(eye))
            .map(|(_, p)| p.source())
            .collect();
        assert_eq!(order, (0..3_000).collect::<Vec<u32>>());
        let far_side = GridPoint {
            x: 1,
            y: 1,
            z: 5_000,
        };
        let order: Vec<u32> = bsp
            .front_to_back(Viewpoint::Point(far_side))
            .map(|(_, p)| p.source())
            .collect();
        assert_eq!(order, (0..3_000).rev().collect::<Vec<u32>>());
    };
    std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(run)
        .unwrap()
        .join()
        .unwrap();
}

#[test]
fn a_polygon_the_eye_stands_on_hides_nothing() {
    // Found by `front_to_back_is_a_visibility_order`. The eye lies inside
    // polygon 4 (in its plane, behind its three edges), which a node's plane
    // cuts: from the eye, sight lines leave that polygon's plane at once, so
    // it hides nothing, wherever it comes in the order.
    let eye = gp(624, -579, -63);
    let polygons: Vec<ConvexPolygon> = [
        &[[31, -45, -137], [-339, 28, -653], [-199, 0, -457]][..],
        &[
            [-24, -16, -36],
            [-494, 487, -1137],
            [-1023, 524, -632],
            [-889, 420, -448],
            [-492, 155, -45],
        ],
        &[
            [105, -322, -237],
            [121, -457, -201],
            [177, -429, -361],
            [269, -297, -673],
            [303, 285, -1093],
            [245, 154, -869],
        ],
        &[
            [-312, -94, 17],
            [-530, -488, -459],
            [-544, -382, -785],
            [-170, 356, -108],
        ],
        &[[109, -259, 52], [95, 253, -574], [827, -875, 104]],
        &[
            [-80, 180, -34],
            [-505, -44, 332],
            [-388, -116, 506],
            [-3, -34, 423],
            [40, 30, 301],
        ],
    ]
    .iter()
    .enumerate()
    .map(|(i, pts)| {
        let pts: Vec<GridPoint> = pts.iter().map(|&[x, y, z]| gp(x, y, z)).collect();
        ConvexPolygon::from_grid_points(&pts, i as u32).unwrap()
    })
    .collect();
    let under = &polygons[4];
    assert_eq!(side_of_point(under.support(), eye), Side::On);
    assert!(under.edges().all(|e| side_of_point(e, eye) == Side::Back));
    let bsp = SceneBsp::build(polygons, &BuildOptions::default());
    let order: Vec<&ConvexPolygon> = bsp
        .front_to_back(Viewpoint::Point(eye))
        .map(|(_, p)| p)
        .collect();
    check_visibility_order(&order, Viewpoint::Point(eye)).unwrap();
}

#[test]
fn the_oracle_sees_a_polygon_hidden_by_a_later_one() {
    // Two stacked squares seen from below and from far below: the upper
    // one first is a wrong order, and the exact oracle must say so.
    let square = |z: i64| {
        let pts = [gp(0, 0, z), gp(4, 0, z), gp(4, 4, z), gp(0, 4, z)];
        ConvexPolygon::from_grid_points(&pts, z as u32).unwrap()
    };
    let (low, high) = (square(0), square(2));
    for view in [
        Viewpoint::Point(gp(1, 1, -5)),
        Viewpoint::Direction([1, 0, -20]),
    ] {
        assert!(check_visibility_order(&[&low, &high], view).is_ok());
        assert!(check_visibility_order(&[&high, &low], view).is_err());
    }
}
