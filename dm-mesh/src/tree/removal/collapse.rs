//! [`Deletion::Collapse`](super::Deletion::Collapse): every subtree under a
//! removed unit's topmost nodes collapses into the cell it split, and the
//! other units that reached that cell are merged in again, restricted to
//! it.

use super::{Planes, ReceiverDm};
use crate::cell::Entry;
use crate::critical::Critical;
use crate::tree::{Node, tracked};
use bsp_core::{ConvexPolygon, Plane, PolygonSide};
use smallvec::SmallVec;
use std::collections::BTreeSet;

/// Whether `polygon` lies inside every plane of `part` (behind each).
fn inside(polygon: &ConvexPolygon, part: &[Plane]) -> bool {
    part.iter()
        .all(|q| polygon.classify(q) == PolygonSide::Back)
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Collapses the subtrees under the topmost nodes of the units in
    /// `gone` (already out of every list) and merges the other units that
    /// reached them again, in unit order.
    pub(super) fn collapse_units(&mut self, gone: &BTreeSet<u32>, planes: &Planes<'_, '_, K>) {
        let mut nodes: Vec<u32> = gone
            .iter()
            .flat_map(|&u| self.unit_nodes(u).iter().copied())
            .collect();
        nodes.sort_unstable();
        let starts: Vec<u32> = nodes
            .iter()
            .copied()
            .filter(|&n| !self.ancestors(n).any(|a| self.owned_by(a, gone)))
            .collect();
        for n in starts {
            let (mut kept, mut redo) = self.units_under(n);
            self.collapse(n);
            let face = self.face_of(n);
            let region = self.mesh.face_polygon(face, 0).ok();
            // A unit whose penumbra comes in parts can be listed by every
            // cell under `n` from different parts, the line between them
            // another unit's node: the merged cell then lies in no one part,
            // and the unit is merged again there instead of kept.
            if let Some(region) = &region {
                kept.retain(|e| {
                    let whole = self.unit(e.unit).is_none_or(|(key, light)| {
                        let parts = &planes.get(key, light).volumes.penumbra;
                        parts.len() == 1 || parts.iter().any(|part| inside(region, part))
                    });
                    if !whole {
                        redo.insert(e.unit);
                    }
                    whole
                });
            }
            let cell = self.cell_mut(n);
            cell.entries = kept.iter().copied().collect();
            cell.culled.clear();
            let Some(region) = region else {
                continue;
            };
            // A kept unit's internal discontinuity may lie along a line of
            // the collapsed subtree, between cells it did not cross: in the
            // merged cell it crosses, so it is grown again there.
            for entry in kept.iter().filter(|e| e.umbra.is_none()) {
                if let Some((key, light)) = self.unit(entry.unit) {
                    let internal: SmallVec<[&Critical; 32]> =
                        planes.get(key, light).internal.iter().collect();
                    if !internal.is_empty() {
                        self.grow_internal(n, &internal, entry.unit);
                    }
                }
            }
            for unit in redo {
                if let Some((key, light)) = self.unit(unit) {
                    self.merge_unit(n, Some(&region), unit, light, planes.get(key, light));
                }
            }
        }
    }

    /// Whether node `n` is a node of a unit in `gone`.
    fn owned_by(&self, n: u32, gone: &BTreeSet<u32>) -> bool {
        matches!(self.nodes[n as usize], Node::Split { unit, .. } if gone.contains(&unit))
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

    /// For the subtree at `node`: the entries every one of its cells has
    /// of units with no node in it (in unit order), and the other live
    /// units that reached it (node owners, listed or culled somewhere), in
    /// order.
    fn units_under(&self, node: u32) -> (Vec<Entry>, BTreeSet<u32>) {
        let mut reached = BTreeSet::new();
        let mut owners = BTreeSet::new();
        let mut common: Option<Vec<Entry>> = None;
        let mut stack = vec![node];
        while let Some(n) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Split {
                    unit, back, front, ..
                } => {
                    owners.insert(*unit);
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
        // A unit with a node inside (an internal discontinuity between
        // cells that all list it) is merged again, not kept.
        let mut kept = common.unwrap_or_default();
        kept.retain(|e| !owners.contains(&e.unit));
        kept.sort_by_key(|e| e.unit);
        reached.extend(owners);
        for e in &kept {
            reached.remove(&e.unit);
        }
        reached.retain(|&u| tracked(u) && self.unit(u).is_some());
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
            self.set_node(n, Node::Leaf(kept));
            for child in [back, front] {
                self.free_node(child);
            }
        }
    }
}
