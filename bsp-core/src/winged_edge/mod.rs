//! Winged-edge meshes (Baumgart) with exact vertices and `slotmap` keys.
//!
//! A planar subdivision of convex faces, the structure that Chrysanthou &
//! Slater keep their discontinuity meshes in: faces are split by planes,
//! merged across edges and condensed again as objects move, and keys stay
//! valid across deletions.
//!
//! # Conventions
//!
//! Walking a face counter-clockwise, seen from the front of its support
//! plane, an edge with the face on its **left** is traversed from `start` to
//! `end`, an edge with the face on its **right** from `end` to `start`. The
//! wings of an edge are its predecessor and successor in those two walks
//! (`left_prev`, `left_next`, `right_prev`, `right_next`). A side with no
//! face (`None`) is the outside; its edges form closed walks too, linked by
//! the same wings.
//!
//! Each edge stores a *line plane*: with the faces' support plane it cuts
//! out the edge's line, and it is oriented with the left face behind it,
//! like a [`ConvexPolygon`]'s edge planes. Vertices are grid points or
//! implicit points; every decision goes through [`predicates`](crate::predicates).

use crate::predicates::{self, PointFilter, Side};
use crate::{ConvexPolygon, Error, GridPoint, ImplicitPoint, Plane};
pub use planes::PlaneRef;
use planes::PlaneTable;
use slotmap::{SlotMap, new_key_type};

mod build;
mod check;
mod edit;
mod graft;
mod planes;

new_key_type! {
    /// Handle of a vertex.
    pub struct VertexKey;
    /// Handle of an edge.
    pub struct EdgeKey;
    /// Handle of a face.
    pub struct FaceKey;
}

/// Where a vertex is, exactly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VertexPosition {
    /// An input grid point.
    Grid(GridPoint),
    /// The intersection of three planes.
    Implicit(ImplicitPoint),
}

impl VertexPosition {
    /// Side of `plane` the vertex lies on, exactly.
    pub fn side(&self, plane: &Plane) -> Side {
        match self {
            VertexPosition::Grid(p) => predicates::side_of_point(plane, *p),
            VertexPosition::Implicit(p) => p.side(plane),
        }
    }

    /// Coordinates in grid units (for output, or to filter a decision by
    /// [`Self::coordinate_error`]).
    pub fn to_f64(&self) -> [f64; 3] {
        match self {
            VertexPosition::Grid(p) => p.to_f64(),
            VertexPosition::Implicit(p) => p.to_f64(),
        }
    }

    /// A bound on how far a coordinate `c` of [`Self::to_f64`] lies from the
    /// exact one, in grid units, with room for the rounding of a
    /// comparison against it: below `2^-20` when taken from the filter
    /// data, else three roundings of the exact homogeneous coordinates'
    /// quotient (`predicates::implicit_to_f64`), each half an ulp.
    pub fn coordinate_error(c: f64) -> f64 {
        1.0 / f64::from(1_u32 << 19) + c.abs() * 4.0 * f64::EPSILON
    }

    /// Whether both are the same point, exactly.
    pub fn same_point(&self, other: &VertexPosition) -> bool {
        match (self, other) {
            (VertexPosition::Grid(a), VertexPosition::Grid(b)) => a == b,
            (VertexPosition::Implicit(a), VertexPosition::Implicit(b)) => a.same_point(b),
            (VertexPosition::Grid(g), VertexPosition::Implicit(p))
            | (VertexPosition::Implicit(p), VertexPosition::Grid(g)) => p
                .planes()
                .iter()
                .all(|plane| predicates::side_of_point(plane, *g) == Side::On),
        }
    }
}

/// A vertex, as read from a mesh ([`WingedMesh::vertex`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertex {
    /// Its position.
    pub position: VertexPosition,
}

/// A vertex's position as the mesh keeps it: an implicit point's planes
/// are numbers in the mesh's plane table (module `planes`).
#[derive(Debug, Clone, Copy, PartialEq)]
enum StoredPosition {
    Grid(GridPoint),
    Implicit {
        planes: [PlaneRef; 3],
        filter: PointFilter,
    },
}

/// A vertex as the mesh keeps it, with one edge incident to it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct StoredVertex {
    at: StoredPosition,
    edge: EdgeKey,
}

