//! Closed triangle meshes made from formulas: a torus and a bumpy sphere,
//! the dense closed surfaces whose umbra on a floor is the joint umbra of
//! many triangles (no single triangle hides the light). The `meshes` demo
//! stands them over a floor; the tests and benchmarks build scenes of them.
//!
//! Both are wound counter-clockwise seen from outside, and every edge is
//! shared by exactly two triangles, walked once each way.
//!
//! ```
//! let ring = umbra::shapes::torus([0.0, 2.5, 0.0], (1.5, 0.6), (12, 8));
//! assert_eq!(ring.len(), 2 * 12 * 8);
//! let blob = umbra::shapes::bumpy_sphere([0.0, 2.5, 0.0], 1.0, 0.06, 2);
//! assert_eq!(blob.len(), 20 * 4 * 4);
//! ```

use std::collections::HashMap;

use crate::vec3::normalize;

/// A triangle's corners.
pub type Triangle = [[f64; 3]; 3];

/// A torus about the vertical (y) axis through `centre`: its ring of
/// radius `big`, its tube of radius `small`, in `rings` x `segments` quads
/// (around the axis, around the tube), each cut into two triangles.
pub fn torus(
    centre: [f64; 3],
    (big, small): (f64, f64),
    (rings, segments): (u32, u32),
) -> Vec<Triangle> {
    let at = |i: u32, j: u32| {
        let u = std::f64::consts::TAU * f64::from(i % rings) / f64::from(rings);
        let v = std::f64::consts::TAU * f64::from(j % segments) / f64::from(segments);
        let r = big + small * v.cos();
        [
            centre[0] + r * u.cos(),
            centre[1] + small * v.sin(),
            centre[2] + r * u.sin(),
        ]
    };
    let mut out = Vec::with_capacity(2 * (rings * segments) as usize);
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            out.extend([[a, b, c], [a, c, d]]);
        }
    }
    out
}

/// The twelve corners of an icosahedron (on the unit sphere once scaled)
/// and its twenty faces, counter-clockwise seen from outside.
fn icosahedron() -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let corners = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .map(normalize)
    .to_vec();
    let faces = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    (corners, faces)
}

/// A sphere about `centre` of `20 * 4^subdivisions` triangles (an
/// icosahedron's faces split in four `subdivisions` times), each corner
/// at a radius off `radius` by up to `bump` of it, from a fixed sequence:
/// the same mesh every run, and far from convex when `bump` is more than
/// the flatness of its triangles.
pub fn bumpy_sphere(centre: [f64; 3], radius: f64, bump: f64, subdivisions: u32) -> Vec<Triangle> {
    let (mut corners, mut faces) = icosahedron();
    for _ in 0..subdivisions {
        let mut middles: HashMap<(usize, usize), usize> = HashMap::new();
        let mut split = Vec::with_capacity(faces.len() * 4);
        for [a, b, c] in faces {
            let mut middle = |i: usize, j: usize| {
                *middles.entry((i.min(j), i.max(j))).or_insert_with(|| {
                    corners.push(normalize(std::array::from_fn(|k| {
                        corners[i][k] + corners[j][k]
                    })));
                    corners.len() - 1
                })
            };
            let (ab, bc, ca) = (middle(a, b), middle(b, c), middle(c, a));
            split.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = split;
    }
    let placed: Vec<[f64; 3]> = corners
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let r = radius * (1.0 + bump * ((i * 37 % 19) as f64 / 9.0 - 1.0));
            std::array::from_fn(|k| centre[k] + r * c[k])
        })
        .collect();
    faces.iter().map(|f| f.map(|i| placed[i])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec3::{cross, dot, norm, sub};

    /// Each directed edge once, and its reverse too: a closed surface
    /// with its triangles wound the same way.
    fn closed_and_consistent(triangles: &[Triangle]) -> bool {
        let key = |p: [f64; 3]| p.map(f64::to_bits);
        let mut edges: HashMap<([u64; 3], [u64; 3]), usize> = HashMap::new();
        for t in triangles {
            for k in 0..3 {
                *edges.entry((key(t[k]), key(t[(k + 1) % 3]))).or_default() += 1;
            }
        }
        edges
            .iter()
            .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
    }

    /// Six times the volume enclosed (positive: wound outward).
    fn six_volume(triangles: &[Triangle], centre: [f64; 3]) -> f64 {
        triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|p| sub(p, centre));
                dot(a, cross(b, c))
            })
            .sum()
    }

    #[test]
    fn the_torus_is_closed_wound_outward_and_holds_its_volume() {
        let (big, small) = (1.5, 0.6);
        let ring = torus([0.5, 2.5, -1.0], (big, small), (48, 32));
        assert_eq!(ring.len(), 2 * 48 * 32);
        assert!(closed_and_consistent(&ring));
        // 2 pi^2 R r^2, up to what the flat quads cut off or add (under
        // 1 % at this resolution).
        let volume = six_volume(&ring, [0.5, 2.5, -1.0]) / 6.0;
        let truth = 2.0 * std::f64::consts::PI.powi(2) * big * small * small;
        assert!((volume - truth).abs() < 0.01 * truth, "{volume} {truth}");
    }

    #[test]
    fn the_bumpy_sphere_is_closed_wound_outward_and_bumpy() {
        let blob = bumpy_sphere([1.0, 2.0, 3.0], 2.0, 0.06, 2);
        assert!(closed_and_consistent(&blob));
        let volume = six_volume(&blob, [1.0, 2.0, 3.0]) / 6.0;
        let ball = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
        assert!(
            volume > 0.8 * ball && volume < 1.1 * ball,
            "{volume} {ball}"
        );
        // Corners from 0.94 to 1.06 of the radius; some triangle has a
        // corner of another in front of its plane: no convex body.
        let radii: Vec<f64> = blob
            .iter()
            .flatten()
            .map(|p| norm(sub(*p, [1.0, 2.0, 3.0])))
            .collect();
        assert!(
            radii
                .iter()
                .all(|&r| (1.88 - 1e-9..=2.12 + 1e-9).contains(&r))
        );
        let concave = blob.iter().any(|t| {
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            blob.iter().flatten().any(|p| dot(n, sub(*p, t[0])) > 1e-9)
        });
        assert!(concave);
    }
}
