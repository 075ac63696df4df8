//! Grafting a mesh into a face of another: the face is replaced by the
//! faces of a mesh of the same polygon, the two boundaries sewn together.
//!
//! This lets the parts of one big subdivision be made in separate meshes
//! (in parallel, say) and joined afterwards. Along the face's boundary the
//! two meshes may have different vertices (the face's neighbours split its
//! edges, the grafted mesh's faces split its outline): each gets the
//! other's, so that the result is one conforming subdivision. Every
//! decision is an exact side test.

use super::{Edge, Face, VertexPosition, WingedMesh};
use crate::predicates::Side;
use crate::{EdgeKey, Error, FaceKey, ImplicitPoint, Plane, VertexKey};
use slotmap::SecondaryMap;

impl<F: Clone, E: Clone> WingedMesh<F, E> {
    /// Makes room for that many more vertices, edges and faces.
    pub fn reserve(&mut self, vertices: usize, edges: usize, faces: usize) {
        self.vertices.reserve(vertices);
        self.edges.reserve(edges);
        self.faces.reserve(faces);
    }

    /// How many vertices, edges and faces the mesh holds without
    /// reallocating.
    pub fn capacity(&self) -> (usize, usize, usize) {
        (
            self.vertices.capacity(),
            self.edges.capacity(),
            self.faces.capacity(),
        )
    }

