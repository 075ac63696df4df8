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

use crate::predicates::{self, Side};
use crate::{ConvexPolygon, Error, GridPoint, ImplicitPoint, Plane};
use slotmap::{SlotMap, new_key_type};

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

    /// Coordinates in grid units (for output only).
    pub fn to_f64(&self) -> [f64; 3] {
        match self {
            VertexPosition::Grid(p) => p.to_f64(),
            VertexPosition::Implicit(p) => p.to_f64(),
        }
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

/// A vertex and one edge incident to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertex {
    /// Its position.
    pub position: VertexPosition,
    edge: EdgeKey,
}

/// An edge with its wings.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge<E> {
    /// First vertex (left face walks from here).
    pub start: VertexKey,
    /// Second vertex.
    pub end: VertexKey,
    /// Face on the left (walked `start -> end`), or the outside.
    pub left: Option<FaceKey>,
    /// Face on the right (walked `end -> start`), or the outside.
    pub right: Option<FaceKey>,
    left_prev: EdgeKey,
    left_next: EdgeKey,
    right_prev: EdgeKey,
    right_next: EdgeKey,
    /// The plane through the edge's line, the left face behind it.
    pub line: Plane,
    /// Whether the right face lies in front of `line` (always so between
    /// faces of one plane; between faces of two planes the line plane need
    /// not separate them).
    right_in_front: bool,
    /// The user's payload.
    pub data: E,
}

/// A face, its support plane and one edge of its boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct Face<F> {
    /// The plane the face lies in; its front is the face's front.
    pub support: Plane,
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
    vertices: SlotMap<VertexKey, Vertex>,
    edges: SlotMap<EdgeKey, Edge<E>>,
    faces: SlotMap<FaceKey, Face<F>>,
}

impl<F: Clone, E: Clone> WingedMesh<F, E> {
    /// A mesh of one face: the polygon, its edges carrying `edge_data`.
    pub fn from_polygon(polygon: &ConvexPolygon, face_data: F, edge_data: E) -> Self {
        let mut mesh = Self {
            vertices: SlotMap::with_key(),
            edges: SlotMap::with_key(),
            faces: SlotMap::with_key(),
        };
        let n = polygon.len();
        let vertices: Vec<VertexKey> = (0..n)
            .map(|i| {
                let position = match polygon.vertex_grid_point(i) {
                    Some(p) => VertexPosition::Grid(p),
                    None => {
                        let [a, b, c] = polygon.vertex_planes(i);
                        VertexPosition::Implicit(
                            ImplicitPoint::new(*a, *b, *c).expect("a polygon's vertex is a point"),
                        )
                    }
                };
                mesh.vertices.insert(Vertex {
                    position,
                    edge: EdgeKey::default(),
                })
            })
            .collect();
        let face = mesh.faces.insert(Face {
            support: *polygon.support(),
            edge: EdgeKey::default(),
            data: face_data,
        });
        let edges: Vec<EdgeKey> = (0..n)
            .map(|i| {
                mesh.edges.insert(Edge {
                    start: vertices[i],
                    end: vertices[(i + 1) % n],
                    left: Some(face),
                    right: None,
                    left_prev: EdgeKey::default(),
                    left_next: EdgeKey::default(),
                    right_prev: EdgeKey::default(),
                    right_next: EdgeKey::default(),
                    line: polygon.edges()[i],
                    right_in_front: true,
                    data: edge_data.clone(),
                })
            })
            .collect();
        for i in 0..n {
            let (prev, next) = (edges[(i + n - 1) % n], edges[(i + 1) % n]);
            let e = &mut mesh.edges[edges[i]];
            e.left_prev = prev;
            e.left_next = next;
            // The outside walks the boundary the other way.
            e.right_prev = next;
            e.right_next = prev;
            mesh.vertices[vertices[i]].edge = edges[i];
        }
        mesh.faces[face].edge = edges[0];
        mesh
    }

