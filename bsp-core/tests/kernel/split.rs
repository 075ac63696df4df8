//! Splitting partitions exactly: every part valid and on its side, areas
//! adding up, degenerate planes decided.

use crate::common::{convex_polygon, gp, grid_point, plane};
use bsp_core::{Behind, ConvexPolygon, Facing, GRID_LIMIT, Plane, PolygonSide, Side, Split};
use proptest::prelude::*;

/// Checks one split against the definition of each outcome.
fn check_split(polygon: &ConvexPolygon, cut: &Plane) -> Result<(), TestCaseError> {
    let sides: Vec<Side> = (0..polygon.len())
        .map(|i| polygon.vertex_side(i, cut))
        .collect();
    let any = |s: Side| sides.contains(&s);
    let result = polygon.split(cut);
    match &result {
        Split::Both(back, front) => {
            prop_assert!(any(Side::Back) && any(Side::Front));
            for (part, forbidden) in [(back, Side::Front), (front, Side::Back)] {
                part.check_invariants().map_err(TestCaseError::fail)?;
                prop_assert_eq!(part.source(), polygon.source());
                prop_assert_eq!(part.support(), polygon.support());
                for i in 0..part.len() {
                    prop_assert_ne!(part.vertex_side(i, cut), forbidden);
                    // Parts stay inside the polygon.
                    for e in polygon.edges() {
                        prop_assert_ne!(part.vertex_side(i, e), Side::Front);
                    }
                }
                prop_assert!(part.area() > 0.0);
            }
            let (a, b, total) = (back.area(), front.area(), polygon.area());
            prop_assert!(
                ((a + b) - total).abs() <= 1e-9 * total,
                "{a} + {b} != {total}"
            );
        }
        Split::Back => prop_assert!(any(Side::Back) && !any(Side::Front)),
        Split::Front => prop_assert!(any(Side::Front) && !any(Side::Back)),
        Split::Coplanar(facing) => {
            prop_assert!(sides.iter().all(|&s| s == Side::On));
            let expected = if cut == polygon.support() {
                Facing::Same
            } else {
                Facing::Opposite
            };
            prop_assert_eq!(*facing, expected);
        }
    }
    let classified = polygon.classify(cut);
    let agrees = matches!(
        (&result, classified),
        (Split::Both(..), PolygonSide::Both)
            | (Split::Back, PolygonSide::Back)
            | (Split::Front, PolygonSide::Front)
            | (Split::Coplanar(_), PolygonSide::Coplanar(_))
    );
    prop_assert!(agrees, "classify {classified:?} disagrees with split");
    Ok(())
}

/// A plane through two of the polygon's vertices (an edge or a diagonal)
/// and a third grid point: the degenerate cases of a split.
fn plane_through_vertices(
    polygon: &ConvexPolygon,
    i: usize,
    j: usize,
    third: bsp_core::GridPoint,
) -> Option<Plane> {
    let (a, b) = (polygon.vertex_grid_point(i)?, polygon.vertex_grid_point(j)?);
    Plane::through(a, b, third)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn random_planes_partition_exactly(polygon in convex_polygon(4000), cut in plane(1200)) {
        check_split(&polygon, &cut)?;
    }

    /// `behind` keeps what `split` puts behind, and only that.
    #[test]
    fn the_part_behind_is_the_back_of_the_split(
        polygon in convex_polygon(4000),
        cut in plane(1200),
    ) {
        match (polygon.split(&cut), polygon.behind(&cut)) {
            (Split::Back, Behind::All) => {}
            (Split::Both(back, _), Behind::Part(part)) => prop_assert_eq!(back, part),
            (Split::Front | Split::Coplanar(_), Behind::Nothing) => {}
            (split, behind) => prop_assert!(false, "{:?} against {:?}", split, behind),
        }
    }

    #[test]
    fn planes_through_vertices_and_edges_are_decided(
        polygon in convex_polygon(4000),
        i in 0_usize..16,
        j in 0_usize..16,
        third in grid_point(1500),
    ) {
        let n = polygon.len();
        if let Some(cut) = plane_through_vertices(&polygon, i % n, j % n, third) {
            check_split(&polygon, &cut)?;
            check_split(&polygon, &cut.flipped())?;
        }
        check_split(&polygon, &polygon.support().clone())?;
        check_split(&polygon, &polygon.support().flipped())?;
    }

    #[test]
    fn repeated_splits_tile_the_polygon(
        polygon in convex_polygon(4000),
        cuts in prop::collection::vec(plane(1200), 1..12),
    ) {
        let mut pieces = vec![polygon.clone()];
        for cut in &cuts {
            let mut next = Vec::new();
            for piece in pieces {
                check_split(&piece, cut)?;
                match piece.split(cut) {
                    Split::Both(b, f) => { next.push(b); next.push(f); }
                    _ => next.push(piece),
                }
            }
            pieces = next;
        }
        let total: f64 = pieces.iter().map(ConvexPolygon::area).sum();
        prop_assert!((total - polygon.area()).abs() <= 1e-9 * polygon.area());
    }

    #[test]
    fn polygons_at_the_grid_limits_split_exactly(
        corners in prop::collection::vec(prop::array::uniform3(prop::bool::ANY), 3),
        cut in plane(i64::from(GRID_LIMIT)),
    ) {
        // A triangle with coordinates at ±2^24.
        let l = i64::from(GRID_LIMIT);
        let c = |b: [bool; 3]| gp(if b[0] { l } else { -l }, if b[1] { l } else { -l }, if b[2] { l } else { -l });
        if let Ok(t) = ConvexPolygon::from_grid_points(&[c(corners[0]), c(corners[1]), c(corners[2])], 0) {
            check_split(&t, &cut)?;
            if let Split::Both(b, f) = t.split(&cut) {
                for part in [b, f] {
                    for e in t.edges() {
                        check_split(&part, e)?;
                    }
                }
            }
        }
    }
}

