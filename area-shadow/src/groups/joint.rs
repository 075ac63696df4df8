//! Convex bodies that touch face to face and together make one convex
//! body: two cubes side by side, a row of them, a stack.
//!
//! Each body hides only part of the light from a point beside the seam,
//! and together they hide all of it: the union's umbra is larger than the
//! union of the bodies' umbrae, and exact (planar) when the union is
//! convex, since it is then one convex body's (module docs of `groups`).
//!
//! Two convex bodies `A` and `B` make a convex union when `A` has a face
//! in a plane `S` in which `B` has one facing the other way, every other
//! face of `A` has all of `B` on or behind it, and every other face of `B`
//! all of `A`. Then the intersection `P` of those other faces' half-spaces
//! holds `A` and `B`, and its part on `A`'s side of `S` lies in `A` (which
//! is that side cut by `A`'s other faces), its part on `B`'s side in `B`:
//! `P` is `A` union `B`, and convex. Every test is a side of a grid point
//! against a face's plane, exactly; the union's faces are its vertices'
//! convex hull's.
//!
//! Unions of more bodies are found by joining unions two at a time, among
//! the bodies that touch through such face planes (a connected set); only
//! the largest are kept, as a smaller one's umbra lies in a larger's.
//!
//! Bodies the grid bent (a turned box: its faces' corners rounded off
//! their planes, each face two triangles) are only nearly convex, so no
//! face plane of one is exactly another's; exact ones turned about an
//! axis keep planar faces but may meet at a crease (one's top a grid step
//! off the other's plane). They join by their surfaces instead: two that share corners give up the pieces whose corners are
//! all the other's (the doubled faces they touch by), and what is left of
//! both, if nearly convex ([`Solid::of_surface`]), is their union. Every
//! piece left is a real occluder, so the union hides no more than the
//! scene does.
//!
//! Coplanar pieces of several objects sharing whole edges (two panels side
//! by side) make flat groups and flat unions as an object's pieces do
//! ([`flat_joints`]).

use super::solid::Solid;
use super::{ConvexGroup, FlatUnion, Shape};
use crate::disjoint_sets::DisjointSets;
use crate::hash::{HashMap, HashSet};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, Plane};
use std::collections::{BTreeMap, BTreeSet};

/// The most unions (single bodies included) tried among one connected set
/// of touching bodies: a wall of many bricks finds some of its unions, not
/// all (their umbrae are then smaller than they could be, never wrong).
const MAX_UNIONS: usize = 256;

/// The largest unions of two or more of `bodies` that are one convex body
/// (module docs): per union, the indices of its bodies (ascending) and the
/// union as a group, its pieces all of theirs (ascending). Closed, exactly
/// convex bodies join by their faces; bodies the grid bent (moved in, or
/// closed over a hole) join by their surfaces where they share corners
/// ([`ConvexGroup::joining_corners`]), with each other or with exact
/// ones, when what their surfaces make without the pieces they touch by is
/// nearly convex. Flat groups join
/// none here. The result depends on the bodies' shapes only, not on their
/// order in `bodies` or their indices; unions in order of first body.
pub fn convex_unions(bodies: &[&ConvexGroup]) -> Vec<(Vec<usize>, ConvexGroup)> {
    let solids: Vec<Option<&Solid>> = bodies
        .iter()
        .map(|body| match &body.shape {
            Shape::Solid(solid) if solid.is_closed_and_exact() => Some(solid),
            _ => None,
        })
        .collect();
    // Bodies the grid bent (moved in, or closed over a bent hole) join
    // through their surfaces where they share corners, with each other or
    // with exact ones.
    let bent: Vec<Option<&Solid>> = bodies
        .iter()
        .map(|body| match &body.shape {
            Shape::Solid(solid) if !solid.surface().is_empty() => Some(solid),
            _ => None,
        })
        .collect();
    let exact_unions = touching_sets(&solids)
        .into_iter()
        .flat_map(|set| unions_of(&set, &solids, joined));
    let bent_unions = corner_sets(&bent)
        .into_iter()
        .flat_map(|set| unions_of(&set, &bent, joined_surfaces));
    let mut found: Vec<(Vec<usize>, ConvexGroup)> = exact_unions
        .chain(bent_unions)
        .map(|(members, solid)| {
            let mut pieces: Vec<u32> = members
                .iter()
                .flat_map(|&i| bodies[i].pieces.iter().copied())
                .collect();
            pieces.sort_unstable();
            let group = ConvexGroup {
                pieces,
                shape: Shape::Solid(solid),
            };
            (members, group)
        })
        .collect();
    found.sort_by(|a, b| a.0.cmp(&b.0));
    found
}

