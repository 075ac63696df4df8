//! Changing a scene: pieces attached ([`super::attach`]) and detached, and
//! the units that come and go per receiver, applied to the receivers side
//! by side.
//!
//! A change that makes many new pieces (a move of a big object) first
//! takes the object's old units out of the receivers they reach, while the
//! pieces are made (the biggest receiver's removal beside the making).
//! Then it decides which units enter each receiver, in what order (and
//! which leave: a removed object's, and those of the joint bodies the
//! change parted), and applies that in one pass: every receiver removes
//! its leaving units, merges its entering ones and, once the scene has
//! been illuminated, computes its vertices' irradiance again, the
//! receivers side by side (each tree only ever sees its own units, in the
//! same order, so the result does not depend on the number of threads). A
//! big receiver's work runs on one thread while the small receivers share
//! the other, instead of passes each waiting for the big receiver.

use super::ahead::AHEAD_CELLS;
use super::contact::ContactPlanes;
use super::{DmScene, MAX_TILE_DEPTH, ObjectId, Order, Piece, PieceId, PieceKind, TILE_UNITS};
use crate::critical::UnitPlanes;
use crate::error::Error;
use crate::hash::KeyMap;
use crate::illuminate::{IllumStats, ReceiverIllum, illuminate_receiver};
use crate::order::unit_order;
use crate::tree::{Flooded, ReceiverDm};
use area_shadow::AreaSource;
use bsp_core::ConvexPolygon;
use illum::VisiblePart;
use rayon::prelude::*;
use slotmap::SlotMap;
use std::collections::{BTreeMap, BTreeSet};
use svbsp::PieceFlags;

/// Polygons of an object from which on a change makes its pieces beside
/// its old units' removal ([`DmScene::replace`]). A smaller object's making
/// is short (a box's: 0.2 ms on the 10k hall), and the second pass costs
/// more: the small receivers' removals, done beside the big one's, leave
/// their insertions for later, where they keep the other thread from the
/// big receiver's illumination (box0 on the 10k hall: 2-3 % slower; the
/// office's desk of 30 polygons: 20 % faster).
const OVERLAPPED_MAKING: usize = 16;

/// Per receiver, the units that leave it.
type Removals = KeyMap<PieceId, BTreeSet<u32>>;
/// Per receiver, the units that enter it (after tiling it to a depth).
type Insertions = KeyMap<PieceId, Order>;
/// Per receiver, the cells of the units that leave it, found ahead.
type Floods = KeyMap<PieceId, Flooded>;
/// One receiver's part of a change: units out, then units in, then its
/// illumination if the scene keeps it; the receiver's state is taken out
/// of the scene for it, and put back after.
struct Work {
    receiver: PieceId,
    dm: ReceiverDm<PieceId>,
    contact: ContactPlanes,
    /// The units that leave, and their cells if found ahead.
    out: Option<(BTreeSet<u32>, Option<Flooded>)>,
    into: Option<Order>,
    illum: Option<ReceiverIllum>,
    /// Whether its cells changed (or may have: before the first
    /// illumination no change is tracked).
    changed: bool,
}

impl DmScene {
    /// Casts the shadows of `added` (new pieces) on every receiver, and of
    /// every occluder on the new receivers.
    pub(super) fn cast(&mut self, added: &[PieceId]) {
        let insertions = self.insertions(added, None);
        self.apply(
            Removals::default(),
            Floods::default(),
            insertions,
            &BTreeSet::new(),
            &KeyMap::default(),
        );
    }

