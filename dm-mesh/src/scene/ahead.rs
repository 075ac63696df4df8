//! A big receiver's removal flood, made while a small change is planned.
//!
//! A small object's move first makes its new pieces and decides which
//! units leave and enter each receiver (0.4-0.5 ms on the 10k hall), while
//! the other thread mostly waits; then the biggest receiver's removal,
//! insertion and illumination (the floor's: 8 ms) hold the change up to its
//! end. The removal begins with a flood over the cells the leaving units
//! hold (0.9 ms there), which needs only the receiver and which units
//! leave: it is started on another thread as soon as the change begins,
//! with the receiver taken out of the scene meanwhile, and the thread that
//! plans the change helps it to its end when done planning, before the
//! receiver goes back and its removal takes the cells found.

use super::{DmScene, PieceId};
use crate::tree::{Flood, Flooded, ReceiverDm};
use std::collections::BTreeSet;
use std::sync::{Arc, OnceLock, PoisonError, RwLock, TryLockError};

/// Cells from which on a receiver's removal flood is made ahead (below,
/// the flood is short and the task costs more than it saves).
pub(super) const AHEAD_CELLS: usize = 1 << 16;

/// A receiver taken out of the scene while the flood of a removal's cells
/// on it is made.
pub(super) struct FloodAhead {
    receiver: PieceId,
    /// The receiver (`None` once back in the scene).
    dm: RwLock<Option<ReceiverDm<PieceId>>>,
    /// The occluders whose units leave.
    gone: BTreeSet<PieceId>,
    /// Their units (occluder, light) with one penumbra region on the
    /// receiver (a flood from a unit's seed cell reaches all of its cells).
    single: BTreeSet<(PieceId, u8)>,
    /// The flood, made by whichever thread gets to it first (`None`: a
    /// unit has no seed cell; the removal floods as usual).
    flood: OnceLock<Option<Flood>>,
}

impl FloodAhead {
    /// The receiver flooded.
    pub(super) fn receiver(&self) -> PieceId {
        self.receiver
    }

    /// Floods alone, or beside another thread, until the flood is made;
    /// nothing once the receiver is back in the scene.
    fn help(&self) {
        let dm = self.dm.read().unwrap_or_else(PoisonError::into_inner);
        let Some(dm) = dm.as_ref() else {
            return;
        };
        let flood = self.flood.get_or_init(|| {
            dm.flood_ahead(
                |o| self.gone.contains(&o),
                |o, light| self.single.contains(&(o, light)),
            )
        });
        if let Some(flood) = flood {
            flood.help(dm);
        }
    }
}

impl DmScene {
    /// Takes the biggest receiver that pieces `gone` (leaving the scene)
    /// reach out of the scene, if it is big (and light reaches it), and
    /// starts the flood of their units' cells on it as a task of `scope`.
    /// Until it is back ([`Self::land`]) the receiver is not in the scene:
    /// the units that leave it are not among what [`Self::removals`]
    /// finds.
    pub(super) fn flood_ahead(
        &mut self,
        scope: &rayon::Scope<'_>,
        gone: &[PieceId],
    ) -> Option<Arc<FloodAhead>> {
        let gone_set: BTreeSet<PieceId> = gone.iter().copied().collect();
        let receiver = self
            .big_receivers
            .iter()
            .copied()
            .filter(|r| !gone_set.contains(r))
            .filter(|&r| {
                gone.iter()
                    .any(|&o| self.overlap.may_shadow(o, r, &self.pieces))
            })
            .filter_map(|r| {
                let dm = self.receivers.get(r).filter(|dm| !dm.in_the_dark())?;
                Some((dm.cell_count(), r))
            })
            .max()?
            .1;
        let contact = self.contacts.get(receiver)?;
        let lights = u8::try_from(self.lights.len()).ok()?;
        let single = gone
            .iter()
            .flat_map(|&o| (0..lights).map(move |light| (o, light)))
            .filter(|&(o, light)| {
                let own = self
                    .pieces
                    .get(o)
                    .and_then(|p| p.volumes.get(usize::from(light)));
                own.is_some_and(|own| contact.get(o, light, own).volumes.penumbra.len() == 1)
            })
            .collect();
        let dm = self.receivers.remove(receiver)?;
        let ahead = Arc::new(FloodAhead {
            receiver,
            dm: RwLock::new(Some(dm)),
            gone: gone_set,
            single,
            flood: OnceLock::new(),
        });
        let task = Arc::clone(&ahead);
        scope.spawn(move |_| task.help());
        Some(ahead)
    }

