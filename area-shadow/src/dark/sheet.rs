//! Open sheets as bodies: pieces of one object joined edge to edge (a
//! tent of triangles, a bent quad, an open box) that tile faces of their
//! convex hull. A point behind every hull face no piece covers
//! (the open faces) sees only covered faces, so a segment from it that
//! meets the hull crosses a piece: the sheet blocks such segments as a
//! [`Body`] with those open faces does. Where the pieces meet, their hidden
//! parts of the light join with no overlap, and no proof that takes them
//! one by one gets across the seam; as one body it needs none.

use crate::hash::HashMap;
use std::collections::BTreeMap;

use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, Plane};

use super::Body;
use crate::disjoint_sets::DisjointSets;
use crate::groups::hull::convex_hull;

/// The most pieces a sheet may have (its hull costs more than it saves
/// past that, and large sheets are seldom convex).
const MAX_SHEET_PIECES: usize = 64;

/// The sheets among `pieces` (those with an owner, joined edge to edge
/// with pieces of the same owner) that make a body with open faces, and
/// the objects whose pieces, all together, tile faces of their hull, open
/// or closed (pieces meeting in T-junctions, a box with a face cut in
/// strips, make no edge-matched surface and so no convex group): each
/// with its pieces (indices, increasing) and the body, in order of first
/// piece. (An object that is also a convex group is left to the caller.)
pub fn sheet_bodies(pieces: &[ConvexPolygon], owners: &[Option<u32>]) -> Vec<(Vec<u32>, Body)> {
    let (sheets, open) = components(pieces, owners);
    let mut bodies: Vec<(Vec<u32>, Body)> = sheets
        .iter()
        .filter(|sheet| (2..=MAX_SHEET_PIECES).contains(&sheet.len()))
        .filter_map(|sheet| {
            let members: Vec<&ConvexPolygon> = sheet.iter().map(|&k| &pieces[k as usize]).collect();
            let body = sheet_body(&members, false)?;
            Some((sheet.clone(), body))
        })
        .collect();
    let mut objects: BTreeMap<u32, (Vec<u32>, usize)> = BTreeMap::new();
    for sheet in &sheets {
        let (members, count) = objects
            .entry(owners[sheet[0] as usize].expect("sheets have owners"))
            .or_default();
        members.extend_from_slice(sheet);
        *count += 1;
    }
    for (mut members, count) in objects.into_values() {
        members.sort_unstable();
        // One sheet closed edge to edge is the convex groups' to take.
        let closed = count == 1 && members.iter().all(|&k| !open[k as usize]);
        if closed
            || !(2..=MAX_SHEET_PIECES).contains(&members.len())
            || bodies.iter().any(|(sheet, _)| *sheet == members)
        {
            continue;
        }
        let polygons: Vec<&ConvexPolygon> = members.iter().map(|&k| &pieces[k as usize]).collect();
        if let Some(body) = sheet_body(&polygons, true) {
            bodies.push((members, body));
        }
    }
    bodies.sort_unstable_by_key(|(members, _)| members[0]);
    bodies
}

/// The pieces joined edge to edge (an edge of one the reverse of an edge
/// of another with the same owner), as lists of indices in increasing
/// order, ordered by their first piece; and per piece, whether it has an
/// edge joined to none. Pieces whose corners are not all grid points join
/// nothing.
fn components(pieces: &[ConvexPolygon], owners: &[Option<u32>]) -> (Vec<Vec<u32>>, Vec<bool>) {
    let mut edges: HashMap<(GridPoint, GridPoint), u32> = HashMap::default();
    let mut outlines: Vec<Option<Vec<GridPoint>>> = Vec::with_capacity(pieces.len());
    for (k, piece) in pieces.iter().enumerate() {
        let outline = owners.get(k).copied().flatten().and(piece.grid_corners());
        if let Some(c) = &outline {
            for i in 0..c.len() {
                edges.insert((c[i], c[(i + 1) % c.len()]), k as u32);
            }
        }
        outlines.push(outline);
    }
    let mut sets = DisjointSets::new(pieces.len());
    let mut open = vec![false; pieces.len()];
    for (k, outline) in outlines.iter().enumerate() {
        let Some(c) = outline else { continue };
        for i in 0..c.len() {
            let Some(&other) = edges.get(&(c[(i + 1) % c.len()], c[i])) else {
                open[k] = true;
                continue;
            };
            if owners[other as usize] != owners[k] {
                open[k] = true;
            } else {
                sets.union(k as u32, other);
            }
        }
    }
    let mut by_root: HashMap<u32, Vec<u32>> = HashMap::default();
    for k in 0..pieces.len() as u32 {
        if outlines[k as usize].is_some() {
            by_root.entry(sets.find(k)).or_default().push(k);
        }
    }
    let mut sheets: Vec<Vec<u32>> = by_root.into_values().collect();
    sheets.sort_unstable_by_key(|s| s[0]);
    (sheets, open)
}