    /// A mesh glued from polygons with grid-point vertices: equal grid
    /// points are one vertex, and an edge used by two polygons (once in
    /// each direction) is one edge between their faces. Every polygon
    /// carries `face_data` and every edge `edge_data`.
    ///
    /// Errors: a vertex that is not a grid point, an edge used twice in
    /// the same direction or by more than two polygons (inconsistent
    /// orientation or a non-manifold edge), or a vertex where the boundary
    /// passes more than once.
    pub fn from_polygons(
        polygons: &[ConvexPolygon],
        face_data: F,
        edge_data: E,
    ) -> Result<Self, Error> {
        use std::collections::HashMap;
        let mut mesh = Self {
            vertices: SlotMap::with_key(),
            edges: SlotMap::with_key(),
            faces: SlotMap::with_key(),
        };
        let mut vertex_of: HashMap<GridPoint, VertexKey> = HashMap::new();
        let mut edge_of: HashMap<(VertexKey, VertexKey), EdgeKey> = HashMap::new();
        let mut loops: Vec<(FaceKey, Vec<EdgeKey>)> = Vec::new();
        let mut polygon_of: HashMap<FaceKey, usize> = HashMap::new();
        for (index, polygon) in polygons.iter().enumerate() {
            let n = polygon.len();
            let mut keys = Vec::with_capacity(n);
            for i in 0..n {
                let p = polygon.vertex_grid_point(i).ok_or(Error::NonPlanar)?;
                let key = *vertex_of.entry(p).or_insert_with(|| {
                    mesh.vertices.insert(Vertex {
                        position: VertexPosition::Grid(p),
                        edge: EdgeKey::default(),
                    })
                });
                keys.push(key);
            }
            let face = mesh.faces.insert(Face {
                support: *polygon.support(),
                edge: EdgeKey::default(),
                data: face_data.clone(),
            });
            polygon_of.insert(face, index);
            let mut walk = Vec::with_capacity(n);
            for i in 0..n {
                let (a, b) = (keys[i], keys[(i + 1) % n]);
                if edge_of.contains_key(&(a, b)) {
                    return Err(Error::NonConvex);
                }
                let e = match edge_of.get(&(b, a)) {
                    Some(&e) if mesh.edges[e].right.is_none() => {
                        mesh.edges[e].right = Some(face);
                        // The left polygon's edge plane may be this face's
                        // support (a cube's neighbours): then pick another
                        // plane through the edge. Either way, record which
                        // side of it this face is on.
                        let left = mesh.edges[e].left.expect("glued edges have a left face");
                        let left_polygon = &polygons[polygon_of[&left]];
                        if mesh.edges[e].line.is_coincident(polygon.support()) {
                            let (Some(p), Some(q)) = (
                                polygon.vertex_grid_point(i),
                                polygon.vertex_grid_point((i + 1) % n),
                            ) else {
                                return Err(Error::NonPlanar);
                            };
                            mesh.edges[e].line = line_between(p, q, left_polygon, polygon)
                                .ok_or(Error::NonConvex)?;
                        }
                        let line = mesh.edges[e].line;
                        mesh.edges[e].right_in_front = (0..n)
                            .filter_map(|k| polygon.vertex_grid_point(k))
                            .map(|v| predicates::side_of_point(&line, v))
                            .any(|side| side == Side::Front);
                        e
                    }
                    Some(_) => return Err(Error::NonConvex),
                    None => mesh.edges.insert(Edge {
                        start: a,
                        end: b,
                        left: Some(face),
                        right: None,
                        left_prev: EdgeKey::default(),
                        left_next: EdgeKey::default(),
                        right_prev: EdgeKey::default(),
                        right_next: EdgeKey::default(),
                        line: polygon.edges()[i],
                        right_in_front: true,
                        data: edge_data.clone(),
                    }),
                };
                edge_of.insert((a, b), e);
                mesh.vertices[a].edge = e;
                walk.push(e);
            }
            mesh.faces[face].edge = walk[0];
            loops.push((face, walk));
        }
        for (face, walk) in &loops {
            let n = walk.len();
            for i in 0..n {
                mesh.set_next(walk[i], Some(*face), walk[(i + 1) % n]);
                mesh.set_prev(walk[(i + 1) % n], Some(*face), walk[i]);
            }
        }
        // The outside walks each boundary edge end -> start; at its start it
        // continues along the boundary edge that ends there.
        let mut boundary_ending_at: HashMap<VertexKey, EdgeKey> = HashMap::new();
        for (k, e) in &mesh.edges {
            if e.right.is_none() && boundary_ending_at.insert(e.end, k).is_some() {
                return Err(Error::NonConvex);
            }
        }
        let boundary: Vec<EdgeKey> = boundary_ending_at.values().copied().collect();
        for e in boundary {
            let start = mesh.edges[e].start;
            let next = *boundary_ending_at.get(&start).ok_or(Error::NonConvex)?;
            mesh.edges[e].right_next = next;
            mesh.edges[next].right_prev = e;
        }
        Ok(mesh)
    }

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

