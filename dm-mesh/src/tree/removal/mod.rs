//! Removing units from a receiver's DM-tree.
//!
//! Three passes, whichever [`Deletion`] is chosen:
//!
//! 1. the removed units leave the occluder lists: every cell that lists or
//!    culled one (flooded over the mesh from a cell that does) drops it;
//!    where a removed unit's umbra was the only one, the units it culled
//!    there are set free;
//! 2. their nodes go: deleted in place one by one ([`Deletion::Local`], the
//!    paper's method, module `local`), or the subtrees under their topmost
//!    nodes collapsed and re-merged ([`Deletion::Collapse`], module
//!    `collapse`);
//! 3. construction nodes over changed cells that separate nothing any
//!    more are condensed, and the units set free are merged again into the
//!    removed units' umbra regions (cells that already hold them are left
//!    alone).
//!
//! Measured by callgrind instruction counts (`dm-cost`, one removal from a
//! fresh build, 1 thread; a rebuild with illumination is 146.5M for the
//! office, 322.2M for the cubes): office desk_1 local 4.77M (3.3 % of a
//! rebuild) / collapse 4.61M, monitor_1 5.14M (3.5 %) / 3.11M, cubes
//! cube_1 16.2M (5.0 %) / 26.4M; moving a box of the 10k hall three times
//! (`umbra update`, loaded machine) took 57-61 ms a step locally and 51 ms
//! to 1.97 s by collapsing (a collapsed tile re-merges every occluder that
//! reached it). After 40 moves back and forth either way the trees have as
//! many cells as a fresh build (office 2915; cubes 4567 built, 4576 after).
//! The paper's method is the default: it never re-merges the occluders
//! that came later, which is what costs most where many reach the removed
//! one's cells.

use super::{ReceiverDm, clip};
use crate::critical::UnitPlanes;
use bsp_core::predicates::Pencil;
use bsp_core::{ConvexPolygon, FaceKey, Plane, VertexKey};
use smallvec::SmallVec;
use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};

mod collapse;
mod flood;
mod local;
#[cfg(test)]
mod tests;

pub(crate) use flood::{Flood, Flooded};

/// How a removal takes an occluder's discontinuities out of a DM-tree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Deletion {
    /// Chrysanthou & Slater's deletion, node by node, deepest first: the
    /// node's edge leaves the mesh; of its two subtrees the one with the
    /// smaller expected cost `D_a * size_b` is kept (`D_a`: the kept side's
    /// nodes whose lines ended on the edge, *dangling*, that must be
    /// expanded across the node's cell; `size_b`: the cells of the other
    /// side, to insert); the other side's cells are filtered down the kept
    /// subtree, where only the expanded nodes can cut them; then cells that
    /// no discontinuity separates any more are merged and straight vertices
    /// removed. The default.
    #[default]
    Local,
    /// The subtrees under a removed unit's topmost nodes collapse into the
    /// cells they split (faces merged, straight vertices removed), and the
    /// other units that reached those cells are merged in again, restricted
    /// to them.
    Collapse,
}

/// The units' volume planes during a removal, looked up by occluder key
/// and light ([`Self::get`]), with the answers of the tests for a line
/// last asked about: a removal asks along one line again and again (for
/// each cell along a deleted node's edge), of cells listing mostly the
/// same units (about half of the tests on the 3k hall are repeats).
pub(super) struct Planes<'a, 'p, K> {
    lookup: &'a dyn Fn(K, u8) -> &'p UnitPlanes,
    along: RefCell<LineAnswers>,
}

/// [`UnitPlanes::has_plane_on`]'s answers for one line, by unit and the
/// planes looked at. They hold for the whole removal: a unit's planes,
/// the line and the receiver do not change in it.
#[derive(Default)]
struct LineAnswers {
    /// The line, and whether its trace on the receiver counted.
    line: Option<(Plane, bool)>,
    /// `(unit, penumbra planes looked at, umbra planes looked at, holds)`.
    answers: Vec<(u32, bool, bool, bool)>,
}

impl<'a, 'p, K> Planes<'a, 'p, K> {
    fn new(lookup: &'a dyn Fn(K, u8) -> &'p UnitPlanes) -> Self {
        Self {
            lookup,
            along: RefCell::default(),
        }
    }