/// The flat groups ([`ConvexGroup`], flat) and flat unions ([`FlatUnion`])
/// that coplanar pieces of two or more objects, or facing both ways, make
/// together (two panels side by side, each its own object or one turned
/// over): as [`super::convex_groups`] and [`super::flat_unions`] find
/// them among an object's pieces facing one way, here among the pieces of
/// each plane whatever their objects, each turned to face
/// [`one_way`] (a polygon blocks light whichever side faces it). `objects[k]` is piece `k`'s object,
/// `None` when it casts no shadow. Piece indices are into `pieces`; in
/// order of first piece.
///
/// # Panics
///
/// If `objects` is shorter than `pieces`.
pub fn flat_joints(
    pieces: &[ConvexPolygon],
    objects: &[Option<u32>],
) -> (Vec<ConvexGroup>, Vec<FlatUnion>) {
    let mut by_plane: HashMap<Plane, Vec<usize>> = HashMap::default();
    for (k, piece) in pieces.iter().enumerate() {
        if objects[k].is_some() {
            by_plane
                .entry(one_way(piece.support()))
                .or_default()
                .push(k);
        }
    }
    // Within a plane, the sets of pieces in contact along their edges
    // ([`edge_contact`]), one after another: pieces sharing an edge are in
    // one, and the answer for a set does not depend on what else lies in
    // the plane (a floor under boxes whose bottoms lie inside it).
    let mut planes: Vec<Vec<usize>> = by_plane
        .into_values()
        .flat_map(|ks| touching_boxes(pieces, ks))
        .collect();
    planes.sort_unstable();
    let (mut groups, mut unions) = (Vec::new(), Vec::new());
    for ks in planes {
        let plane = one_way(pieces[ks[0]].support());
        let sub: Vec<ConvexPolygon> = ks
            .iter()
            .map(|&k| match *pieces[k].support() == plane {
                true => pieces[k].clone(),
                false => pieces[k].flipped(),
            })
            .collect();
        let one = vec![Some(0); sub.len()];
        // What an object's own groups do not find: pieces of several
        // objects, or of both orientations.
        let of_several = |members: &[u32]| {
            let first = ks[members[0] as usize];
            members.iter().any(|&m| {
                let k = ks[m as usize];
                objects[k] != objects[first] || pieces[k].support() != pieces[first].support()
            })
        };
        let renumber = |members: &mut Vec<u32>| {
            for m in members.iter_mut() {
                *m = ks[*m as usize] as u32;
            }
        };
        for mut group in super::convex_groups(&sub, &one) {
            if group.is_flat() && of_several(&group.pieces) {
                renumber(&mut group.pieces);
                groups.push(group);
            }
        }
        for mut union in super::flat_unions(&sub, &one) {
            if of_several(&union.pieces) {
                renumber(&mut union.pieces);
                unions.push(union);
            }
        }
    }
    groups.sort_by(|a, b| a.pieces.cmp(&b.pieces));
    unions.sort_by(|a, b| a.pieces.cmp(&b.pieces));
    (groups, unions)
}

/// `plane` turned, if need be, to the one of its two orientations whose
/// normal's first non-zero component is positive: the way
/// [`flat_joints`] turns coplanar pieces to face.
pub fn one_way(plane: &Plane) -> Plane {
    let normal = plane.normal();
    match normal.iter().find(|&&c| c != 0) {
        Some(&c) if c < 0 => plane.flipped(),
        _ => *plane,
    }
}

/// Whether two convex polygons with grid-point vertices touch along their
/// boundaries: a vertex of one is a vertex of the other or lies inside
/// one of its edges (pieces sharing an edge, or meeting in a T-junction,
/// do). Exact; `false` when a vertex is no grid point.
pub fn edge_contact(a: &ConvexPolygon, b: &ConvexPolygon) -> bool {
    let outline = |p: &ConvexPolygon| -> Option<Vec<GridPoint>> {
        (0..p.len()).map(|k| p.vertex_grid_point(k)).collect()
    };
    let (Some(a), Some(b)) = (outline(a), outline(b)) else {
        return false;
    };
    let on = |p: GridPoint, of: &[GridPoint]| {
        of.contains(&p)
            || (0..of.len())
                .any(|k| super::strictly_inside(p, of[k], of[(k + 1) % of.len()]).is_some())
    };
    a.iter().any(|&p| on(p, &b)) || b.iter().any(|&p| on(p, &a))
}

