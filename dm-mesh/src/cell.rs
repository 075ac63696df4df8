//! The payload of a DM cell: which occluders block the light from it.

use smallvec::SmallVec;

/// One occluder in a cell's list: the insertion (a *unit*: one occluder
/// under one light) that reached the cell, and whether it hides all of that
/// light from the cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Entry {
    /// The unit's sequence number in its receiver (insertion order).
    pub unit: u32,
    /// The light of the unit.
    pub light: u8,
    /// Whether the occluder hides all of the light (the cell is in its
    /// umbra).
    pub umbra: bool,
}

/// A cell of a DM-tree: a leaf of the 2D BSP and a face of the winged-edge
/// mesh.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Cell {
    /// The leaf node of the tree holding this cell.
    pub(crate) leaf: u32,
    /// Occluders blocking some of a light from the cell, in insertion order.
    pub(crate) entries: SmallVec<[Entry; 4]>,
    /// Units not merged into the cell because it was in another's umbra
    /// for their light (they must be merged again if that one goes).
    pub(crate) culled: SmallVec<[u32; 2]>,
    /// Bit `i`: light `i` does not reach the cell at all (behind the light's
    /// plane, or the receiver faces away from it).
    pub(crate) unreached: u32,
}

/// What one light does to a cell (FORMATS.md's lit / penumbra / umbra).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CellClass {
    /// Sees all of the light.
    Lit,
    /// Sees part of it.
    Penumbra,
    /// Sees none of it (one occluder, or one convex body of several,
    /// hides it all, or the light does not reach the cell).
    Umbra,
}

impl Cell {
    /// The occluder entries, in insertion order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// Whether light `light` does not reach the cell at all.
    pub fn unreached(&self, light: usize) -> bool {
        self.unreached & (1 << light) != 0
    }

    /// Whether the cell lies in some occluder's umbra for `light`.
    pub fn in_umbra(&self, light: usize) -> bool {
        self.unreached(light)
            || self
                .entries
                .iter()
                .any(|e| e.umbra && usize::from(e.light) == light)
    }

    /// Whether some occluder blocks part of `light` from the cell.
    pub fn occluded(&self, light: usize) -> bool {
        self.entries.iter().any(|e| usize::from(e.light) == light)
    }

    /// Whether the cell has `unit` in its list.
    pub(crate) fn has_unit(&self, unit: u32) -> bool {
        self.entries.iter().any(|e| e.unit == unit)
    }

    /// Adds `entry` (or upgrades its unit's entry to umbra).
    pub(crate) fn add(&mut self, entry: Entry) {
        match self.entries.iter_mut().find(|e| e.unit == entry.unit) {
            Some(e) => e.umbra |= entry.umbra,
            None => self.entries.push(entry),
        }
    }
}