    /// Changes an object: its pieces and discontinuities leave, and
    /// (unless `polygons` is `None`) pieces of `polygons` (validated) take
    /// their place and cast their shadows; the joint bodies of the objects
    /// it touched and touches are brought up to date
    /// ([`Self::reconcile_joints`]). With many pieces to make, its old
    /// units leave the receivers first, while the pieces are made
    /// ([`Self::replace`]); with few, the units that leave are only found
    /// while the pieces are made. The other units come and go, and the
    /// receivers changed are illuminated, in one pass.
    pub(super) fn change(
        &mut self,
        id: ObjectId,
        polygons: Option<(Vec<ConvexPolygon>, PieceFlags)>,
    ) -> Result<(), Error> {
        // On a pool thread: from outside the pool each parallel step would
        // hand its work over and sleep until woken (a few wake-ups a
        // change, 0.13-0.2 ms of a small move's 8.8-9.1 on the 10k hall);
        // on a pool thread the steps start at once.
        if !self.objects.contains_key(id) {
            return Err(Error::UnknownObject);
        }
        self.revision += 1;
        let mut result = Ok(());
        rayon::scope(|scope| result = self.change_on_pool(scope, id, polygons));
        result
    }

    /// [`Self::change`], on a pool thread, its tasks in `scope`.
    fn change_on_pool(
        &mut self,
        scope: &rayon::Scope<'_>,
        id: ObjectId,
        polygons: Option<(Vec<ConvexPolygon>, PieceFlags)>,
    ) -> Result<(), Error> {
        let mut seeds = self.touching(id);
        let normals = self.receiver_normals(id);
        let mut gone = self.take(id)?;
        // The units that leave the receivers, found for the first
        // `planned` pieces of `gone` so far.
        let (mut removals, mut planned) = (Removals::default(), 0);
        let mut floods = Floods::default();
        // The biggest receiver's removal flood, made meanwhile.
        let mut ahead = None;
        let (mut added, mut left, relight) = match polygons {
            Some((polygons, flags)) if polygons.len() >= OVERLAPPED_MAKING => {
                self.replace(id, std::mem::take(&mut gone), polygons, flags)
            }
            Some((polygons, flags)) => {
                // The old units that leave are found while the new pieces
                // are made (neither needs the other).
                self.overlap.refresh(&self.pieces);
                ahead = self.flood_ahead(scope, &gone);
                let prepared;
                (prepared, removals) = {
                    let scene = &*self;
                    rayon::join(
                        || scene.prepare(id, polygons, flags),
                        || scene.removals_of(&gone),
                    )
                };
                planned = gone.len();
                let added = self.commit(id, prepared);
                (added, KeyMap::default(), BTreeSet::new())
            }
            // Nothing to make: the old units leave in the one pass.
            None => (Vec::new(), KeyMap::default(), BTreeSet::new()),
        };
        self.keep_receiver_normals(&normals, &added);
        seeds.insert(id);
        let (joined, parted) = self.reconcile_joints(&seeds);
        added.extend(joined);
        gone.extend(parted);
        for (r, units) in self.removals(&gone[planned..]) {
            removals.entry(r).or_default().extend(units);
        }
        // (Out of the scene, the receiver flooded ahead is not among them.)
        let also_gone = gone[planned..].to_vec();
        left.extend(self.forget(gone));
        let insertions = self.insertions(&added, ahead.as_ref().map(|a| a.receiver()));
        if let Some(ahead) = ahead {
            let (r, units, flooded) = self.land(ahead, &also_gone);
            if !units.is_empty() {
                removals.insert(r, units);
            }
            if let Some(flooded) = flooded {
                floods.insert(r, flooded);
            }
        }
        self.apply(removals, floods, insertions, &relight, &left);
        Ok(())
    }

    /// Takes the units of pieces `gone` out of the receivers they reach
    /// while object `id`'s new pieces are made of `polygons` (validated),
    /// the biggest receiver's removal beside the making, which waited for
    /// it; then puts the new pieces in the scene. Returns them (receivers
    /// first), the pieces gone (their planes), and the receivers changed,
    /// to illuminate.
    fn replace(
        &mut self,
        id: ObjectId,
        gone: Vec<PieceId>,
        polygons: Vec<ConvexPolygon>,
        flags: PieceFlags,
    ) -> (Vec<PieceId>, KeyMap<PieceId, Piece>, BTreeSet<PieceId>) {
        let removals = self.removals(&gone);
        let left = self.forget(gone);
        let mut leaving = self.take_work(
            removals,
            Floods::default(),
            Insertions::default(),
            &BTreeSet::new(),
            false,
        );
        let changed: BTreeSet<PieceId> = leaving.iter().map(|work| work.receiver).collect();
        let prepared = {
            let (scene, left) = (&*self, &left);
            rayon::join(
                || scene.prepare(id, polygons, flags),
                || scene.run_work(&mut leaving, left),
            )
            .0
        };
        self.put_back(leaving);
        (self.commit(id, prepared), left, changed)
    }