    /// Replaces face `f` by the faces of `sub`, a connected subdivision of
    /// the same convex polygon in the same support plane (for instance a
    /// mesh made by [`from_polygon`](Self::from_polygon) from
    /// [`face_polygon`](Self::face_polygon) of `f`, then split). Edges of
    /// `f`'s boundary are split where `sub`'s outline has vertices and the
    /// other way round; the boundary edges and vertices of `f` stay (with
    /// their payloads), `sub`'s are dropped. Returns the key each face of
    /// `sub` now has.
    ///
    /// Errors: `f` is not a face, the supports differ, or the outlines do
    /// not match (then both meshes are still valid, though edges of either
    /// outline may have been split at vertices of the other).
    pub fn graft(
        &mut self,
        f: FaceKey,
        mut sub: WingedMesh<F, E>,
    ) -> Result<SecondaryMap<FaceKey, FaceKey>, Error> {
        let face = self.faces.get(f).ok_or(Error::NoIntersection)?;
        let plane = face.plane;
        if sub
            .faces
            .values()
            .any(|g| sub.support(g) != self.support(face))
        {
            return Err(Error::NonPlanar);
        }
        // A corner of the face, in both meshes.
        let polygon = self.face_polygon(f, 0)?;
        let corner = match polygon.vertex_grid_point(0) {
            Some(g) => VertexPosition::Grid(g),
            None => {
                let [a, b, c] = polygon.vertex_planes(0);
                VertexPosition::Implicit(ImplicitPoint::new(*a, *b, *c)?)
            }
        };
        let m_start = self
            .face_edges(f)
            .into_iter()
            .find(|&e| {
                let v = self.walk_start(e, Some(f));
                self.position(v).same_point(&corner)
            })
            .ok_or(Error::NoIntersection)?;
        let s_start = sub
            .outline()
            .into_iter()
            .find(|&(g, inner)| {
                let u = sub.walk_start(g, Some(inner));
                sub.position(u).same_point(&corner)
            })
            .ok_or(Error::NoIntersection)?;
        // The corner's vertex in each (edges at it may be split, the
        // vertices stay).
        let m_corner = self.walk_start(m_start, Some(f));
        let s_corner = sub.walk_start(s_start.0, Some(s_start.1));
        let bound = self.edges.len() + sub.edges.len() + 4;
        // Sew: walk both outlines counter-clockwise from the corner; where
        // the next vertices differ, the nearer one is put into the other
        // outline.
        let (mut em, (mut es, mut inner)) = (m_start, s_start);
        let mut at = self.position(self.walk_start(em, Some(f)));
        let mut steps = 0;
        loop {
            steps += 1;
            if steps > bound {
                return Err(Error::NoIntersection);
            }
            let m = self.walk_end(em, Some(f));
            let s = sub.walk_end(es, Some(inner));
            let (pm, ps) = (self.position(m), sub.position(s));
            if pm.same_point(&ps) {
                if m == m_corner {
                    break;
                }
                em = self.next_in(em, Some(f));
                (es, inner) = sub.next_outline(es);
                at = pm;
                continue;
            }
            // Which comes first, strictly between the last common point and
            // the other? (Both lie on the face's side from `at`.)
            let line = self.edges[em].line;
            let first = |p: &VertexPosition, q: &VertexPosition| {
                let before = crossing_plane(q, &line, &at)?;
                let after = crossing_plane(&at, &line, q)?;
                let inside = p.side(&line) == Side::On
                    && p.side(&before) == at.side(&before)
                    && p.side(&after) == q.side(&after);
                Some(inside)
            };
            if first(&ps, &pm).ok_or(Error::NoIntersection)? {
                // The outline of `sub` has a vertex first: into the face's.
                em = self.split_toward(em, Some(f), ps);
                (es, inner) = sub.next_outline(es);
                at = ps;
            } else if first(&pm, &ps).ok_or(Error::NoIntersection)? {
                es = sub.split_toward(es, Some(inner), pm);
                em = self.next_in(em, Some(f));
                at = pm;
            } else {
                return Err(Error::NoIntersection);
            }
        }
        // Now both outlines have the same vertices: pair them up, from the
        // corner.
        let m_start = self
            .face_edges(f)
            .into_iter()
            .find(|&e| self.walk_start(e, Some(f)) == m_corner)
            .ok_or(Error::NoIntersection)?;
        let s_start = sub
            .outline()
            .into_iter()
            .find(|&(g, inner)| sub.walk_start(g, Some(inner)) == s_corner)
            .ok_or(Error::NoIntersection)?;
        let mut vmap: SecondaryMap<VertexKey, VertexKey> = SecondaryMap::new();
        let mut emap: SecondaryMap<EdgeKey, EdgeKey> = SecondaryMap::new();
        let mut pairs: Vec<(EdgeKey, EdgeKey, FaceKey)> = Vec::new();
        let (mut em, (mut es, mut inner)) = (m_start, s_start);
        loop {
            let (u, v) = (
                sub.walk_start(es, Some(inner)),
                self.walk_start(em, Some(f)),
            );
            if !sub.position(u).same_point(&self.position(v)) {
                return Err(Error::NoIntersection);
            }
            vmap.insert(u, v);
            emap.insert(es, em);
            pairs.push((em, es, inner));
            em = self.next_in(em, Some(f));
            (es, inner) = sub.next_outline(es);
            if em == m_start {
                break;
            }
            if pairs.len() > bound {
                return Err(Error::NoIntersection);
            }
        }
        if (es, inner) != s_start {
            return Err(Error::NoIntersection);
        }
        // Append the rest of `sub`, keys to be mapped once all are known.
        self.reserve(sub.vertices.len(), sub.edges.len(), sub.faces.len());
        let mut fmap: SecondaryMap<FaceKey, FaceKey> = SecondaryMap::new();
        for (g, face) in sub.faces.drain() {
            fmap.insert(g, self.faces.insert(Face { plane, ..face }));
        }
        // (The vertices inside, with the edge each points at in `sub`.)
        let mut inside: Vec<(VertexKey, EdgeKey)> = Vec::new();
        // (Their planes go into this mesh's table.)
        let vertices: Vec<_> = sub.vertices.drain().collect();
        for (u, vertex) in vertices {
            if !vmap.contains_key(u) {
                let v = self.insert_vertex(sub.position_of(&vertex.at), vertex.edge);
                vmap.insert(u, v);
                inside.push((v, vertex.edge));
            }
        }
        let sub_edges: Vec<(EdgeKey, Edge<E>)> = sub.edges.drain().collect();
        let mut boundary: SecondaryMap<EdgeKey, Edge<E>> = SecondaryMap::new();
        for (g, edge) in sub_edges {
            if emap.contains_key(g) {
                boundary.insert(g, edge);
            } else {
                emap.insert(g, self.edges.insert(edge));
            }
        }
        let face_of = |side: Option<FaceKey>| side.map(|g| fmap[g]);
        for (g, &e) in &emap {
            if boundary.contains_key(g) {
                continue;
            }
            let edge = &mut self.edges[e];
            edge.start = vmap[edge.start];
            edge.end = vmap[edge.end];
            edge.left = face_of(edge.left);
            edge.right = face_of(edge.right);
            for wing in [
                &mut edge.left_prev,
                &mut edge.left_next,
                &mut edge.right_prev,
                &mut edge.right_next,
            ] {
                *wing = emap[*wing];
            }
        }
        for (em, es, inner) in pairs {
            let g = &boundary[es];
            let (prev, next) = if g.left == Some(inner) {
                (g.left_prev, g.left_next)
            } else {
                (g.right_prev, g.right_next)
            };
            let edge = &mut self.edges[em];
            let to = Some(fmap[inner]);
            if edge.left == Some(f) {
                (edge.left, edge.left_prev, edge.left_next) = (to, emap[prev], emap[next]);
            } else {
                (edge.right, edge.right_prev, edge.right_next) = (to, emap[prev], emap[next]);
            }
        }
        for (v, e) in inside {
            self.vertices[v].edge = emap[e];
        }
        for (_, &g) in &fmap {
            let face = &mut self.faces[g];
            face.edge = emap[face.edge];
        }
        self.faces.remove(f);
        Ok(fmap)
    }

