//! Occluders that hide a light together, as one convex body.
//!
//! Chin & Feiner's umbra volume belongs to one polygon: where it alone
//! hides all of the light. A body made of several polygons (a triangulated
//! sphere, a box whose faces were split, a quad given as two triangles)
//! hides all of the light from a region that no single polygon of it does,
//! and every point there sees none of the light: FORMATS.md's umbra.
//!
//! For a convex body `O` and a convex light `L` that region is exact and
//! planar. Write `Far_v(O) = { v + t (q - v) : q in O, t >= 1 }` for what
//! `O` hides from a point `v` outside it. A point `p` outside `O` sees none
//! of `L` exactly when it lies in `Far_v(O)` for every *vertex* `v` of `L`:
//! if the segments from `p` to the vertices `v_i` meet `O` at
//! `q_i = p + s_i (v_i - p)`, the segment to `x = sum l_i v_i` meets `O` at
//! the convex combination of the `q_i` with weights `l_i / s_i` (scaled to
//! sum to one). Each `Far_v(O)` is convex: the cone from `v` over `O`
//! (bounded by planes through `v` and an edge of `O`, with `O` behind),
//! cut by the planes of the faces of `O` that `v` sees (the ray from `v`
//! enters `O` through one of them). So the umbra is an intersection of
//! half-spaces, and of those planes only the ones with all of `L` on or
//! behind them bound it: a plane through `v` with another light vertex `w`
//! strictly in front holds all of `Far_w(O)` strictly behind, except `O`'s
//! edge in it, so it carries no facet. Every plane is a plane through three
//! grid points.
//!
//! Groups are found exactly, per object, among edge-connected pieces
//! (a directed edge between two grid points matched by its reverse):
//!
//! - **flat**: pieces in one plane, facing one way, each interior edge
//!   matched once, whose unmatched edges close into one convex cycle. As
//!   2-chains the pieces and that polygon have the same boundary, and a
//!   chain in a plane is fixed by its boundary, so the pieces cover the
//!   polygon once and nothing else;
//! - **solid**: every directed edge matched by its reverse exactly once (a
//!   closed surface) and every vertex on or behind every piece's plane (or
//!   on or in front of every one: a surface facing in blocks light all the
//!   same). The pieces then lie on the boundary of the vertices' convex
//!   hull, all facing out (or all in), and as a closed 2-cycle there they
//!   cover all of it. A closed surface that the grid's rounding left a
//!   few units from convex stands for a convex body inside it (module
//!   `solid`), whose umbra is part of the surface's; so does a closed
//!   surface really concave (a bumpy sphere), for a convex core of its
//!   kernel (module `kernel`), when it has one, and one with no kernel
//!   (a torus) for several convex cores inside it, each in the local
//!   kernel of a point (module `cores`): a group each, of the same
//!   pieces.
//!
//! - **open solid**: a surface closed but for one face (its unmatched
//!   edges close into one planar convex cycle) that, closed by that face,
//!   is a solid as above. From outside it blocks light as the solid does
//!   (a segment through the solid crosses its boundary twice, at most once
//!   in the hole's plane), so its umbra is the solid's outside the solid,
//!   in parts ([`ConvexGroup::umbra_parts`]); from inside, light comes in
//!   through the hole. A quad the grid bent, cut into two triangles,
//!   closes likewise into a thin tetrahedron by the other two triangles,
//!   under a light on one side of both (module `solid`).
//! - **flat union** ([`FlatUnion`], module `flat_union`): pieces as for a
//!   flat group whose cycles bound a region that is not convex: a simple
//!   outline, concave or with holes (a concave input polygon cut into
//!   convex pieces, a frame). Its umbra is its convex hull's with the
//!   pockets' penumbrae taken out (the holes are pockets too), in convex
//!   parts.
//! - **section** ([`section_unions`], module `section`): a closed surface
//!   that is no convex body also stands for plane regions inside it, the
//!   widest sections along each axis, inset, rounded to grid points and
//!   checked exactly inside; each is a flat union of the surface's
//!   pieces, cast under the lights facing its axis.
//!
//! Anything else (closed bodies where no core is found, concave open ones,
//! twice-open bodies, a face shared by two bodies) forms no group, and
//! its umbra stays the union of its pieces' umbrae.
//!
//! Closed convex bodies (of any objects) that touch face to face and make
//! one convex body together join into it ([`convex_unions`], module
//! `joint`); separate bodies whose union is not convex hide the light
//! together behind quadric (EEE) boundaries in general, and get nothing.

