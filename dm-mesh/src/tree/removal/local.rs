//! [`Deletion::Local`](super::Deletion::Local): Chrysanthou & Slater's
//! deletion of a node from a DM-tree, in three steps.
//!
//! 1. **Take the node's edge out.** The node's line `L` no longer bounds
//!    anything of its own; the nodes of either subtree whose lines ended on
//!    it are *dangling*.
//! 2. **Choose the subtree to keep**, `a`, by the expected cost
//!    `E[cost_a] = D_a * size_b`: `D_a` the dangling nodes of `a` (one less
//!    than its cells along the line, counted on the mesh: those lines must
//!    be expanded across the other half of the cell), `size_b` the cells of
//!    the other subtree `b` (each is filtered through the expansion). A
//!    leaf costs nothing to keep. The sizes are counted lazily, only as far
//!    as the decision needs, and no geometry is computed.
//! 3. **Expand and insert.** `a` takes the node's place and now spans the
//!    whole cell: every one of its nodes keeps its line, extended across
//!    `b`'s half. Each cell of `b` is filtered down `a`, split (exactly, in
//!    the winged-edge mesh) only by the expanded nodes, since `a`'s other
//!    nodes lie wholly in `a`'s half. Every leaf of `a` that received
//!    pieces gets `b`'s structure restricted to them (a node of `b` is
//!    copied where it still separates pieces, kept as it is where all of it
//!    landed whole in that leaf), behind a construction line on `L` that
//!    keeps `b`'s lines out of `a`'s cell.
//! 4. **Condense.** Where a leaf of `a` received a single cell with the
//!    same occluder list, the two merge across `L` (straight vertices
//!    removed); construction nodes whose two cells have equal lists merge
//!    too. A construction line along which some listed occluder's
//!    discontinuity plane meets the receiver is kept and given to that
//!    occluder (its internal discontinuity, say, would be lost otherwise);
//!    the planes need not be the same in space, only their lines on the
//!    receiver.
//!
//! Nodes are deleted deepest first, so a node's subtrees hold no node of
//! a removed unit when it goes. Every decision is an exact side test of
//! `bsp_core::predicates` (face splits, polygon splits).

use super::{Planes, ReceiverDm};
use crate::tree::{CONSTRUCTION, Node};
use bsp_core::{FaceKey, FaceSplit, Plane, Side};
use smallvec::SmallVec;
use std::collections::BTreeSet;

/// Where a subtree of `b` went: whole into one leaf of `a`, or in parts
/// (per leaf of `a`, ascending, the root of what landed there).
enum Placed {
    Whole(u32),
    Parts(SmallVec<[(u32, u32); 2]>),
}

impl Placed {
    /// As parts, `node` being the subtree that landed whole.
    fn into_parts(self, node: u32) -> SmallVec<[(u32, u32); 2]> {
        match self {
            Placed::Whole(leaf) => smallvec::smallvec![(leaf, node)],
            Placed::Parts(parts) => parts,
        }
    }
}

/// Lists a subtree's leaves a few nodes at a time.
struct Count {
    stack: Vec<u32>,
    leaves: Vec<u32>,
}

impl Count {
    fn new(root: u32) -> Self {
        Self {
            stack: vec![root],
            leaves: Vec::new(),
        }
    }

    fn done(&self) -> bool {
        self.stack.is_empty()
    }

