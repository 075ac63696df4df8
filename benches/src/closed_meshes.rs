//! The closed meshes of [`umbra::shapes`] on the grid: a bumpy sphere (a
//! closed surface far from convex, where `area-shadow` finds a core of its
//! kernel) and a torus (no kernel: cores of local kernels, and sections).

use bsp_core::{ConvexPolygon, GridPoint};
use umbra::shapes::{self, Triangle};

/// `triangles` (grid units) with their corners rounded to grid points;
/// those the rounding leaves flat are left out.
fn on_grid(triangles: &[Triangle]) -> Vec<ConvexPolygon> {
    triangles
        .iter()
        .filter_map(|t| {
            let corners = t.map(|c| {
                let [x, y, z] = c.map(|x| x.round() as i64);
                GridPoint::new(x, y, z).expect("within the grid")
            });
            ConvexPolygon::from_grid_points(&corners, 0).ok()
        })
        .collect()
}

/// [`shapes::bumpy_sphere`] about `centre`, of radius `radius` (grid
/// units).
pub fn bumpy_sphere(
    centre: [i64; 3],
    radius: f64,
    bump: f64,
    subdivisions: u32,
) -> Vec<ConvexPolygon> {
    on_grid(&shapes::bumpy_sphere(
        centre.map(|c| c as f64),
        radius,
        bump,
        subdivisions,
    ))
}

/// [`shapes::torus`] about `centre`, its radii in grid units.
pub fn torus(centre: [i64; 3], radii: (f64, f64), quads: (u32, u32)) -> Vec<ConvexPolygon> {
    on_grid(&shapes::torus(centre.map(|c| c as f64), radii, quads))
}