    /// Helps the flood of `ahead` to its end and puts its receiver back
    /// in the scene. Returns the receiver, the units that leave it (of the
    /// occluders flooded for and of `also_gone`) and the cells of the
    /// former.
    pub(super) fn land(
        &mut self,
        ahead: Arc<FloodAhead>,
        also_gone: &[PieceId],
    ) -> (PieceId, BTreeSet<u32>, Option<Flooded>) {
        ahead.help();
        // (Once the task reads the receiver no more: its part of the
        // flood is in.)
        let dm = loop {
            // (Spinning: a thread woken from sleep would start a tenth of
            // a millisecond late, and the task's last read ends at once.)
            match ahead.dm.try_write() {
                Ok(mut dm) => break dm.take(),
                Err(TryLockError::Poisoned(dm)) => break dm.into_inner().take(),
                Err(TryLockError::WouldBlock) => std::thread::yield_now(),
            }
        };
        let dm = dm.expect("only landing takes the receiver, once");
        let flooded = ahead
            .flood
            .get()
            .and_then(|f| f.as_ref())
            .map(Flood::finish);
        // (The flood's units are those of the occluders flooded for.)
        let units = match &flooded {
            Some(flooded) if also_gone.is_empty() => flooded.units.iter().copied().collect(),
            _ => dm.units_of(|o| ahead.gone.contains(&o) || also_gone.contains(&o)),
        };
        #[cfg(test)]
        {
            self.floods_ahead += usize::from(flooded.is_some());
        }
        self.receivers.insert(ahead.receiver, dm);
        (ahead.receiver, units, flooded)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::{boxes_on_a_floor, moved};
    use super::super::{DmScene, PieceId};
    use crate::cell::Entry;

    /// One cell: vertex coordinate bits, entries, vertex irradiance bits.
    type CellPrint = (Vec<[u64; 3]>, Vec<Entry>, Vec<u64>);

    /// Every receiver's cells: vertices (exact coordinates as `f64` bits),
    /// entries, vertex irradiance bits.
    fn fingerprint(scene: &DmScene) -> Vec<CellPrint> {
        let mut out = Vec::new();
        for (piece, dm) in scene.receivers() {
            for (face, cell) in dm.cells() {
                let vertices = dm.mesh().face_vertices(face);
                let at = |v| dm.mesh().vertex(v).expect("a vertex").position.to_f64();
                out.push((
                    vertices.iter().map(|&v| at(v).map(f64::to_bits)).collect(),
                    cell.entries().to_vec(),
                    vertices
                        .iter()
                        .map(|&v| scene.vertex_irradiance(piece, v).unwrap_or(-1.0).to_bits())
                        .collect(),
                ));
            }
        }
        out
    }

    fn on_threads<T: Send>(threads: usize, work: impl FnOnce() -> T + Send) -> T {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
            .install(work)
    }

    /// The floor flooded ahead for a box's units, on one thread or two,
    /// finds the cells a removal of those units finds itself.
    #[test]
    fn a_flood_ahead_finds_the_cells_of_the_removed_units() {
        for threads in [1, 2] {
            on_threads(threads, || {
                let (mut scene, ids) = boxes_on_a_floor();
                let floor: PieceId = scene.objects[ids[0]].pieces[0];
                let mut checked = 0;
                for &id in &ids[1..] {
                    let object = &scene.objects[id];
                    let gone: Vec<PieceId> = object
                        .pieces
                        .iter()
                        .chain(&object.bodies)
                        .copied()
                        .collect();
                    // (Every receiver taken for big.)
                    scene.big_receivers = scene.receivers.keys().collect();
                    scene.overlap.refresh(&scene.pieces);
                    let (r, units, flooded) = rayon::scope(|scope| {
                        let ahead = scene
                            .flood_ahead(scope, &gone)
                            .expect("a receiver to flood");
                        scene.land(ahead, &[])
                    });
                    let dm = &scene.receivers[r];
                    let expected: std::collections::BTreeSet<u32> = dm
                        .units()
                        .filter(|(_, (o, _))| gone.contains(o))
                        .map(|(u, _)| u)
                        .collect();
                    assert_eq!(units, expected);
                    if r != floor || units.is_empty() {
                        continue;
                    }
                    let flooded = flooded.expect("each unit's seed holds it");
                    let contact = &scene.contacts[r];
                    let removed: Vec<_> = units
                        .iter()
                        .map(|&u| {
                            let (o, light) = dm.unit(u).expect("a unit");
                            let own = &scene.pieces[o].volumes[usize::from(light)];
                            (u, light, contact.get(o, light, own))
                        })
                        .collect();
                    assert_eq!(dm.cells_of(&removed, None), flooded.held);
                    assert!(flooded.held.len() > 1);
                    checked += 1;
                }
                assert!(checked >= 6, "{checked} boxes' floods checked on the floor");
            });
        }
    }

    /// Moves whose floor removal floods ahead, on one thread or two, leave
    /// every cell, list and vertex value as moves that do not.
    #[test]
    fn moves_flooded_ahead_change_nothing() {
        let run = |ahead: bool| {
            let (mut scene, ids) = boxes_on_a_floor();
            scene.illuminate();
            for step in 0..4_i64 {
                let id = ids[1 + (step as usize * 4) % 9];
                let by = [9 - 6 * step, 0, 5 * step - 7];
                if ahead {
                    scene.big_receivers = scene.receivers.keys().collect();
                }
                let polygons = moved(&scene, id, by);
                scene.move_object(id, polygons).expect("a move");
            }
            scene.illuminate();
            assert_eq!(scene.floods_ahead, if ahead { 4 } else { 0 });
            fingerprint(&scene)
        };
        let plain = on_threads(2, || run(false));
        assert_eq!(on_threads(2, || run(true)), plain);
        assert_eq!(on_threads(1, || run(true)), plain);
    }
}
