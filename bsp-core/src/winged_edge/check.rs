//! The invariants of a winged-edge mesh, checked exactly.

use super::{PlaneRef, WingedMesh};
use crate::predicates::Side;

impl<F: Clone, E: Clone> WingedMesh<F, E> {
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
                let at = &self.vertices.get(v).ok_or("dangling vertex")?.at;
                if self.side_at(at, &e.line) != Side::On || self.side_at(at, &support) != Side::On {
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
        self.check_plane_counts()?;
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
                let p = &self.vertices[v].at;
                if self.side_at(p, self.support(face)) != Side::On {
                    return Err(format!("{k:?}: a vertex is off the support plane"));
                }
                if planes
                    .iter()
                    .any(|plane| self.side_at(p, plane) == Side::Front)
                {
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

    /// Every plane the mesh names is held at least as often
    /// (the user's holds, [`Self::hold_plane`], come on top: see
    /// [`Self::check_plane_holds`]).
    fn check_plane_counts(&self) -> Result<(), String> {
        let held: std::collections::HashMap<PlaneRef, u32> = self.planes.held().collect();
        for (r, count) in self.mesh_planes() {
            if held.get(&r).is_none_or(|&h| h < count) {
                return Err(format!(
                    "plane table: {r:?} named {count} times, held fewer"
                ));
            }
        }
        Ok(())
    }

    /// How often the mesh names each plane of the table: once per face
    /// support, and per implicit vertex.
    fn mesh_planes(&self) -> std::collections::HashMap<PlaneRef, u32> {
        let mut named = std::collections::HashMap::new();
        for &r in &self.supports {
            *named.entry(r).or_default() += 1;
        }
        for (_, v) in &self.vertices {
            if let super::StoredPosition::Implicit { planes, .. } = v.at {
                for r in planes {
                    *named.entry(r).or_default() += 1;
                }
            }
        }
        named
    }

    /// Checks that the table holds exactly the mesh's planes (supports and
    /// the vertices') and the user's holds `user` (each plane as often as
    /// named), nothing more.
    pub fn check_plane_holds(
        &self,
        user: impl IntoIterator<Item = PlaneRef>,
    ) -> Result<(), String> {
        let mut named = self.mesh_planes();
        for r in user {
            *named.entry(r).or_default() += 1;
        }
        let held: std::collections::HashMap<PlaneRef, u32> = self.planes.held().collect();
        if held != named {
            let extra = held.iter().filter(|(r, c)| named.get(r) != Some(c)).count();
            return Err(format!(
                "plane table: {} planes held, {} named; {extra} counts differ",
                held.len(),
                named.len()
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
}