    /// The receiver normals set on an object's polygons, in order, with
    /// their planes' normals.
    fn receiver_normals(&self, id: ObjectId) -> Vec<([i64; 3], Option<[f64; 3]>)> {
        let Some(object) = self.objects.get(id) else {
            return Vec::new();
        };
        object
            .pieces
            .iter()
            .map(|&p| {
                let normal = self.illum.get(p).and_then(|s| s.normal);
                (self.pieces[p].polygon.support().normal(), normal)
            })
            .collect()
    }

    /// Gives the new polygons (leading `added`) the receiver normals
    /// their predecessors had, where the plane kept its orientation.
    fn keep_receiver_normals(
        &mut self,
        normals: &[([i64; 3], Option<[f64; 3]>)],
        added: &[PieceId],
    ) {
        for (&(plane, normal), &p) in normals.iter().zip(added) {
            let (Some(normal), Some(piece)) = (normal, self.pieces.get(p)) else {
                continue;
            };
            if piece.kind == PieceKind::Polygon
                && piece.polygon.support().normal() == plane
                && let Some(state) = self.illum.get_mut(p)
            {
                state.normal = Some(normal);
            }
        }
    }

    /// Takes an object's pieces from it (polygons, bodies and the joint
    /// bodies it is part of), leaving them in the scene.
    fn take(&mut self, id: ObjectId) -> Result<Vec<PieceId>, Error> {
        let object = self.objects.get_mut(id).ok_or(Error::UnknownObject)?;
        let mut gone: Vec<PieceId> = std::mem::take(&mut object.pieces);
        gone.append(&mut object.bodies);
        let joints = std::mem::take(&mut object.joints);
        let solids = std::mem::take(&mut object.solids);
        self.forget_planes(id, &solids, &gone);
        for joint in joints {
            self.unlist_joint(joint);
            gone.push(joint);
        }
        Ok(gone)
    }

    /// The units the pieces `gone` make on every other receiver.
    fn removals(&mut self, gone: &[PieceId]) -> Removals {
        self.overlap.refresh(&self.pieces);
        self.removals_of(gone)
    }

    /// [`Self::removals`], the overlap structure up to date.
    fn removals_of(&self, gone_pieces: &[PieceId]) -> Removals {
        let gone: BTreeSet<PieceId> = gone_pieces.iter().copied().collect();
        let mut touched: BTreeSet<PieceId> = BTreeSet::new();
        for &o in gone_pieces {
            touched.extend(self.overlap.receivers_near(o, &self.pieces));
        }
        touched
            .into_iter()
            .filter(|r| !gone.contains(r))
            .filter_map(|r| {
                let units = self.receivers.get(r)?.units_of(|o| gone.contains(&o));
                (!units.is_empty()).then_some((r, units))
            })
            .collect()
    }

    /// Drops pieces from the scene (their receivers, illumination and
    /// overlap entries), returning them: their planes are still needed to
    /// take their units out of the other receivers.
    fn forget(&mut self, gone: Vec<PieceId>) -> KeyMap<PieceId, Piece> {
        let mut left = KeyMap::default();
        for p in gone {
            self.overlap.remove(p);
            self.receivers.remove(p);
            self.changed_at.remove(p);
            self.big_receivers.remove(&p);
            self.illum.remove(p);
            self.contacts.remove(p);
            self.unlit.remove(&p);
            if let Some(piece) = self.pieces.remove(p) {
                left.insert(p, piece);
            }
        }
        left
    }

