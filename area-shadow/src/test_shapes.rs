//! Shapes the unit tests of several modules build.

use bsp_core::{ConvexPolygon, GridPoint};

/// The six faces of the box from `lo` to `hi`, facing out.
pub(crate) fn cuboid(lo: [i32; 3], hi: [i32; 3]) -> Vec<ConvexPolygon> {
    let g = |x, y, z| GridPoint { x, y, z };
    let ([a, b, c], [d, e, f]) = (lo, hi);
    let faces = [
        [g(a, b, c), g(a, e, c), g(d, e, c), g(d, b, c)],
        [g(a, b, f), g(d, b, f), g(d, e, f), g(a, e, f)],
        [g(a, b, c), g(d, b, c), g(d, b, f), g(a, b, f)],
        [g(a, e, c), g(a, e, f), g(d, e, f), g(d, e, c)],
        [g(a, b, c), g(a, b, f), g(a, e, f), g(a, e, c)],
        [g(d, b, c), g(d, e, c), g(d, e, f), g(d, b, f)],
    ];
    faces
        .iter()
        .map(|f| ConvexPolygon::from_grid_points(f, 0).unwrap())
        .collect()
}