use crate::AreaSource;
use crate::disjoint_sets::DisjointSets;
use crate::hash::{HashMap, HashSet};
use crate::volumes::volume_planes;
use bsp_core::{ConvexPolygon, GridPoint, Plane};
use solid::Solid;

mod closed;
mod cores;
mod flat_union;
pub(crate) mod hull;
mod joint;
mod kernel;
mod section;
mod solid;
mod winding;

pub use flat_union::FlatUnion;
pub use joint::{convex_unions, edge_contact, flat_joints, one_way};
pub use winding::winding_number;

/// The most side tests (pieces times vertices) spent checking that one
/// closed surface is convex; bigger surfaces form no group. About a
/// 16k-triangle sphere.
pub const MAX_SOLID_WORK: usize = 1 << 26;

/// What a [`ConvexGroup`] blocks light as ([`ConvexGroup::blocker`]).
#[derive(Debug, Clone)]
pub enum Blocker<'a> {
    /// A convex polygon (coplanar pieces covering it once).
    Polygon(&'a ConvexPolygon),
    /// A convex body, its boundary made of the pieces (and open faces).
    Body(crate::dark::Body),
}

/// Pieces that block light together as one convex body.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexGroup {
    /// The pieces' indices, ascending.
    pub pieces: Vec<u32>,
    shape: Shape,
}

#[derive(Debug, Clone, PartialEq)]
enum Shape {
    /// Coplanar pieces covering this convex polygon once.
    Flat(ConvexPolygon),
    /// Pieces covering the boundary of a convex polyhedron.
    Solid(Solid),
}

impl ConvexGroup {
    /// Whether the group is flat (a convex polygon cut into pieces).
    pub fn is_flat(&self) -> bool {
        matches!(self.shape, Shape::Flat(_))
    }

    /// Whether the group is the whole boundary of a convex polyhedron, its
    /// own solid (closed, not moved in): a segment from a point of it into
    /// the solid leaves the solid through another of its pieces.
    pub fn is_closed_convex(&self) -> bool {
        matches!(&self.shape, Shape::Solid(solid) if solid.is_closed_and_exact())
    }

    /// The planes of the group's umbra volume under `light`, each with the
    /// volume behind it: where the body hides all of the light. `None` when
    /// it has none: the body touches or crosses the light's plane, or (flat)
    /// the light touches or crosses the body's plane.
    pub fn umbra_planes(&self, light: &AreaSource) -> Option<Vec<Plane>> {
        match &self.shape {
            Shape::Flat(polygon) => volume_planes(polygon, light).umbra,
            // An open surface's is given in parts (`umbra_parts`).
            Shape::Solid(solid) if solid.is_capped() => None,
            Shape::Solid(solid) => solid.umbra_planes(light),
        }
    }

    /// The umbra of a solid group that holds `light` in: the light lies in
    /// the body (every vertex on or behind every face; in a face's plane
    /// only facing into the body), so no light leaves it and every point
    /// outside sees none. In convex parts, each with the volume behind its
    /// planes: in front of each face. Empty when the light is not held in
    /// (the usual case, where [`Self::umbra_planes`] applies), for a flat
    /// group, and for a nearly convex surface (a body moved in is not what
    /// holds the light).
    pub fn enclosing_umbra(&self, light: &AreaSource) -> Vec<Vec<Plane>> {
        match &self.shape {
            Shape::Flat(_) => Vec::new(),
            Shape::Solid(solid) => solid.enclosing_umbra(light),
        }
    }

