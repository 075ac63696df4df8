//! Moving a polygon by whole grid steps is exact: every corner moves by
//! the step and nothing else changes; corners that are not grid points or
//! would leave the grid are errors.

use crate::common::{convex_polygon, gp, plane};
use bsp_core::{ConvexPolygon, Error, GRID_LIMIT, Split};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn a_translation_moves_every_corner_and_comes_back(
        polygon in convex_polygon(40_000),
        d in prop::array::uniform3(-100_000_i64..=100_000),
    ) {
        let moved = polygon.translated(d).unwrap();
        moved.check_invariants().map_err(TestCaseError::fail)?;
        prop_assert_eq!(moved.len(), polygon.len());
        prop_assert_eq!(moved.source(), polygon.source());
        for i in 0..polygon.len() {
            let (a, b) = (
                polygon.vertex_grid_point(i).unwrap().to_i64(),
                moved.vertex_grid_point(i).unwrap().to_i64(),
            );
            prop_assert_eq!(b, [a[0] + d[0], a[1] + d[1], a[2] + d[2]]);
        }
        prop_assert_eq!(moved.support().normal(), polygon.support().normal());
        let (x, y) = (polygon.area(), moved.area());
        prop_assert!((x - y).abs() <= 1e-12 * x, "{x} vs {y}");
        let back = moved.translated(d.map(|c| -c)).unwrap();
        prop_assert_eq!(back, polygon);
    }

    #[test]
    fn a_cut_part_does_not_translate(polygon in convex_polygon(40_000), cut in plane(12_000)) {
        if let Split::Both(back, front) = polygon.split(&cut) {
            for part in [back, front] {
                let exact = part.grid_corners().is_some();
                match part.translated([1, 2, 3]) {
                    Ok(moved) => prop_assert!(exact, "{moved:?}"),
                    Err(e) => {
                        prop_assert!(!exact);
                        prop_assert_eq!(e, Error::ImplicitVertex);
                    }
                }
            }
        }
    }
}

#[test]
fn a_translation_past_the_grid_limit_is_an_error() {
    let limit = i64::from(GRID_LIMIT);
    let triangle =
        ConvexPolygon::from_grid_points(&[gp(0, 0, 0), gp(10, 0, 0), gp(0, 10, 0)], 3).unwrap();
    let edge = triangle.translated([limit - 10, 0, 0]).unwrap();
    assert_eq!(edge.vertex_grid_point(1), Some(gp(limit, 0, 0)));
    assert_eq!(
        triangle.translated([limit - 9, 0, 0]),
        Err(Error::CoordinateRange { value: limit + 1 })
    );
    // A cut makes its corners implicit points (three planes meeting),
    // even where they fall on grid positions, as (3, 0, 0) and (3, 7, 0)
    // do here.
    let cut = bsp_core::Plane::through(gp(3, 0, 0), gp(3, 1, 0), gp(3, 0, 1)).unwrap();
    let Split::Both(back, front) = triangle.split(&cut) else {
        panic!("x = 3 cuts the triangle");
    };
    for part in [back, front] {
        assert_eq!(part.translated([1, 1, 1]), Err(Error::ImplicitVertex));
    }
    // No overflow on the way: a step of any size is an error, not a panic.
    assert!(matches!(
        triangle.translated([i64::MAX, i64::MIN, 0]),
        Err(Error::CoordinateRange { .. })
    ));
}
