//! One receiver's DM-tree: a 2D BSP whose leaves are the faces of a
//! winged-edge mesh (Chrysanthou & Slater).
//!
//! The root cell is the receiver polygon; its boundary edges bound the
//! subspace and are no nodes. Each light first splits the receiver by its
//! own plane (nothing arrives behind it). Then every *unit* (one occluder
//! under one light) is merged in: its single tree, a linear chain of the
//! penumbra volume's planes with the umbra chain at its back, is filtered
//! down the receiver's tree with the unit's region (the receiver clipped by
//! the penumbra planes) as Naylor's merge filters a linear tree, and at each
//! leaf it reaches the chain is grown in place: a plane that cuts the cell
//! becomes a node, the cell part in front keeps its list, and the innermost
//! part adds the occluder to its list (marked umbra past the umbra chain).
//! Only the planes that bound the cell's part of the region (edges of the
//! piece the filtering brought to the leaf) are tried: the others are
//! redundant in that cell, and would only cut off cells with the same list.
//! (A removal merging freed units again restricts their regions to a cell;
//! those pieces can be smaller than the leaves' parts, so there every plane
//! is tried, and the umbra is looked for in the listing cell itself.)
//! So every node's line spans just its own cell (the sub-hyperplane is the
//! mesh edge it made).
//!
//! A receiver many units reach is first cut into tiles
//! ([`ReceiverDm::tile`]): construction nodes like the light planes', never
//! removed, that keep every later subtree local. A new receiver's tiles are
//! then grown apart, in parallel, each in a mesh of its own, and grafted
//! into its tree and mesh (module `tiled`).
//!
//! Every unit keeps the exact list of its nodes, wherever they are, so that
//! removing it ([`ReceiverDm::remove_units`], module `removal`) finds them:
//! by default each node is deleted in place as the paper does (its edge
//! taken out, one subtree kept and expanded across the node's cell, the
//! other inserted into it, what became redundant condensed), or, on
//! request, the subtrees under the unit's topmost nodes are collapsed and
//! the other units that reached them merged in again.

use crate::cell::{Cell, CellClass};
use crate::hash::KeySet;
use area_shadow::{AreaSource, SourceSide};
use bsp_core::predicates::Side;
use bsp_core::{Behind, ConvexPolygon, FaceKey, Plane, PlaneRef, WingedMesh};

mod arena;
mod check;
mod insert;
mod regions;
mod removal;
#[cfg(test)]
mod testing;
mod tile;
mod tiled;

pub use regions::Region;
pub use removal::Deletion;
pub(crate) use removal::{Flood, Flooded};

/// The unit number of the light-plane splits and tiles made when a
/// receiver is created (they are never removed, and always above every
/// other node).
pub(crate) const LIGHT_UNIT: u32 = u32::MAX;

/// The unit number of construction nodes made by deletions: lines that
/// bound what one side of a deleted node holds, and that are condensed
/// away once they separate nothing.
pub(crate) const CONSTRUCTION: u32 = u32::MAX - 1;

/// Whether nodes of `unit` are listed per unit (an occluder's, not a
/// construction line).
pub(crate) fn tracked(unit: u32) -> bool {
    unit < CONSTRUCTION
}

/// A node of the 2D BSP.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Node {
    /// A cell: a face of the mesh.
    Leaf(FaceKey),
    /// A split of the node's cell by `line` (the receiver cut by that
    /// plane, held in the mesh's table of planes, where the vertices its
    /// cuts made name it too: 4 bytes instead of 48): `back` behind it,
    /// `front` in front.
    Split {
        line: PlaneRef,
        unit: u32,
        back: u32,
        front: u32,
    },
    /// A free arena slot.
    Free,
}

/// How much of a light can reach a receiver's front (or either side, when
/// it is two-sided).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Reach {
    /// None: every cell is in umbra for it.
    None,
    /// The receiver's plane cuts the light: unoccluded cells see part.
    Part,
    /// All of it, where nothing blocks.
    All,
}

/// What the receiver's units are: one occluder key under one light.
pub(crate) type UnitRef<K> = (K, u8);

/// One receiver's DM-tree and its cells.
#[derive(Debug, Clone)]
pub struct ReceiverDm<K> {
    polygon: ConvexPolygon,
    mesh: WingedMesh<Cell, ()>,
    nodes: Vec<Node>,
    /// The parent of each node (the root's is itself).
    parent: Vec<u32>,
    /// Each node's position in its unit's list in `unit_nodes`.
    slot: Vec<u32>,
    free: Vec<u32>,
    /// Per unit, its nodes.
    unit_nodes: Vec<Vec<u32>>,
    /// Per unit, a face that listed or culled it when last seen (a removal
    /// floods the unit's cells from there; stale ones are checked).
    seeds: Vec<FaceKey>,
    root: u32,
    reach: Vec<Reach>,
    units: Vec<Option<UnitRef<K>>>,
    /// Faces whose shape or list changed since [`Self::take_touched`]
    /// (some may be gone since).
    touched: Vec<FaceKey>,
    /// Whether changes are recorded in `touched` (not before the first
    /// illumination, which looks at every face anyway).
    tracking: bool,
}

