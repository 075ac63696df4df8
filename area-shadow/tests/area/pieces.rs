//! Partition and merging keep fragments few: cuts that change nothing are
//! undone, same-class neighbours are joined, and the area never changes.

use crate::oracle::gp;
use area_shadow::{Class, VolumeTree, merge_same_class};
use bsp_core::{ConvexPolygon, Plane};
use svbsp::ConvexPolyhedron;

fn rect(x0: i64, z0: i64, x1: i64, z1: i64, y: i64) -> ConvexPolygon {
    ConvexPolygon::from_grid_points(
        &[gp(x0, y, z1), gp(x1, y, z1), gp(x1, y, z0), gp(x0, y, z0)],
        0,
    )
    .unwrap()
}

fn area(pieces: &[ConvexPolygon]) -> f64 {
    pieces.iter().map(ConvexPolygon::area).sum()
}

/// A skeleton of 16 cells over `[-40, 40]^3` (cut at 0 along each axis,
/// then at +-20 along x) and one volume inside one cell, the box
/// `[22, 38] x [1, 5] x [22, 38]` from its six planes.
fn tree_with_box() -> VolumeTree {
    let mut tree = VolumeTree::with_cells([-40; 3], [40; 3], 16);
    let planes = [
        ([1, 0, 0], gp(38, 0, 0)),
        ([-1, 0, 0], gp(22, 0, 0)),
        ([0, 1, 0], gp(0, 5, 0)),
        ([0, -1, 0], gp(0, 1, 0)),
        ([0, 0, 1], gp(0, 0, 38)),
        ([0, 0, -1], gp(0, 0, 22)),
    ]
    .map(|(normal, through)| Plane::with_normal_through(normal, through).unwrap());
    tree.insert(ConvexPolyhedron::from_planes(&planes).unwrap());
    tree
}

#[test]
fn a_polygon_the_skeleton_cuts_but_no_volume_meets_comes_back_whole() {
    let tree = tree_with_box();
    // Crosses the skeleton's planes x = 0, z = 0 and x = 20, and the box's
    // z = 22 and z = 38 planes, but lies at x < 22, outside the box.
    let polygon = rect(-30, -30, 21, 39, 2);
    let split = tree.partition(polygon.clone());
    assert!(split.inside.is_empty());
    assert_eq!(split.outside.len(), 1);
    assert_eq!(split.outside[0].area(), polygon.area());
}

#[test]
fn a_polygon_through_the_box_is_cut_only_around_it() {
    let tree = tree_with_box();
    let polygon = rect(-30, -30, 39, 39, 2);
    let split = tree.partition(polygon.clone());
    assert!((area(&split.inside) - 16.0 * 16.0).abs() < 1e-9);
    assert!((area(&split.inside) + area(&split.outside) - polygon.area()).abs() < 1e-9);
    // The box lies in one skeleton cell: its inside is one piece, and no
    // cut is kept where both sides are outside.
    assert_eq!(split.inside.len(), 1);
    let skeleton_alone = VolumeTree::with_cells([-40; 3], [40; 3], 16);
    assert_eq!(skeleton_alone.partition(polygon).outside.len(), 1);
}

/// A `4 x 4` grid of unit squares, classed by `class(i, j)`.
fn grid(class: impl Fn(i64, i64) -> Class) -> Vec<(ConvexPolygon, Class)> {
    (0..4)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| (rect(i, j, i + 1, j + 1, 0), class(i, j)))
        .collect()
}

#[test]
fn same_class_neighbours_merge_without_losing_area() {
    let merged = merge_same_class(grid(|_, _| Class::Lit));
    let polygons: Vec<_> = merged.iter().map(|(p, _)| p.clone()).collect();
    assert!((area(&polygons) - 16.0).abs() < 1e-12);
    assert!(merged.len() <= 4, "{} pieces", merged.len());
    assert!(merged.iter().all(|(_, c)| *c == Class::Lit));
}

#[test]
fn different_classes_never_merge() {
    let checker = |i: i64, j: i64| {
        if (i + j) % 2 == 0 {
            Class::Lit
        } else {
            Class::Umbra
        }
    };
    let merged = merge_same_class(grid(checker));
    assert_eq!(merged.len(), 16);
    // Two stripes of classes: each stripe merges on its own.
    let stripes = merge_same_class(grid(
        |i, _| if i < 2 { Class::Penumbra } else { Class::Lit },
    ));
    for class in [Class::Penumbra, Class::Lit] {
        let polygons: Vec<_> = stripes
            .iter()
            .filter(|(_, c)| *c == class)
            .map(|(p, _)| p.clone())
            .collect();
        assert!((area(&polygons) - 8.0).abs() < 1e-12);
        assert!(
            polygons.len() <= 2,
            "{} pieces of {class:?}",
            polygons.len()
        );
    }
}