/// An edge with its wings.
///
/// Laid out in this order (`repr(C)`) so that a walk around a face or a
/// vertex, which reads the ends, the faces and the next edges, touches one
/// cache line of the edge's 128-byte slot, the one that also holds the
/// slot's version: the line plane and the previous edges, which edits use,
/// fill the other.
#[derive(Debug, Clone, PartialEq)]
#[repr(C)]
pub struct Edge<E> {
    /// The plane through the edge's line, the left face behind it.
    pub line: Plane,
    left_prev: EdgeKey,
    right_prev: EdgeKey,
    /// First vertex (left face walks from here).
    pub start: VertexKey,
    /// Second vertex.
    pub end: VertexKey,
    /// Face on the left (walked `start -> end`), or the outside.
    pub left: Option<FaceKey>,
    /// Face on the right (walked `end -> start`), or the outside.
    pub right: Option<FaceKey>,
    left_next: EdgeKey,
    right_next: EdgeKey,
    /// Whether the right face lies in front of `line` (always so between
    /// faces of one plane; between faces of two planes the line plane need
    /// not separate them).
    right_in_front: bool,
    /// The user's payload.
    pub data: E,
}

/// One edge of a face's walk ([`WingedMesh::face_sides`]).
#[derive(Debug, Clone, Copy)]
pub struct FaceSide<'a, E> {
    /// The edge's key.
    pub key: EdgeKey,
    /// The edge.
    pub edge: &'a Edge<E>,
    /// The face on the edge's other side (`None`: the outside).
    pub across: Option<FaceKey>,
    /// The vertex the walk leaves the edge from (counter-clockwise).
    pub start: VertexKey,
    /// The vertex the walk reaches at the edge's other end.
    pub end: VertexKey,
}

/// A face: its support plane (by number, [`WingedMesh::face_support`])
/// and one edge of its boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct Face<F> {
    /// The number of the plane the face lies in among the mesh's support
    /// planes (its front is the face's front): a subdivision of one
    /// polygon, whose faces all lie in one plane, keeps it once, not a
    /// copy per face (a third of a face's bytes, over a million faces on a
    /// big receiver).
    plane: u32,
    edge: EdgeKey,
    /// The user's payload.
    pub data: F,
}

/// What [`WingedMesh::split_face`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceSplit {
    /// The plane does not cut the face's interior; the face lies on this
    /// side of it (`On` never: a face has area).
    NotSplit(Side),
    /// The face was cut: the parts behind and in front of the plane, and
    /// the new edge between them.
    Split {
        /// The part behind the plane (it keeps the face's key).
        back: FaceKey,
        /// The part in front.
        front: FaceKey,
        /// The edge along the plane.
        edge: EdgeKey,
    },
}

/// A winged-edge mesh of convex faces; see the module docs.
#[derive(Debug, Clone)]
pub struct WingedMesh<F = (), E = ()> {
    vertices: SlotMap<VertexKey, StoredVertex>,
    /// The planes of the faces' supports and the implicit vertices, each
    /// once.
    planes: PlaneTable,
    edges: SlotMap<EdgeKey, Edge<E>>,
    faces: SlotMap<FaceKey, Face<F>>,
    /// The faces' support planes, each once, held in `planes` for the
    /// mesh's life (every cut's vertices name their face's).
    supports: Vec<PlaneRef>,
}

impl<F: Clone, E: Clone> WingedMesh<F, E> {
    /// Number of vertices, edges and faces.
    pub fn counts(&self) -> (usize, usize, usize) {
        (self.vertices.len(), self.edges.len(), self.faces.len())
    }

    /// The faces.
    pub fn faces(&self) -> impl Iterator<Item = (FaceKey, &Face<F>)> {
        self.faces.iter()
    }

    /// The edges.
    pub fn edges(&self) -> impl Iterator<Item = (EdgeKey, &Edge<E>)> {
        self.edges.iter()
    }

    /// The plane face `f` lies in; its front is the face's front.
    pub fn face_support(&self, f: FaceKey) -> Option<&Plane> {
        self.faces.get(f).map(|face| self.support(face))
    }

    /// The support plane of a face of the mesh.
    fn support(&self, face: &Face<F>) -> &Plane {
        self.planes.get(self.supports[face.plane as usize])
    }

    /// A face.
    pub fn face(&self, f: FaceKey) -> Option<&Face<F>> {
        self.faces.get(f)
    }

    /// A face's payload, mutably.
    pub fn face_data_mut(&mut self, f: FaceKey) -> Option<&mut F> {
        self.faces.get_mut(f).map(|face| &mut face.data)
    }

    /// An edge.
    pub fn edge(&self, e: EdgeKey) -> Option<&Edge<E>> {
        self.edges.get(e)
    }

