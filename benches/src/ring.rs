//! A torus: a closed surface with no kernel (the scene where `area-shadow`
//! finds cores of local kernels).

use bsp_core::{ConvexPolygon, GridPoint};

/// The torus's triangles, counter-clockwise seen from outside: about the
/// vertical axis through `centre`, its ring of radius `big` and its tube
/// of radius `small` (grid units), in `rings` x `segments` quads each cut
/// into two.
pub fn torus(
    centre: [i64; 3],
    (big, small): (f64, f64),
    (rings, segments): (u32, u32),
) -> Vec<ConvexPolygon> {
    let at = |i: u32, j: u32| {
        let (u, v) = (
            std::f64::consts::TAU * f64::from(i % rings) / f64::from(rings),
            std::f64::consts::TAU * f64::from(j % segments) / f64::from(segments),
        );
        let r = big + small * v.cos();
        GridPoint::new(
            centre[0] + (r * u.cos()).round() as i64,
            centre[1] + (small * v.sin()).round() as i64,
            centre[2] + (r * u.sin()).round() as i64,
        )
        .expect("within the grid")
    };
    let mut faces = Vec::with_capacity(2 * (rings * segments) as usize);
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            for t in [[a, b, c], [a, c, d]] {
                faces.extend(ConvexPolygon::from_grid_points(&t, 0).ok());
            }
        }
    }
    faces
}