    /// The planes of the unit of occluder `key` under `light`.
    pub(super) fn get(&self, key: K, light: u8) -> &'p UnitPlanes {
        (self.lookup)(key, light)
    }

    /// [`UnitPlanes::has_plane_on`] for `unit` (whose planes are `planes`),
    /// remembered for the line.
    #[allow(clippy::too_many_arguments)] // (the question, and what it is remembered by)
    fn has_plane_on(
        &self,
        unit: u32,
        planes: &UnitPlanes,
        line: &Plane,
        on_receiver: bool,
        trace: Option<&Pencil>,
        penumbra: bool,
        umbra: bool,
    ) -> bool {
        let mut along = self.along.borrow_mut();
        if along.line != Some((*line, on_receiver)) {
            along.line = Some((*line, on_receiver));
            along.answers.clear();
        }
        let asked = (unit, penumbra, umbra);
        if let Some(&(.., holds)) = along.answers.iter().find(|a| (a.0, a.1, a.2) == asked) {
            return holds;
        }
        let holds = planes.has_plane_on(line, trace, penumbra, umbra);
        along.answers.push((unit, penumbra, umbra, holds));
        holds
    }
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Removes the units in `gone` by `how`; `planes(key, light)` gives a
    /// unit's volume planes (of the removed units too: they are still
    /// there when this is called). `ahead`: their cells, if already found
    /// ([`Self::flood_ahead`]; a flood of other units is not used).
    pub(crate) fn remove_units<'p>(
        &mut self,
        gone: &BTreeSet<u32>,
        planes: impl Fn(K, u8) -> &'p UnitPlanes,
        how: Deletion,
        ahead: Option<Flooded>,
    ) {
        let planes = Planes::new(&planes);
        let removed: Vec<(u32, u8, &UnitPlanes)> = gone
            .iter()
            .filter_map(|&u| self.unit(u).map(|(k, l)| (u, l, planes.get(k, l))))
            .collect();
        if removed.is_empty() {
            return;
        }
        for &(u, _, _) in &removed {
            self.units[u as usize] = None;
        }
        // Construction nodes over cells whose lists change may separate
        // nothing any more: they are looked at once the nodes are gone.
        let mut made = Vec::new();
        let freed = self.drop_from_lists(&removed, &mut made, ahead);
        match how {
            Deletion::Local => self.delete_nodes(gone, &planes, &mut made),
            Deletion::Collapse => self.collapse_units(gone, &planes),
        }
        self.condense(made, &planes);
        for (unit, by) in freed {
            let Some((key, light)) = self.unit(unit) else {
                continue;
            };
            let own = planes.get(key, light);
            for &(u, _, removed_planes) in &removed {
                if !by.contains(&u) {
                    continue;
                }
                for region in umbra_regions(&self.polygon, removed_planes) {
                    self.merge_unit(self.root, Some(&region), unit, light, own);
                }
            }
        }
    }

    /// Pass 1: the removed units (already marked gone) leave every list;
    /// the parents of the cells changed go to `parents`. Returns the units
    /// set free, each with the removed units whose umbra had culled it.
    fn drop_from_lists(
        &mut self,
        removed: &[(u32, u8, &UnitPlanes)],
        parents: &mut Vec<u32>,
        ahead: Option<Flooded>,
    ) -> BTreeMap<u32, BTreeSet<u32>> {
        let mut freed: BTreeMap<u32, BTreeSet<u32>> = BTreeMap::new();
        let held = self.cells_of(removed, ahead);
        // Each cell's units leave in the order of `removed` (a cell's lists
        // change only by its own units leaving); the parents are listed
        // unit by unit, each unit's cells in ascending order.
        let mut cells_of_unit: Vec<Vec<u32>> = vec![Vec::new(); removed.len()];
        for (leaf, units) in held {
            for i in units {
                let i = i as usize;
                let (u, light, _) = removed[i];
                cells_of_unit[i].push(leaf);
                let l = usize::from(light);
                let cell = self.cell(leaf);
                let was_umbra = cell.in_umbra(l);
                let culled: SmallVec<[(u32, Option<u8>); 4]> = cell
                    .culled
                    .iter()
                    .filter(|&&v| v != u)
                    .map(|&v| (v, self.unit(v).map(|(_, lv)| lv)))
                    .collect();
                let cell = self.cell_mut(leaf);
                cell.entries.retain(|e| e.unit != u);
                let free = was_umbra && !cell.in_umbra(l);
                cell.culled.clear();
                for (v, lv) in culled {
                    match lv {
                        Some(lv) if free && lv == light => {
                            freed.entry(v).or_default().insert(u);
                        }
                        // (Another removed unit leaves in its own turn.)
                        _ => cell.culled.push(v),
                    }
                }
            }
        }
        for leaf in cells_of_unit.into_iter().flatten() {
            if leaf != self.root {
                parents.push(self.parent[leaf as usize]);
            }
        }
        freed
    }

    /// The faces holding unit `u` that its penumbra regions reach with
    /// area, filtered down the tree exactly.
    fn cells_by_descent(&self, u: u32, planes: &UnitPlanes) -> Vec<FaceKey> {
        let mut out = Vec::new();
        for part in &planes.volumes.penumbra {
            let Some(region) = clip(&self.polygon, part) else {
                continue;
            };
            out.extend(
                self.descend(self.root, region)
                    .map(|(leaf, _)| self.face_of(leaf))
                    .filter(|&f| self.holds(f, u)),
            );
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Merges two adjacent cells (their union is convex: a node's cell),
    /// condensing the vertices they shared that became straight; returns
    /// the face that remains (its payload is one of theirs: the caller sets
    /// it).
    fn merge_cells(&mut self, a: FaceKey, b: FaceKey) -> FaceKey {
        // The edges between the two, and their ends (the vertices that may
        // become straight).
        let mut edge = None;
        let mut shared: Vec<VertexKey> = Vec::with_capacity(4);
        for side in self.mesh.face_sides(a) {
            let x = side.edge;
            if side.across == Some(b) {
                edge.get_or_insert(side.key);
                for v in [x.start, x.end] {
                    if !shared.contains(&v) {
                        shared.push(v);
                    }
                }
            }
        }
        let edge = edge.expect("sibling cells share an edge");
        let units: Vec<u32> = [a, b]
            .iter()
            .flat_map(|&f| {
                let data = &self.mesh.face(f).expect("cell face").data;
                data.entries
                    .iter()
                    .map(|e| e.unit)
                    .chain(data.culled.iter().copied())
            })
            .collect();
        let kept = self
            .mesh
            .merge_faces(edge)
            .expect("sibling cells make their parent's convex cell");
        // Seeds of the face that went move to the one that stays.
        let gone = if kept == a { b } else { a };
        for u in units {
            if let Some(seed) = self.seeds.get_mut(u as usize)
                && *seed == gone
            {
                *seed = kept;
            }
        }
        for v in shared {
            self.mesh.remove_vertex_if_collinear(v);
        }
        if self.tracking {
            self.touched.push(kept);
        }
        kept
    }

    /// The smallest live unit listed in one of `leaves` whose penumbra,
    /// umbra or internal discontinuity planes hold `line`: on the receiver
    /// (`on_receiver`, for cells that may merge with those across the line:
    /// the owner of a discontinuity there, if any, before they merge), or
    /// in space (the occluder a node on `line` belongs to).
    fn owner_of_line(
        &self,
        line: &Plane,
        leaves: &[u32],
        planes: &Planes<'_, '_, K>,
        on_receiver: bool,
    ) -> Option<u32> {
        let mut owner: Option<u32> = None;
        let trace = if on_receiver { self.trace(line) } else { None };
        for &leaf in leaves {
            for e in &self.cell(leaf).entries {
                if owner.is_some_and(|o| o <= e.unit) {
                    continue;
                }
                let Some((key, light)) = self.unit(e.unit) else {
                    continue;
                };
                // Cells that may merge list the same units, umbra or not,
                // on both sides of the line; both then lie inside each
                // convex part of a unit's region they list it in, so the
                // line cannot be the trace of a plane bounding that part:
                // only the planes between penumbra parts, and umbra planes
                // where the cells lie outside the umbra, are looked at.
                let p = planes.get(key, light);
                let penumbra = !on_receiver || p.volumes.penumbra.len() > 1;
                let umbra = !on_receiver || e.umbra.is_none();
                let holds = planes.has_plane_on(
                    e.unit,
                    p,
                    line,
                    on_receiver,
                    trace.as_ref(),
                    penumbra,
                    umbra,
                );
                if holds {
                    owner = Some(e.unit);
                }
            }
        }
        owner
    }

    /// The line where `line` meets the receiver, to find the planes that
    /// meet it there too: planes other than `line` may (a discontinuity
    /// plane and the plane of a node, both through one line of the
    /// receiver, differ in space but bound the same cells).
    fn trace(&self, line: &Plane) -> Option<Pencil> {
        Pencil::new(line, self.polygon.support())
    }
}

/// The umbra regions of a unit on `receiver` (where it can have culled
/// others).
fn umbra_regions(receiver: &ConvexPolygon, planes: &UnitPlanes) -> Vec<ConvexPolygon> {
    let Some(umbra) = &planes.volumes.umbra else {
        return Vec::new();
    };
    planes
        .volumes
        .penumbra
        .iter()
        .filter_map(|part| clip(receiver, part))
        .filter_map(|region| clip(&region, umbra))
        .collect()
}