/// The pieces `ks` (ascending) in sets connected by contact along their
/// edges ([`edge_contact`], among those whose bounding boxes meet), each
/// ascending.
fn touching_boxes(pieces: &[ConvexPolygon], ks: Vec<usize>) -> Vec<Vec<usize>> {
    // Positions in `ks`, by their boxes' least x: swept along x, each
    // piece meets only those still open at its start.
    let boxes: Vec<Bounds> = ks
        .iter()
        .map(|&k| grid_bounds((0..pieces[k].len()).filter_map(|i| pieces[k].vertex_grid_point(i))))
        .collect();
    let mut order: Vec<usize> = (0..ks.len()).collect();
    order.sort_by_key(|&i| (boxes[i].0[0], i));
    let mut sets = DisjointSets::new(ks.len());
    let mut open: Vec<usize> = Vec::new();
    for i in order {
        open.retain(|&o| boxes[o].1[0] >= boxes[i].0[0]);
        for &o in &open {
            if meet(&boxes[i], &boxes[o]) && edge_contact(&pieces[ks[i]], &pieces[ks[o]]) {
                sets.union(i as u32, o as u32);
            }
        }
        open.push(i);
    }
    grouped(&mut sets, (0..ks.len()).map(|i| (i, ks[i])))
}

/// The sets of two or more solids connected by touching faces (a face
/// plane of one that another has facing the other way, their bounding
/// boxes meeting: bodies at one height far apart share face planes), each
/// ascending, in order of first solid.
fn touching_sets(solids: &[Option<&Solid>]) -> Vec<Vec<usize>> {
    let mut by_face: HashMap<Plane, Vec<usize>> = HashMap::default();
    for (i, solid) in solids.iter().enumerate() {
        let Some(solid) = solid else { continue };
        let faces: HashSet<Plane> = solid.faces().iter().copied().collect();
        for face in faces {
            by_face.entry(face).or_default().push(i);
        }
    }
    let boxes: Vec<Option<Bounds>> = solids
        .iter()
        .map(|solid| Some(grid_bounds((*solid)?.vertices().iter().copied())))
        .collect();
    let mut sets = DisjointSets::new(solids.len());
    for (face, holders) in &by_face {
        let Some(facing) = by_face.get(&face.flipped()) else {
            continue;
        };
        for &i in holders {
            for &j in facing {
                if let (Some(a), Some(b)) = (&boxes[i], &boxes[j])
                    && meet(a, b)
                {
                    sets.union(i as u32, j as u32);
                }
            }
        }
    }
    let present = (0..solids.len()).filter(|&i| solids[i].is_some());
    grouped(&mut sets, present.map(|i| (i, i)))
}

/// A box of grid points: least and greatest coordinates.
type Bounds = ([i32; 3], [i32; 3]);

/// The bounding box of `points` (at least one).
fn grid_bounds(points: impl Iterator<Item = GridPoint>) -> Bounds {
    points.fold(([i32::MAX; 3], [i32::MIN; 3]), |(lo, hi), p| {
        let c = [p.x, p.y, p.z];
        (
            std::array::from_fn(|a| lo[a].min(c[a])),
            std::array::from_fn(|a| hi[a].max(c[a])),
        )
    })
}

/// Whether two closed boxes meet (touching counts).
fn meet(a: &Bounds, b: &Bounds) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

/// The sets of two or more `items` (union-find position, value) by their
/// positions' sets, each ascending by value, in order of least value.
fn grouped(
    sets: &mut DisjointSets,
    items: impl Iterator<Item = (usize, usize)>,
) -> Vec<Vec<usize>> {
    let mut by_root: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
    for (i, value) in items {
        by_root.entry(sets.find(i as u32)).or_default().push(value);
    }
    let mut out: Vec<Vec<usize>> = by_root
        .into_values()
        .filter(|set| set.len() > 1)
        .map(|mut set| {
            set.sort_unstable();
            set
        })
        .collect();
    out.sort_unstable();
    out
}

/// The largest convex unions of two or more of the solids `set` (indices
/// into `solids`, ascending), each with its members ascending.
fn unions_of(
    set: &[usize],
    solids: &[Option<&Solid>],
    join: fn(&Solid, &Solid) -> Option<Solid>,
) -> Vec<(Vec<usize>, Solid)> {
    // Joined in an order of the solids' shapes, so that which unions the
    // limit leaves out does not depend on how the bodies were numbered.
    let mut order: Vec<usize> = set.to_vec();
    order.sort_by_key(|&i| solids[i].map(Solid::vertices));
    let mut found: Vec<(BTreeSet<usize>, Solid)> = order
        .iter()
        .filter_map(|&i| Some((BTreeSet::from([i]), solids[i]?.clone())))
        .collect();
    let mut seen: HashSet<BTreeSet<usize>> = found.iter().map(|(m, _)| m.clone()).collect();
    let mut next = 1;
    while next < found.len() && found.len() < MAX_UNIONS {
        for other in 0..next {
            let (a, b) = (&found[next], &found[other]);
            if !a.0.is_disjoint(&b.0) {
                continue;
            }
            let members: BTreeSet<usize> = a.0.union(&b.0).copied().collect();
            if seen.contains(&members) {
                continue;
            }
            if let Some(joined) = join(&a.1, &b.1) {
                seen.insert(members.clone());
                found.push((members, joined));
                if found.len() == MAX_UNIONS {
                    break;
                }
            }
        }
        next += 1;
    }
    let largest: Vec<(BTreeSet<usize>, Solid)> = found
        .iter()
        .filter(|(m, _)| m.len() > 1)
        .filter(|(m, _)| {
            !found
                .iter()
                .any(|(n, _)| n.len() > m.len() && m.is_subset(n))
        })
        .cloned()
        .collect();
    largest
        .into_iter()
        .map(|(members, solid)| (members.into_iter().collect(), solid))
        .collect()
}