    /// A vertex.
    pub fn vertex(&self, v: VertexKey) -> Option<&Vertex> {
        self.vertices.get(v)
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

    fn walk(&self, first: EdgeKey, side: Option<FaceKey>) -> Vec<EdgeKey> {
        let mut out = vec![first];
        let mut e = self.next_in(first, side);
        while e != first && out.len() <= self.edges.len() {
            out.push(e);
            e = self.next_in(e, side);
        }
        out
    }

    /// The vertices around a face, counter-clockwise.
    pub fn face_vertices(&self, f: FaceKey) -> Vec<VertexKey> {
        self.face_edges(f)
            .into_iter()
            .map(|e| self.walk_start(e, Some(f)))
            .collect()
    }

    /// The edges around a vertex, in the order of the faces around it.
    pub fn vertex_edges(&self, v: VertexKey) -> Vec<EdgeKey> {
        let first = self.vertices[v].edge;
        let mut out = Vec::new();
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
        let edge = &self.edges[e];
        if edge.left == side || !edge.right_in_front {
            edge.line
        } else {
            edge.line.flipped()
        }
    }

    /// The face's edge planes, counter-clockwise, each with the face behind
    /// it; a plane repeated by collinear edges appears once.
    fn face_planes(&self, f: FaceKey) -> Vec<Plane> {
        let mut planes: Vec<Plane> = Vec::new();
        for e in self.face_edges(f) {
            let plane = self.edge_plane_for(e, Some(f));
            if planes.last() != Some(&plane) {
                planes.push(plane);
            }
        }
        if planes.len() > 1 && planes.first() == planes.last() {
            planes.pop();
        }
        planes
    }

    /// The face as a convex polygon with source `source`.
    pub fn face_polygon(&self, f: FaceKey, source: u32) -> Result<ConvexPolygon, Error> {
        ConvexPolygon::from_planes(self.faces[f].support, &self.face_planes(f), source)
    }

    /// The face's outline in grid units, counter-clockwise (output only).
    pub fn face_outline(&self, f: FaceKey) -> Vec<[f64; 3]> {
        self.face_vertices(f)
            .into_iter()
            .map(|v| self.vertices[v].position.to_f64())
            .collect()
    }

    /// Splits edge `e` at `position`, which must lie strictly inside it
    /// (checked exactly: on the edge's line and strictly between its ends).
    /// The edge keeps its first half; returns the new vertex and the new
    /// edge (the second half).
    pub fn split_edge(
        &mut self,
        e: EdgeKey,
        position: VertexPosition,
    ) -> Result<(VertexKey, EdgeKey), Error> {
        let edge = self.edges.get(e).ok_or(Error::NoIntersection)?;
        let support = self.support_of(e);
        if position.side(&edge.line) != Side::On || position.side(&support) != Side::On {
            return Err(Error::NonPlanar);
        }
        let (a, b) = (
            self.vertices[edge.start].position,
            self.vertices[edge.end].position,
        );
        if !strictly_between(&position, &a, &b) {
            return Err(Error::NonConvex);
        }
        Ok(self.split_edge_unchecked(e, position))
    }

    fn split_edge_unchecked(
        &mut self,
        e: EdgeKey,
        position: VertexPosition,
    ) -> (VertexKey, EdgeKey) {
        let v = self.vertices.insert(Vertex { position, edge: e });
        let old = self.edges[e].clone();
        let second = self.edges.insert(Edge {
            start: v,
            end: old.end,
            left: old.left,
            right: old.right,
            left_prev: e,
            left_next: old.left_next,
            right_prev: old.right_prev,
            right_next: e,
            line: old.line,
            right_in_front: old.right_in_front,
            data: old.data.clone(),
        });
        // The walk around the left face: e, second, old successor.
        self.set_prev(old.left_next, old.left, second);
        // Around the right face (end -> start): old predecessor, second, e.
        self.set_next(old.right_prev, old.right, second);
        let first = &mut self.edges[e];
        first.end = v;
        first.left_next = second;
        first.right_prev = second;
        if self.vertices[old.end].edge == e {
            self.vertices[old.end].edge = second;
        }
        (v, second)
    }

    /// The support plane of an edge's faces.
    fn support_of(&self, e: EdgeKey) -> Plane {
        let edge = &self.edges[e];
        let f = edge.left.or(edge.right).expect("an edge has a face");
        self.faces[f].support
    }

    /// Splits face `f` by `plane`, exactly: edges crossed are split at new
    /// implicit vertices, a vertex on the plane is reused, and a new edge
    /// along the plane separates the parts. No zero-area face is made: a
    /// plane that only touches the face leaves it whole.
    pub fn split_face(&mut self, f: FaceKey, plane: &Plane) -> FaceSplit {
        let support = self.faces[f].support;
        let mut back = false;
        let mut front = false;
        for v in self.face_vertices(f) {
            match self.vertices[v].position.side(plane) {
                Side::Back => back = true,
                Side::Front => front = true,
                Side::On => {}
            }
        }
        if !(back && front) {
            return FaceSplit::NotSplit(if back { Side::Back } else { Side::Front });
        }
        // Split the edges that cross the plane strictly.
        for e in self.face_edges(f) {
            let edge = &self.edges[e];
            let (s, t) = (
                self.vertices[edge.start].position.side(plane),
                self.vertices[edge.end].position.side(plane),
            );
            if (s == Side::Back && t == Side::Front) || (s == Side::Front && t == Side::Back) {
                let point = ImplicitPoint::new(support, edge.line, *plane)
                    .expect("an edge with ends on both sides meets the plane");
                self.split_edge_unchecked(e, VertexPosition::Implicit(point));
            }
        }
        // Now exactly two vertices of the loop are on the plane where the
        // walk changes side: find the edges entering and leaving them.
        let edges = self.face_edges(f);
        let n = edges.len();
        let sides: Vec<Side> = edges
            .iter()
            .map(|&e| {
                self.vertices[self.walk_start(e, Some(f))]
                    .position
                    .side(plane)
            })
            .collect();
        // Vertex i is the start of edges[i]. `a`: the On vertex after which
        // the walk goes strictly back; `b`: the one after which it goes front.
        let on_before = |i: usize, want: Side| {
            sides[i] == Side::On
                && (1..n).map(|k| sides[(i + k) % n]).find(|&s| s != Side::On) == Some(want)
        };
        let a = (0..n)
            .find(|&i| on_before(i, Side::Back))
            .expect("a cut face has an On vertex before its back run");
        let b = (0..n)
            .find(|&i| on_before(i, Side::Front))
            .expect("and one before its front run");
        let (va, vb) = (
            self.walk_start(edges[a], Some(f)),
            self.walk_start(edges[b], Some(f)),
        );
        let (in_a, out_a) = (edges[(a + n - 1) % n], edges[a]);
        let (in_b, out_b) = (edges[(b + n - 1) % n], edges[b]);
        // The new edge runs va -> vb. Walking f counter-clockwise from va
        // goes into the back part (out_a .. in_b), which then returns along
        // the new edge from vb to va: the back part is on its right. The
        // front part (out_b .. in_a) walks it va -> vb: on its left, so the
        // line plane, with the left face behind it, is the plane flipped.
        let front_face = self.faces.insert(Face {
            support,
            edge: out_b,
            data: self.faces[f].data.clone(),
        });
        let front_edges: Vec<EdgeKey> = {
            let mut list = Vec::new();
            let mut k = b;
            while k != a {
                list.push(edges[k]);
                k = (k + 1) % n;
            }
            list
        };
        let data = self.edges[out_a].data.clone();
        let cut = self.edges.insert(Edge {
            start: va,
            end: vb,
            left: Some(front_face),
            right: Some(f),
            left_prev: in_a,
            left_next: out_b,
            right_prev: in_b,
            right_next: out_a,
            line: plane.flipped(),
            right_in_front: true,
            data,
        });
        for &e in &front_edges {
            self.set_side(e, Some(f), Some(front_face));
        }
        self.set_next(in_a, Some(front_face), cut);
        self.set_prev(out_b, Some(front_face), cut);
        self.set_next(in_b, Some(f), cut);
        self.set_prev(out_a, Some(f), cut);
        self.faces[f].edge = out_a;
        FaceSplit::Split {
            back: f,
            front: front_face,
            edge: cut,
        }
    }

    /// Merges the two faces on either side of `e` by deleting it; the left
    /// face keeps its key and payload. Errors: `e` borders the outside or
    /// the same face twice, the faces lie in different planes, or the union
    /// would not be convex.
    pub fn merge_faces(&mut self, e: EdgeKey) -> Result<FaceKey, Error> {
        let edge = self.edges.get(e).ok_or(Error::NoIntersection)?.clone();
        let (Some(keep), Some(gone)) = (edge.left, edge.right) else {
            return Err(Error::TooFewVertices);
        };
        if keep == gone {
            return Err(Error::TooFewVertices);
        }
        if self.faces[keep].support != self.faces[gone].support {
            return Err(Error::NonPlanar);
        }
        // The two faces may share a straight chain of edges (a vertex of
        // degree two between them): join it into one edge first, so that
        // no other edge is left with the merged face on both sides.
        let mut e = e;
        loop {
            let (start, end) = (self.edges[e].start, self.edges[e].end);
            match self.join_at(start).or_else(|| self.join_at(end)) {
                Some(kept) => e = kept,
                None => break,
            }
        }
        let edge = self.edges[e].clone();
        // At each end, the edge arriving in `keep` and the one leaving in
        // `gone` become consecutive: the turn between them must be convex
        // (or straight).
        let (a, d) = (edge.left_prev, edge.right_next);
        let (c, b) = (edge.right_prev, edge.left_next);
        for (arriving, from, leaving, to) in [(a, keep, d, gone), (c, gone, b, keep)] {
            let plane = self.edge_plane_for(arriving, Some(from));
            let y = &self.edges[leaving];
            let far = if y.left == Some(to) { y.end } else { y.start };
            if self.vertices[far].position.side(&plane) == Side::Front {
                return Err(Error::NonConvex);
            }
        }
        for g in self.walk(edge.right_next, Some(gone)) {
            if g != e {
                self.set_side(g, Some(gone), Some(keep));
            }
        }
        self.set_next(a, Some(keep), d);
        self.set_prev(d, Some(keep), a);
        self.set_next(c, Some(keep), b);
        self.set_prev(b, Some(keep), c);
        if self.vertices[edge.start].edge == e {
            self.vertices[edge.start].edge = d;
        }
        if self.vertices[edge.end].edge == e {
            self.vertices[edge.end].edge = b;
        }
        self.faces[keep].edge = a;
        self.faces.remove(gone);
        self.edges.remove(e);
        Ok(keep)
    }

    /// Removes vertex `v` if exactly two edges meet there along one line
    /// (checked exactly), joining them into one; returns whether it did.
    pub fn remove_vertex_if_collinear(&mut self, v: VertexKey) -> bool {
        self.join_at(v).is_some()
    }

    /// [`remove_vertex_if_collinear`](Self::remove_vertex_if_collinear),
    /// returning the edge that remains.
    fn join_at(&mut self, v: VertexKey) -> Option<EdgeKey> {
        if !self.vertices.contains_key(v) {
            return None;
        }
        let around = self.vertex_edges(v);
        let [e1, e2] = around[..] else { return None };
        if !self.edges[e1].line.is_coincident(&self.edges[e2].line) {
            return None;
        }
        // Make both run one way through v: `first` ends there, `second`
        // starts there.
        let (first, second) = (e1, e2);
        if self.edges[first].end != v {
            self.reverse_edge(first);
        }
        if self.edges[second].start != v {
            self.reverse_edge(second);
        }
        let s = self.edges[second].clone();
        let f = &mut self.edges[first];
        f.end = s.end;
        f.left_next = s.left_next;
        f.right_prev = s.right_prev;
        self.set_prev(s.left_next, s.left, first);
        self.set_next(s.right_prev, s.right, first);
        if self.vertices[s.end].edge == second {
            self.vertices[s.end].edge = first;
        }
        for side in [s.left, s.right].into_iter().flatten() {
            if self.faces[side].edge == second {
                self.faces[side].edge = first;
            }
        }
        self.edges.remove(second);
        self.vertices.remove(v);
        Some(first)
    }

    /// Reverses an edge's direction (swapping its sides), keeping the mesh
    /// the same.
    fn reverse_edge(&mut self, e: EdgeKey) {
        let edge = &mut self.edges[e];
        std::mem::swap(&mut edge.start, &mut edge.end);
        std::mem::swap(&mut edge.left, &mut edge.right);
        std::mem::swap(&mut edge.left_prev, &mut edge.right_prev);
        std::mem::swap(&mut edge.left_next, &mut edge.right_next);
        // The new left face (the old right) must be behind the line.
        if edge.right_in_front {
            edge.line = edge.line.flipped();
        }
    }

    /// Checks every invariant exactly: wings consistent and walks closed,
    /// incident edges valid, each face's vertices on its support plane, each
    /// edge's ends on its line plane with the left face behind it, faces
    /// strictly convex up to straight (collinear) vertices, and Euler's
    /// formula `V - E + F = 1` for one connected disk.
    pub fn check_invariants(&self) -> Result<(), String> {
        for (k, e) in &self.edges {
            for (side, next, prev) in [
                (e.left, e.left_next, e.left_prev),
                (e.right, e.right_next, e.right_prev),
            ] {
                let n = self.edges.get(next).ok_or("dangling wing")?;
                let p = self.edges.get(prev).ok_or("dangling wing")?;
                if n.left != side && n.right != side {
                    return Err(format!("{k:?}: successor is not on the same face"));
                }
                if p.left != side && p.right != side {
                    return Err(format!("{k:?}: predecessor is not on the same face"));
                }
                if self.prev_in(next, side) != k || self.next_in(prev, side) != k {
                    return Err(format!("{k:?}: wings disagree"));
                }
                // Consecutive in the walk: this edge's walk end is the
                // successor's walk start.
                let end = if e.left == side { e.end } else { e.start };
                if self.walk_start(next, side) != end {
                    return Err(format!("{k:?}: successor does not start where it ends"));
                }
            }
            if e.left == e.right {
                return Err(format!("{k:?}: the same face on both sides"));
            }
            let support = self.support_of(k);
            for v in [e.start, e.end] {
                let position = &self.vertices.get(v).ok_or("dangling vertex")?.position;
                if position.side(&e.line) != Side::On || position.side(&support) != Side::On {
                    return Err(format!("{k:?}: an end is off the edge's line"));
                }
            }
        }
        for (k, v) in &self.vertices {
            let e = self.edges.get(v.edge).ok_or("vertex without edge")?;
            if e.start != k && e.end != k {
                return Err(format!("{k:?}: its edge does not touch it"));
            }
        }
        for (k, face) in &self.faces {
            let e = self.edges.get(face.edge).ok_or("face without edge")?;
            if e.left != Some(k) && e.right != Some(k) {
                return Err(format!("{k:?}: its edge does not border it"));
            }
            let planes = self.face_planes(k);
            let vertices = self.face_vertices(k);
            if planes.len() < 3 {
                return Err(format!("{k:?}: fewer than three sides"));
            }
            for &v in &vertices {
                let p = &self.vertices[v].position;
                if p.side(&face.support) != Side::On {
                    return Err(format!("{k:?}: a vertex is off the support plane"));
                }
                if planes.iter().any(|plane| p.side(plane) == Side::Front) {
                    return Err(format!("{k:?}: not convex"));
                }
            }
            self.face_polygon(k, 0).map_err(|e| format!("{k:?}: {e}"))?;
        }
        // Euler: each component is a disk (one outside walk, V - E + F = 1)
        // or closed (none, V - E + F = 2); here only genus 0 is built, so
        // V - E + F + (outside walks) = 2 (components).
        let mut outside_walks = 0_i64;
        let mut seen = std::collections::HashSet::new();
        for (k, e) in &self.edges {
            for side in [e.left, e.right] {
                if side.is_none() && seen.insert(k) {
                    outside_walks += 1;
                    for g in self.walk(k, None) {
                        seen.insert(g);
                    }
                }
            }
        }
        let euler = self.vertices.len() as i64 - self.edges.len() as i64 + self.faces.len() as i64;
        let components = self.components() as i64;
        if euler + outside_walks != 2 * components {
            return Err(format!(
                "V - E + F = {euler} with {outside_walks} boundaries and {components} components"
            ));
        }
        Ok(())
    }

    /// Connected components (through edges).
    fn components(&self) -> usize {
        let mut seen = std::collections::HashSet::new();
        let mut count = 0;
        for start in self.vertices.keys() {
            if !seen.insert(start) {
                continue;
            }
            count += 1;
            let mut stack = vec![start];
            while let Some(v) = stack.pop() {
                for e in self.vertex_edges(v) {
                    let edge = &self.edges[e];
                    let other = if edge.start == v {
                        edge.end
                    } else {
                        edge.start
                    };
                    if seen.insert(other) {
                        stack.push(other);
                    }
                }
            }
        }
        count
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

/// A plane through the segment `pq`, an edge shared by two polygons in
/// different planes, that is neither polygon's support plane, oriented with
/// `left` behind it. Small integer directions keep the coefficients within
/// the kernel's bounds.
fn line_between(
    p: GridPoint,
    q: GridPoint,
    left: &ConvexPolygon,
    right: &ConvexPolygon,
) -> Option<Plane> {
    const DIRECTIONS: [[i64; 3]; 7] = [
        [1, 0, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 1, 0],
        [1, 0, 1],
        [0, 1, 1],
        [1, 1, 1],
    ];
    let e = [
        i64::from(q.x) - i64::from(p.x),
        i64::from(q.y) - i64::from(p.y),
        i64::from(q.z) - i64::from(p.z),
    ];
    for d in DIRECTIONS {
        let normal = [
            e[1] * d[2] - e[2] * d[1],
            e[2] * d[0] - e[0] * d[2],
            e[0] * d[1] - e[1] * d[0],
        ];
        let Some(plane) = Plane::with_normal_through(normal, p) else {
            continue;
        };
        if plane.is_coincident(left.support()) || plane.is_coincident(right.support()) {
            continue;
        }
        // The left polygon has a vertex off the plane (it is not the
        // polygon's support): it decides the orientation.
        let side = (0..left.len())
            .filter_map(|k| left.vertex_grid_point(k))
            .map(|v| predicates::side_of_point(&plane, v))
            .find(|&s| s != Side::On)?;
        return Some(if side == Side::Back {
            plane
        } else {
            plane.flipped()
        });
    }
    None
}

/// Whether `x`, on the line through `a` and `b`, lies strictly between
/// them: some plane through `x` that does not hold the line has `a` and `b`
/// strictly on opposite sides.
fn strictly_between(x: &VertexPosition, a: &VertexPosition, b: &VertexPosition) -> bool {
    let planes: Vec<Plane> = match x {
        VertexPosition::Implicit(p) => p.planes().to_vec(),
        VertexPosition::Grid(g) => (0..3)
            .filter_map(|axis| {
                let mut n = [0_i64; 3];
                n[axis] = 1;
                Plane::with_normal_through(n, *g)
            })
            .collect(),
    };
    planes.iter().any(|plane| {
        matches!(
            (a.side(plane), b.side(plane)),
            (Side::Back, Side::Front) | (Side::Front, Side::Back)
        )
    })
}