    /// An edge's payload, mutably. An edge made by [`split_face`](Self::split_face)
    /// starts with a copy of a neighbour's payload.
    pub fn edge_data_mut(&mut self, e: EdgeKey) -> Option<&mut E> {
        self.edges.get_mut(e).map(|edge| &mut edge.data)
    }

    /// A vertex (its position made from the plane table: a copy).
    pub fn vertex(&self, v: VertexKey) -> Option<Vertex> {
        self.vertices.get(v).map(|stored| Vertex {
            position: self.position_of(&stored.at),
        })
    }

    /// Whether `v` is a vertex of the mesh.
    pub fn contains_vertex(&self, v: VertexKey) -> bool {
        self.vertices.contains_key(v)
    }

    /// Side of `plane` vertex `v` lies on, exactly (`None`: not a vertex).
    /// Cheaper than [`Self::vertex`]'s `side`: the planes are read only
    /// when the filter cannot decide.
    pub fn vertex_side(&self, v: VertexKey, plane: &Plane) -> Option<Side> {
        self.vertices
            .get(v)
            .map(|stored| self.side_at(&stored.at, plane))
    }

    /// Number of distinct planes in the mesh's table: its faces' supports,
    /// those its implicit vertices lie on, and those held by
    /// [`Self::hold_plane`].
    pub fn plane_count(&self) -> usize {
        self.planes.len()
    }

    /// Holds `plane` in the mesh's table of planes (one count more; added
    /// if new), for a structure of the caller's that names planes the
    /// mesh's vertices lie on (a BSP's splitting lines, say) by 4 bytes
    /// instead of 48. Each hold must be released once
    /// ([`Self::release_plane`]); until then [`Self::plane`] reads it.
    pub fn hold_plane(&mut self, plane: &Plane) -> PlaneRef {
        self.planes.intern(*plane)
    }

    /// Holds a plane held already once more.
    pub fn retain_plane(&mut self, r: PlaneRef) -> PlaneRef {
        self.planes.retain(r)
    }

    /// Releases one hold of [`Self::hold_plane`] or [`Self::retain_plane`].
    pub fn release_plane(&mut self, r: PlaneRef) {
        self.planes.release(r);
    }

    /// A plane held in the table.
    #[inline]
    pub fn plane(&self, r: PlaneRef) -> &Plane {
        self.planes.get(r)
    }

    /// Side of `q` a stored position lies on, exactly.
    #[inline]
    fn side_at(&self, at: &StoredPosition, q: &Plane) -> Side {
        match at {
            StoredPosition::Grid(p) => predicates::side_of_point(q, *p),
            StoredPosition::Implicit { planes, filter } => match filter.side(q) {
                Some(side) => side,
                None => predicates::exact_side_of_implicit(planes.map(|r| self.planes.get(r)), q),
            },
        }
    }

    /// The position a stored one stands for.
    fn position_of(&self, at: &StoredPosition) -> VertexPosition {
        match at {
            StoredPosition::Grid(p) => VertexPosition::Grid(*p),
            StoredPosition::Implicit { planes, filter } => VertexPosition::Implicit(
                ImplicitPoint::from_parts(planes.map(|r| *self.planes.get(r)), *filter),
            ),
        }
    }

    /// The position of vertex `v` (which must be one).
    fn position(&self, v: VertexKey) -> VertexPosition {
        self.position_of(&self.vertices[v].at)
    }

    /// A position kept: an implicit point's planes go into the table.
    fn store(&mut self, position: VertexPosition) -> StoredPosition {
        match position {
            VertexPosition::Grid(p) => StoredPosition::Grid(p),
            VertexPosition::Implicit(point) => {
                let [a, b, c] = *point.planes();
                StoredPosition::Implicit {
                    planes: [
                        self.planes.intern(a),
                        self.planes.intern(b),
                        self.planes.intern(c),
                    ],
                    filter: *point.filter(),
                }
            }
        }
    }

    /// A new vertex at `position`, its incident edge `edge`.
    fn insert_vertex(&mut self, position: VertexPosition, edge: EdgeKey) -> VertexKey {
        let at = self.store(position);
        self.vertices.insert(StoredVertex { at, edge })
    }

    /// Removes vertex `v`, releasing its planes.
    fn remove_vertex(&mut self, v: VertexKey) {
        if let Some(StoredVertex {
            at: StoredPosition::Implicit { planes, .. },
            ..
        }) = self.vertices.remove(v)
        {
            for r in planes {
                self.planes.release(r);
            }
        }
    }

