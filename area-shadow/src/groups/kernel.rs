//! A convex core inside a closed surface that is really concave (a bumpy
//! sphere, a rock): grid points of the surface's *kernel*, the
//! intersection `K` of the half-spaces behind its faces.
//!
//! From a point of `K` every face turns its back, so the point has a
//! winding number of at least one about the surface (module `solid`), and
//! a segment from it to a point outside the surface's hull crosses the
//! surface. The hull of grid points of `K` lies in `K` (it is convex), so
//! it blocks no segment from outside the hull that the surface does not:
//! its umbra is part of the surface's. A star-shaped surface whose bumps
//! are shallow has a kernel nearly as large as itself; one with none (a
//! torus, an L) gets no core.
//!
//! The points are found in floating point (how far `K` reaches from a
//! centre along 162 directions) and kept only when exactly behind
//! or on every face's plane, so rounding can shrink the core, never put it
//! outside `K`.

use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{GridPoint, Plane};

/// How far short of `K`'s boundary a point is aimed, as a fraction of
/// its distance from the centre, when the grid point nearest the boundary
/// is not in `K`: room for rounding to the grid.
const MARGIN: f64 = 1.0 / 256.0;

/// The fewest grid units such a point is aimed short of the boundary.
const MIN_MARGIN: f64 = 2.0;

/// How many times the icosahedron's edges are halved for the directions
/// the core reaches out along: twice, 162 directions. More make a core
/// closer to the kernel (a larger umbra, fewer joint-umbra proofs) with
/// more faces (costlier proofs through it). A 1,280-triangle bumpy
/// sphere's `umbra dm` (2 cores): 42 directions 44.8 s, floor umbra
/// 2.448; 162: 38.6 s, 2.490; 642: 40.8 s, 2.493. Its 320-triangle
/// sibling: 12: 3.5 s; 42: 2.1 s; 162: 1.7 s; 642: 1.9 s.
pub(super) const SUBDIVISIONS: usize = 2;

/// How many directions [`directions`] gives for `subdivisions`.
pub(super) fn direction_count(subdivisions: usize) -> usize {
    10 * 4_usize.pow(subdivisions as u32) + 2
}

/// The directions from the centre along which the core reaches out: the
/// corners of an icosahedron, with each edge's midpoint added
/// [`SUBDIVISIONS`] times over (a geodesic sphere), stretched by the
/// surface's extent along each axis (in [`kernel_points`]) so that a long
/// body gets a long core.
fn directions(subdivisions: usize) -> Vec<[f64; 3]> {
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    };
    let phi = (1.0 + 5.0_f64.sqrt()) / 2.0;
    let mut points: Vec<[f64; 3]> = Vec::with_capacity(12);
    for s in [-1.0, 1.0] {
        for t in [-1.0, 1.0] {
            points.push(unit([0.0, s, t * phi]));
            points.push(unit([s, t * phi, 0.0]));
            points.push(unit([t * phi, 0.0, s]));
        }
    }
    let dist2 = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>();
    for _ in 0..subdivisions {
        // Neighbours are the closest pairs; the edges of a geodesic sphere
        // differ in length by less than a fifth, and the nearest points
        // that are no neighbours are farther by more than half.
        let shortest = points
            .iter()
            .enumerate()
            .flat_map(|(i, a)| points[i + 1..].iter().map(move |b| dist2(a, b)))
            .fold(f64::INFINITY, f64::min);
        let mut more = Vec::new();
        for (i, a) in points.iter().enumerate() {
            for b in &points[i + 1..] {
                if dist2(a, b) < shortest * 1.44 {
                    more.push(unit(std::array::from_fn(|k| a[k] + b[k])));
                }
            }
        }
        points.extend(more);
    }
    points
}

