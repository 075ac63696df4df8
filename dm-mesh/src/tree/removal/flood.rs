//! Pass 1's flood: the cells that list or culled the removed units, found
//! over the mesh, by one thread or by two side by side.
//!
//! A small object's removal from the 10k hall floor floods some 4k cells
//! in about 0.9 ms, waiting on memory cell by cell. A move finds which
//! units leave the floor before it is ready to change it, so the flood
//! can start then on another thread ([`ReceiverDm::flood_ahead`]); the
//! thread that makes the change joins it when it gets there
//! ([`Flood::help`]), and the removal takes the cells found
//! ([`Flooded`]).

use super::super::ReceiverDm;
use crate::cell::Cell;
use crate::critical::UnitPlanes;
use crate::hash::KeySet;
use crate::marks::SharedMarks;
use bsp_core::FaceKey;
use smallvec::SmallVec;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// The leaves whose cells hold removed units (ascending), each with the
/// positions among the removed units (ascending by unit) of those it
/// holds.
pub(crate) type Held = Vec<(u32, SmallVec<[u32; 2]>)>;

/// Cells a thread floods between two looks at whether another waits for
/// some of its cells.
const SHARE_EVERY: usize = 32;

/// The cells a removal of `units` leaves, found before the removal.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Flooded {
    /// The units removed, ascending.
    pub(crate) units: Vec<u32>,
    /// Their cells.
    pub(crate) held: Held,
}

/// A flood over the cells that hold any of some units, from cells that
/// hold them, that threads may work on side by side: each floods from
/// cells of its own, and hands half of them over when another waits.
pub(crate) struct Flood {
    /// The units, ascending.
    units: Vec<u32>,
    /// Leaves reached (a cell that holds none of the units too: the cells
    /// around the flood are each reached from several inside it).
    seen: SharedMarks,
    /// Threads waiting for cells to flood from.
    waiting: AtomicUsize,
    state: Mutex<FloodState>,
}

#[derive(Default)]
struct FloodState {
    /// Cells reached whose neighbours are still to look at.
    stack: Vec<FaceKey>,
    /// Threads flooding from cells taken off `stack`.
    busy: usize,
    /// The cells found: those it started from, and each thread's, each
    /// run ascending (sorted by the thread that found it, side by side).
    runs: Vec<Held>,
}

impl Flood {
    /// The flood of `dm`'s cells holding `units` (ascending), from the
    /// faces `starts` (each holding some of them, or not reached).
    fn new<K: Copy + Ord>(dm: &ReceiverDm<K>, units: Vec<u32>, starts: &[FaceKey]) -> Self {
        let flood = Self {
            units,
            seen: SharedMarks::new(dm.nodes.len()),
            waiting: AtomicUsize::new(0),
            state: Mutex::new(FloodState::default()),
        };
        {
            let mut state = flood.lock();
            let mut held = Vec::new();
            for &f in starts {
                flood.visit(dm, f, &mut state.stack, &mut held);
            }
            held.sort_unstable_by_key(|(leaf, _)| *leaf);
            state.runs.push(held);
        }
        flood
    }

