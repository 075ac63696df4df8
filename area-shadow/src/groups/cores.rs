//! Convex cores of a closed surface with no kernel (a torus, a U, most
//! scanned or modelled meshes): *local kernels* of points inside it.
//!
//! Take a grid point `c` inside the surface (its winding number, module
//! `winding`, at least 1) and on no face's plane, and a box `B` around
//! it; let `H` be the intersection of `B` with the half-spaces behind
//! the faces `c` is behind (faces facing out), leaving out faces wholly
//! beyond one of `B`'s planes. A segment from `c` to a point `p` of `H`
//! stays in `B` and so crosses none of the faces left out, nor any face
//! `c` is behind that was kept (both ends are behind its plane): every
//! face it crosses is one `c` is in front of, crossed from front to back,
//! into the body. The winding number never drops along it, and `p` is
//! inside too. So `H` lies in the surface's closed inside, and so does
//! the hull of grid points of `H` (found along directions from `c`, as
//! module `kernel` finds them in the kernel, which `H` is when every face
//! turns its back to `c` and `B` holds the surface): a core whose umbra
//! is part of the surface's, since a segment from one of its points to a
//! point outside the surface's hull goes from a winding number of at
//! least 1 to 0, and crosses the surface.
//!
//! Without the box, faces far off whose planes pass close by `c` (the
//! other side of a torus's ring) would flatten `H`; a box as wide as the
//! body is thick at `c` keeps out most of them. Seeds for `c` are found
//! between walls: from the centre of a face, halfway to the nearest face
//! the ray into the body meets (the wall's distance sets the box). Thick
//! places come first; seeds inside a core found already are passed over.

use super::kernel::{SUBDIVISIONS, direction_count, points_along, with_centre};
use super::solid::Solid;
use super::winding::winding_number;
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{GridPoint, Plane};

/// The most cores one surface gets: each adds an umbra volume per light
/// and a shell to every joint-umbra proof near it.
pub(super) const MAX_CORES: usize = 8;

/// The most faces seeds are sought from (spread evenly over the
/// surface's faces in their order): each seed costs a ray against every
/// face.
const MAX_SEED_FACES: usize = 64;

/// How far the box a local kernel is taken in reaches from its seed
/// along each axis, in walls' distances (module docs): half, a box as
/// wide as the body is thick. A 1,024-triangle torus's floor umbra under
/// `umbra shadow`: 0.35, 0.59; 0.5, 1.14; 0.6, 0.36.
const BOX_REACH: f64 = 0.5;

/// How many times the icosahedron's edges are halved for the directions
/// whose points make a core's shell (42): a core of 162 directions' points
/// casts a larger umbra, but proofs through its shell test its faces at
/// every step. A 1,024-triangle torus's `umbra dm` (2 cores): no shells
/// 20.7 s, floor umbra 1.16 (of about 7.8 in truth); 12 directions 28.4 s,
/// 2.80; 42: 35.4 s, 3.89; 162: 54.2 s, 4.44.
const SHELL_SUBDIVISIONS: usize = 1;

/// Convex cores (module docs) inside the closed surface of convex
/// `outlines` with planes `faces` (facing out): at most [`MAX_CORES`],
/// thick places first, none holding another's seed; each with a shell
/// made about the hull of its first 42 directions' points.
pub(super) fn local_cores(outlines: &[&[GridPoint]], faces: &[Plane]) -> Vec<Solid> {
    let mut cores: Vec<Solid> = Vec::new();
    for (wall, seed) in seeds(outlines, faces) {
        if cores.len() == MAX_CORES {
            break;
        }
        let Ok(c) = GridPoint::new(
            seed[0].round() as i64,
            seed[1].round() as i64,
            seed[2].round() as i64,
        ) else {
            continue;
        };
        let held = cores.iter().any(|core| {
            core.faces()
                .iter()
                .all(|f| side_of_point(f, c) != Side::Front)
        });
        if held || winding_number(c, outlines, faces).is_none_or(|w| w < 1) {
            continue;
        }
        let reach = (wall * BOX_REACH).ceil().max(1.0) as i64;
        let Some(planes) = local_kernel(c, reach, outlines, faces) else {
            continue;
        };
        let half = [reach as f64; 3];
        let found = points_along(&planes, c, half, SUBDIVISIONS);
        let Some(core) = Solid::of_hull(&with_centre(found.iter().flatten().copied(), c), false)
        else {
            continue;
        };
        let first = direction_count(SHELL_SUBDIVISIONS).min(found.len());
        let shell = with_centre(found[..first].iter().flatten().copied(), c);
        cores.push(core.with_shell_core(shell));
    }
    cores
}

/// The planes (facing out) of the local kernel of `c` (a grid point on no
/// face's plane) within the box of grid points at most `reach` from it
/// along each axis: the box's, and those of the faces `c` is behind but
/// for those wholly beyond one of the box's planes (no segment from `c`
/// within the box crosses them). `None` when the box leaves the grid.
fn local_kernel(
    c: GridPoint,
    reach: i64,
    outlines: &[&[GridPoint]],
    faces: &[Plane],
) -> Option<Vec<Plane>> {
    let at = c.to_i64();
    let mut planes = Vec::with_capacity(6);
    for axis in 0..3 {
        for sign in [-1_i64, 1] {
            let mut normal = [0; 3];
            normal[axis] = sign;
            let mut corner = at;
            corner[axis] += sign * reach;
            planes.push(Plane::with_normal_through(
                normal,
                GridPoint::new(corner[0], corner[1], corner[2]).ok()?,
            )?);
        }
    }
    let beyond = |outline: &[GridPoint]| {
        (0..3).any(|axis| {
            let (low, high) = (at[axis] - reach, at[axis] + reach);
            outline.iter().all(|p| p.to_i64()[axis] > high)
                || outline.iter().all(|p| p.to_i64()[axis] < low)
        })
    };
    planes.extend(
        outlines
            .iter()
            .zip(faces)
            .filter(|(outline, face)| side_of_point(face, c) == Side::Back && !beyond(outline))
            .map(|(_, face)| *face),
    );
    Some(planes)
}