    /// The group's umbra where it is no one convex volume, in convex parts
    /// each with the volume behind its planes: of a body that holds the
    /// light in ([`Self::enclosing_umbra`]), and of an open surface one
    /// face short (module `solid`: closed by that face it blocks light as
    /// the body does from outside, so its umbra is the body's outside the
    /// body, a part in front of each face). Empty otherwise.
    pub fn umbra_parts(&self, light: &AreaSource) -> Vec<Vec<Plane>> {
        let Shape::Solid(solid) = &self.shape else {
            return Vec::new();
        };
        if !solid.is_capped() {
            return solid.enclosing_umbra(light);
        }
        if solid.caps_let_through(light) {
            return Vec::new();
        }
        let Some(umbra) = solid.umbra_planes(light) else {
            return Vec::new();
        };
        // Outside the surface's hull, not just outside the body: a body
        // moved in leaves part of the surface's inside, which light
        // reaches through the hole, outside it.
        solid
            .hull()
            .iter()
            .map(|face| {
                let mut part = umbra.clone();
                part.push(face.flipped());
                part
            })
            .collect()
    }

    /// What the group blocks light as, for joint-umbra proofs
    /// ([`crate::dark`]): a flat group's convex polygon, or a solid's
    /// body (`None` for a body the grid's rounding moved in). `pieces`
    /// are those the group's indices refer to.
    pub fn blocker(&self, pieces: &[ConvexPolygon]) -> Option<Blocker<'_>> {
        match &self.shape {
            Shape::Flat(polygon) => Some(Blocker::Polygon(polygon)),
            Shape::Solid(solid) => {
                let surface: Vec<&ConvexPolygon> = self
                    .pieces
                    .iter()
                    .map(|&k| pieces.get(k as usize))
                    .collect::<Option<_>>()?;
                solid.blocking_body(&surface).map(Blocker::Body)
            }
        }
    }

    /// A solid group that closes an open surface (a cup) as a shell for
    /// joint-umbra proofs ([`crate::dark::Body::shell`]), besides its
    /// pieces; `None` for other groups.
    pub fn shell(&self) -> Option<crate::dark::Body> {
        match &self.shape {
            Shape::Solid(solid) => solid.shell(),
            Shape::Flat(_) => None,
        }
    }

    /// The planes of a solid group's faces, each with the body behind it
    /// (planes may repeat); empty for a flat group.
    pub fn faces(&self) -> &[Plane] {
        match &self.shape {
            Shape::Flat(_) => &[],
            Shape::Solid(solid) => solid.faces(),
        }
    }

    /// The corners through which the body joins other bodies by their
    /// surfaces ([`convex_unions`], when the grid bent one of them): its
    /// surface's, ascending; none for a flat group or a body made as a
    /// hull (a union).
    pub fn joining_corners(&self) -> Vec<GridPoint> {
        match &self.shape {
            Shape::Solid(solid) => joint::surface_corners(solid).into_iter().collect(),
            Shape::Flat(_) => Vec::new(),
        }
    }

    /// The support plane `support` of one of the group's pieces, turned to
    /// face out of the body (a closed surface may face in); a flat group's
    /// as it is.
    pub fn outward(&self, support: &Plane) -> Plane {
        match &self.shape {
            Shape::Flat(_) => *support,
            Shape::Solid(solid) => solid.outward(support),
        }
    }

    /// The planes of a solid group's penumbra volume under `light`, each
    /// with the volume behind it: the points from which the body hides
    /// part or all of the light, for any receiver (the volume is convex:
    /// it is where no plane through the point separates the body from the
    /// light). `None` for a flat group (its polygon's volume planes are
    /// the group's), for a nearly convex surface that stands for a body
    /// moved in (that body's penumbra would miss some of the surface's),
    /// and when the body touches or crosses the light's plane.
    pub fn penumbra_planes(&self, light: &AreaSource) -> Option<Vec<Plane>> {
        match &self.shape {
            Shape::Flat(_) => None,
            Shape::Solid(solid) => solid.penumbra_planes(light),
        }
    }
}

