//! Editing winged-edge meshes: splitting edges and faces, merging faces,
//! removing straight vertices.

use super::{
    Edge, Face, FaceSplit, PlaneRef, StoredPosition, StoredVertex, VertexPosition, WingedMesh,
};
use crate::predicates::Side;
use crate::{EdgeKey, Error, FaceKey, ImplicitPoint, Plane, VertexKey};
use smallvec::SmallVec;

impl<F: Clone, E: Clone> WingedMesh<F, E> {
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
        let (a, b) = (self.position(edge.start), self.position(edge.end));
        if !strictly_between(&position, &a, &b) {
            return Err(Error::NonConvex);
        }
        Ok(self.split_edge_unchecked(e, position))
    }

    pub(super) fn split_edge_unchecked(
        &mut self,
        e: EdgeKey,
        position: VertexPosition,
    ) -> (VertexKey, EdgeKey) {
        let at = self.store(position);
        self.split_edge_at(e, at)
    }

    /// [`Self::split_edge_unchecked`] at a position already stored (its
    /// planes held for the new vertex).
    fn split_edge_at(&mut self, e: EdgeKey, at: StoredPosition) -> (VertexKey, EdgeKey) {
        let v = self.vertices.insert(StoredVertex { at, edge: e });
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

    /// Splits face `f` by `plane`, exactly: edges crossed are split at new
    /// implicit vertices, a vertex on the plane is reused, and a new edge
    /// along the plane separates the parts. No zero-area face is made: a
    /// plane that only touches the face leaves it whole.
    pub fn split_face(&mut self, f: FaceKey, plane: &Plane) -> FaceSplit {
        let support = *self.support(&self.faces[f]);
        let side = Some(f);
        // One walk around the face: each edge with the side of the vertex
        // the walk leaves it from.
        let mut walk: SmallVec<[(EdgeKey, Side); 16]> = SmallVec::new();
        let (mut back, mut front) = (false, false);
        let first = self.faces[f].edge;
        let mut e = first;
        loop {
            let s = self.side_at(&self.vertices[self.walk_start(e, side)].at, plane);
            back |= s == Side::Back;
            front |= s == Side::Front;
            walk.push((e, s));
            e = self.next_in(e, side);
            if e == first || walk.len() > self.edges.len() {
                break;
            }
        }
        if !(back && front) {
            return FaceSplit::NotSplit(if back { Side::Back } else { Side::Front });
        }
        // Split the edges that cross the plane strictly (in walk order); the
        // new vertex is on the plane, and the walk of `f` takes the two
        // halves in its own direction.
        let m = walk.len();
        let mut edges: SmallVec<[EdgeKey; 16]> = SmallVec::with_capacity(m + 2);
        let mut sides: SmallVec<[Side; 16]> = SmallVec::with_capacity(m + 2);
        // The support's number in the plane table, and the plane's once
        // looked up, shared by the (two) new vertices.
        let on_support = self.supports[self.faces[f].plane as usize];
        let mut on_plane: Option<PlaneRef> = None;
        for i in 0..m {
            let (e, s) = walk[i];
            let t = walk[(i + 1) % m].1;
            if (s == Side::Back && t == Side::Front) || (s == Side::Front && t == Side::Back) {
                let edge = &self.edges[e];
                let forward = edge.left == side;
                let line = edge.line;
                let point = ImplicitPoint::new(support, line, *plane)
                    .expect("an edge with ends on both sides meets the plane");
                let held = match on_plane {
                    Some(r) => self.planes.retain(r),
                    None => *on_plane.insert(self.planes.intern(*plane)),
                };
                let at = StoredPosition::Implicit {
                    planes: [
                        self.planes.retain(on_support),
                        self.planes.intern(line),
                        held,
                    ],
                    filter: *point.filter(),
                };
                let (_, second) = self.split_edge_at(e, at);
                if forward {
                    edges.extend([e, second]);
                } else {
                    edges.extend([second, e]);
                }
                sides.extend([s, Side::On]);
            } else {
                edges.push(e);
                sides.push(s);
            }
        }
        // Now exactly two vertices of the loop are on the plane where the
        // walk changes side: find the edges entering and leaving them.
        let n = edges.len();
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
            plane: self.faces[f].plane,
            edge: out_b,
            data: self.faces[f].data.clone(),
        });
        let front_edges: SmallVec<[EdgeKey; 16]> = {
            let mut list = SmallVec::new();
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
        if self.faces[keep].plane != self.faces[gone].plane {
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
            if self.side_at(&self.vertices[far].at, &plane) == Side::Front {
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
    /// (checked exactly; their line planes may be two planes through that
    /// line), joining them into one, which keeps the first one's line
    /// plane; returns whether it did.
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
        // Along one line on the faces' plane: either the same line plane,
        // or two planes through that line (two planes of a scene can cut a
        // face's plane in one line), when e2's far end lies in e1's plane.
        if !self.edges[e1].line.is_coincident(&self.edges[e2].line) {
            let far = if self.edges[e2].start == v {
                self.edges[e2].end
            } else {
                self.edges[e2].start
            };
            if self.side_at(&self.vertices[far].at, &self.edges[e1].line) != Side::On {
                return None;
            }
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
        self.remove_vertex(v);
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