/// Points between walls of the surface, the thickest first: from the
/// centre of each of up to [`MAX_SEED_FACES`] faces, halfway along the
/// ray into the body to the nearest other face it meets (floating point:
/// a seed is only a guess, checked exactly before use).
fn seeds(outlines: &[&[GridPoint]], faces: &[Plane]) -> Vec<(f64, [f64; 3])> {
    let corners: Vec<Vec<[f64; 3]>> = outlines
        .iter()
        .map(|o| o.iter().map(|p| p.to_f64()).collect())
        .collect();
    let planes: Vec<[f64; 4]> = faces.iter().map(Plane::approx).collect();
    let stride = faces.len().div_ceil(MAX_SEED_FACES).max(1);
    let mut found: Vec<(f64, usize, [f64; 3])> = (0..faces.len())
        .step_by(stride)
        .filter_map(|i| {
            let [a, b, c, _] = planes[i];
            let length = (a * a + b * b + c * c).sqrt();
            if length == 0.0 {
                return None;
            }
            let inward = [-a / length, -b / length, -c / length];
            let n = corners[i].len() as f64;
            let centre: [f64; 3] =
                std::array::from_fn(|k| corners[i].iter().map(|p| p[k]).sum::<f64>() / n);
            let wall = (0..faces.len())
                .filter(|&j| j != i)
                .filter_map(|j| ray_hit(centre, inward, &planes[j], &corners[j]))
                .fold(f64::INFINITY, f64::min);
            wall.is_finite().then(|| {
                let seed = std::array::from_fn(|k| centre[k] + inward[k] * wall / 2.0);
                (wall, i, seed)
            })
        })
        .collect();
    found.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
    found
        .into_iter()
        .map(|(wall, _, seed)| (wall, seed))
        .collect()
}

/// How far along the ray from `from` in unit direction `d` it meets the
/// convex polygon with `corners` in plane `plane`, if ahead.
fn ray_hit(from: [f64; 3], d: [f64; 3], plane: &[f64; 4], corners: &[[f64; 3]]) -> Option<f64> {
    let [a, b, c, w] = *plane;
    let along = a * d[0] + b * d[1] + c * d[2];
    if along == 0.0 {
        return None;
    }
    let t = -(a * from[0] + b * from[1] + c * from[2] + w) / along;
    if t <= 0.0 {
        return None;
    }
    let x: [f64; 3] = std::array::from_fn(|k| from[k] + t * d[k]);
    // Inside when the point turns the same way about every edge (seen
    // along the plane's normal).
    let n = corners.len();
    let (mut left, mut right) = (false, false);
    for i in 0..n {
        let (p, q) = (corners[i], corners[(i + 1) % n]);
        let e = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let v = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
        let turn = a * (e[1] * v[2] - e[2] * v[1])
            + b * (e[2] * v[0] - e[0] * v[2])
            + c * (e[0] * v[1] - e[1] * v[0]);
        left |= turn > 0.0;
        right |= turn < 0.0;
    }
    (!(left && right)).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_shapes::{solid_angle_winding, torus};

    #[test]
    fn a_toruss_cores_lie_inside_it() {
        for (big, small, rings, segments) in [
            (4000.0, 1500.0, 12, 8),
            (6000.0, 900.0, 24, 6),
            (3000.0, 2000.0, 16, 12),
        ] {
            let (triangles, planes) = torus(big, small, rings, segments);
            let outlines: Vec<&[GridPoint]> = triangles.iter().map(|t| &t[..]).collect();
            let cores = local_cores(&outlines, &planes);
            assert!(cores.len() >= 2, "{} cores", cores.len());
            for core in &cores {
                let corners = core.vertices();
                assert!(corners.len() >= 4);
                // Its middle inside, and each corner inside or on the
                // surface: a point just inside the core from it is inside
                // (the sum of solid angles is unreliable at points in a
                // face's plane).
                let n = corners.len() as f64;
                let middle: [f64; 3] =
                    std::array::from_fn(|a| corners.iter().map(|p| p.to_f64()[a]).sum::<f64>() / n);
                let w = solid_angle_winding(middle, &triangles);
                assert!((w - 1.0).abs() < 1e-6, "middle {middle:?} wound {w}");
                for p in corners {
                    let p = p.to_f64();
                    let near: [f64; 3] = std::array::from_fn(|a| p[a] + (middle[a] - p[a]) / 64.0);
                    let w = solid_angle_winding(near, &triangles);
                    assert!((w - 1.0).abs() < 1e-6, "corner {p:?} wound {w}");
                }
                // A core reaches across a third of the tube's width at
                // least, along some axis.
                let (least, most) = super::super::kernel::extent(corners).expect("corners");
                let widest = (0..3).map(|a| most[a] - least[a]).fold(0.0, f64::max);
                assert!(
                    widest > small / 1.5,
                    "a core {widest} wide in a tube of radius {small}"
                );
            }
        }
    }
}
