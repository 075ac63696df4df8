//! Turning world-space triangles into the kernel's pieces.

use bsp_core::{ConvexPolygon, Grid, GridPoint};

/// World triangles snapped to one grid over them and the given extra points
/// (lights), as convex pieces numbered in order; degenerate ones dropped.
pub fn pieces(triangles: &[[[f64; 3]; 3]], extra: &[[f64; 3]]) -> (Grid, Vec<ConvexPolygon>) {
    let points: Vec<&[f64; 3]> = triangles.iter().flatten().chain(extra).collect();
    let grid = Grid::enclosing(points, 0.01).expect("a finite, non-empty scene");
    let mut out = Vec::with_capacity(triangles.len());
    for t in triangles {
        let g: Vec<GridPoint> = t
            .iter()
            .map(|&p| grid.snap(p).expect("inside the grid"))
            .collect();
        if let Ok(p) = ConvexPolygon::from_grid_points(&g, out.len() as u32) {
            out.push(p);
        }
    }
    (grid, out)
}