/// Grid points of the kernel of a closed surface with vertices `vertices`
/// and faces' planes `faces` (the kernel behind them all), each behind or
/// on every plane, among them one strictly behind every plane (the centre
/// the others were sought from). `None` when no centre is found strictly
/// behind every plane (no kernel, or the faces face the other way).
pub(super) fn kernel_points(faces: &[Plane], vertices: &[GridPoint]) -> Option<Vec<GridPoint>> {
    let (least, most) = extent(vertices)?;
    let centre = centre(faces, vertices, least, most)?;
    let half: [f64; 3] = std::array::from_fn(|a| (most[a] - least[a]) / 2.0);
    let found = points_along(faces, centre, half, SUBDIVISIONS);
    Some(with_centre(found.into_iter().flatten(), centre))
}

/// `points` and `centre`, ascending, each once.
pub(super) fn with_centre(
    points: impl Iterator<Item = GridPoint>,
    centre: GridPoint,
) -> Vec<GridPoint> {
    let mut points: Vec<GridPoint> = points.chain([centre]).collect();
    points.sort_unstable();
    points.dedup();
    points
}

/// Per direction (in the order of a geodesic sphere's `subdivisions`: the
/// icosahedron's 12 corners first), a grid point behind or on every plane
/// of `faces` (facing out of a bounded convex region) found along it from
/// `centre` (a grid point strictly behind them all), if any; directions
/// stretched by `half` (half the extent along each axis of what the
/// region lies in).
pub(super) fn points_along(
    faces: &[Plane],
    centre: GridPoint,
    half: [f64; 3],
    subdivisions: usize,
) -> Vec<Option<GridPoint>> {
    let from = centre.to_f64();
    let planes: Vec<[f64; 4]> = faces.iter().map(Plane::approx).collect();
    let inside = |p: GridPoint| faces.iter().all(|f| side_of_point(f, p) != Side::Front);
    let mut points = Vec::new();
    for unit in directions(subdivisions) {
        let d: [f64; 3] = std::array::from_fn(|a| unit[a] * half[a].max(1.0));
        // The farthest `t` with `from + t d` behind every plane.
        let reach = planes
            .iter()
            .filter_map(|[a, b, c, w]| {
                let along = a * d[0] + b * d[1] + c * d[2];
                let at = a * from[0] + b * from[1] + c * from[2] + w;
                (along > 0.0).then(|| -at / along)
            })
            .fold(f64::INFINITY, f64::min);
        if !reach.is_finite() || reach <= 0.0 {
            points.push(None);
            continue;
        }
        // The grid point nearest where the ray leaves `K`, else that
        // nearest it truncated towards the centre (a small body's corners
        // are often grid points of `K` just so), else one aimed short.
        let length = reach * d.iter().map(|c| c * c).sum::<f64>().sqrt();
        let short = (length * MARGIN).max(MIN_MARGIN).min(length);
        let at = |t: f64| -> [f64; 3] { std::array::from_fn(|a| from[a] + t * d[a]) };
        let (edge, aimed) = (at(reach), at(reach * (1.0 - short / length)));
        let towards_centre: [f64; 3] = std::array::from_fn(|a| {
            if edge[a] > from[a] {
                edge[a].floor()
            } else {
                edge[a].ceil()
            }
        });
        let found = [edge, towards_centre, aimed].into_iter().find_map(|q| {
            GridPoint::new(
                q[0].round() as i64,
                q[1].round() as i64,
                q[2].round() as i64,
            )
            .ok()
            .filter(|&p| inside(p))
        });
        points.push(found);
    }
    points
}

/// The least and greatest coordinates of `vertices`.
pub(super) fn extent(vertices: &[GridPoint]) -> Option<([f64; 3], [f64; 3])> {
    let first = vertices.first()?.to_f64();
    let (mut least, mut most) = (first, first);
    for p in vertices {
        let p = p.to_f64();
        for a in 0..3 {
            least[a] = least[a].min(p[a]);
            most[a] = most[a].max(p[a]);
        }
    }
    Some((least, most))
}

