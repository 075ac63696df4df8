//! The closed parts of objects' surfaces: polygons joined edge to edge
//! into a surface that every edge of which two of its polygons share,
//! walked once each way, so that it bounds a volume.
//!
//! From a light clear of such a part ([`AreaSource::clear_of`]) a segment
//! that reaches one of its faces turned away from the light has crossed a
//! face turned towards it first, when the part faces out: the faces towards
//! the light cast its whole shadow (`PieceFlags::closed_surface`). The
//! rule holds part by part, so an object that is a closed mesh and a floor
//! in one (a single OBJ object) still has its mesh's faces turned away
//! cast nothing, as a mesh of its own would.
//!
//! [`AreaSource::clear_of`]: crate::AreaSource::clear_of
//!
//! # Example
//!
//! ```
//! use area_shadow::closed_parts;
//! use bsp_core::{ConvexPolygon, GridPoint};
//!
//! let g = |x, y, z| GridPoint::new(x, y, z).unwrap();
//! let tri = |a, b, c| ConvexPolygon::from_grid_points(&[a, b, c], 0).unwrap();
//! // A tetrahedron wound outward, and a lone triangle of the same object.
//! let (o, x, y, z) = (g(0, 0, 0), g(9, 0, 0), g(0, 9, 0), g(0, 0, 9));
//! let polygons = [
//!     tri(o, y, x),
//!     tri(o, x, z),
//!     tri(o, z, y),
//!     tri(x, y, z),
//!     tri(g(20, 0, 0), g(29, 0, 0), g(20, 9, 0)),
//! ];
//! let parts = closed_parts(&polygons, &[0; 5]);
//! assert_eq!(parts.len(), 1);
//! assert_eq!(parts[0].pieces, [0, 1, 2, 3]);
//! assert_eq!(parts[0].six_volume, 9 * 9 * 9);
//! ```

use crate::disjoint_sets::DisjointSets;
use crate::hash::HashMap;
use bsp_core::{ConvexPolygon, GridPoint};
use smallvec::SmallVec;

/// A closed part of an object's surface.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ClosedPart {
    /// Its polygons (indices into the polygons given), ascending.
    pub pieces: Vec<u32>,
    /// Six times the volume it encloses, exactly: positive when its
    /// polygons face out, negative when they face in.
    pub six_volume: i128,
}

impl ClosedPart {
    /// The corners of its polygons (`polygons` being those it was found
    /// in), with repeats: what a light must lie clear of
    /// ([`AreaSource::clear_of`](crate::AreaSource::clear_of)).
    pub fn corners(&self, polygons: &[ConvexPolygon]) -> Vec<GridPoint> {
        self.pieces
            .iter()
            .flat_map(|&k| {
                let polygon = &polygons[k as usize];
                (0..polygon.len()).filter_map(|i| polygon.vertex_grid_point(i))
            })
            .collect()
    }
}

/// The closed parts of the surfaces of `polygons`, `objects[k]` being
/// polygon `k`'s object, ordered by their first polygon. A part is a set of
/// polygons joined across shared edges (an edge joins two polygons of one
/// object that walk it one each way); it is closed when every polygon's
/// corners are grid points and each of its edges is walked once each way,
/// by its polygons and no other of the object's. Polygons of no closed
/// part are left out.
pub fn closed_parts(polygons: &[ConvexPolygon], objects: &[u32]) -> Vec<ClosedPart> {
    let corners: Vec<Option<Vec<GridPoint>>> =
        polygons.iter().map(ConvexPolygon::grid_corners).collect();
    // Each directed edge of an object with the polygons that walk it.
    let mut edges: HashMap<(u32, GridPoint, GridPoint), SmallVec<[usize; 2]>> = HashMap::default();
    for (k, corners) in corners.iter().enumerate() {
        for (a, b) in corners.iter().flat_map(|c| cyclic_pairs(c)) {
            edges.entry((objects[k], a, b)).or_default().push(k);
        }
    }
    let mut parts = DisjointSets::new(polygons.len());
    for (&(object, a, b), owners) in &edges {
        if let ([k], Some([j])) = (
            owners.as_slice(),
            edges.get(&(object, b, a)).map(|o| o.as_slice()),
        ) {
            parts.union(*k as u32, *j as u32);
        }
    }
    // A part is open where a polygon has a corner off the grid, or an edge
    // is walked other than once each way.
    let mut open = vec![false; polygons.len()];
    for (k, corners) in corners.iter().enumerate() {
        if corners.is_none() {
            open[parts.find(k as u32) as usize] = true;
        }
    }
    for (&(object, a, b), owners) in &edges {
        let back = edges.get(&(object, b, a)).map_or(0, |o| o.len());
        if owners.len() != 1 || back != 1 {
            for &k in owners {
                open[parts.find(k as u32) as usize] = true;
            }
        }
    }
    let mut found: HashMap<usize, ClosedPart> = HashMap::default();
    for (k, corners) in corners.iter().enumerate() {
        let root = parts.find(k as u32) as usize;
        if open[root] {
            continue;
        }
        let part = found.entry(root).or_insert_with(|| ClosedPart {
            pieces: Vec::new(),
            six_volume: 0,
        });
        part.pieces.push(k as u32);
        part.six_volume += corners.as_deref().map_or(0, six_volume_under);
    }
    let mut out: Vec<ClosedPart> = found.into_values().collect();
    out.sort_unstable_by_key(|part| part.pieces[0]);
    out
}

