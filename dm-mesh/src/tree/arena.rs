//! The tree's arena: nodes, parent links, free slots, and every unit's
//! exact list of nodes (so that a removal finds them wherever earlier
//! removals moved them).

use super::{Node, ReceiverDm, tracked};
use crate::cell::Cell;
use bsp_core::{ConvexPolygon, FaceKey, FaceSplit, Plane, PlaneRef, Side, Split};

/// No position in a unit's node list (a leaf, a free slot, or a node of
/// an untracked unit).
pub(super) const UNLISTED: u32 = u32::MAX;

impl<K: Copy + Ord> ReceiverDm<K> {
    /// The face of a leaf.
    pub(super) fn face_of(&self, leaf: u32) -> FaceKey {
        match self.nodes[leaf as usize] {
            Node::Leaf(f) => f,
            _ => unreachable!("not a leaf"),
        }
    }

    /// The cell of a leaf, to change (recorded as touched).
    pub(super) fn cell_mut(&mut self, leaf: u32) -> &mut Cell {
        let f = self.face_of(leaf);
        self.face_data_mut(f)
    }

    /// A face's cell, to change (recorded as touched).
    pub(super) fn face_data_mut(&mut self, f: FaceKey) -> &mut Cell {
        // (A cell is often changed several times in a row: recorded once.)
        if self.tracking && self.touched.last() != Some(&f) {
            self.touched.push(f);
        }
        self.mesh.face_data_mut(f).expect("a leaf's face exists")
    }

    /// The cell of a leaf.
    pub(super) fn cell(&self, leaf: u32) -> &Cell {
        &self
            .mesh
            .face(self.face_of(leaf))
            .expect("a leaf's face")
            .data
    }

    /// Whether node `n` is a leaf.
    pub(super) fn is_leaf(&self, n: u32) -> bool {
        matches!(self.nodes[n as usize], Node::Leaf(_))
    }

    /// The nodes of `unit` (in no particular order).
    pub(super) fn unit_nodes(&self, unit: u32) -> &[u32] {
        self.unit_nodes
            .get(unit as usize)
            .map_or(&[][..], Vec::as_slice)
    }

    /// Takes node `n` out of its unit's list, if it is in one.
    fn unlist(&mut self, n: u32) {
        let slot = self.slot[n as usize];
        if slot == UNLISTED {
            return;
        }
        let Node::Split { unit, .. } = self.nodes[n as usize] else {
            unreachable!("only splits are listed");
        };
        let list = &mut self.unit_nodes[unit as usize];
        list.swap_remove(slot as usize);
        if let Some(&moved) = list.get(slot as usize) {
            self.slot[moved as usize] = slot;
        }
        self.slot[n as usize] = UNLISTED;
    }

    /// Puts node `n` (already stored) in its unit's list, if tracked.
    fn list(&mut self, n: u32) {
        if let Node::Split { unit, .. } = self.nodes[n as usize]
            && tracked(unit)
        {
            let u = unit as usize;
            if self.unit_nodes.len() <= u {
                self.unit_nodes.resize_with(u + 1, Vec::new);
            }
            self.slot[n as usize] = self.unit_nodes[u].len() as u32;
            self.unit_nodes[u].push(n);
        }
    }

    /// Stores `node` at `n` (keeping the unit lists right); a leaf's face
    /// is pointed back at it.
    pub(super) fn set_node(&mut self, n: u32, node: Node) {
        // Each split node holds its line in the mesh's table: the new one
        // is held before the old one goes (they may be one plane).
        if let Node::Split { line, .. } = node {
            self.mesh.retain_plane(line);
        }
        if let Node::Split { line, .. } = self.nodes[n as usize] {
            self.mesh.release_plane(line);
        }
        self.unlist(n);
        self.nodes[n as usize] = node;
        self.list(n);
        if let Node::Leaf(f) = node {
            self.face_data_mut(f).leaf = n;
        }
    }

    /// A new node under `parent` (a leaf's face is pointed at it).
    pub(super) fn alloc(&mut self, node: Node, parent: u32) -> u32 {
        let n = match self.free.pop() {
            Some(k) => k,
            None => {
                self.nodes.push(Node::Free);
                self.parent.push(0);
                self.slot.push(UNLISTED);
                (self.nodes.len() - 1) as u32
            }
        };
        self.parent[n as usize] = parent;
        self.set_node(n, node);
        n
    }

    /// Frees node `n` (its children, if any, are the caller's business).
    pub(super) fn free_node(&mut self, n: u32) {
        if let Node::Split { line, .. } = self.nodes[n as usize] {
            self.mesh.release_plane(line);
        }
        self.unlist(n);
        self.nodes[n as usize] = Node::Free;
        self.free.push(n);
    }

