//! The convex hull of grid points, exactly (incremental, with the
//! kernel's exact side of a grid point against a plane through three).

use crate::hash::HashSet;
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{GridPoint, Plane};

/// The hull's faces: triangles counter-clockwise seen from outside, each
/// with its plane (the hull behind it). A point on a face (not strictly
/// outside the hull so far) is left out, so faces in one plane may meet.
/// `None` when the points do not span a volume.
pub(crate) fn convex_hull(points: &[GridPoint]) -> Option<Vec<([GridPoint; 3], Plane)>> {
    let (a, b, c, d) = first_tetrahedron(points)?;
    let face =
        |x: GridPoint, y: GridPoint, z: GridPoint| Some(([x, y, z], Plane::through(x, y, z)?));
    // Oriented so that the fourth point is behind each face.
    let inward = side_of_point(&Plane::through(a, b, c)?, d) == Side::Front;
    let (b, c) = if inward { (c, b) } else { (b, c) };
    let mut faces = vec![
        face(a, b, c)?,
        face(a, d, b)?,
        face(b, d, c)?,
        face(c, d, a)?,
    ];
    for &p in points {
        let seen: Vec<bool> = faces
            .iter()
            .map(|(_, plane)| side_of_point(plane, p) == Side::Front)
            .collect();
        if !seen.contains(&true) {
            continue;
        }
        // The horizon: edges of seen faces whose other face is not seen.
        let seen_edges: HashSet<(GridPoint, GridPoint)> = faces
            .iter()
            .zip(&seen)
            .filter(|(_, s)| **s)
            .flat_map(|(([x, y, z], _), _)| [(*x, *y), (*y, *z), (*z, *x)])
            .collect();
        let horizon: Vec<(GridPoint, GridPoint)> = seen_edges
            .iter()
            .filter(|(x, y)| !seen_edges.contains(&(*y, *x)))
            .copied()
            .collect();
        let mut kept: Vec<([GridPoint; 3], Plane)> = faces
            .into_iter()
            .zip(seen)
            .filter(|(_, s)| !*s)
            .map(|(f, _)| f)
            .collect();
        for (x, y) in horizon {
            kept.push(face(x, y, p)?);
        }
        faces = kept;
    }
    // A fixed order, whatever the hash sets did.
    faces.sort_unstable_by_key(|(t, _)| *t);
    Some(faces)
}

/// Four points spanning a volume, if there are.
fn first_tetrahedron(points: &[GridPoint]) -> Option<(GridPoint, GridPoint, GridPoint, GridPoint)> {
    let a = *points.first()?;
    let b = *points.iter().find(|&&p| p != a)?;
    let (c, plane) = points
        .iter()
        .find_map(|&p| Plane::through(a, b, p).map(|plane| (p, plane)))?;
    let d = *points
        .iter()
        .find(|&&p| side_of_point(&plane, p) != Side::On)?;
    Some((a, b, c, d))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    #[test]
    fn a_cube_with_inner_and_face_points_has_its_corners_only() {
        let mut points = Vec::new();
        for i in 0..8 {
            points.push(g((i & 1) * 10, (i >> 1 & 1) * 10, (i >> 2 & 1) * 10));
        }
        points.extend([g(5, 5, 5), g(5, 5, 0), g(10, 5, 5), g(3, 7, 2)]);
        points.rotate_left(8);
        let hull = convex_hull(&points).unwrap();
        let mut corners: Vec<GridPoint> = hull.iter().flat_map(|(t, _)| *t).collect();
        corners.sort_unstable();
        corners.dedup();
        // Every corner is a vertex, no inner point is (a point on a face
        // may stay, on the face's plane).
        assert!(points[4..].iter().all(|p| corners.contains(p)));
        assert!(!corners.contains(&g(5, 5, 5)) && !corners.contains(&g(3, 7, 2)));
        for (_, plane) in &hull {
            assert!(
                points
                    .iter()
                    .all(|&p| side_of_point(plane, p) != Side::Front)
            );
        }
        // Every edge is shared by two faces, once each way.
        let edges: Vec<(GridPoint, GridPoint)> = hull
            .iter()
            .flat_map(|([a, b, c], _)| [(*a, *b), (*b, *c), (*c, *a)])
            .collect();
        for &(a, b) in &edges {
            assert_eq!(edges.iter().filter(|e| **e == (b, a)).count(), 1);
        }
    }

    #[test]
    fn flat_points_span_no_hull() {
        assert!(convex_hull(&[g(0, 0, 0), g(1, 0, 0), g(0, 1, 0), g(1, 1, 0)]).is_none());
    }
}