/// The convex groups among `pieces`: `objects[k]` is the object of piece
/// `k`, or `None` when it casts no shadow (it joins no group). Pieces group
/// only within their object. Groups of one piece are left out (its own
/// umbra volume is the group's); the list is in order of first piece.
/// A closed surface with several cores (module `cores`) makes a group of
/// its pieces for each.
///
/// # Panics
///
/// If `objects` is shorter than `pieces`.
pub fn convex_groups(pieces: &[ConvexPolygon], objects: &[Option<u32>]) -> Vec<ConvexGroup> {
    let (outlines, groups) = edge_connected(pieces, objects);
    let flats = t_junction_flats(pieces, objects, &outlines);
    // A flat convex polygon whose pieces meet in T-junctions takes the
    // place of the groups its pieces make by whole edges (its umbra holds
    // theirs), unless one of those reaches beyond it.
    let mut taken: HashMap<u32, usize> = HashMap::default();
    for (f, flat) in flats.iter().enumerate() {
        for &k in &flat.pieces {
            taken.insert(k, f);
        }
    }
    let spill = |members: &[u32]| {
        members
            .iter()
            .filter_map(|k| taken.get(k))
            .any(|&f| members.iter().any(|k| taken.get(k) != Some(&f)))
    };
    let blocked: HashSet<usize> = groups
        .iter()
        .filter(|members| spill(members))
        .flat_map(|members| members.iter().filter_map(|k| taken.get(k).copied()))
        .collect();
    let groups: Vec<Vec<u32>> = groups
        .into_iter()
        .filter(|members| blocked_or_free(members, &taken, &blocked))
        .collect();
    let mut out: Vec<ConvexGroup> = groups
        .into_iter()
        .flat_map(|members| {
            let (outlines, supports) = members_of(&members, &outlines, pieces);
            // A closed surface with no kernel may stand for several
            // cores, a group each.
            let shapes: Vec<Shape> = if supports.iter().all(|s| *s == supports[0]) {
                flat_shape(&outlines, &supports[0])
                    .map(Shape::Flat)
                    .into_iter()
                    .collect()
            } else {
                let mut solids = Solid::of_closed_surface(&outlines, &supports);
                if solids.is_empty() {
                    solids.extend(Solid::of_open_surface(&outlines, &supports));
                }
                solids.into_iter().map(Shape::Solid).collect()
            };
            shapes.into_iter().map(move |shape| ConvexGroup {
                pieces: members.clone(),
                shape,
            })
        })
        .collect();
    out.extend(
        flats
            .into_iter()
            .enumerate()
            .filter(|(f, _)| !blocked.contains(f))
            .map(|(_, flat)| flat),
    );
    out.sort_by(|a, b| a.pieces.cmp(&b.pieces));
    out
}

/// The most holes a surface closed into a shell may have
/// ([`holed_shells`]): each bent one doubles the ways to close them.
const MAX_HOLES: usize = 4;

/// The most pieces of a surface that does not close for which
/// [`holed_shells`] tries it less one input polygon's pieces.
const MAX_TRIMMED_PIECES: usize = 32;