    /// Puts `child` where `old` was under `old`'s parent (or at the root).
    pub(super) fn replace_child(&mut self, old: u32, child: u32) {
        if old == self.root {
            self.root = child;
            self.parent[child as usize] = child;
            return;
        }
        let p = self.parent[old as usize];
        if let Node::Split { back, front, .. } = &mut self.nodes[p as usize] {
            if *back == old {
                *back = child;
            } else if *front == old {
                *front = child;
            }
        }
        self.parent[child as usize] = p;
    }

    /// The leaves under `node`.
    pub(super) fn leaves(&self, node: u32) -> Vec<u32> {
        let mut out = Vec::new();
        let mut stack = vec![node];
        while let Some(n) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf(_) => out.push(n),
                Node::Split { back, front, .. } => {
                    stack.push(*front);
                    stack.push(*back);
                }
                Node::Free => {}
            }
        }
        out
    }

    /// The depth of node `n` (the root's is 0).
    pub(super) fn depth(&self, n: u32) -> usize {
        let mut depth = 0;
        let mut at = n;
        while at != self.root {
            at = self.parent[at as usize];
            depth += 1;
        }
        depth
    }

    /// Splits a leaf's cell by `plane`: the leaf becomes a node, and the
    /// new back and front leaves come back; `Err(side)` when the plane does
    /// not cut the cell, which lies on that side of it.
    pub(super) fn split_leaf(
        &mut self,
        leaf: u32,
        plane: &Plane,
        unit: u32,
    ) -> Result<(u32, u32), Side> {
        let face = self.face_of(leaf);
        let (back, front) = match self.mesh.split_face(face, plane) {
            FaceSplit::Split { back, front, .. } => (back, front),
            FaceSplit::NotSplit(side) => return Err(side),
        };
        let b = self.alloc(Node::Leaf(back), leaf);
        let f = self.alloc(Node::Leaf(front), leaf);
        self.set_split(leaf, plane, unit, b, f);
        Ok((b, f))
    }

    /// Makes node `n` a split by `plane` (held in the mesh's table).
    pub(super) fn set_split(&mut self, n: u32, plane: &Plane, unit: u32, back: u32, front: u32) {
        let line = self.mesh.hold_plane(plane);
        self.set_node(
            n,
            Node::Split {
                line,
                unit,
                back,
                front,
            },
        );
        self.mesh.release_plane(line);
    }

    /// The plane of a split node's line.
    #[inline]
    pub(super) fn line(&self, line: PlaneRef) -> &Plane {
        self.mesh.plane(line)
    }

    /// Filters `piece` (inside `node`'s cell) down to the leaves it covers
    /// with area, each with its part.
    pub(super) fn descend(
        &self,
        node: u32,
        piece: ConvexPolygon,
    ) -> impl Iterator<Item = (u32, ConvexPolygon)> + use<K> {
        self.descend_with(node, piece, (), |(), _| ((), ()), |_, _| false)
            .into_iter()
            .map(|(leaf, part, ())| (leaf, part))
    }

    /// [`Self::descend`], with what the piece carries divided between the
    /// back and front parts at every cut (by `divide`, given the cut's
    /// line). A part that comes out of a cut and is `settled` stops at the
    /// node it reaches, which is then returned in place of the leaves
    /// under it (in the order the walk would have reached them: back
    /// first).
    pub(super) fn descend_with<C>(
        &self,
        node: u32,
        piece: ConvexPolygon,
        carried: C,
        mut divide: impl FnMut(C, &Plane) -> (C, C),
        settled: impl Fn(&ConvexPolygon, &C) -> bool,
    ) -> Vec<(u32, ConvexPolygon, C)> {
        let mut out = Vec::new();
        // A piece walks down in place; only the front part of a cut waits
        // on the stack (back parts first: the order of a plain recursion).
        let mut stack = vec![(node, piece, carried, false)];
        while let Some((mut n, mut piece, mut carried, mut cut)) = stack.pop() {
            loop {
                match &self.nodes[n as usize] {
                    Node::Leaf(_) => {
                        out.push((n, piece, carried));
                        break;
                    }
                    Node::Split { .. } if cut && settled(&piece, &carried) => {
                        out.push((n, piece, carried));
                        break;
                    }
                    Node::Split {
                        line, back, front, ..
                    } => match piece.split(self.line(*line)) {
                        Split::Back => (n, cut) = (*back, false),
                        Split::Front => (n, cut) = (*front, false),
                        Split::Both(b, f) => {
                            let (to_back, to_front) = divide(carried, self.line(*line));
                            stack.push((*front, f, to_front, true));
                            (n, piece, carried, cut) = (*back, b, to_back, true);
                        }
                        Split::Coplanar(_) => break,
                    },
                    Node::Free => break,
                }
            }
        }
        out
    }
}
