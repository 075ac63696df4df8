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

/// A closed sphere-like mesh: the octahedron with each face cut into `n^2`
/// triangles, vertices pushed out to the unit sphere, scaled by `radius`
/// and moved to `center` (`8 n^2` triangles, wound outward). Shared
/// vertices come from the same lattice point, so they snap identically.
pub fn sphere_mesh(n: usize, center: [f64; 3], radius: f64) -> Vec<[[f64; 3]; 3]> {
    let point = |a: i64, b: i64, c: i64| {
        let (x, y, z) = (a as f64, b as f64, c as f64);
        let len = (x * x + y * y + z * z).sqrt();
        [
            center[0] + radius * x / len,
            center[1] + radius * y / len,
            center[2] + radius * z / len,
        ]
    };
    let n = n as i64;
    let mut out = Vec::with_capacity(8 * (n * n) as usize);
    for sx in [1, -1] {
        for sy in [1, -1] {
            for sz in [1, -1] {
                // Lattice (i, j, k), i + j + k = n, on the face of signs (sx, sy, sz).
                let p = |i: i64, j: i64| point(sx * i, sy * j, sz * (n - i - j));
                let outward = sx * sy * sz > 0;
                let mut tri = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
                    out.push(if outward { [a, b, c] } else { [a, c, b] });
                };
                for i in 0..n {
                    for j in 0..n - i {
                        tri(p(i, j), p(i + 1, j), p(i, j + 1));
                        if i + j + 1 < n {
                            tri(p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
                        }
                    }
                }
            }
        }
    }
    out
}

/// A square floor at height `y`, facing up, as two triangles.
pub fn floor(y: f64, half: f64) -> Vec<[[f64; 3]; 3]> {
    let c = |x: f64, z: f64| [x, y, z];
    vec![
        [c(-half, half), c(half, half), c(half, -half)],
        [c(-half, half), c(half, -half), c(-half, -half)],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_is_closed_and_outward() {
        let mesh = sphere_mesh(3, [0.0; 3], 2.0);
        assert_eq!(mesh.len(), 72);
        // Every directed edge appears once and its reverse once.
        let key = |p: [f64; 3]| p.map(f64::to_bits);
        let mut edges = std::collections::HashMap::new();
        for t in &mesh {
            for k in 0..3 {
                *edges.entry((key(t[k]), key(t[(k + 1) % 3]))).or_insert(0) += 1;
            }
            // Outward: the normal points away from the centre.
            let (a, b, c) = (t[0], t[1], t[2]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            assert!(n[0] * a[0] + n[1] * a[1] + n[2] * a[2] > 0.0);
        }
        for (&(a, b), &count) in &edges {
            assert_eq!(count, 1);
            assert_eq!(edges.get(&(b, a)), Some(&1));
        }
    }
}
