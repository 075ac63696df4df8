//! Closed surfaces the scene targets decode: boxes, bodies with slanted
//! faces, a concave prism, and surfaces that are not quite closed. Corners
//! are in half units on small integer coordinates.

use arbitrary::Unstructured;

/// A coordinate in `-half_extent..=half_extent`.
fn small(u: &mut Unstructured<'_>, half_extent: i8) -> arbitrary::Result<i8> {
    u.int_in_range(-half_extent..=half_extent)
}

/// A point with coordinates in `-half_extent..=half_extent`.
pub(crate) fn point(u: &mut Unstructured<'_>, half_extent: i8) -> arbitrary::Result<[i8; 3]> {
    Ok([
        small(u, half_extent)?,
        small(u, half_extent)?,
        small(u, half_extent)?,
    ])
}

/// A box from `lo` to `lo + size`, its faces wound outwards.
pub(crate) fn box_faces(lo: [i8; 3], size: [i8; 3]) -> Vec<Vec<[i8; 3]>> {
    let [x0, y0, z0] = lo;
    let [x1, y1, z1] = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
    vec![
        vec![[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],
        vec![[x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]],
        vec![[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0]],
        vec![[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],
        vec![[x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]],
        vec![[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
    ]
}

/// Every corner of `faces` moved by `by`.
fn shifted(mut faces: Vec<Vec<[i8; 3]>>, by: [i8; 3]) -> Vec<Vec<[i8; 3]>> {
    for corner in faces.iter_mut().flatten() {
        for k in 0..3 {
            corner[k] = corner[k].saturating_add(by[k]);
        }
    }
    faces
}

/// Six times the volume a closed surface wound counter-clockwise from
/// outside encloses (negative: wound inwards), by its faces' fans.
pub(crate) fn six_volumes(faces: &[Vec<[i8; 3]>]) -> i64 {
    let at = |c: [i8; 3]| c.map(i64::from);
    let det = |a: [i64; 3], b: [i64; 3], c: [i64; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
    };
    faces
        .iter()
        .flat_map(|f| (1..f.len().saturating_sub(1)).map(move |i| (f[0], f[i], f[i + 1])))
        .map(|(a, b, c)| det(at(a), at(b), at(c)))
        .sum()
}

/// `faces` of a closed surface, wound outwards (as they are, or all
/// reversed).
fn outwards(mut faces: Vec<Vec<[i8; 3]>>) -> Vec<Vec<[i8; 3]>> {
    if six_volumes(&faces) < 0 {
        faces.iter_mut().for_each(|f| f.reverse());
    }
    faces
}

/// A prism: the polygon `base` (in a plane `y` = const, any winding)
/// extruded up by `height`, its faces wound outwards. A concave base makes
/// a closed surface with concave faces.
fn prism(base: &[[i8; 3]], height: i8) -> Vec<Vec<[i8; 3]>> {
    let top: Vec<[i8; 3]> = base.iter().map(|&[x, y, z]| [x, y + height, z]).collect();
    let mut faces = vec![base.to_vec(), top.iter().rev().copied().collect()];
    for i in 0..base.len() {
        let j = (i + 1) % base.len();
        faces.push(vec![base[j], base[i], top[i], top[j]]);
    }
    outwards(faces)
}

/// Closed surfaces other than a box: bodies with slanted faces (a
/// tetrahedron, a pyramid, a wedge), a concave one (an L-shaped prism),
/// two boxes of one object touching face to face, and a box whose top is
/// cut in two (edges meeting in a T: no exact closed surface).
pub(crate) fn solid(u: &mut Unstructured<'_>) -> arbitrary::Result<Vec<Vec<[i8; 3]>>> {
    let at = point(u, 6)?;
    let size = |u: &mut Unstructured<'_>| u.int_in_range(1..=4_i8);
    Ok(match u.int_in_range(0..=5_u8)? {
        0 => {
            let [a, b, c, d] = [point(u, 6)?, point(u, 6)?, point(u, 6)?, point(u, 6)?];
            outwards(vec![
                vec![a, b, c],
                vec![a, c, d],
                vec![a, d, b],
                vec![b, d, c],
            ])
        }
        1 => {
            let (s, h) = (size(u)?, size(u)?);
            let apex = [u.int_in_range(-2..=s + 2)?, h, u.int_in_range(-2..=s + 2)?];
            let base = [[0, 0, 0], [s, 0, 0], [s, 0, s], [0, 0, s]];
            let mut faces = vec![base.to_vec()];
            for i in 0..4 {
                faces.push(vec![base[(i + 1) % 4], base[i], apex]);
            }
            shifted(outwards(faces), at)
        }
        2 => {
            let (w, d, h) = (size(u)?, size(u)?, size(u)?);
            let peak = u.int_in_range(0..=w)?;
            shifted(prism(&[[0, 0, 0], [w, 0, 0], [peak, 0, d]], h), at)
        }
        3 => {
            let (w, d, h) = (size(u)? + 1, size(u)? + 1, size(u)?);
            let (a, b) = (u.int_in_range(1..=w - 1)?, u.int_in_range(1..=d - 1)?);
            let base = [
                [0, 0, 0],
                [w, 0, 0],
                [w, 0, b],
                [a, 0, b],
                [a, 0, d],
                [0, 0, d],
            ];
            shifted(prism(&base, h), at)
        }
        4 => {
            let first = [size(u)?, size(u)?, size(u)?];
            let second = [size(u)?, size(u)?, size(u)?];
            let offset = [first[0], u.int_in_range(-2..=2)?, u.int_in_range(-2..=2)?];
            let mut faces = box_faces(at, first);
            faces.extend(shifted(box_faces(at, second), offset));
            faces
        }
        _ => {
            let size = [size(u)? + 1, size(u)?, size(u)?];
            let mut faces = box_faces(at, size);
            // The top (`y` high) is face 1: cut across x.
            let [x0, _, z0] = at;
            let (y1, z1) = (at[1] + size[1], at[2] + size[2]);
            let xm = x0 + u.int_in_range(1..=size[0] - 1)?;
            let x1 = x0 + size[0];
            faces[1] = vec![[x0, y1, z0], [x0, y1, z1], [xm, y1, z1], [xm, y1, z0]];
            faces.push(vec![[xm, y1, z0], [xm, y1, z1], [x1, y1, z1], [x1, y1, z0]]);
            faces
        }
    })
}