/// `a` union `b` as one solid, if it is convex (module docs).
fn joined(a: &Solid, b: &Solid) -> Option<Solid> {
    let behind = |faces: &[Plane], skip: Plane, points: &[GridPoint]| {
        faces
            .iter()
            .filter(|f| **f != skip)
            .all(|f| points.iter().all(|&p| side_of_point(f, p) != Side::Front))
    };
    let convex = a.faces().iter().any(|s| {
        b.faces().contains(&s.flipped())
            && behind(a.faces(), *s, b.vertices())
            && behind(b.faces(), s.flipped(), a.vertices())
    });
    if !convex {
        return None;
    }
    let points: Vec<GridPoint> = a.vertices().iter().chain(b.vertices()).copied().collect();
    Solid::of_hull(&points, true)
}

/// The sets of two or more solids connected by shared corners of their
/// surfaces ([`Solid::surface`]), each ascending, in order of first solid.
fn corner_sets(solids: &[Option<&Solid>]) -> Vec<Vec<usize>> {
    let mut by_corner: BTreeMap<GridPoint, Vec<usize>> = BTreeMap::new();
    for (i, solid) in solids.iter().enumerate() {
        let Some(solid) = solid else { continue };
        let corners: BTreeSet<GridPoint> = surface_corners(solid);
        for corner in corners {
            by_corner.entry(corner).or_default().push(i);
        }
    }
    let mut sets = DisjointSets::new(solids.len());
    for holders in by_corner.values() {
        for pair in holders.windows(2) {
            sets.union(pair[0] as u32, pair[1] as u32);
        }
    }
    let present = (0..solids.len()).filter(|&i| solids[i].is_some());
    grouped(&mut sets, present.map(|i| (i, i)))
}

/// The corners of a solid's surface pieces.
pub(super) fn surface_corners(solid: &Solid) -> BTreeSet<GridPoint> {
    solid
        .surface()
        .iter()
        .flat_map(|(outline, _)| outline.iter().copied())
        .collect()
}

/// `a` union `b` as one nearly convex solid made from their surfaces,
/// when they share an edge's corners at least: the pieces of each whose
/// corners are all the other's (the faces they touch by, doubled) are left
/// out, and what remains, closed or open, goes to [`Solid::of_surface`] or
/// [`Solid::of_open_surface`]. Every piece left is a real occluder, so the
/// body found blocks no more light than the scene does.
fn joined_surfaces(a: &Solid, b: &Solid) -> Option<Solid> {
    if a.is_closed_and_exact() && b.is_closed_and_exact() && joined(a, b).is_some() {
        // Exact bodies join by their faces ([`joined`]) when they can:
        // only a crease the grid left between their faces brings them here.
        return None;
    }
    let (ca, cb) = (surface_corners(a), surface_corners(b));
    // Two corners at least (an edge) in common.
    ca.intersection(&cb).nth(1)?;
    let kept = |solid: &Solid, other: &BTreeSet<GridPoint>| -> Vec<(Vec<GridPoint>, Plane)> {
        solid
            .surface()
            .iter()
            .filter(|(outline, _)| !outline.iter().all(|p| other.contains(p)))
            .cloned()
            .collect()
    };
    let mut pieces = kept(a, &cb);
    pieces.extend(kept(b, &ca));
    let supports: Vec<Plane> = pieces.iter().map(|(_, s)| *s).collect();
    if supports.iter().all(|s| *s == supports[0]) {
        // Coplanar: flat joints' business.
        return None;
    }
    let outlines: Vec<&[GridPoint]> = pieces.iter().map(|(o, _)| o.as_slice()).collect();
    Solid::of_surface(&outlines, &supports).or_else(|| Solid::of_open_surface(&outlines, &supports))
}

#[cfg(test)]
mod tests;