    /// The successor of `e` in the walk of `side` (one of its faces).
    fn next_in(&self, e: EdgeKey, side: Option<FaceKey>) -> EdgeKey {
        let edge = &self.edges[e];
        if edge.left == side {
            edge.left_next
        } else {
            edge.right_next
        }
    }

    fn set_next(&mut self, e: EdgeKey, side: Option<FaceKey>, next: EdgeKey) {
        let edge = &mut self.edges[e];
        if edge.left == side {
            edge.left_next = next;
        } else {
            edge.right_next = next;
        }
    }

    fn set_prev(&mut self, e: EdgeKey, side: Option<FaceKey>, prev: EdgeKey) {
        let edge = &mut self.edges[e];
        if edge.left == side {
            edge.left_prev = prev;
        } else {
            edge.right_prev = prev;
        }
    }

    fn set_side(&mut self, e: EdgeKey, from: Option<FaceKey>, to: Option<FaceKey>) {
        let edge = &mut self.edges[e];
        if edge.left == from {
            edge.left = to;
        } else {
            edge.right = to;
        }
    }

    /// The vertex an edge's walk around `side` starts from.
    fn walk_start(&self, e: EdgeKey, side: Option<FaceKey>) -> VertexKey {
        let edge = &self.edges[e];
        if edge.left == side {
            edge.start
        } else {
            edge.end
        }
    }

    /// The edges around a face, counter-clockwise.
    pub fn face_edges(&self, f: FaceKey) -> Vec<EdgeKey> {
        self.walk(self.faces[f].edge, Some(f))
    }

    /// The edges around a face, counter-clockwise, each with its key, its
    /// ends in the walk's order and the face across it (`None`: the
    /// outside), without allocating: the walk for code that looks at a
    /// face's neighbours (floods over a big mesh, where a list per face
    /// costs more than the walk).
    pub fn face_sides(&self, f: FaceKey) -> impl Iterator<Item = FaceSide<'_, E>> + '_ {
        self.sides_from(self.faces[f].edge, Some(f))
    }

    /// The walk around `side` (a face, or the outside) from edge `first`.
    fn sides_from(
        &self,
        first: EdgeKey,
        side: Option<FaceKey>,
    ) -> impl Iterator<Item = FaceSide<'_, E>> + '_ {
        let mut at = Some(first);
        let mut steps = 0;
        std::iter::from_fn(move || {
            let key = at?;
            let edge = &self.edges[key];
            let (next, across, start, end) = if edge.left == side {
                (edge.left_next, edge.right, edge.start, edge.end)
            } else {
                (edge.right_next, edge.left, edge.end, edge.start)
            };
            // A broken cycle (never in a valid mesh) still ends.
            steps += 1;
            at = (next != first && steps <= self.edges.len()).then_some(next);
            Some(FaceSide {
                key,
                edge,
                across,
                start,
                end,
            })
        })
    }

    fn walk(&self, first: EdgeKey, side: Option<FaceKey>) -> Vec<EdgeKey> {
        self.sides_from(first, side).map(|s| s.key).collect()
    }

    /// The vertices around a face, counter-clockwise.
    pub fn face_vertices(&self, f: FaceKey) -> Vec<VertexKey> {
        self.face_sides(f).map(|side| side.start).collect()
    }

    /// The edges around a vertex, in the order of the faces around it.
    pub fn vertex_edges(&self, v: VertexKey) -> Vec<EdgeKey> {
        let first = self.vertices[v].edge;
        let mut out = Vec::with_capacity(8);
        let mut e = first;
        loop {
            out.push(e);
            // Around v: leave along the face walk that arrives at v on e.
            let edge = &self.edges[e];
            let side = if edge.end == v { edge.left } else { edge.right };
            e = self.next_in(e, side);
            if e == first || out.len() > self.edges.len() {
                return out;
            }
        }
    }