#[test]
fn slivers_are_exact_and_never_empty() {
    // A long thin triangle cut by planes nearly along its long edge.
    let t =
        ConvexPolygon::from_grid_points(&[gp(0, 0, 0), gp(1 << 24, 1, 0), gp(0, 2, 0)], 3).unwrap();
    for k in 0..40 {
        let cut = Plane::through(gp(k, 0, 0), gp((1 << 24) - k, 2, 0), gp(k, 0, 1)).unwrap();
        check_split(&t, &cut).unwrap();
    }
}

#[test]
fn planes_along_an_edge_and_through_a_vertex_do_not_cut() {
    let square = ConvexPolygon::from_grid_points(
        &[gp(0, 0, 0), gp(10, 0, 0), gp(10, 10, 0), gp(0, 10, 0)],
        1,
    )
    .unwrap();
    // Along the edge y = 0 (normal +y): the square is in front.
    let along = Plane::through(gp(0, 0, 0), gp(10, 0, 0), gp(0, 0, -5)).unwrap();
    assert_eq!(square.split(&along), Split::Front);
    assert_eq!(square.split(&along.flipped()), Split::Back);
    // Through the corner (10, 10) only, tilted so the rest is behind.
    let corner = Plane::through(gp(10, 10, 0), gp(20, 0, 0), gp(10, 10, 1)).unwrap();
    assert!(matches!(square.split(&corner), Split::Back | Split::Front));
    // Through two opposite corners: two triangles, the diagonal shared.
    let diagonal = Plane::through(gp(0, 0, 0), gp(10, 10, 0), gp(0, 0, 1)).unwrap();
    match square.split(&diagonal) {
        Split::Both(b, f) => {
            assert_eq!((b.len(), f.len()), (3, 3));
            assert_eq!(b.area() + f.area(), 100.0);
        }
        other => panic!("expected two triangles, got {other:?}"),
    }
    assert_eq!(
        square.split(square.support()),
        Split::Coplanar(Facing::Same)
    );
    assert_eq!(
        square.split(&square.support().flipped()),
        Split::Coplanar(Facing::Opposite)
    );
}

#[test]
fn invalid_input_polygons_are_errors() {
    use bsp_core::Error;
    let e = |pts: &[bsp_core::GridPoint]| ConvexPolygon::from_grid_points(pts, 0).unwrap_err();
    assert_eq!(e(&[gp(0, 0, 0), gp(1, 1, 1)]), Error::TooFewVertices);
    assert_eq!(
        e(&[gp(0, 0, 0), gp(1, 1, 1), gp(2, 2, 2)]),
        Error::TooFewVertices
    );
    assert_eq!(
        e(&[gp(0, 0, 0), gp(4, 0, 0), gp(4, 4, 1), gp(0, 4, 0)]),
        Error::NonPlanar
    );
    // A reflex vertex.
    assert_eq!(
        e(&[
            gp(0, 0, 0),
            gp(4, 0, 0),
            gp(2, 1, 0),
            gp(4, 4, 0),
            gp(0, 4, 0)
        ]),
        Error::NonConvex
    );
    // A pentagram turns left at every vertex but winds twice.
    let star = [
        gp(0, 10, 0),
        gp(-6, -8, 0),
        gp(10, 3, 0),
        gp(-10, 3, 0),
        gp(6, -8, 0),
    ];
    assert_eq!(e(&star), Error::NonConvex);
    // Repeated and collinear vertices are dropped, not errors.
    let p = ConvexPolygon::from_grid_points(
        &[
            gp(0, 0, 0),
            gp(0, 0, 0),
            gp(2, 0, 0),
            gp(4, 0, 0),
            gp(4, 4, 0),
            gp(0, 4, 0),
            gp(0, 0, 0),
        ],
        0,
    )
    .unwrap();
    assert_eq!(p.len(), 4);
    p.check_invariants().unwrap();
    // Clockwise input is a polygon facing the other way.
    let cw =
        ConvexPolygon::from_grid_points(&[gp(0, 0, 0), gp(0, 4, 0), gp(4, 4, 0), gp(4, 0, 0)], 0)
            .unwrap();
    assert_eq!(cw.support().normal(), [0, 0, -1]);
    assert_eq!(cw.flipped().support(), p.support());
    cw.flipped().check_invariants().unwrap();
}

#[test]
fn from_planes_round_trips_a_split_part() {
    let square =
        ConvexPolygon::from_grid_points(&[gp(0, 0, 0), gp(9, 0, 0), gp(9, 9, 0), gp(0, 9, 0)], 2)
            .unwrap();
    let cut = Plane::through(gp(3, 0, 0), gp(5, 9, 0), gp(3, 0, 1)).unwrap();
    let Split::Both(back, _) = square.split(&cut) else {
        panic!("expected a cut")
    };
    let rebuilt = ConvexPolygon::from_planes(
        *back.support(),
        &back.edges().copied().collect::<Vec<_>>(),
        2,
    )
    .unwrap();
    rebuilt.check_invariants().unwrap();
    assert!((rebuilt.area() - back.area()).abs() < 1e-9);
    // Edge planes that do not bound a convex polygon are rejected.
    let mut edges = back.edges().copied().collect::<Vec<_>>();
    edges.swap(0, 1);
    assert!(ConvexPolygon::from_planes(*back.support(), &edges, 2).is_err());
}
