//! Flat unions that are no convex polygon (an L, a T, a U, a Z of
//! rectangles, and a ring of them): their umbra parts against an exact
//! oracle, where the light seen through a point onto the union's plane
//! lies in the union.

use crate::oracle::gp;
use area_shadow::{AreaSource, flat_unions};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint};
use proptest::prelude::*;

/// Cells `(column, row)` of a 3 x 3 layout: an L, a T, a U, a Z and a
/// ring (a frame round a hole).
const SHAPES: [&[(usize, usize)]; 5] = [
    &[(0, 0), (1, 0), (0, 1)],
    &[(0, 0), (1, 0), (2, 0), (1, 1)],
    &[(0, 0), (1, 0), (2, 0), (0, 1), (2, 1)],
    &[(0, 0), (1, 0), (1, 1), (2, 1)],
    &[
        (0, 0),
        (1, 0),
        (2, 0),
        (0, 1),
        (2, 1),
        (0, 2),
        (1, 2),
        (2, 2),
    ],
];

/// A layout at height `h`: column bounds along x, row bounds along z.
#[derive(Debug, Clone)]
struct Layout {
    xs: [i64; 4],
    zs: [i64; 4],
    h: i64,
}

impl Layout {
    fn cell(&self, (i, j): (usize, usize)) -> [i64; 4] {
        [self.xs[i], self.xs[i + 1], self.zs[j], self.zs[j + 1]]
    }

    /// A cell as a rectangle, counter-clockwise seen from above (`up`) or
    /// from below.
    fn piece(&self, cell: (usize, usize), up: bool) -> ConvexPolygon {
        let [x0, x1, z0, z1] = self.cell(cell);
        let h = self.h;
        let mut corners = vec![gp(x0, h, z0), gp(x0, h, z1), gp(x1, h, z1), gp(x1, h, z0)];
        if !up {
            corners.reverse();
        }
        ConvexPolygon::from_grid_points(&corners, 0).unwrap()
    }
}

fn layout() -> impl Strategy<Value = Layout> {
    (
        -60_i64..0,
        prop::array::uniform3(8_i64..50),
        -60_i64..0,
        prop::array::uniform3(8_i64..50),
        60_i64..150,
    )
        .prop_map(|(x, w, z, d, h)| Layout {
            xs: [x, x + w[0], x + w[0] + w[1], x + w[0] + w[1] + w[2]],
            zs: [z, z + d[0], z + d[0] + d[1], z + d[0] + d[1] + d[2]],
            h,
        })
}

/// A rectangle light at height `y`, facing down.
fn light(x0: i64, z0: i64, w: i64, d: i64, y: i64) -> AreaSource {
    let corners = [
        gp(x0, y, z0),
        gp(x0 + w, y, z0),
        gp(x0 + w, y, z0 + d),
        gp(x0, y, z0 + d),
    ];
    AreaSource::new(ConvexPolygon::from_grid_points(&corners, 0).unwrap()).unwrap()
}

