//! Haines' SPD `tetra` scene: recursive tetrahedra over a ground plane, the
//! scene of Chin & Feiner 1989's Table 1.

/// The SPD light position.
pub const LIGHT: [f64; 3] = [2.0, -18.0, -5.0];

/// The triangles of the recursive tetrahedron of the given depth (depth 4:
/// 256 triangles, depth 5: 1024), wound outward: the generator of
/// `umbra demo tetra`.
pub use umbra::tetra_triangles;

/// Flags for a scene of `tetra` tetra triangles followed by other pieces:
/// each leaf tetrahedron is a closed surface (as `umbra shadow` finds it,
/// every edge shared by two faces, and as Chin & Feiner process only the
/// faces towards the light), the rest is not.
pub fn flags(tetra: usize, pieces: usize) -> Vec<svbsp::PieceFlags> {
    (0..pieces)
        .map(|i| svbsp::PieceFlags {
            closed_surface: i < tetra,
            ..svbsp::PieceFlags::default()
        })
        .collect()
}

/// The ground: two triangles in the plane `x + y - z = offset`, facing the
/// light (normal along `(-1, -1, 1)`). With `offset = 1` the tetrahedra's
/// bottom faces lie in it (coplanar contact). Corners are binary fractions,
/// so they snap to the grid exactly.
pub fn ground(offset: f64, half_size: f64) -> Vec<[[f64; 3]; 3]> {
    // In-plane axes u = (1, -1, 0), v = (1, 1, 2); origin (offset, 0, 0).
    let p = |a: f64, b: f64| [offset + a + b, -a + b, 2.0 * b];
    let s = half_size;
    let (c0, c1, c2, c3) = (p(-s, -s), p(s, -s), p(s, s), p(-s, s));
    // u x v = (-2, -2, 2): counter-clockwise in (u, v) faces (-1, -1, 1).
    vec![[c0, c1, c2], [c0, c2, c3]]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn counts_and_contact() {
        assert_eq!(tetra_triangles(4).len(), 256);
        assert_eq!(tetra_triangles(5).len(), 1024);
        // Three of four children touch each face of their parent: 3^3 leaf
        // faces of depth 4 lie in x + y - z = 1, on the ground.
        let bottom = tetra_triangles(4)
            .iter()
            .filter(|t| t.iter().all(|v: &[f64; 3]| v[0] + v[1] - v[2] == 1.0))
            .count();
        assert_eq!(bottom, 27);
        for t in ground(1.0, 8.0) {
            assert!(t.iter().all(|v| v[0] + v[1] - v[2] == 1.0));
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            assert!(dot(n, sub(LIGHT, t[0])) > 0.0, "the ground faces the light");
        }
    }
}