/// Shells ([`crate::dark::Body::shell`]) of the open surfaces the convex
/// groups do not close: edge-connected pieces of one object (`objects`
/// as for [`convex_groups`]) whose unmatched edges close into two cycles
/// or more (a tube open at both ends), or into one that is neither a
/// planar convex polygon nor four corners (a lidded cup's slot the grid
/// bent), each closed by itself or a fan of triangles, the surface then
/// convex or nearly so. Where the whole does not close, the pieces less
/// those of one input polygon (`inputs[k]` is piece `k`'s) may: a cup
/// whose lid meets its walls in T-junctions is a cup without the lid.
/// Each with its pieces (ascending), in order of first piece. For
/// joint-umbra proofs only: such a surface gets no umbra volume (a
/// segment may pass in at one hole and out at another).
///
/// # Panics
///
/// If `objects` or `inputs` is shorter than `pieces`.
pub fn holed_shells(
    pieces: &[ConvexPolygon],
    objects: &[Option<u32>],
    inputs: &[u32],
) -> Vec<(Vec<u32>, crate::dark::Body)> {
    let (outlines, groups) = edge_connected(pieces, objects);
    let closing = |members: &[u32], whole: bool| -> Closing {
        let member_outlines: Vec<&[GridPoint]> = members
            .iter()
            .map(|&k| outlines[k as usize].as_deref().expect("grid outline"))
            .collect();
        let Some(holes) = boundary_cycles(&member_outlines) else {
            return Closing::Not { open: false };
        };
        if holes.len() > MAX_HOLES {
            return Closing::Not { open: true };
        }
        let supports: Vec<Plane> = members
            .iter()
            .map(|&k| *pieces[k as usize].support())
            .collect();
        if whole
            && holes.len() == 1
            && Solid::capped(&member_outlines, &supports, &holes, false).is_some()
        {
            return Closing::ByGroups;
        }
        match Solid::capped(&member_outlines, &supports, &holes, true).and_then(|s| s.shell()) {
            Some(shell) => Closing::Shell(shell),
            None => Closing::Not { open: true },
        }
    };
    groups
        .into_iter()
        .filter_map(|members| {
            match closing(&members, true) {
                Closing::Shell(shell) => return Some((members, shell)),
                Closing::Not { open: true } if members.len() <= MAX_TRIMMED_PIECES => {}
                _ => return None,
            }
            let mut dropped: Vec<u32> = members.iter().map(|&k| inputs[k as usize]).collect();
            dropped.sort_unstable();
            dropped.dedup();
            if dropped.len() < 3 {
                return None;
            }
            dropped.into_iter().find_map(|input| {
                let rest: Vec<u32> = members
                    .iter()
                    .copied()
                    .filter(|&k| inputs[k as usize] != input)
                    .collect();
                match closing(&rest, false) {
                    Closing::Shell(shell) => Some((rest, shell)),
                    _ => None,
                }
            })
        })
        .collect()
}

/// How the open surface of some pieces closes ([`holed_shells`]).
enum Closing {
    /// The convex groups close it (one hole, no fan needed).
    ByGroups,
    /// Into a shell.
    Shell(crate::dark::Body),
    /// Not: it is closed already (`open: false`), or its holes are too
    /// many or close into no convex surface.
    Not { open: bool },
}

/// Whether an edge-connected group stays: its pieces are in no T-junction
/// flat, or only in flats that give way to it (`blocked`).
fn blocked_or_free(members: &[u32], taken: &HashMap<u32, usize>, blocked: &HashSet<usize>) -> bool {
    members
        .iter()
        .filter_map(|k| taken.get(k))
        .all(|f| blocked.contains(f))
}