/// The body of a sheet whose pieces tile faces of the hull of their
/// corners (each piece in one face, the pieces of a face apart and their
/// areas adding up to its area), with the faces no piece covers open;
/// `None` otherwise, or when no face is open and `closed` is not allowed.
fn sheet_body(pieces: &[&ConvexPolygon], closed: bool) -> Option<Body> {
    let points: Vec<GridPoint> = pieces
        .iter()
        .flat_map(|p| (0..p.len()).filter_map(|i| p.vertex_grid_point(i)))
        .collect();
    // The hull's faces: its triangles grouped by plane, with their vector
    // areas (twice, in grid units: exact integers) summed, and the pieces
    // in each.
    let mut faces: Vec<(Plane, [i128; 3], Vec<usize>)> = Vec::new();
    for (triangle, plane) in convex_hull(&points)? {
        let area = vector_area(&triangle);
        match faces.iter_mut().find(|(p, ..)| p.is_coincident(&plane)) {
            Some((_, sum, _)) => *sum = [0, 1, 2].map(|k| sum[k] + area[k]),
            None => faces.push((plane, area, Vec::new())),
        }
    }
    for (k, piece) in pieces.iter().enumerate() {
        faces
            .iter_mut()
            .find(|(plane, ..)| plane.is_coincident(piece.support()))?
            .2
            .push(k);
    }
    for (_, area, members) in &faces {
        if !members.is_empty() && !tiles(area, members.iter().map(|&k| pieces[k]))? {
            return None;
        }
    }
    let open: Vec<Plane> = faces
        .iter()
        .filter(|(.., members)| members.is_empty())
        .map(|(plane, ..)| *plane)
        .collect();
    if open.is_empty() && !closed {
        return None;
    }
    let all = faces.iter().map(|(plane, ..)| *plane).collect();
    Body::new(all, open, pieces)
}

/// Whether convex polygons in one face of a hull (its vector area
/// `face`) tile it: no two overlap, and their areas add up to its. (Each
/// lies in the face: its corners are points of the hull in the face's
/// plane.) `None` for a polygon whose corners are not all grid points.
fn tiles<'a>(face: &[i128; 3], pieces: impl Iterator<Item = &'a ConvexPolygon>) -> Option<bool> {
    let pieces: Vec<(&ConvexPolygon, Vec<GridPoint>)> = pieces
        .map(|p| p.grid_corners().map(|c| (p, c)))
        .collect::<Option<_>>()?;
    // The areas are all along the face's normal: one component of the
    // largest tells their sizes.
    let axis = (0..3).max_by_key(|&k| face[k].unsigned_abs())?;
    let total: u128 = pieces
        .iter()
        .map(|(_, c)| vector_area(c)[axis].unsigned_abs())
        .sum();
    if total != face[axis].unsigned_abs() {
        return Some(false);
    }
    // Convex polygons in one plane are apart when an edge of one has the
    // other on or outside its line.
    let apart = |(a, _): &(&ConvexPolygon, Vec<GridPoint>),
                 (_, b): &(&ConvexPolygon, Vec<GridPoint>)| {
        a.edges()
            .any(|edge| b.iter().all(|&p| side_of_point(edge, p) != Side::Back))
    };
    Some((0..pieces.len()).all(|i| {
        (i + 1..pieces.len())
            .all(|j| apart(&pieces[i], &pieces[j]) || apart(&pieces[j], &pieces[i]))
    }))
}

/// Twice the vector area of a polygon of grid points (exact).
fn vector_area(points: &[GridPoint]) -> [i128; 3] {
    let mut sum = [0_i128; 3];
    for i in 0..points.len() {
        let (p, q) = (points[i].to_i64(), points[(i + 1) % points.len()].to_i64());
        let [px, py, pz] = p.map(i128::from);
        let [qx, qy, qz] = q.map(i128::from);
        sum[0] += py * qz - pz * qy;
        sum[1] += pz * qx - px * qz;
        sum[2] += px * qy - py * qx;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: i64, z: i64) -> GridPoint {
        GridPoint::new(x, 0, z).unwrap()
    }

    fn triangle(points: [GridPoint; 3]) -> ConvexPolygon {
        ConvexPolygon::from_grid_points(&points, 0).unwrap()
    }

    #[test]
    fn pieces_tile_a_face_only_apart_and_adding_up() {
        let square = vector_area(&[g(0, 0), g(0, 2), g(2, 2), g(2, 0)]);
        let a = triangle([g(0, 0), g(0, 2), g(2, 0)]);
        let rest = triangle([g(2, 0), g(0, 2), g(2, 2)]);
        assert_eq!(tiles(&square, [&a, &rest].into_iter()), Some(true));
        // As large together, but overlapping (and leaving a gap).
        let across = triangle([g(2, 0), g(0, 0), g(2, 2)]);
        assert_eq!(tiles(&square, [&a, &across].into_iter()), Some(false));
        // Apart, but short of the face.
        assert_eq!(tiles(&square, [&a].into_iter()), Some(false));
    }
}