    /// Which units of `added` (new pieces) enter which receivers, in what
    /// order: on an old receiver the new occluders, appended; on a new one
    /// every occluder the overlap structure pairs it with. `parked`: a
    /// receiver out of the scene for now, that light reaches.
    fn insertions(&mut self, added: &[PieceId], parked: Option<PieceId>) -> Insertions {
        self.overlap.refresh(&self.pieces);
        let new: BTreeSet<PieceId> = added.iter().copied().collect();
        // Old receivers the new occluders may reach, each with those
        // occluders (in the order of `added`). The very pairs a removal
        // finds (`Self::removals_of`): a unit that entered a receiver the
        // occluder's removal would not look at would stay there, of a
        // piece gone (a body under a floor passes the floor's box test,
        // but its shadow's tiles miss the floor).
        let mut touched: BTreeMap<PieceId, Vec<PieceId>> = BTreeMap::new();
        for &o in added {
            for r in self.overlap.receivers_near(o, &self.pieces) {
                if !new.contains(&r) {
                    touched.entry(r).or_default().push(o);
                }
            }
        }
        let targets: Vec<(PieceId, Option<Vec<PieceId>>)> = added
            .iter()
            .map(|&r| (r, None))
            .chain(touched.into_iter().map(|(r, near)| (r, Some(near))))
            .filter(|(r, _)| {
                self.receivers
                    .get(*r)
                    .map_or(parked == Some(*r), |dm| !dm.in_the_dark())
            })
            .collect();
        let (lights, pieces, overlap) = (&self.lights, &self.pieces, &self.overlap);
        targets
            .into_par_iter()
            .map(|(r, near)| {
                // New receivers: every occluder the overlap structure pairs
                // them with. Old ones: the new occluders, appended.
                let fresh = near.is_none();
                let candidates = near.unwrap_or_else(|| overlap.occluders_near(r, pieces));
                let order = unit_order(lights, pieces, &candidates);
                // A new receiver that many units reach starts as a
                // balanced tree of tiles, about one per TILE_UNITS units.
                let depth = if fresh {
                    (order.len() / TILE_UNITS)
                        .max(1)
                        .ilog2()
                        .min(MAX_TILE_DEPTH)
                } else {
                    0
                };
                (r, (depth, order))
            })
            .filter(|(_, (_, order))| !order.is_empty())
            .collect()
    }

    /// Applies a change: each receiver named removes its leaving units,
    /// then merges its entering ones, then (once the scene has been
    /// illuminated) computes its vertices' irradiance again, as do the
    /// receivers `relight` changed before. `left` holds the pieces already
    /// gone whose units leave.
    fn apply(
        &mut self,
        removals: Removals,
        floods: Floods,
        insertions: Insertions,
        relight: &BTreeSet<PieceId>,
        left: &KeyMap<PieceId, Piece>,
    ) {
        let mut work = self.take_work(removals, floods, insertions, relight, self.lit);
        let stats = self.run_work(&mut work, left);
        self.put_back(work);
        self.lit_since = self.lit_since.add(stats);
        if self.lit {
            // New receivers that no unit reaches, not among the work.
            let rest = self.illuminate_pending();
            self.lit_since = self.lit_since.add(rest);
        }
    }

    /// The receivers a change names (in `removals`, `insertions` or
    /// `relight`), taken out of the scene with what leaves and enters
    /// each, and their illumination if `lit` (looked up by key: a walk
    /// over every receiver costs a tenth of a small move on the 10k hall).
    fn take_work(
        &mut self,
        mut removals: Removals,
        mut floods: Floods,
        mut insertions: Insertions,
        relight: &BTreeSet<PieceId>,
        lit: bool,
    ) -> Vec<Work> {
        let changed: BTreeSet<PieceId> = removals
            .keys()
            .chain(insertions.keys())
            .chain(relight)
            .copied()
            .collect();
        let mut work: Vec<Work> = Vec::with_capacity(changed.len());
        for r in changed {
            if !self.receivers.contains_key(r) || !self.contacts.contains_key(r) {
                continue;
            }
            if let (Some(dm), Some(contact)) = (self.receivers.remove(r), self.contacts.remove(r)) {
                let illum = if lit { self.illum.remove(r) } else { None };
                work.push(Work {
                    receiver: r,
                    dm,
                    contact,
                    out: removals.remove(&r).map(|units| (units, floods.remove(&r))),
                    into: insertions.remove(&r),
                    illum,
                    changed: false,
                });
            }
        }
        work
    }

