//! `ConvexPolygon::crosses_inside` against its definition: clip by the
//! bounds, then classify the part.

use crate::common::{convex_polygon, grid_point, plane};
use bsp_core::{ConvexPolygon, GridPoint, Plane, PolygonSide, Split};
use proptest::prelude::*;

/// The definition: the part behind every bound (none if a bound leaves
/// nothing of area) has points strictly on both sides of `cut`.
fn by_clipping(polygon: &ConvexPolygon, cut: &Plane, bounds: &[Plane]) -> bool {
    let mut part = polygon.clone();
    for bound in bounds {
        part = match part.split(bound) {
            Split::Back => part,
            Split::Both(back, _) => back,
            Split::Front | Split::Coplanar(_) => return false,
        };
    }
    part.classify(cut) == PolygonSide::Both
}

/// A polygon with implicit vertices too: the back part of a cut, when the
/// cut crosses it.
fn cut_polygon(scale: i64) -> impl Strategy<Value = ConvexPolygon> {
    (convex_polygon(scale), plane(scale / 3)).prop_map(|(polygon, cut)| match polygon.split(&cut) {
        Split::Both(back, _) => back,
        _ => polygon,
    })
}

/// Grid vertices of a polygon, for planes through them (degenerate cases).
fn grid_vertices(polygon: &ConvexPolygon) -> Vec<GridPoint> {
    (0..polygon.len())
        .filter_map(|i| polygon.vertex_grid_point(i))
        .collect()
}

/// A plane: random, or through two of the polygon's grid vertices (when
/// it has them) and a random point.
fn plane_near(
    polygon: &ConvexPolygon,
    pick: (u8, usize, usize),
    extra: GridPoint,
    random: Plane,
) -> Plane {
    let grid = grid_vertices(polygon);
    if pick.0.is_multiple_of(3) && grid.len() >= 2 {
        let (a, b) = (grid[pick.1 % grid.len()], grid[pick.2 % grid.len()]);
        if let Some(p) = Plane::through(a, b, extra) {
            return p;
        }
    }
    random
}

fn check(polygon: &ConvexPolygon, cut: &Plane, bounds: &[Plane]) -> Result<(), TestCaseError> {
    prop_assert_eq!(
        polygon.crosses_inside(cut, bounds),
        by_clipping(polygon, cut, bounds),
        "cut {:?}, bounds {:?}",
        cut,
        bounds
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(600))]

    #[test]
    fn crossing_inside_bounds_agrees_with_clipping(
        polygon in cut_polygon(4000),
        cut in plane(1200),
        bounds in prop::collection::vec(plane(1200), 0..4),
    ) {
        check(&polygon, &cut, &bounds)?;
    }

    #[test]
    fn crossing_through_vertices_agrees_with_clipping(
        polygon in cut_polygon(240),
        picks in prop::collection::vec((any::<u8>(), any::<usize>(), any::<usize>(), grid_point(80), plane(80)), 1..5),
    ) {
        let planes: Vec<Plane> = picks
            .iter()
            .map(|&(pick, a, b, extra, random)| plane_near(&polygon, (pick, a, b), extra, random))
            .collect();
        check(&polygon, &planes[0], &planes[1..])?;
    }
}

#[test]
fn a_cut_outside_the_bounds_does_not_cross() {
    let square = ConvexPolygon::from_grid_points(
        &[
            crate::common::gp(0, 0, 0),
            crate::common::gp(10, 0, 0),
            crate::common::gp(10, 10, 0),
            crate::common::gp(0, 10, 0),
        ],
        0,
    )
    .expect("a square");
    let gp = crate::common::gp;
    // x = 5 cuts the square; y <= 4 (behind) keeps its lower band, where
    // x = 5 still crosses; y >= 6 and y <= 4 together keep nothing.
    let cut = Plane::through(gp(5, 0, 0), gp(5, 1, 0), gp(5, 0, 1)).expect("x = 5");
    let below = Plane::through(gp(0, 4, 0), gp(0, 4, 1), gp(1, 4, 0)).expect("y = 4");
    let below = if below.normal()[1] > 0 {
        below
    } else {
        below.flipped()
    };
    assert!(square.crosses_inside(&cut, &[below]));
    assert!(!square.crosses_inside(&cut, &[below, below.flipped()]));
    // A plane parallel to the cut, right of it: the band x < 3 misses x = 5.
    let left = Plane::through(gp(3, 0, 0), gp(3, 1, 0), gp(3, 0, 1)).expect("x = 3");
    let left = if left.normal()[0] > 0 {
        left
    } else {
        left.flipped()
    };
    assert!(!square.crosses_inside(&cut, &[left]));
    assert!(square.crosses_inside(&cut, &[left.flipped()]));
}

/// Follows `polygon` down the cuts `splits` (to the back part where the
/// bool says, else the front), its chord of `cut` within `bounds` divided
/// at each: each part's chord exists exactly where the part, clipped by
/// the bounds, has points strictly on both sides of `cut`.
fn check_kept_chord(
    polygon: &ConvexPolygon,
    cut: &Plane,
    bounds: &[Plane],
    splits: &[(Plane, bool)],
) -> Result<(), TestCaseError> {
    let mut part = polygon.clone();
    let mut chord = polygon.chord_inside(cut, bounds);
    prop_assert_eq!(chord.is_some(), by_clipping(&part, cut, bounds));
    for (line, to_back) in splits {
        let (back, front) = match part.split(line) {
            Split::Both(back, front) => (back, front),
            // Wholly on one side: the part and its chord stay as they are.
            _ => continue,
        };
        let (chord_back, chord_front) = match &chord {
            Some(chord) => chord.split(part.support(), line),
            None => (None, None),
        };
        prop_assert_eq!(
            chord_back.is_some(),
            by_clipping(&back, cut, bounds),
            "back of {:?}",
            line
        );
        prop_assert_eq!(
            chord_front.is_some(),
            by_clipping(&front, cut, bounds),
            "front of {:?}",
            line
        );
        (part, chord) = if *to_back {
            (back, chord_back)
        } else {
            (front, chord_front)
        };
    }
    Ok(())
}

proptest! {
    // (Most random chords miss the polygon or its bounds: many cases.)
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn a_kept_chord_crosses_the_parts_it_is_split_into(
        polygon in cut_polygon(4000),
        cut in plane(1200),
        bounds in prop::collection::vec(plane(1200), 0..3),
        splits in prop::collection::vec((plane(1200), any::<bool>()), 1..6),
    ) {
        check_kept_chord(&polygon, &cut, &bounds, &splits)?;
    }

    #[test]
    fn a_kept_chord_split_through_vertices_agrees_with_clipping(
        polygon in cut_polygon(240),
        picks in prop::collection::vec((any::<u8>(), any::<usize>(), any::<usize>(), grid_point(80), plane(80), any::<bool>()), 2..7),
    ) {
        let planes: Vec<(Plane, bool)> = picks
            .iter()
            .map(|&(pick, a, b, extra, random, to_back)| {
                (plane_near(&polygon, (pick, a, b), extra, random), to_back)
            })
            .collect();
        // The chord's plane, one bound, then the cuts (through the
        // polygon's vertices, or through the chord's ends' lines, often).
        let (cut, bound) = (planes[0].0, planes[1].0);
        check_kept_chord(&polygon, &cut, &[bound], &planes[2..])?;
    }
}