/// The flat convex groups that coplanar pieces of one object, facing one
/// way, make when some of them meet in a T-junction (an edge running past
/// another piece's corner, which whole-edge groups miss): their unmatched
/// edges, cut at such corners, close into one convex cycle, which they
/// then cover once ([`flat_unions`], the same sets, takes the cycles that
/// are not convex). `outlines` as [`edge_connected`] gives them.
fn t_junction_flats(
    pieces: &[ConvexPolygon],
    objects: &[Option<u32>],
    outlines: &[Option<Vec<GridPoint>>],
) -> Vec<ConvexGroup> {
    let refined = with_t_junctions(pieces, objects, outlines.to_vec());
    connected_sets(&refined, objects)
        .into_iter()
        .filter_map(|members| {
            // Only sets that a T-junction joins.
            if members
                .iter()
                .all(|&k| refined[k as usize] == outlines[k as usize])
            {
                return None;
            }
            let support = *pieces[members[0] as usize].support();
            if members
                .iter()
                .any(|&k| *pieces[k as usize].support() != support)
            {
                return None;
            }
            let cycle_outlines: Vec<&[GridPoint]> = members
                .iter()
                .map(|&k| refined[k as usize].as_deref().expect("grid outline"))
                .collect();
            let polygon = flat_shape(&cycle_outlines, &support)?;
            Some(ConvexGroup {
                pieces: members,
                shape: Shape::Flat(polygon),
            })
        })
        .collect()
}

/// The flat unions among `pieces` that are no convex polygon (those are
/// [`convex_groups`]): pieces of one object (`objects` as there) in one
/// plane, facing one way, edge-connected (an edge running past another
/// piece's corner, a T-junction, taken as cut there), each interior edge
/// matched once, whose unmatched edges close into one simple cycle that
/// is not convex.
/// As for a flat convex group, the pieces then cover the polygon of that
/// cycle once and nothing else. In order of first piece.
///
/// # Panics
///
/// If `objects` is shorter than `pieces`.
pub fn flat_unions(pieces: &[ConvexPolygon], objects: &[Option<u32>]) -> Vec<FlatUnion> {
    let outlines = with_t_junctions(pieces, objects, grid_outlines(pieces, objects));
    let groups = connected_sets(&outlines, objects);
    groups
        .into_iter()
        .filter_map(|members| {
            let support = *pieces[members[0] as usize].support();
            if members
                .iter()
                .any(|&k| *pieces[k as usize].support() != support)
            {
                return None;
            }
            let outlines: Vec<&[GridPoint]> = members
                .iter()
                .map(|&k| outlines[k as usize].as_deref().expect("grid outline"))
                .collect();
            let cycles = boundary_cycles(&outlines)?;
            FlatUnion::new(members, cycles, support)
        })
        .collect()
}

/// Flat unions inside the closed surfaces of edge-connected pieces of
/// one object (`objects` as for [`convex_groups`]) that are no convex
/// body: sections through them along each axis (module `section`), whose
/// umbrae are parts of the surfaces' (each casts only under lights whose
/// plane's normal is nearest to its axis). In order of first piece.
///
/// # Panics
///
/// If `objects` is shorter than `pieces`.
pub fn section_unions(pieces: &[ConvexPolygon], objects: &[Option<u32>]) -> Vec<FlatUnion> {
    let (outlines, groups) = edge_connected(pieces, objects);
    groups
        .into_iter()
        .flat_map(|members| {
            let (outlines, supports) = members_of(&members, &outlines, pieces);
            match Solid::concave_faces(&outlines, &supports) {
                Some(faces) => section::sections(&outlines, &faces, &members),
                None => Vec::new(),
            }
        })
        .collect()
}

/// The grid outlines and the planes of the pieces `members` of an
/// edge-connected set (`outlines` by piece, each set's pieces' present).
fn members_of<'a>(
    members: &[u32],
    outlines: &'a [Option<Vec<GridPoint>>],
    pieces: &[ConvexPolygon],
) -> (Vec<&'a [GridPoint]>, Vec<Plane>) {
    members
        .iter()
        .map(|&k| {
            let outline = outlines[k as usize].as_deref().expect("grid outline");
            (outline, *pieces[k as usize].support())
        })
        .unzip()
}