fn cyclic_pairs(corners: &[GridPoint]) -> impl Iterator<Item = (GridPoint, GridPoint)> + '_ {
    corners
        .iter()
        .copied()
        .zip(corners.iter().copied().cycle().skip(1))
}

/// Six times the signed volume of the cone from the origin over the
/// polygon `corners` (positive when the polygon faces away from the
/// origin); summed over a closed surface, six times the volume it
/// encloses, positive when it faces out. Exact: grid coordinates are
/// below 2^31, so each term is below 2^95.
fn six_volume_under(corners: &[GridPoint]) -> i128 {
    let v = |p: &GridPoint| [i128::from(p.x), i128::from(p.y), i128::from(p.z)];
    let a = v(&corners[0]);
    corners[1..]
        .windows(2)
        .map(|w| {
            let (b, c) = (v(&w[0]), v(&w[1]));
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_shapes::cuboid;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint::new(x.into(), y.into(), z.into()).unwrap()
    }

    /// The six faces of the box `[lo, hi]`, wound outward (or inward).
    fn cube(lo: [i32; 3], hi: [i32; 3], outward: bool) -> Vec<ConvexPolygon> {
        let faces = cuboid(lo, hi);
        if outward {
            faces
        } else {
            faces.iter().map(ConvexPolygon::flipped).collect()
        }
    }

    #[test]
    fn boxes_are_closed_parts_with_their_volumes_signed_by_winding() {
        let mut polygons = cube([0, 0, 0], [2, 3, 4], true);
        polygons.extend(cube([10, 0, 0], [11, 1, 1], false));
        let parts = closed_parts(&polygons, &[0; 12]);
        assert_eq!(parts.len(), 2);
        assert_eq!(parts[0].pieces, (0..6).collect::<Vec<u32>>());
        assert_eq!(parts[0].six_volume, 6 * 24);
        assert_eq!(parts[1].pieces, (6..12).collect::<Vec<u32>>());
        assert_eq!(parts[1].six_volume, -6);
    }

    #[test]
    fn a_box_with_a_face_missing_doubled_or_of_another_object_is_open() {
        let cube = cube([0, 0, 0], [2, 2, 2], true);
        let floor = ConvexPolygon::from_grid_points(&[g(-9, -1, -9), g(-9, -1, 9), g(9, -1, 9)], 0)
            .unwrap();
        // Missing a face: open; the floor beside it is no part either.
        let mut five = cube[..5].to_vec();
        five.push(floor.clone());
        assert!(closed_parts(&five, &[0; 6]).is_empty());
        // A face twice: its edges are walked three times.
        let mut seven = cube.clone();
        seven.push(cube[0].clone());
        assert!(closed_parts(&seven, &[0; 7]).is_empty());
        // The same box whole, beside the floor: closed.
        let mut whole = cube.clone();
        whole.push(floor);
        let parts = closed_parts(&whole, &[0; 7]);
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].pieces.len(), 6);
        // One face of another object: no edge joins it to the rest.
        assert!(closed_parts(&cube, &[0, 0, 0, 0, 0, 1]).is_empty());
    }

    #[test]
    fn two_boxes_sharing_a_face_in_one_object_are_no_closed_part() {
        // Walked once each way by each box, the shared face's edges are
        // walked twice each way in all: open.
        let mut polygons = cube([0, 0, 0], [2, 2, 2], true);
        polygons.extend(cube([2, 0, 0], [4, 2, 2], true));
        assert!(closed_parts(&polygons, &[0; 12]).is_empty());
        // Of two objects, each is closed.
        let objects: Vec<u32> = (0..12).map(|k| u32::from(k >= 6)).collect();
        assert_eq!(closed_parts(&polygons, &objects).len(), 2);
    }
}
