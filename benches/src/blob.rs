//! A bumpy sphere: an icosahedron split into `20 * 4^n` triangles, its
//! corners pushed in and out along their radii, a closed surface far from
//! convex (the scene where `area-shadow` finds a core of its kernel).

use bsp_core::{ConvexPolygon, GridPoint};
use std::collections::HashMap;

/// The sphere's triangles, counter-clockwise seen from outside: radius
/// `radius` grid units about `centre`, each corner off the radius by up to
/// `bump` of it (a fixed sequence: the same mesh every run), the
/// icosahedron's faces split in four `subdivisions` times.
pub fn bumpy_sphere(
    centre: [i64; 3],
    radius: f64,
    bump: f64,
    subdivisions: usize,
) -> Vec<ConvexPolygon> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    };
    let mut corners: Vec<[f64; 3]> = [
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
    .map(unit)
    .to_vec();
    let mut faces: Vec<[usize; 3]> = vec![
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
    for _ in 0..subdivisions {
        let mut middles: HashMap<(usize, usize), usize> = HashMap::new();
        let mut split = Vec::with_capacity(faces.len() * 4);
        for [a, b, c] in faces {
            let mut middle = |i: usize, j: usize| {
                *middles.entry((i.min(j), i.max(j))).or_insert_with(|| {
                    corners.push(unit(std::array::from_fn(|k| corners[i][k] + corners[j][k])));
                    corners.len() - 1
                })
            };
            let (ab, bc, ca) = (middle(a, b), middle(b, c), middle(c, a));
            split.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = split;
    }
    let placed: Vec<GridPoint> = corners
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let r = radius * (1.0 + bump * ((i * 37 % 19) as f64 / 9.0 - 1.0));
            GridPoint::new(
                centre[0] + (r * c[0]).round() as i64,
                centre[1] + (r * c[1]).round() as i64,
                centre[2] + (r * c[2]).round() as i64,
            )
            .expect("on the grid")
        })
        .collect();
    faces
        .iter()
        .filter_map(|f| ConvexPolygon::from_grid_points(&f.map(|i| placed[i]), 0).ok())
        .collect()
}