    /// Puts receivers taken out by [`Self::take_work`] back.
    fn put_back(&mut self, work: Vec<Work>) {
        for work in work {
            let r = work.receiver;
            if work.dm.cell_count() >= AHEAD_CELLS {
                self.big_receivers.insert(r);
            } else {
                self.big_receivers.remove(&r);
            }
            self.receivers.insert(r, work.dm);
            if work.changed {
                self.changed_at.insert(r, self.revision);
            }
            self.contacts.insert(r, work.contact);
            if let Some(illum) = work.illum {
                self.illum.insert(r, illum);
                self.unlit.remove(&r);
            }
        }
    }

    /// Each receiver of `work` removes its leaving units, merges its
    /// entering ones and computes its vertices' irradiance again (if its
    /// illumination was taken out with it): the receivers in parallel, the
    /// biggest first (so that no thread is left with one at the end).
    fn run_work(&self, work: &mut [Work], left: &KeyMap<PieceId, Piece>) -> IllumStats {
        let (lights, pieces, how) = (&self.lights, &self.pieces, self.options.deletion);
        let sources: Vec<AreaSource> = lights.iter().map(|l| l.source.clone()).collect();
        let run = |work: &mut Work| {
            let Work {
                receiver: r,
                dm,
                contact,
                out,
                into,
                illum,
                changed,
            } = work;
            let piece = |o: PieceId| left.get(&o).unwrap_or_else(|| &pieces[o]);
            let entering = into.iter().flat_map(|(_, order)| order.iter().copied());
            contact.add(&pieces[*r], &sources, entering, piece);
            let seen = &*contact;
            let planes = |occluder: PieceId, light: u8| {
                seen.get(occluder, light, unit_planes(pieces, left, occluder, light))
            };
            if let Some((units, flooded)) = out {
                dm.remove_units(units, planes, how, flooded.take());
            }
            if let Some((depth, order)) = into {
                dm.insert_tiled(*depth, order, &planes);
            }
            if out.is_some() {
                contact.forget(|o| left.contains_key(&o));
            }
            // Its cells changed, or (untracked before the first
            // illumination) may have; or its values were computed again.
            *changed = dm.has_touched() || !dm.is_tracking();
            let stats = illum.as_mut().map_or_else(IllumStats::default, |state| {
                illuminate_receiver(lights, pieces, *r, dm, state, &mut VisiblePart::new())
            });
            *changed |= stats.evaluated > 0;
            stats
        };
        if work.len() <= 2 {
            // A small change: no tasks to hand out.
            return work
                .iter_mut()
                .map(run)
                .fold(IllumStats::default(), IllumStats::add);
        }
        work.sort_by_key(|work| {
            let units = work.into.as_ref().map_or(0, |(_, order)| order.len());
            std::cmp::Reverse((
                work.dm.cell_count() + units * TILE_UNITS,
                work.out.is_some(),
            ))
        });
        // Each receiver a task of its own: a run of receivers split off
        // together would go on one thread, after the biggest, while the
        // other waits at the end (10k hall: the last 1.3-1.7 s of the
        // build on about one core).
        work.par_iter_mut()
            .with_max_len(1)
            .map(run)
            .reduce(IllumStats::default, IllumStats::add)
    }
}

/// A unit's volume planes: of a piece of the scene, or of one that left.
fn unit_planes<'p>(
    pieces: &'p SlotMap<PieceId, Piece>,
    left: &'p KeyMap<PieceId, Piece>,
    occluder: PieceId,
    light: u8,
) -> &'p UnitPlanes {
    let piece = left.get(&occluder).unwrap_or_else(|| &pieces[occluder]);
    &piece.volumes[usize::from(light)]
}
