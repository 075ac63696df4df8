//! Removing units from a receiver's DM-tree: every subtree a removed unit
//! grew collapses into the cell it split, and the later units that reached
//! that cell are merged in again, restricted to it.

use super::{LIGHT_UNIT, Node, ReceiverDm};
use crate::cell::Entry;
use crate::critical::UnitPlanes;
use bsp_core::{FaceKey, VertexKey};
use std::collections::BTreeSet;

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Removes the units in `gone`. Every subtree such a unit grew (found
    /// from its recorded roots) collapses into the cell it split (faces
    /// merged, straight vertices condensed); that cell keeps the entries
    /// every one of its parts had, and the other units that reached it are
    /// merged in again, in order, restricted to it. `planes(key, light)`
    /// gives a unit's volume planes.
    pub(crate) fn remove_units<'p>(
        &mut self,
        gone: &BTreeSet<u32>,
        planes: impl Fn(K, u8) -> &'p UnitPlanes,
    ) {
        if gone.is_empty() {
            return;
        }
        let recorded: Vec<u32> = gone
            .iter()
            .filter_map(|&u| self.roots.get_mut(u as usize).map(std::mem::take))
            .flatten()
            .collect();
        let mut starts: Vec<u32> = recorded
            .into_iter()
            .filter(|&n| self.reached_by(n, gone))
            .collect();
        starts.sort_unstable();
        starts.dedup();
        // Only the topmost: a start below another goes with it.
        let all: BTreeSet<u32> = starts.iter().copied().collect();
        starts.retain(|&n| {
            !self
                .ancestors(n)
                .any(|a| all.contains(&a) || self.owned_by(a, gone))
        });
        for unit in gone {
            if let Some(slot) = self.units.get_mut(*unit as usize) {
                *slot = None;
            }
        }
        for n in starts {
            let (kept, redo) = self.units_under(n, gone);
            self.collapse(n);
            let cell = self.cell_mut(n);
            cell.entries = kept.iter().copied().collect();
            cell.culled.clear();
            for e in &kept {
                self.roots_of(e.unit).push(n);
            }
            let face = self.face_of(n);
            let Ok(region) = self.mesh.face_polygon(face, 0) else {
                continue;
            };
            for unit in redo {
                if let Some((key, light)) = self.unit(unit) {
                    self.merge_unit(n, Some(&region), unit, light, planes(key, light));
                }
            }
        }
    }

    /// Whether node `n` is a node of a unit in `gone`.
    fn owned_by(&self, n: u32, gone: &BTreeSet<u32>) -> bool {
        matches!(self.nodes[n as usize], Node::Split { unit, .. } if gone.contains(&unit))
    }

    /// Whether node `n` (a recorded root) is still something a unit in
    /// `gone` made or reached: its node, or a cell listing or culling it
    /// (split since by later units: its first leaf tells, as a unit that
    /// grew in a cell without splitting it is in every part of it).
    fn reached_by(&self, n: u32, gone: &BTreeSet<u32>) -> bool {
        let mut at = n;
        loop {
            match self.nodes.get(at as usize) {
                Some(Node::Split { unit, back, .. }) => {
                    if gone.contains(unit) {
                        return true;
                    }
                    at = *back;
                }
                Some(Node::Leaf(_)) => {
                    let cell = self.cell(at);
                    return cell.entries.iter().any(|e| gone.contains(&e.unit))
                        || cell.culled.iter().any(|u| gone.contains(u));
                }
                _ => return false,
            }
        }
    }

    /// The proper ancestors of `n`, nearest first.
    fn ancestors(&self, n: u32) -> impl Iterator<Item = u32> + '_ {
        let mut at = n;
        std::iter::from_fn(move || {
            if at == self.root {
                return None;
            }
            at = self.parent[at as usize];
            Some(at)
        })
    }

    /// For the subtree at `node`, leaving out units in `gone`: the entries
    /// every one of its cells has (in order), and the other units that
    /// reached it (node owners, listed or culled somewhere), in order.
    fn units_under(&self, node: u32, gone: &BTreeSet<u32>) -> (Vec<Entry>, BTreeSet<u32>) {
        let mut reached = BTreeSet::new();
        let mut common: Option<Vec<Entry>> = None;
        let mut stack = vec![node];
        while let Some(n) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Split {
                    unit, back, front, ..
                } => {
                    reached.insert(*unit);
                    stack.push(*back);
                    stack.push(*front);
                }
                Node::Leaf(_) => {
                    let cell = self.cell(n);
                    reached.extend(cell.entries.iter().map(|e| e.unit));
                    reached.extend(cell.culled.iter().copied());
                    match &mut common {
                        None => common = Some(cell.entries.to_vec()),
                        Some(c) => c.retain(|e| cell.entries.contains(e)),
                    }
                }
                Node::Free => {}
            }
        }
        let mut kept = common.unwrap_or_default();
        kept.retain(|e| !gone.contains(&e.unit));
        kept.sort_by_key(|e| e.unit);
        for e in &kept {
            reached.remove(&e.unit);
        }
        reached.retain(|u| !gone.contains(u) && *u != LIGHT_UNIT);
        (kept, reached)
    }

    /// Collapses the subtree at `node` into one leaf: children first, each
    /// pair of sibling cells merged across the edges between them.
    fn collapse(&mut self, node: u32) {
        // Post-order of the inner nodes.
        let mut order = Vec::new();
        let mut stack = vec![node];
        while let Some(n) = stack.pop() {
            if let Node::Split { back, front, .. } = self.nodes[n as usize] {
                order.push(n);
                stack.push(back);
                stack.push(front);
            }
        }
        for &n in order.iter().rev() {
            let Node::Split { back, front, .. } = self.nodes[n as usize] else {
                continue;
            };
            let (fb, ff) = (self.face_of(back), self.face_of(front));
            let kept = self.merge_cells(fb, ff);
            self.nodes[n as usize] = Node::Leaf(kept);
            self.cell_mut(n).leaf = n;
            for child in [back, front] {
                self.nodes[child as usize] = Node::Free;
                self.free.push(child);
            }
        }
    }

    /// Merges two adjacent cells (their union is convex: a node's cell);
    /// returns the face that remains.
    fn merge_cells(&mut self, a: FaceKey, b: FaceKey) -> FaceKey {
        let shared: Vec<VertexKey> = {
            let vb = self.mesh.face_vertices(b);
            self.mesh
                .face_vertices(a)
                .into_iter()
                .filter(|v| vb.contains(v))
                .collect()
        };
        let edge = self
            .mesh
            .face_edges(a)
            .into_iter()
            .find(|&e| {
                let edge = self.mesh.edge(e).expect("face edge");
                edge.left == Some(b) || edge.right == Some(b)
            })
            .expect("sibling cells share an edge");
        let kept = self
            .mesh
            .merge_faces(edge)
            .expect("sibling cells make their parent's convex cell");
        for v in shared {
            self.mesh.remove_vertex_if_collinear(v);
        }
        kept
    }
}
