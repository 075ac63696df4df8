//! The scene BSP: its polygons tile the input, its order is a visibility
//! order (checked with exact segment tests), and builds are deterministic.

use crate::common::{convex_polygon, grid_point, segment_crosses_polygon};
use bsp_core::{
    BuildOptions, ConvexPolygon, GridPoint, Location, SceneBsp, SceneChild, Side, Viewpoint,
};
use proptest::prelude::*;

/// Interior sample points of a polygon: the centroid, and each vertex moved
/// a tenth of the way to it.
fn samples(polygon: &ConvexPolygon) -> Vec<[f64; 3]> {
    let c = polygon.centroid();
    let mut out = vec![c];
    for v in polygon.vertices_f64() {
        out.push([
            0.9 * v[0] + 0.1 * c[0],
            0.9 * v[1] + 0.1 * c[1],
            0.9 * v[2] + 0.1 * c[2],
        ]);
    }
    out
}

/// Where the viewer is, for the oracle.
#[derive(Clone, Copy)]
enum Eye {
    At([f64; 3]),
    /// Infinitely far in this direction: sight lines are parallel.
    Toward([f64; 3]),
}

/// Fails unless no polygon of `order` hides a point of one before it from
/// `eye`.
fn check_visibility_order(order: &[&ConvexPolygon], eye: Eye) -> Result<(), TestCaseError> {
    // Later polygons shrink by a relative 1e-9 toward their centroids: sample
    // points are rounded to f64, and a sight line that only grazes a
    // polygon's edge within rounding (viewer parallel to a plane, say) is no
    // occlusion.
    let outlines: Vec<Vec<[f64; 3]>> = order
        .iter()
        .map(|p| {
            let c = p.centroid();
            let shrink = |v: [f64; 3]| std::array::from_fn(|k| c[k] + (v[k] - c[k]) * (1.0 - 1e-9));
            p.vertices_f64().into_iter().map(shrink).collect()
        })
        .collect();
    for (i, near) in order.iter().enumerate() {
        for s in samples(near) {
            let viewer = match eye {
                Eye::At(p) => p,
                // Far beyond the scene (coordinates below 1e4) along the
                // parallel sight line through `s`.
                Eye::Toward(d) => [s[0] + d[0] * 1e7, s[1] + d[1] * 1e7, s[2] + d[2] * 1e7],
            };
            for (j, far) in outlines.iter().enumerate().skip(i + 1) {
                prop_assert!(
                    !segment_crosses_polygon(viewer, s, far),
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
        check_visibility_order(&order, Eye::At(eye.to_f64()))?;
        let mut reversed: Vec<&ConvexPolygon> = bsp.back_to_front(Viewpoint::Point(eye)).map(|(_, p)| p).collect();
        reversed.reverse();
        // Back-to-front is a visibility order read backwards.
        check_visibility_order(&reversed, Eye::At(eye.to_f64()))?;
    }

    #[test]
    fn direction_order_is_a_parallel_visibility_order(polygons in soup(), dir in prop::array::uniform3(-20_i32..=20)) {
        prop_assume!(dir != [0, 0, 0]);
        let bsp = SceneBsp::build(polygons, &BuildOptions::default());
        let order: Vec<&ConvexPolygon> = bsp.front_to_back(Viewpoint::Direction(dir)).map(|(_, p)| p).collect();
        check_visibility_order(&order, Eye::Toward(dir.map(f64::from)))?;
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