    /// The outline: the edges with the outside on one side, counter-clockwise,
    /// each with the face on its other side.
    fn outline(&self) -> Vec<(EdgeKey, FaceKey)> {
        let Some(first) = self
            .edges
            .iter()
            .find(|(_, e)| e.left.is_none() || e.right.is_none())
            .map(|(k, _)| k)
        else {
            return Vec::new();
        };
        // The outside's walk goes clockwise.
        let mut out: Vec<(EdgeKey, FaceKey)> = self
            .walk(first, None)
            .into_iter()
            .filter_map(|e| {
                let edge = &self.edges[e];
                edge.left.or(edge.right).map(|g| (e, g))
            })
            .collect();
        out.reverse();
        out
    }

    /// The outline's edge after `e` (an outline edge), counter-clockwise,
    /// with its face.
    fn next_outline(&self, e: EdgeKey) -> (EdgeKey, FaceKey) {
        let g = self.prev_in(e, None);
        let edge = &self.edges[g];
        (g, edge.left.or(edge.right).expect("an edge has a face"))
    }

    /// The vertex where the walk of `side` leaves edge `e`.
    fn walk_end(&self, e: EdgeKey, side: Option<FaceKey>) -> VertexKey {
        let edge = &self.edges[e];
        if edge.left == side {
            edge.end
        } else {
            edge.start
        }
    }

    /// Splits edge `e` (of `side`'s walk) at `position`, strictly inside
    /// it; returns the edge the walk of `side` goes on along after the new
    /// vertex.
    fn split_toward(
        &mut self,
        e: EdgeKey,
        side: Option<FaceKey>,
        position: VertexPosition,
    ) -> EdgeKey {
        let forward = self.edges[e].left == side;
        let (_, second) = self.split_edge_unchecked(e, position);
        if forward { second } else { e }
    }
}

/// A plane through the point at `point` that does not hold `line` (on
/// which `point` and `other`, a different point, lie): one of its defining
/// planes, or an axis plane through a grid point.
fn crossing_plane(point: &VertexPosition, line: &Plane, other: &VertexPosition) -> Option<Plane> {
    let off = |q: &Plane| !q.is_coincident(line) && other.side(q) != Side::On;
    match point {
        VertexPosition::Implicit(p) => p.planes().iter().copied().find(off),
        VertexPosition::Grid(g) => (0..3)
            .filter_map(|axis| {
                let mut n = [0_i64; 3];
                n[axis] = 1;
                Plane::with_normal_through(n, *g)
            })
            .find(off),
    }
}