    /// The vertices (positions made from the plane table: copies).
    pub fn vertices(&self) -> impl Iterator<Item = (VertexKey, Vertex)> + '_ {
        self.vertices.iter().map(|(v, stored)| {
            (
                v,
                Vertex {
                    position: self.position_of(&stored.at),
                },
            )
        })
    }

    /// The faces around a vertex (the outside as `None`), in the order of
    /// [`vertex_faces`](Self::vertex_faces), without allocating.
    pub fn faces_around(&self, v: VertexKey) -> impl Iterator<Item = Option<FaceKey>> + '_ {
        let first = self.vertices[v].edge;
        let mut at = Some(first);
        let mut steps = 0;
        std::iter::from_fn(move || {
            let e = at?;
            let edge = &self.edges[e];
            let side = if edge.end == v { edge.left } else { edge.right };
            let next = self.next_in(e, side);
            steps += 1;
            at = (next != first && steps <= self.edges.len()).then_some(next);
            Some(side)
        })
    }

    /// The faces around a vertex (the outside as `None`).
    pub fn vertex_faces(&self, v: VertexKey) -> Vec<Option<FaceKey>> {
        self.vertex_edges(v)
            .into_iter()
            .map(|e| {
                let edge = &self.edges[e];
                if edge.end == v { edge.left } else { edge.right }
            })
            .collect()
    }

    /// The plane of edge `e` oriented with `side` (one of its faces) behind.
    fn edge_plane_for(&self, e: EdgeKey, side: Option<FaceKey>) -> Plane {
        Self::oriented_line(&self.edges[e], side)
    }

    /// The plane of `edge` oriented with `side` (one of its faces) behind.
    fn oriented_line(edge: &Edge<E>, side: Option<FaceKey>) -> Plane {
        if edge.left == side || !edge.right_in_front {
            edge.line
        } else {
            edge.line.flipped()
        }
    }

    /// The face's edge planes, counter-clockwise, each with the face behind
    /// it; collinear edges give one plane (the first one's: two planes
    /// through one line may bound edges along it).
    fn face_planes(&self, f: FaceKey) -> Vec<Plane> {
        let mut planes: Vec<Plane> = Vec::with_capacity(8);
        // Whether an edge of the walk lies along `plane` (its start, the end
        // of the edge before it, does when that one lies in it): tested at
        // its end vertex.
        let along =
            |end: VertexKey, plane: &Plane| self.side_at(&self.vertices[end].at, plane) == Side::On;
        let mut first_end = None;
        for side in self.face_sides(f) {
            let end = side.end;
            first_end.get_or_insert(end);
            let plane = Self::oriented_line(side.edge, Some(f));
            match planes.last() {
                Some(last) if *last == plane || along(end, last) => {}
                _ => planes.push(plane),
            }
        }
        if planes.len() > 1
            && let (Some(last), Some(end)) = (planes.last(), first_end)
            && (planes.first() == Some(last) || along(end, last))
        {
            planes.pop();
        }
        planes
    }

    /// The face as a convex polygon with source `source`.
    pub fn face_polygon(&self, f: FaceKey, source: u32) -> Result<ConvexPolygon, Error> {
        ConvexPolygon::from_planes(*self.support(&self.faces[f]), &self.face_planes(f), source)
    }

    /// The face's outline in grid units, counter-clockwise (output only).
    pub fn face_outline(&self, f: FaceKey) -> Vec<[f64; 3]> {
        self.face_vertices(f)
            .into_iter()
            .map(|v| self.position(v).to_f64())
            .collect()
    }

    /// The support plane of an edge's faces.
    fn support_of(&self, e: EdgeKey) -> Plane {
        let edge = &self.edges[e];
        let f = edge.left.or(edge.right).expect("an edge has a face");
        *self.support(&self.faces[f])
    }

    fn prev_in(&self, e: EdgeKey, side: Option<FaceKey>) -> EdgeKey {
        let edge = &self.edges[e];
        if edge.left == side {
            edge.left_prev
        } else {
            edge.right_prev
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Edge;
    use std::mem::{offset_of, size_of};

    /// A vertex names its planes in the table: with its filter data and
    /// edge, 64 bytes (200 with the planes by value).
    #[test]
    fn a_vertex_takes_a_cache_line() {
        assert_eq!(size_of::<super::StoredVertex>(), 64);
    }

    /// An edge's slot is 128 bytes (the edge, then the slot's version), and
    /// the fields a walk reads share its second 64 bytes with the version.
    #[test]
    fn a_walk_reads_one_half_of_an_edge_slot() {
        assert_eq!(size_of::<Edge<()>>(), 120);
        for offset in [
            offset_of!(Edge<()>, start),
            offset_of!(Edge<()>, end),
            offset_of!(Edge<()>, left),
            offset_of!(Edge<()>, right),
            offset_of!(Edge<()>, left_next),
            offset_of!(Edge<()>, right_next),
        ] {
            assert!((64..120).contains(&offset), "a walked field at {offset}");
        }
    }
}