/// The grid outlines of the pieces (of those that join groups), and the
/// sets of at least two pieces of one object connected by directed edges
/// matched by their reverses, each ascending, in order of first piece.
#[allow(clippy::type_complexity)] // (the two results, named where used)
fn edge_connected(
    pieces: &[ConvexPolygon],
    objects: &[Option<u32>],
) -> (Vec<Option<Vec<GridPoint>>>, Vec<Vec<u32>>) {
    let outlines = grid_outlines(pieces, objects);
    let groups = connected_sets(&outlines, objects);
    (outlines, groups)
}

/// Each piece's vertices, if all are grid points and it has an object.
fn grid_outlines(pieces: &[ConvexPolygon], objects: &[Option<u32>]) -> Vec<Option<Vec<GridPoint>>> {
    (0..pieces.len())
        .map(|k| {
            objects[k]?;
            pieces[k].grid_corners()
        })
        .collect()
}

/// The most pieces of one object in one plane whose edges are searched
/// for T-junctions.
const MAX_T_JUNCTION_PIECES: usize = 64;

/// `outlines` with, on each edge, the vertices of the other pieces of its
/// object in its plane (same orientation) that lie strictly inside it: an
/// L of two quads, one's edge running past the other's corner, then
/// shares an edge like pieces cut from one polygon.
fn with_t_junctions(
    pieces: &[ConvexPolygon],
    objects: &[Option<u32>],
    mut outlines: Vec<Option<Vec<GridPoint>>>,
) -> Vec<Option<Vec<GridPoint>>> {
    let mut by_plane: HashMap<(u32, Plane), Vec<usize>> = HashMap::default();
    for (k, outline) in outlines.iter().enumerate() {
        if let (Some(_), Some(object)) = (outline, objects[k]) {
            by_plane
                .entry((object, *pieces[k].support()))
                .or_default()
                .push(k);
        }
    }
    for ks in by_plane.into_values() {
        if ks.len() < 2 || ks.len() > MAX_T_JUNCTION_PIECES {
            continue;
        }
        let mut points: Vec<GridPoint> = ks
            .iter()
            .flat_map(|&k| outlines[k].iter().flatten().copied())
            .collect();
        points.sort_unstable();
        points.dedup();
        for &k in &ks {
            let Some(outline) = outlines[k].take() else {
                continue;
            };
            let mut refined = Vec::with_capacity(outline.len());
            for (a, b) in directed_edges(&outline) {
                refined.push(a);
                let mut inside: Vec<(i128, GridPoint)> = points
                    .iter()
                    .filter_map(|&p| strictly_inside(p, a, b).map(|t| (t, p)))
                    .collect();
                inside.sort_unstable();
                refined.extend(inside.into_iter().map(|(_, p)| p));
            }
            outlines[k] = Some(refined);
        }
    }
    outlines
}

