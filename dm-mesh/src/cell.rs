//! The payload of a DM cell: which occluders block the light from it.

use std::ops::{BitOr, BitOrAssign};

use smallvec::SmallVec;

/// The sides of its receiver from which an occluder hides all of a light
/// from a cell. A receiver lit on one side only (one-sided, or two-sided
/// with the light wholly on one side of its plane) knows only `NONE` and
/// `BOTH`. A two-sided one whose plane cuts the light receives each part
/// on its own side, and a body it lies against, its face in the body's
/// surface, hides the light from that side only (the receiver sees that
/// part of the light through the body): the cell is umbra where the two
/// sides are both hidden, by one occluder or by two.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Sides(u8);

impl Sides {
    /// Hides the light from neither side: not in the occluder's umbra.
    pub const NONE: Self = Self(0);
    /// From the side the receiver's plane faces (its normal points to).
    pub const FRONT: Self = Self(1);
    /// From the other side.
    pub const BACK: Self = Self(2);
    /// From every side the light reaches: the occluder's umbra.
    pub const BOTH: Self = Self(3);

    /// Whether no side is hidden.
    pub fn is_none(self) -> bool {
        self == Self::NONE
    }

    /// Whether both sides are hidden.
    pub fn is_both(self) -> bool {
        self == Self::BOTH
    }

    /// Whether every side of `other` is among these.
    pub fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }
}

impl BitOr for Sides {
    type Output = Self;
    fn bitor(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }
}

impl BitOrAssign for Sides {
    fn bitor_assign(&mut self, other: Self) {
        self.0 |= other.0;
    }
}

/// One occluder in a cell's list: the insertion (a *unit*: one occluder
/// under one light) that reached the cell, and the sides from which it
/// hides all of that light from the cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Entry {
    /// The unit's sequence number in its receiver (insertion order).
    pub unit: u32,
    /// The light of the unit.
    pub light: u8,
    /// The sides from which the occluder hides all of the light (`BOTH`:
    /// the cell is in its umbra; `NONE`: in its penumbra only).
    pub umbra: Sides,
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
    /// hides it all, or two hide it from either side of a two-sided
    /// receiver, or the light does not reach the cell).
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

    /// Whether the cell lies in some occluder's umbra for `light`, or in
    /// the umbrae of two from either side.
    pub fn in_umbra(&self, light: usize) -> bool {
        if self.unreached(light) {
            return true;
        }
        let mut sides = Sides::NONE;
        for e in &self.entries {
            if usize::from(e.light) == light {
                sides |= e.umbra;
                if sides.is_both() {
                    return true;
                }
            }
        }
        false
    }

    /// The sides from which the cell's occluders hide all of `light`.
    pub fn umbra_sides(&self, light: usize) -> Sides {
        self.entries
            .iter()
            .filter(|e| usize::from(e.light) == light)
            .fold(Sides::NONE, |sides, e| sides | e.umbra)
    }

    /// Whether some occluder blocks part of `light` from the cell.
    pub fn occluded(&self, light: usize) -> bool {
        self.entries.iter().any(|e| usize::from(e.light) == light)
    }

    /// Whether the cell has `unit` in its list.
    pub(crate) fn has_unit(&self, unit: u32) -> bool {
        self.entries.iter().any(|e| e.unit == unit)
    }

    /// Adds `entry` (or adds its umbra sides to its unit's entry).
    pub(crate) fn add(&mut self, entry: Entry) {
        match self.entries.iter_mut().find(|e| e.unit == entry.unit) {
            Some(e) => e.umbra |= entry.umbra,
            None => self.entries.push(entry),
        }
    }
}