/// Whether the light `[lx0, lx1] x [lz0, lz1]` at height `y`, seen from
/// grid point `p` below the layout, lies wholly in the cells: exactly, in
/// coordinates scaled by `y - p.y` (the light's image through `p` on the
/// layout's plane is a rectangle, and the cells do not overlap, so it lies
/// in them when their overlaps with it add up to its area).
fn sees_none(
    p: GridPoint,
    light: [i64; 4],
    y: i64,
    layout: &Layout,
    cells: &[(usize, usize)],
) -> bool {
    let (px, py, pz) = (i128::from(p.x), i128::from(p.y), i128::from(p.z));
    let (y, h) = (i128::from(y), i128::from(layout.h));
    let image = |c: i64, pc: i128| pc * (y - h) + i128::from(c) * (h - py);
    let [lx0, lx1, lz0, lz1] = light;
    let q = [
        image(lx0, px),
        image(lx1, px),
        image(lz0, pz),
        image(lz1, pz),
    ];
    let overlap = |a0: i128, a1: i128, b0: i128, b1: i128| (a1.min(b1) - a0.max(b0)).max(0);
    let covered: i128 = cells
        .iter()
        .map(|&c| {
            let [x0, x1, z0, z1] = layout.cell(c).map(|v| i128::from(v) * (y - py));
            overlap(q[0], q[1], x0, x1) * overlap(q[2], q[3], z0, z1)
        })
        .sum();
    covered == (q[1] - q[0]) * (q[3] - q[2])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Strictly inside an umbra part the light seen through the point
    /// lies in the union; strictly outside every part it does not.
    #[test]
    fn a_flat_unions_umbra_is_where_it_holds_the_whole_light(
        shape in 0_usize..5,
        layout in layout(),
        up in any::<bool>(),
        light_at in (-60_i64..60, -60_i64..60, 2_i64..24, 2_i64..24, 170_i64..260),
        points in prop::collection::vec(prop::array::uniform3(-150_i64..150), 300),
    ) {
        let cells = SHAPES[shape];
        let pieces: Vec<ConvexPolygon> = cells.iter().map(|&c| layout.piece(c, up)).collect();
        let unions = flat_unions(&pieces, &vec![Some(0); pieces.len()]);
        prop_assert_eq!(unions.len(), 1);
        prop_assert_eq!(&unions[0].pieces, &(0..pieces.len() as u32).collect::<Vec<_>>());
        let (x0, z0, w, d, y) = light_at;
        let source = light(x0, z0, w, d, y);
        let parts = unions[0].umbra_parts(&source);
        let (mut inside, mut outside) = (0, 0);
        for c in points {
            // Below the layout's plane.
            let p = gp(c[0], c[1].rem_euclid(layout.h + 100) - 100, c[2]);
            let sides: Vec<Vec<Side>> = parts
                .iter()
                .map(|part| part.iter().map(|q| side_of_point(q, p)).collect())
                .collect();
            if sides.iter().flatten().any(|s| *s == Side::On) {
                continue;
            }
            let dark = sees_none(p, [x0, x0 + w, z0, z0 + d], y, &layout, cells);
            if sides.iter().any(|s| s.iter().all(|s| *s == Side::Back)) {
                prop_assert!(dark, "{p:?} in an umbra part sees light");
                inside += 1;
            } else {
                prop_assert!(!dark, "{p:?} outside every part sees none of the light");
                outside += 1;
            }
        }
        prop_assert!(outside > 0, "{inside} in, {outside} out");
    }
}

#[test]
fn flat_unions_are_simple_polygons_that_are_not_convex() {
    let layout = Layout {
        xs: [0, 10, 20, 30],
        zs: [0, 10, 20, 30],
        h: 50,
    };
    let pieces = |cells: &[(usize, usize)]| -> Vec<ConvexPolygon> {
        cells.iter().map(|&c| layout.piece(c, true)).collect()
    };
    let all = |n: usize| vec![Some(0); n];
    // An L is one; in two objects, or with one piece casting nothing, not.
    let l = pieces(SHAPES[0]);
    assert_eq!(flat_unions(&l, &all(3)).len(), 1);
    assert!(flat_unions(&l, &[Some(0), Some(1), Some(0)]).is_empty());
    assert!(flat_unions(&l, &[Some(0), Some(0), None]).is_empty());
    // A row of rectangles is a convex polygon (a convex group's).
    assert!(flat_unions(&pieces(&[(0, 0), (1, 0), (2, 0)]), &all(3)).is_empty());
    // A ring round a hole is one (the hole a pocket of its hull).
    assert_eq!(flat_unions(&pieces(SHAPES[4]), &all(8)).len(), 1);
    // A square of four is a convex polygon.
    assert!(flat_unions(&pieces(&[(0, 0), (1, 0), (0, 1), (1, 1)]), &all(4)).is_empty());
    // Pieces facing opposite ways, none.
    let mut turned = l.clone();
    turned[1] = turned[1].flipped();
    assert!(flat_unions(&turned, &all(3)).is_empty());
    // An L of two rectangles, one's edge running past the other's corner
    // (a T-junction): one, taken as cut at the corner.
    let long = ConvexPolygon::from_grid_points(
        &[gp(0, 50, 0), gp(0, 50, 10), gp(20, 50, 10), gp(20, 50, 0)],
        0,
    )
    .unwrap();
    let unions = flat_unions(&[long.clone(), l[2].clone()], &all(2));
    assert_eq!(unions.len(), 1);
    assert_eq!(unions[0].pieces, [0, 1]);
    // Its umbra is the three-rectangle L's under a light above it.
    let light = light(2, 2, 4, 4, 120);
    let parts =
        |pieces: &[ConvexPolygon]| flat_unions(pieces, &all(pieces.len()))[0].umbra_parts(&light);
    let (two, three) = (parts(&[long, l[2].clone()]), parts(&l));
    assert!(!two.is_empty());
    for x in -40..60 {
        for z in -40..60 {
            let p = gp(x, -20, z);
            let inside = |parts: &[Vec<bsp_core::Plane>]| {
                parts
                    .iter()
                    .any(|part| part.iter().all(|q| side_of_point(q, p) == Side::Back))
            };
            assert_eq!(inside(&two), inside(&three), "{p:?}");
        }
    }
}