/// A grid point strictly behind every plane: the vertices' mean or the
/// centre of their box, rounded, whichever is; else where a relaxation
/// from the mean ends (a box dented deep has its mean in the dent).
fn centre(
    faces: &[Plane],
    vertices: &[GridPoint],
    least: [f64; 3],
    most: [f64; 3],
) -> Option<GridPoint> {
    let n = vertices.len() as f64;
    let mean: [f64; 3] =
        std::array::from_fn(|a| vertices.iter().map(|p| p.to_f64()[a]).sum::<f64>() / n);
    let middle: [f64; 3] = std::array::from_fn(|a| (least[a] + most[a]) / 2.0);
    let behind_all = |c: [f64; 3]| {
        let p = GridPoint::new(
            c[0].round() as i64,
            c[1].round() as i64,
            c[2].round() as i64,
        )
        .ok()?;
        faces
            .iter()
            .all(|f| side_of_point(f, p) == Side::Back)
            .then_some(p)
    };
    [mean, middle]
        .into_iter()
        .find_map(behind_all)
        .or_else(|| behind_all(relaxed(faces, mean)))
}

/// The most steps [`relaxed`] takes.
const RELAXATION_STEPS: usize = 64;

/// How far (grid units) [`relaxed`] puts a point behind every plane:
/// rounding to the grid moves it less than one unit.
const CLEARANCE: f64 = 1.5;

/// A point behind every plane by [`CLEARANCE`], if the relaxation from
/// `from` finds one: step by step, across the plane it is farthest in
/// front of (or least behind) to twice the clearance behind it.
fn relaxed(faces: &[Plane], from: [f64; 3]) -> [f64; 3] {
    let planes: Vec<([f64; 3], f64)> = faces
        .iter()
        .map(|f| {
            let [a, b, c, d] = f.approx();
            let norm = (a * a + b * b + c * c).sqrt();
            ([a / norm, b / norm, c / norm], d / norm)
        })
        .collect();
    let mut p = from;
    for _ in 0..RELAXATION_STEPS {
        let Some((normal, ahead)) = planes
            .iter()
            .map(|(n, d)| (*n, n[0] * p[0] + n[1] * p[1] + n[2] * p[2] + d))
            .max_by(|x, y| x.1.total_cmp(&y.1))
        else {
            break;
        };
        if ahead < -CLEARANCE {
            break;
        }
        let step = ahead + 2.0 * CLEARANCE;
        p = std::array::from_fn(|a| p[a] - step * normal[a]);
    }
    p
}

/// The planes of a convex polytope around `vertices`, facing out: for
/// each of the 26 directions with components in {-1, 0, 1}, the plane
/// with that normal through the vertex farthest along it (a box with its
/// edges and corners cut). A point in front of one is outside the
/// vertices' hull. Far fewer planes than the hull of a dense surface has,
/// for tests run at every step of a joint-umbra proof.
pub(super) fn bounding_planes(vertices: &[GridPoint]) -> Vec<Plane> {
    let mut planes = Vec::with_capacity(26);
    for x in -1..=1_i64 {
        for y in -1..=1_i64 {
            for z in -1..=1_i64 {
                let normal = [x, y, z];
                let along = |p: &GridPoint| {
                    let [px, py, pz] = p.to_i64();
                    x * px + y * py + z * pz
                };
                let Some(farthest) = vertices.iter().max_by_key(|p| along(p)) else {
                    continue;
                };
                planes.extend(Plane::with_normal_through(normal, *farthest));
            }
        }
    }
    planes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_directions_are_a_geodesic_sphere() {
        let d = directions(SUBDIVISIONS);
        assert_eq!(d.len(), direction_count(SUBDIVISIONS));
        for (i, a) in d.iter().enumerate() {
            assert!((a.iter().map(|c| c * c).sum::<f64>() - 1.0).abs() < 1e-12);
            for b in &d[i + 1..] {
                assert!((0..3).any(|k| (a[k] - b[k]).abs() > 1e-6), "{a:?} twice");
            }
        }
    }
}