    fn lock(&self) -> MutexGuard<'_, FloodState> {
        // (A panic elsewhere while flooding leaves the state as it was.)
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Positions in `units` of the units `data` lists or culled.
    fn units_held(&self, data: &Cell) -> SmallVec<[u32; 2]> {
        let mut out: SmallVec<[u32; 2]> = data
            .entries
            .iter()
            .map(|e| e.unit)
            .chain(data.culled.iter().copied())
            .filter_map(|u| self.units.binary_search(&u).ok())
            .map(|i| i as u32)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Marks face `f` reached; if it is new and holds some of the units,
    /// it goes to `stack` and `held`.
    fn visit<K: Copy + Ord>(
        &self,
        dm: &ReceiverDm<K>,
        f: FaceKey,
        stack: &mut Vec<FaceKey>,
        held: &mut Held,
    ) {
        let Some(face) = dm.mesh.face(f) else {
            return;
        };
        let data = &face.data;
        if !self.seen.insert(data.leaf) {
            return;
        }
        let units = self.units_held(data);
        if !units.is_empty() {
            stack.push(f);
            held.push((data.leaf, units));
        }
    }

    /// Floods until no cell is left to flood from on any thread: alone, or
    /// beside other threads helping with the same flood of the same `dm`.
    pub(crate) fn help<K: Copy + Ord>(&self, dm: &ReceiverDm<K>) {
        let mut mine: Vec<FaceKey> = Vec::new();
        let mut held: Held = Vec::new();
        let mut waits = false;
        loop {
            {
                let mut state = self.lock();
                if state.stack.is_empty() {
                    if state.busy == 0 {
                        break;
                    }
                    // Another thread floods: it hands cells over.
                    drop(state);
                    if !waits {
                        waits = true;
                        self.waiting.fetch_add(1, Ordering::Relaxed);
                    }
                    std::thread::yield_now();
                    continue;
                }
                std::mem::swap(&mut mine, &mut state.stack);
                state.busy += 1;
            }
            if waits {
                waits = false;
                self.waiting.fetch_sub(1, Ordering::Relaxed);
            }
            let mut since = 0;
            while let Some(f) = mine.pop() {
                for side in dm.mesh.face_sides(f) {
                    if let Some(g) = side.across {
                        self.visit(dm, g, &mut mine, &mut held);
                    }
                }
                since += 1;
                if since >= SHARE_EVERY {
                    since = 0;
                    if mine.len() >= 2 && self.waiting.load(Ordering::Relaxed) > 0 {
                        let half = mine.len() / 2;
                        self.lock().stack.extend(mine.drain(..half));
                    }
                }
            }
            self.lock().busy -= 1;
        }
        if waits {
            self.waiting.fetch_sub(1, Ordering::Relaxed);
        }
        held.sort_unstable_by_key(|(leaf, _)| *leaf);
        self.lock().runs.push(held);
    }

    /// What the flood found, once no thread helps any more.
    pub(crate) fn finish(&self) -> Flooded {
        let runs = std::mem::take(&mut self.lock().runs);
        let held = runs.into_iter().fold(Vec::new(), merge_by_leaf);
        Flooded {
            units: self.units.clone(),
            held,
        }
    }
}

/// Two runs of cells, each ascending by leaf (no leaf in both), merged.
fn merge_by_leaf(a: Held, b: Held) -> Held {
    if a.is_empty() || b.is_empty() {
        return if a.is_empty() { b } else { a };
    }
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut a, mut b) = (a.into_iter().peekable(), b.into_iter().peekable());
    while let (Some(x), Some(y)) = (a.peek(), b.peek()) {
        let next = if x.0 < y.0 { a.next() } else { b.next() };
        out.extend(next);
    }
    out.extend(a);
    out.extend(b);
    out
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// The leaves whose cells list or culled one of the `removed` units
    /// (ascending), each with the positions in `removed` (ascending by
    /// unit) of those units.
    ///
    /// A cell lists a unit only inside its penumbra region, and every cell
    /// that meets the region lists or culled it (outside the part its
    /// light does not reach); a cell split after culling it keeps it in
    /// both parts. So a unit's cells are connected through shared edges (a
    /// convex region, and the parts of split cells), and all of them are
    /// found by one flood over the cells holding any removed unit, from
    /// each unit's seed cell, or, when that no longer holds the unit or the
    /// unit has several penumbra regions, from the cells its regions reach
    /// down the tree. (One flood for all: the units of one object cover
    /// much the same cells.) `ahead`: the flood already made, if it was of
    /// these units.
    pub(crate) fn cells_of(
        &self,
        removed: &[(u32, u8, &UnitPlanes)],
        ahead: Option<Flooded>,
    ) -> Held {
        let units: Vec<u32> = removed.iter().map(|r| r.0).collect();
        let held = match ahead {
            Some(flooded) if flooded.units == units => flooded.held,
            _ => {
                let mut starts: Vec<FaceKey> = Vec::new();
                for &(u, _, planes) in removed {
                    match self.seed_of(u, planes.volumes.penumbra.len() == 1) {
                        Some(seed) => starts.push(seed),
                        None => starts.extend(self.cells_by_descent(u, planes)),
                    }
                }
                let flood = Flood::new(self, units, &starts);
                flood.help(self);
                flood.finish().held
            }
        };
        debug_assert!(
            removed.iter().enumerate().all(|(i, &(u, _, planes))| {
                let found: Vec<u32> = held
                    .iter()
                    .filter(|(_, units)| units.contains(&(i as u32)))
                    .map(|(leaf, _)| *leaf)
                    .collect();
                found == self.flood(u, self.cells_by_descent(u, planes))
            }),
            "one flood for the removed units finds each unit's cells"
        );
        held
    }

    /// The flood of the cells of the units of the occluders `gone` (each
    /// unit's occluder and light to `single`: whether the unit has one
    /// penumbra region), started from their seed cells, to make before
    /// they are removed; `None` if a unit has no seed to start from (its
    /// removal then floods from the cells its regions reach down the
    /// tree, as usual).
    pub(crate) fn flood_ahead(
        &self,
        gone: impl Fn(K) -> bool,
        single: impl Fn(K, u8) -> bool,
    ) -> Option<Flood> {
        let mut units = Vec::new();
        let mut starts = Vec::new();
        for (u, (key, light)) in self.units() {
            if gone(key) {
                units.push(u);
                starts.push(self.seed_of(u, single(key, light))?);
            }
        }
        Some(Flood::new(self, units, &starts))
    }

    /// Unit `u`'s seed cell, if it still holds the unit and (`single`) the
    /// unit has one penumbra region.
    fn seed_of(&self, u: u32, single: bool) -> Option<FaceKey> {
        self.seeds
            .get(u as usize)
            .copied()
            .filter(|&f| single && self.holds(f, u))
    }

    /// Whether face `f` exists and lists or culled unit `u`.
    pub(super) fn holds(&self, f: FaceKey, u: u32) -> bool {
        self.mesh
            .face(f)
            .is_some_and(|face| face.data.has_unit(u) || face.data.culled.contains(&u))
    }

    /// The leaves of the faces holding unit `u` connected to `starts`
    /// (faces that hold it) through shared edges, ascending (a check of
    /// [`cells_of`](Self::cells_of) in debug builds).
    fn flood(&self, u: u32, starts: Vec<FaceKey>) -> Vec<u32> {
        let mut seen: KeySet<FaceKey> = starts.iter().copied().collect();
        let mut stack = starts;
        while let Some(f) = stack.pop() {
            for side in self.mesh.face_sides(f) {
                if let Some(g) = side.across
                    && !seen.contains(&g)
                    && self.holds(g, u)
                {
                    seen.insert(g);
                    stack.push(g);
                }
            }
        }
        let mut out: Vec<u32> = seen
            .into_iter()
            .map(|f| self.mesh.face(f).expect("face").data.leaf)
            .collect();
        out.sort_unstable();
        out
    }
}