/// The region of a unit on a receiver: `polygon` clipped by `planes`.
pub(crate) fn clip<'a>(
    polygon: &ConvexPolygon,
    planes: impl IntoIterator<Item = &'a Plane>,
) -> Option<ConvexPolygon> {
    // (`None` while no plane has cut it: the polygon is copied only if
    // kept whole.)
    let mut piece: Option<ConvexPolygon> = None;
    for plane in planes {
        match piece.as_ref().unwrap_or(polygon).behind(plane) {
            Behind::All => {}
            Behind::Part(back) => piece = Some(back),
            Behind::Nothing => return None,
        }
    }
    Some(piece.unwrap_or_else(|| polygon.clone()))
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// A receiver's tree before any occluder: the light planes' splits.
    pub(crate) fn new(polygon: ConvexPolygon, two_sided: bool, lights: &[AreaSource]) -> Self {
        let mesh = WingedMesh::from_polygon(&polygon, Cell::default(), ());
        let face = mesh.faces().next().map(|(k, _)| k).expect("one face");
        let mut dm = Self {
            polygon,
            mesh,
            nodes: vec![Node::Leaf(face)],
            parent: vec![0],
            slot: vec![u32::MAX],
            free: Vec::new(),
            unit_nodes: Vec::new(),
            seeds: Vec::new(),
            root: 0,
            reach: Vec::with_capacity(lights.len()),
            units: Vec::new(),
            touched: Vec::new(),
            tracking: false,
        };
        for (i, light) in lights.iter().enumerate() {
            let reach = match light.side_of(dm.polygon.support()) {
                SourceSide::In => Reach::None,
                SourceSide::Front => Reach::All,
                // A two-sided receiver whose plane cuts the light receives
                // each part on its own side: all of it, where unblocked.
                SourceSide::Back | SourceSide::Both if two_sided => Reach::All,
                SourceSide::Back => Reach::None,
                SourceSide::Both => Reach::Part,
            };
            dm.reach.push(reach);
            let bit = 1_u32 << i;
            let leaves = dm.leaves(dm.root);
            for leaf in leaves {
                if reach == Reach::None {
                    dm.cell_mut(leaf).unreached |= bit;
                    continue;
                }
                match dm.split_leaf(leaf, light.support(), LIGHT_UNIT) {
                    Ok((back, _)) => dm.cell_mut(back).unreached |= bit,
                    Err(Side::Back) => dm.cell_mut(leaf).unreached |= bit,
                    Err(_) => {}
                }
            }
        }
        dm
    }

    /// Whether no light reaches the receiver at all (no occluder can
    /// change anything on it).
    pub(crate) fn in_the_dark(&self) -> bool {
        self.reach.iter().all(|r| *r == Reach::None)
    }

    /// Forgets the changes so far and records those from now on (called by
    /// the first illumination, which looks at every face).
    pub(crate) fn start_tracking(&mut self) {
        self.touched.clear();
        self.tracking = true;
    }

    /// Whether changes are recorded ([`Self::start_tracking`] has run).
    pub(crate) fn is_tracking(&self) -> bool {
        self.tracking
    }

    /// Whether some face changed since the last [`Self::take_touched`].
    pub(crate) fn has_touched(&self) -> bool {
        !self.touched.is_empty()
    }

    /// The faces changed since the last call (each once, those still
    /// there), and forgets them.
    pub(crate) fn take_touched(&mut self) -> Vec<FaceKey> {
        let mut out = std::mem::take(&mut self.touched);
        // (A hash set keeps the first of each: sorting the repeats, two
        // or three per face, cost more.)
        let mut seen: KeySet<FaceKey> = KeySet::default();
        seen.reserve(out.len());
        out.retain(|f| seen.insert(*f) && self.mesh.face(*f).is_some());
        out
    }

    /// The receiver polygon.
    pub fn polygon(&self) -> &ConvexPolygon {
        &self.polygon
    }

    /// The winged-edge mesh of the cells.
    pub fn mesh(&self) -> &WingedMesh<Cell, ()> {
        &self.mesh
    }

    /// The cells (faces of the mesh) with their occluder lists.
    pub fn cells(&self) -> impl Iterator<Item = (FaceKey, &Cell)> + '_ {
        self.mesh.faces().map(|(k, f)| (k, &f.data))
    }

    /// What light `light` does to `cell` (a cell of this receiver).
    pub fn class(&self, cell: &Cell, light: usize) -> CellClass {
        if cell.in_umbra(light) {
            CellClass::Umbra
        } else if cell.occluded(light) || self.reach[light] == Reach::Part {
            CellClass::Penumbra
        } else {
            CellClass::Lit
        }
    }

    /// The occluder piece and light of a unit listed in a cell's entries.
    pub fn unit_source(&self, unit: u32) -> Option<(K, usize)> {
        self.unit(unit).map(|(k, l)| (k, usize::from(l)))
    }

    /// Inner nodes of the tree.
    pub fn node_count(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| matches!(n, Node::Split { .. }))
            .count()
    }

    /// The lines of the nodes cast by units, each with its unit (not the
    /// light planes', tiles' or construction nodes).
    pub(crate) fn unit_lines(&self) -> impl Iterator<Item = (u32, &Plane)> + '_ {
        self.nodes.iter().filter_map(|n| match n {
            Node::Split { line, unit, .. } if tracked(*unit) => {
                Some((*unit, self.mesh.plane(*line)))
            }
            _ => None,
        })
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.mesh.counts().2
    }

    /// The occluder and light of a unit.
    pub(crate) fn unit(&self, unit: u32) -> Option<UnitRef<K>> {
        self.units.get(unit as usize).copied().flatten()
    }

    /// The units, in insertion order.
    pub(crate) fn units(&self) -> impl Iterator<Item = (u32, UnitRef<K>)> + '_ {
        self.units
            .iter()
            .enumerate()
            .filter_map(|(u, v)| v.map(|v| (u as u32, v)))
    }

    /// The units of the occluders `of` picks.
    pub(crate) fn units_of(&self, of: impl Fn(K) -> bool) -> std::collections::BTreeSet<u32> {
        self.units()
            .filter(|&(_, (key, _))| of(key))
            .map(|(u, _)| u)
            .collect()
    }
}
