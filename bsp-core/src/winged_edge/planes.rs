//! The planes a mesh's vertices and edges lie on, each kept once.
//!
//! A subdivision made by cutting one polygon with planes has few distinct
//! planes and many vertices and edges on each: a discontinuity mesh's
//! splitting planes cut many of its faces, and every vertex made by a cut
//! lies on the face's support plane, the cut edge's line plane and the
//! splitting plane. Kept by value, the three planes were 144 of a vertex's
//! 200 bytes; kept here once and named by 4-byte [`PlaneRef`]s, a vertex
//! takes 64 bytes. The mesh's user may hold planes in the table too
//! ([`WingedMesh::hold_plane`]): a BSP over the mesh names its splitting
//! lines so, the very planes its cuts' vertices lie on.
//!
//! Every vertex holds counted references, as does each face support (for
//! the mesh's life: a cut's vertices retain it without a lookup) and
//! every hold of the user's: a plane no one names any more is dropped and its slot reused, so
//! that a mesh edited frame after frame (objects moving over a receiver)
//! does not keep every plane it ever saw.
//!
//! [`WingedMesh::hold_plane`]: super::WingedMesh::hold_plane

use crate::Plane;
use rustc_hash::FxHashMap;

/// The number of a plane in a mesh's table of planes, while held
/// ([`WingedMesh::hold_plane`]); it means nothing in another mesh.
///
/// [`WingedMesh::hold_plane`]: super::WingedMesh::hold_plane
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PlaneRef(u32);

/// Counted planes, each once; see the module docs.
#[derive(Debug, Clone, Default)]
pub(super) struct PlaneTable {
    planes: Vec<Plane>,
    /// References held per slot (0: a free slot).
    counts: Vec<u32>,
    /// The slot of each plane held.
    index: FxHashMap<Plane, u32>,
    /// Free slots, reused first.
    free: Vec<u32>,
}

impl PlaneTable {
    /// A reference to `plane`, added if new.
    pub(super) fn intern(&mut self, plane: Plane) -> PlaneRef {
        if let Some(&slot) = self.index.get(&plane) {
            self.counts[slot as usize] += 1;
            return PlaneRef(slot);
        }
        let slot = match self.free.pop() {
            Some(slot) => {
                self.planes[slot as usize] = plane;
                self.counts[slot as usize] = 1;
                slot
            }
            None => {
                let slot = u32::try_from(self.planes.len()).expect("fewer than 2^32 planes");
                self.planes.push(plane);
                self.counts.push(1);
                slot
            }
        };
        self.index.insert(plane, slot);
        PlaneRef(slot)
    }

    /// One more reference to a plane held.
    #[inline]
    pub(super) fn retain(&mut self, r: PlaneRef) -> PlaneRef {
        self.counts[r.0 as usize] += 1;
        r
    }

    /// One reference fewer; the plane goes when none is left.
    pub(super) fn release(&mut self, r: PlaneRef) {
        let count = &mut self.counts[r.0 as usize];
        // (A plane freed while named would read as another one later.)
        assert!(*count > 0, "a plane released more often than held");
        *count -= 1;
        if *count == 0 {
            self.index.remove(&self.planes[r.0 as usize]);
            self.free.push(r.0);
        }
    }

    /// The plane `r` names.
    #[inline]
    pub(super) fn get(&self, r: PlaneRef) -> &Plane {
        &self.planes[r.0 as usize]
    }

    /// The planes held, with their reference counts (for the invariants).
    pub(super) fn held(&self) -> impl Iterator<Item = (PlaneRef, u32)> + '_ {
        self.counts
            .iter()
            .enumerate()
            .filter(|(_, count)| **count > 0)
            .map(|(slot, &count)| (PlaneRef(slot as u32), count))
    }

    /// Number of planes held.
    pub(super) fn len(&self) -> usize {
        self.index.len()
    }
}