/// Where `p` lies on the open segment `ab`, if it does: its position along
/// it (scaled by |b - a|^2), exactly.
pub(super) fn strictly_inside(p: GridPoint, a: GridPoint, b: GridPoint) -> Option<i128> {
    let (u, v) = (difference(a, b), difference(a, p));
    let dot = |x: [i128; 3], y: [i128; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let t = dot(u, v);
    (cross(u, v) == [0; 3] && 0 < t && t < dot(u, u)).then_some(t)
}

/// `q - p`, exactly.
pub(super) fn difference(p: GridPoint, q: GridPoint) -> [i128; 3] {
    [(q.x, p.x), (q.y, p.y), (q.z, p.z)].map(|(a, b)| i128::from(a) - i128::from(b))
}

/// `u x v`, exactly for differences of grid points (below 2^51).
pub(super) fn cross(u: [i128; 3], v: [i128; 3]) -> [i128; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

/// The sets of at least two pieces of one object connected by directed
/// edges of `outlines` matched by their reverses, each ascending, in
/// order of first piece.
fn connected_sets(outlines: &[Option<Vec<GridPoint>>], objects: &[Option<u32>]) -> Vec<Vec<u32>> {
    let mut by_edge: HashMap<(u32, GridPoint, GridPoint), Vec<u32>> = HashMap::default();
    for (k, outline) in outlines.iter().enumerate() {
        let (Some(outline), Some(object)) = (outline, objects[k]) else {
            continue;
        };
        for (a, b) in directed_edges(outline) {
            by_edge.entry((object, a, b)).or_default().push(k as u32);
        }
    }
    let mut sets = DisjointSets::new(outlines.len());
    for (&(object, a, b), ks) in &by_edge {
        if let Some(others) = by_edge.get(&(object, b, a)) {
            for &k in ks.iter().chain(others) {
                sets.union(ks[0], k);
            }
        }
    }
    let mut members: HashMap<u32, Vec<u32>> = HashMap::default();
    for (k, outline) in outlines.iter().enumerate() {
        if outline.is_some() {
            members
                .entry(sets.find(k as u32))
                .or_default()
                .push(k as u32);
        }
    }
    let mut groups: Vec<Vec<u32>> = members.into_values().filter(|m| m.len() > 1).collect();
    groups.sort_unstable_by_key(|m| m[0]);
    groups
}

pub(super) fn directed_edges(
    outline: &[GridPoint],
) -> impl Iterator<Item = (GridPoint, GridPoint)> + '_ {
    let n = outline.len();
    (0..n).map(move |i| (outline[i], outline[(i + 1) % n]))
}

/// Directed edges of the pieces with their counts; `None` if one repeats.
pub(super) fn edge_set(outlines: &[&[GridPoint]]) -> Option<HashMap<(GridPoint, GridPoint), u32>> {
    let mut edges = HashMap::default();
    for (f, outline) in outlines.iter().enumerate() {
        for edge in directed_edges(outline) {
            if edges.insert(edge, f as u32).is_some() {
                return None;
            }
        }
    }
    Some(edges)
}

/// The convex polygon coplanar pieces (one orientation) cover once, if
/// their unmatched edges close into one convex cycle.
fn flat_shape(outlines: &[&[GridPoint]], support: &Plane) -> Option<ConvexPolygon> {
    let cycle = boundary_cycle(outlines)?;
    let polygon = ConvexPolygon::from_grid_points(&cycle, 0).ok()?;
    (polygon.support() == support).then_some(polygon)
}

/// The one cycle the pieces' unmatched directed edges close into (each
/// vertex left by at most one), from its least vertex; `None` if a
/// directed edge repeats or they make no single cycle.
pub(super) fn boundary_cycle(outlines: &[&[GridPoint]]) -> Option<Vec<GridPoint>> {
    let mut cycles = boundary_cycles(outlines)?;
    (cycles.len() == 1).then(|| cycles.pop()).flatten()
}

/// The cycles the pieces' unmatched directed edges close into (each
/// vertex left by at most one), each from its least vertex, in order of
/// those; `None` if a directed edge repeats or a vertex is left twice.
fn boundary_cycles(outlines: &[&[GridPoint]]) -> Option<Vec<Vec<GridPoint>>> {
    let edges = edge_set(outlines)?;
    let mut next: HashMap<GridPoint, GridPoint> = HashMap::default();
    for &(a, b) in edges.keys() {
        if !edges.contains_key(&(b, a)) && next.insert(a, b).is_some() {
            return None;
        }
    }
    let mut starts: Vec<GridPoint> = next.keys().copied().collect();
    starts.sort_unstable();
    let mut seen: HashSet<GridPoint> = HashSet::default();
    let mut cycles = Vec::new();
    for start in starts {
        if seen.contains(&start) {
            continue;
        }
        let mut cycle = vec![start];
        seen.insert(start);
        let mut at = *next.get(&start)?;
        while at != start {
            if !seen.insert(at) {
                return None;
            }
            cycle.push(at);
            at = *next.get(&at)?;
        }
        cycles.push(cycle);
    }
    (!cycles.is_empty()).then_some(cycles)
}