    fn step(&mut self, nodes: &[Node], steps: usize) {
        for _ in 0..steps {
            let Some(n) = self.stack.pop() else { return };
            match nodes[n as usize] {
                Node::Split { back, front, .. } => self.stack.extend([back, front]),
                Node::Leaf(_) => self.leaves.push(n),
                Node::Free => {}
            }
        }
    }
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Deletes every node of the units in `gone` (already out of every
    /// list), deepest first; the construction nodes to condense go to
    /// `made`.
    pub(super) fn delete_nodes(
        &mut self,
        gone: &BTreeSet<u32>,
        planes: &Planes<'_, '_, K>,
        made: &mut Vec<u32>,
    ) {
        let mut nodes: Vec<(usize, u32)> = gone
            .iter()
            .flat_map(|&u| self.unit_nodes(u).to_vec())
            .map(|n| (self.depth(n), n))
            .collect();
        nodes.sort_unstable_by(|x, y| y.cmp(x));
        for (_, n) in nodes {
            self.delete_node(n, planes, made);
        }
    }

    /// Deletes node `n`, whose subtrees hold no node of a removed unit.
    fn delete_node(&mut self, n: u32, planes: &Planes<'_, '_, K>, made: &mut Vec<u32>) {
        let Node::Split {
            line, back, front, ..
        } = self.nodes[n as usize]
        else {
            return;
        };
        // (By value: the node goes before its line is done with.)
        let line = *self.line(line);
        let keep_front = self.keep_front(&line, back, front);
        let (a, b) = if keep_front {
            (front, back)
        } else {
            (back, front)
        };
        let landed = self.insert_subtree(a, b, planes, made);
        // The parent may be a construction node left with two cells.
        if n != self.root {
            made.push(self.parent[n as usize]);
        }
        self.replace_child(n, a);
        self.free_node(n);
        for (leaf, sub) in landed {
            self.attach(leaf, sub, line, keep_front, planes, made);
        }
    }

    /// Step 2: whether to keep the front subtree (else the back one), by
    /// the smaller `D_a * size_b`; on a tie the larger subtree stays.
    ///
    /// Both subtrees are counted a few nodes at a time until the smaller,
    /// `s`, is done. Its cells along the line (those with an edge on it) and
    /// the cells across those edges are the two sides' cells along the
    /// line: one more than each side's dangling nodes (`D_s`, `D_l`), as
    /// each dangling node's line ends between two of them. Then the larger
    /// one, `l`, is counted on only while `D_s * |l|` might still be below
    /// `D_l * |s|`.
    fn keep_front(&self, line: &Plane, back: u32, front: u32) -> bool {
        if self.is_leaf(front) {
            return true;
        }
        if self.is_leaf(back) {
            return false;
        }
        let (mut f, mut b) = (Count::new(front), Count::new(back));
        while !f.done() && !b.done() {
            f.step(&self.nodes, 64);
            b.step(&self.nodes, 64);
        }
        let small_is_front = f.done() && (!b.done() || f.leaves.len() <= b.leaves.len());
        let (small, mut large) = if small_is_front { (f, b) } else { (b, f) };
        let (d_small, d_large) = self.dangling(&small.leaves, line);
        let s = small.leaves.len() as u64;
        let keep_small = loop {
            let l = large.leaves.len() as u64;
            let (cost_small, cost_large) = (d_small * l, d_large * s);
            if large.done() {
                break cost_small < cost_large || (cost_small == cost_large && s > l);
            }
            // |l| only grows: keeping the small side costs more and more.
            if cost_small > cost_large {
                break false;
            }
            if d_small == 0 && d_large > 0 {
                break true;
            }
            large.step(&self.nodes, 64);
        };
        keep_small == small_is_front
    }

    /// The dangling nodes of the side with cells `leaves` and of the other
    /// side, at the deleted node's line `line`.
    fn dangling(&self, leaves: &[u32], line: &Plane) -> (u64, u64) {
        let (mut mine, mut across) = (0_u64, Vec::new());
        for &leaf in leaves {
            let face = self.face_of(leaf);
            let mut on_line = false;
            for side in self.mesh.face_sides(face) {
                if side.edge.line.is_coincident(line) {
                    on_line = true;
                    across.extend(side.across);
                }
            }
            mine += u64::from(on_line);
        }
        across.sort_unstable();
        across.dedup();
        (
            mine.saturating_sub(1),
            (across.len() as u64).saturating_sub(1),
        )
    }

    /// Step 3: filters every cell of `b` down `a` (splitting faces by the
    /// expanded nodes), rebuilding `b`'s structure over what landed in each
    /// leaf of `a`. Returns, per leaf of `a` that received anything, the
    /// root of the subtree that goes there (its parent is still to be
    /// set). `b`'s nodes not reused are freed.
    fn insert_subtree(
        &mut self,
        a: u32,
        b: u32,
        planes: &Planes<'_, '_, K>,
        made: &mut Vec<u32>,
    ) -> SmallVec<[(u32, u32); 2]> {
        let mut freed = Vec::new();
        let mut results: Vec<Placed> = Vec::new();
        // Post-order, back before front.
        let mut stack = vec![(b, false)];
        while let Some((j, children_done)) = stack.pop() {
            match self.nodes[j as usize] {
                Node::Leaf(face) => {
                    let pieces = self.filter_face(a, face);
                    if let [(leaf, f)] = pieces[..]
                        && f == face
                    {
                        results.push(Placed::Whole(leaf));
                        continue;
                    }
                    freed.push(j);
                    let parts = pieces
                        .into_iter()
                        .map(|(leaf, f)| (leaf, self.alloc(Node::Leaf(f), j)))
                        .collect();
                    results.push(Placed::Parts(parts));
                }
                Node::Split { back, front, .. } if !children_done => {
                    stack.push((j, true));
                    stack.push((front, false));
                    stack.push((back, false));
                }
                Node::Split {
                    line,
                    unit,
                    back,
                    front,
                } => {
                    let on_front = results.pop().expect("front placed");
                    let on_back = results.pop().expect("back placed");
                    if let (Placed::Whole(x), Placed::Whole(y)) = (&on_back, &on_front)
                        && x == y
                    {
                        results.push(Placed::Whole(*x));
                        continue;
                    }
                    freed.push(j);
                    let (lb, lf) = (on_back.into_parts(back), on_front.into_parts(front));
                    let line = *self.line(line);
                    let parts = self.join(&line, unit, &lb, &lf, planes, made);
                    results.push(Placed::Parts(parts));
                }
                Node::Free => {}
            }
        }
        for j in freed {
            self.free_node(j);
        }
        match results.pop() {
            Some(placed) => placed.into_parts(b),
            None => SmallVec::new(),
        }
    }

    /// The pieces of face `face` (a cell of the other side) in the leaves
    /// of the subtree at `a`, ascending by leaf: the face split by every
    /// node it reaches whose line cuts it.
    fn filter_face(&mut self, a: u32, face: FaceKey) -> SmallVec<[(u32, FaceKey); 2]> {
        let mut out: SmallVec<[(u32, FaceKey); 2]> = SmallVec::new();
        let mut stack: SmallVec<[(u32, FaceKey); 8]> = smallvec::smallvec![(a, face)];
        while let Some((m, f)) = stack.pop() {
            match self.nodes[m as usize] {
                Node::Leaf(_) => out.push((m, f)),
                Node::Split {
                    line, back, front, ..
                } => {
                    // (By value: the split edits the mesh that holds it.)
                    let line = *self.line(line);
                    match self.mesh.split_face(f, &line) {
                        FaceSplit::NotSplit(Side::Back) => stack.push((back, f)),
                        FaceSplit::NotSplit(_) => stack.push((front, f)),
                        FaceSplit::Split {
                            back: fb,
                            front: ff,
                            ..
                        } => {
                            stack.push((front, ff));
                            stack.push((back, fb));
                        }
                    }
                }
                Node::Free => {}
            }
        }
        out.sort_unstable_by_key(|p| p.0);
        out
    }

    /// A copy of a node of `b` (line `line`, unit `unit`) over what landed
    /// in each leaf of `a`: where both sides received something it
    /// separates them, elsewhere the one side passes through.
    fn join(
        &mut self,
        line: &Plane,
        unit: u32,
        back: &[(u32, u32)],
        front: &[(u32, u32)],
        planes: &Planes<'_, '_, K>,
        made: &mut Vec<u32>,
    ) -> SmallVec<[(u32, u32); 2]> {
        let mut out = SmallVec::with_capacity(back.len().max(front.len()));
        let (mut i, mut k) = (0, 0);
        while i < back.len() || k < front.len() {
            let (lb, lf) = (back.get(i).map(|p| p.0), front.get(k).map(|p| p.0));
            match (lb, lf) {
                (Some(x), Some(y)) if x == y => {
                    let node = self.make_split(line, unit, back[i].1, front[k].1, planes, made);
                    out.push((x, node));
                    i += 1;
                    k += 1;
                }
                (Some(x), Some(y)) if x < y => {
                    out.push(back[i]);
                    i += 1;
                }
                (Some(_), None) => {
                    out.push(back[i]);
                    i += 1;
                }
                _ => {
                    out.push(front[k]);
                    k += 1;
                }
            }
        }
        out
    }

    /// A node splitting `back` from `front` by `line`, or, for a
    /// construction node between two cells that may merge, the merged
    /// cell.
    fn make_split(
        &mut self,
        line: &Plane,
        unit: u32,
        back: u32,
        front: u32,
        planes: &Planes<'_, '_, K>,
        made: &mut Vec<u32>,
    ) -> u32 {
        if unit == CONSTRUCTION
            && self.may_merge(back, front)
            && self.owner_of_line(line, &[back], planes, true).is_none()
        {
            self.merge_leaves(back, front);
            return back;
        }
        // (Held for the making: the new node holds it too.)
        let held = self.mesh.hold_plane(line);
        let node = self.alloc(
            Node::Split {
                line: held,
                unit,
                back,
                front,
            },
            back,
        );
        self.mesh.release_plane(held);
        self.parent[back as usize] = node;
        self.parent[front as usize] = node;
        if unit == CONSTRUCTION {
            made.push(node);
        }
        node
    }

    /// Gives leaf `leaf` of the kept subtree what landed in it, `sub`
    /// (behind the deleted node's line `line` if the front was kept):
    /// merged with it if it is a single cell with the same list and no
    /// listed occluder's discontinuity lies on `line`, else split from it
    /// by a node on `line`.
    fn attach(
        &mut self,
        leaf: u32,
        sub: u32,
        line: Plane,
        kept_front: bool,
        planes: &Planes<'_, '_, K>,
        made: &mut Vec<u32>,
    ) {
        let both = [leaf, sub];
        let leaves = if self.is_leaf(sub) {
            &both[..]
        } else {
            &both[..1]
        };
        // Whether the cells may merge is decided on the receiver; a node
        // that stays goes to the occluder whose plane it lies in, if any
        // (the cheaper test: most cells along the line cannot merge).
        let mergeable = self.may_merge(leaf, sub);
        let owner = self.owner_of_line(&line, leaves, planes, mergeable);
        if owner.is_none() && mergeable {
            self.merge_leaves(leaf, sub);
            if leaf != self.root {
                made.push(self.parent[leaf as usize]);
            }
            return;
        }
        let kept = self.alloc(Node::Leaf(self.face_of(leaf)), leaf);
        let (back, front) = if kept_front { (sub, kept) } else { (kept, sub) };
        let unit = owner.unwrap_or(CONSTRUCTION);
        self.set_split(leaf, &line, unit, back, front);
        self.parent[sub as usize] = leaf;
        if unit == CONSTRUCTION {
            made.push(leaf);
        }
    }

    /// Whether `x` and `y` are leaves whose cells may merge: the same
    /// occluder entries (as sets) and the same unreached lights.
    fn may_merge(&self, x: u32, y: u32) -> bool {
        if !(self.is_leaf(x) && self.is_leaf(y)) {
            return false;
        }
        let (cx, cy) = (self.cell(x), self.cell(y));
        cx.unreached == cy.unreached
            && cx.entries.len() == cy.entries.len()
            && cx.entries.iter().all(|e| cy.entries.contains(e))
    }

    /// Merges leaf `y`'s cell into leaf `x`'s (adjacent, with a convex
    /// union); `x` keeps its list, with the units either had culled, and
    /// `y` is freed.
    fn merge_leaves(&mut self, x: u32, y: u32) {
        let mut data = self.cell(x).clone();
        for &u in &self.cell(y).culled {
            if !data.culled.contains(&u) {
                data.culled.push(u);
            }
        }
        let kept = self.merge_cells(self.face_of(x), self.face_of(y));
        *self.face_data_mut(kept) = data;
        self.set_node(x, Node::Leaf(kept));
        self.free_node(y);
    }

    /// Step 4 for the construction nodes in `made`: one whose two children
    /// are cells that may merge (and no listed occluder's discontinuity
    /// lies on its line) becomes their merged cell, and its parent is
    /// looked at again.
    pub(super) fn condense(&mut self, mut made: Vec<u32>, planes: &Planes<'_, '_, K>) {
        while let Some(n) = made.pop() {
            let Node::Split {
                line,
                unit: CONSTRUCTION,
                back,
                front,
            } = self.nodes[n as usize]
            else {
                continue;
            };
            if !self.may_merge(back, front) {
                continue;
            }
            let plane = *self.line(line);
            if let Some(owner) = self.owner_of_line(&plane, &[back], planes, true) {
                self.set_node(
                    n,
                    Node::Split {
                        line,
                        unit: owner,
                        back,
                        front,
                    },
                );
                continue;
            }
            self.merge_leaves(back, front);
            // The merged cell takes the node's place.
            self.replace_child(n, back);
            self.free_node(n);
            if back != self.root {
                made.push(self.parent[back as usize]);
            }
        }
    }
}
