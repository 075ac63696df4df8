//! Changing a scene: pieces attached and detached, and the units that
//! come and go per receiver, applied to the receivers in one parallel pass.
//!
//! A change is decided first (which units leave and which enter each
//! receiver, in what order), then applied: every receiver removes its
//! leaving units and then merges its entering ones, the receivers side by
//! side (each tree only ever sees its own units, in the same order, so the
//! result does not depend on the number of threads), and, once the scene
//! has been illuminated, illuminates each receiver right after its update.
//! A move does both in that one pass: a big receiver's removal and
//! insertion run on one thread while the small ones share the other,
//! instead of two passes each waiting for the big receiver.

use super::contact::ContactPlanes;
use super::silhouette::SolidCorners;
use super::{
    DmScene, MAX_TILE_DEPTH, Member, ObjectId, Order, Piece, PieceId, PieceKind, TILE_UNITS,
    bounds_of,
};
use crate::critical::{UnitPlanes, body_internal_planes, internal_planes};
use crate::error::Error;
use crate::hash::KeyMap;
use crate::illuminate::{IllumStats, ReceiverIllum, illuminate_receiver};
use crate::order::unit_order;
use crate::surface::{Surroundings, surroundings};
use crate::tree::ReceiverDm;
use area_shadow::{
    AreaSource, ConvexGroup, SourceSide, VolumePlanes, closed_parts, convex_groups, flat_unions,
    section_unions, volume_planes,
};
use bsp_core::{ConvexPolygon, Plane};
use illum::VisiblePart;
use rayon::prelude::*;
use slotmap::SlotMap;
use std::collections::BTreeSet;
use svbsp::PieceFlags;

/// Per receiver, the units that leave it.
type Removals = KeyMap<PieceId, BTreeSet<u32>>;
/// Per receiver, the units that enter it (after tiling it to a depth).
type Insertions = KeyMap<PieceId, Order>;
/// One receiver's part of a change: units out, then units in, then its
/// illumination if the scene keeps it; the receiver's state is taken out
/// of the scene for it, and put back after.
type Work = (
    PieceId,
    ReceiverDm<PieceId>,
    ContactPlanes,
    Option<BTreeSet<u32>>,
    Option<Order>,
    Option<ReceiverIllum>,
);

impl DmScene {
    /// Creates the pieces and their empty receivers, and the bodies their
    /// polygons form; returns all of them (receivers first).
    pub(super) fn attach(
        &mut self,
        id: ObjectId,
        polygons: Vec<ConvexPolygon>,
        flags: PieceFlags,
    ) -> Result<Vec<PieceId>, Error> {
        Self::validate(&polygons)?;
        let sources: Vec<AreaSource> = self.lights.iter().map(|l| l.source.clone()).collect();
        let mut added = Vec::with_capacity(polygons.len());
        let surface = if flags.casts_shadows && self.options.internal_discontinuities {
            surroundings(&polygons)
        } else {
            Vec::new()
        };
        let bodies = if flags.casts_shadows {
            convex_groups(&polygons, &vec![Some(0); polygons.len()])
        } else {
            Vec::new()
        };
        // Per body and light, its umbra volume, and its penumbra volume
        // where it casts in place of its polygons (never without an umbra:
        // cells where it hides all of the light must be umbra); per
        // polygon, the lights its body casts for it.
        let volumes: Vec<Vec<BodyVolumes>> = bodies
            .iter()
            .map(|body| {
                sources
                    .iter()
                    .map(|light| {
                        let umbra = body.umbra_planes(light);
                        let penumbra = (self.options.convex_bodies && umbra.is_some())
                            .then(|| body.penumbra_planes(light))
                            .flatten();
                        (penumbra, umbra)
                    })
                    .collect()
            })
            .collect();
        // Per polygon, whether it is a face of a closed surface facing out
        // that no light lies on or in: such faces turned away from a light
        // cast nothing. The object's closed parts,
        // when its flags say it has some (the whole object, or a mesh and a
        // floor in one); a part some light is not clear of casts every
        // face under every light, as the flag's meaning asks ("no light
        // lies in it"), so that an object of several parts casts as its
        // parts would as objects of their own. Decided as the object is
        // added, so a move into a light decides again.
        let mut closed = vec![false; polygons.len()];
        if flags.closed_surface && flags.casts_shadows {
            for part in closed_parts(&polygons, &vec![0; polygons.len()]) {
                let corners = part.corners(&polygons);
                if part.six_volume > 0 && sources.iter().all(|light| light.clear_of(&corners)) {
                    for &k in &part.pieces {
                        closed[k as usize] = true;
                    }
                }
            }
        }
        let mut in_body = vec![0_u32; polygons.len()];
        for (body, volumes) in bodies.iter().zip(&volumes) {
            let whole = light_mask(volumes.iter().map(|(penumbra, _)| penumbra.is_some()));
            for &k in &body.pieces {
                in_body[k as usize] |= whole;
            }
        }
        for (i, polygon) in polygons.iter().enumerate() {
            let volumes = if flags.casts_shadows {
                self.polygon_units(polygon, closed[i], in_body[i], surface.get(i), &sources)
            } else {
                vec![UnitPlanes::default(); sources.len()]
            };
            let outline = polygon.vertices_f64();
            let receiver = ReceiverDm::new(polygon.clone(), flags.two_sided, &sources);
            let key = self.pieces.insert(Piece {
                polygon: polygon.clone(),
                kind: PieceKind::Polygon,
                object: id,
                flags,
                volumes,
                bounds: bounds_of(&outline),
                outline,
                members: Vec::new(),
                whole: 0,
                solid: false,
                corners: None,
            });
            self.receivers.insert(key, receiver);
            self.illum.insert(key, ReceiverIllum::default());
            self.contacts.insert(key, ContactPlanes::default());
            self.unlit.insert(key);
            self.overlap.insert(key, &self.pieces[key], true);
            added.push(key);
        }
        self.objects[id].pieces.extend(&added);
        let made: Vec<PieceId> = bodies
            .iter()
            .zip(volumes)
            .map(|(body, volumes)| {
                let members: Vec<(&ConvexPolygon, Option<&Surroundings>)> = body
                    .pieces
                    .iter()
                    .map(|&k| (&polygons[k as usize], surface.get(k as usize)))
                    .collect();
                let cast = BodyCast {
                    outward: members
                        .iter()
                        .map(|(polygon, _)| body.outward(polygon.support()))
                        .collect(),
                    members: &members,
                    keys: body.pieces.iter().map(|&k| added[k as usize]).collect(),
                    volumes,
                    solid: body.is_closed_convex(),
                };
                self.attach_body(id, flags, cast, &sources)
            })
            .collect();
        self.objects[id].bodies.extend(&made);
        let parts = self.attach_umbra_parts(id, flags, &polygons, &bodies, &added, &sources);
        self.objects[id].bodies.extend(&parts);
        self.list_planes(id, bodies);
        added.extend(parts);
        added.extend(made);
        Ok(added)
    }

    /// The bodies of the object's polygons for the umbrae they make only
    /// together that are no convex volume: of a flat union that is no
    /// convex polygon ([`flat_unions`]), of a body that holds a light in,
    /// and of one a face short ([`ConvexGroup::umbra_parts`]). Each convex
    /// part of such an umbra is a body of the polygons (pieces `added`,
    /// in the order of `polygons`) with only that umbra.
    fn attach_umbra_parts(
        &mut self,
        id: ObjectId,
        flags: PieceFlags,
        polygons: &[ConvexPolygon],
        bodies: &[ConvexGroup],
        added: &[PieceId],
        sources: &[AreaSource],
    ) -> Vec<PieceId> {
        let unions = if flags.casts_shadows {
            let one = vec![Some(0); polygons.len()];
            let mut unions = flat_unions(polygons, &one);
            unions.extend(section_unions(polygons, &one));
            unions
        } else {
            Vec::new()
        };
        // Per group: its pieces, per light its umbra's parts, and each
        // piece's plane facing out (a flat union's as it is).
        let umbra = |pieces: &'_ [u32],
                     parts: &dyn Fn(&AreaSource) -> Vec<Vec<Plane>>,
                     outward: &dyn Fn(&Plane) -> Plane| {
            let parts: Vec<Vec<Vec<Plane>>> = sources.iter().map(parts).collect();
            let outward: Vec<Plane> = pieces
                .iter()
                .map(|&k| outward(polygons[k as usize].support()))
                .collect();
            (pieces.to_vec(), parts, outward)
        };
        let of_bodies = bodies.iter().map(|body| {
            umbra(&body.pieces, &|light| body.umbra_parts(light), &|s| {
                body.outward(s)
            })
        });
        let of_unions = unions
            .iter()
            .map(|union| umbra(&union.pieces, &|light| union.umbra_parts(light), &|s| *s));
        let umbrae: Vec<_> = of_bodies.chain(of_unions).collect();
        let mut made = Vec::new();
        for (pieces, parts, outward) in umbrae {
            let members: Vec<(&ConvexPolygon, Option<&Surroundings>)> = pieces
                .iter()
                .map(|&k| (&polygons[k as usize], None))
                .collect();
            // Per light its parts; body `i` takes each light's `i`-th.
            let count = parts.iter().map(Vec::len).max().unwrap_or(0);
            for i in 0..count {
                let cast = BodyCast {
                    outward: outward.clone(),
                    members: &members,
                    keys: pieces.iter().map(|&k| added[k as usize]).collect(),
                    volumes: parts.iter().map(|p| (None, p.get(i).cloned())).collect(),
                    solid: false,
                };
                made.push(self.attach_body(id, flags, cast, sources));
            }
        }
        made
    }

    /// What a polygon of a shadow-casting object casts under each light:
    /// nothing under a light it is turned away from when `closed` (a face
    /// of a closed surface facing out that no light lies in), nor under a
    /// light whose bit `in_body` sets (its body casts in its place), else
    /// its own volumes and internal discontinuities (given its
    /// surroundings).
    fn polygon_units(
        &self,
        polygon: &ConvexPolygon,
        closed: bool,
        in_body: u32,
        around: Option<&Surroundings>,
        sources: &[AreaSource],
    ) -> Vec<UnitPlanes> {
        sources
            .iter()
            .enumerate()
            .map(|(l, light)| {
                let turned_away = closed
                    && matches!(
                        light.side_of(polygon.support()),
                        SourceSide::Back | SourceSide::In
                    );
                if turned_away || in_body & (1 << l) != 0 {
                    return UnitPlanes::default();
                }
                let volumes = volume_planes(polygon, light);
                let internal = match around {
                    Some(around) => internal_planes(polygon, light, &volumes, around),
                    None => Vec::new(),
                };
                UnitPlanes::new(volumes, internal)
            })
            .collect()
    }

    /// Creates the occluder of a body of the object's polygons.
    pub(super) fn attach_body(
        &mut self,
        id: ObjectId,
        flags: PieceFlags,
        cast: BodyCast,
        sources: &[AreaSource],
    ) -> PieceId {
        let BodyCast {
            outward,
            members,
            keys,
            volumes: body_volumes,
            solid,
        } = cast;
        // The lights with some area in front of each member's outward
        // plane.
        let facing: Vec<u32> = outward
            .iter()
            .map(|plane| {
                light_mask(sources.iter().map(|light| {
                    !matches!(light.side_of(plane), SourceSide::Back | SourceSide::In)
                }))
            })
            .collect();
        let whole = light_mask(body_volumes.iter().map(|(penumbra, _)| penumbra.is_some()));
        let volumes = sources
            .iter()
            .zip(body_volumes)
            .enumerate()
            .map(|(l, (light, found))| match found {
                (Some(penumbra), umbra @ Some(_)) => {
                    let volumes = VolumePlanes {
                        penumbra: [penumbra].into_iter().collect(),
                        umbra,
                    };
                    let lit: Vec<(&ConvexPolygon, &Surroundings)> = members
                        .iter()
                        .zip(&facing)
                        .filter(|(_, f)| *f & (1 << l) != 0)
                        .filter_map(|((polygon, around), _)| Some((*polygon, (*around)?)))
                        .collect();
                    let internal = body_internal_planes(&lit, light, &volumes);
                    UnitPlanes::new(volumes, internal)
                }
                // All of the region is umbra: penumbra and umbra planes
                // alike.
                (_, Some(planes)) => UnitPlanes::new(
                    VolumePlanes {
                        penumbra: [planes.clone()].into_iter().collect(),
                        umbra: Some(planes),
                    },
                    Vec::new(),
                ),
                (_, None) => UnitPlanes::default(),
            })
            .collect();
        let faces: Vec<Vec<[f64; 3]>> = members
            .iter()
            .map(|(polygon, _)| polygon.vertices_f64())
            .collect();
        // A solid's faces counter-clockwise seen from outside: reversed
        // where the outward plane is the polygon's turned.
        let corners = if solid {
            let outside: Vec<Vec<[f64; 3]>> = faces
                .iter()
                .zip(members)
                .zip(&outward)
                .map(|((corners, (polygon, _)), outward)| {
                    let mut corners = corners.clone();
                    if polygon.support() != outward {
                        corners.reverse();
                    }
                    corners
                })
                .collect();
            SolidCorners::new(outside.iter().map(Vec::as_slice))
        } else {
            None
        };
        let outline: Vec<[f64; 3]> = faces.into_iter().flatten().collect();
        let piece = Piece {
            polygon: members[0].0.clone(),
            kind: PieceKind::Body,
            object: id,
            flags,
            volumes,
            bounds: bounds_of(&outline),
            outline,
            members: keys
                .into_iter()
                .zip(outward)
                .zip(facing)
                .map(|((piece, outward), facing)| Member {
                    piece,
                    outward,
                    facing,
                })
                .collect(),
            whole,
            solid,
            corners,
        };
        let key = self.pieces.insert(piece);
        self.overlap.insert(key, &self.pieces[key], false);
        key
    }

    /// Casts the shadows of `added` (new pieces) on every receiver, and of
    /// every occluder on the new receivers.
    pub(super) fn cast(&mut self, added: &[PieceId]) {
        let insertions = self.insertions(added);
        self.apply(Removals::default(), insertions, &KeyMap::default());
    }

    /// Changes an object, in one pass over the receivers: its pieces and
    /// discontinuities leave, and (unless `polygons` is `None`) pieces of
    /// `polygons` (validated) take their place and cast their shadows;
    /// the joint bodies of the objects it touched and touches are brought
    /// up to date ([`Self::reconcile_joints`]).
    pub(super) fn change(
        &mut self,
        id: ObjectId,
        polygons: Option<(Vec<ConvexPolygon>, PieceFlags)>,
    ) -> Result<(), Error> {
        let mut seeds = self.touching(id);
        let normals = self.receiver_normals(id);
        let mut gone = self.take(id)?;
        let mut added = match polygons {
            Some((polygons, flags)) => self.attach(id, polygons, flags)?,
            None => Vec::new(),
        };
        self.keep_receiver_normals(&normals, &added);
        seeds.insert(id);
        let (joined, parted) = self.reconcile_joints(&seeds);
        gone.extend(parted);
        added.extend(joined);
        let removals = self.removals(&gone);
        let left = self.forget(gone);
        let insertions = self.insertions(&added);
        self.apply(removals, insertions, &left);
        Ok(())
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
    fn removals(&mut self, gone_pieces: &[PieceId]) -> Removals {
        let gone: BTreeSet<PieceId> = gone_pieces.iter().copied().collect();
        self.overlap.refresh(&self.pieces);
        let mut touched: BTreeSet<PieceId> = BTreeSet::new();
        for &o in gone_pieces {
            touched.extend(self.overlap.receivers_near(o, &self.pieces));
        }
        touched
            .into_iter()
            .filter(|r| !gone.contains(r))
            .filter_map(|r| {
                let units: BTreeSet<u32> = self
                    .receivers
                    .get(r)?
                    .units()
                    .filter(|(_, (o, _))| gone.contains(o))
                    .map(|(u, _)| u)
                    .collect();
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
    /// every occluder the overlap structure pairs it with.
    fn insertions(&mut self, added: &[PieceId]) -> Insertions {
        self.overlap.refresh(&self.pieces);
        let new: BTreeSet<PieceId> = added.iter().copied().collect();
        // Old receivers the new occluders may reach.
        let mut touched: BTreeSet<PieceId> = BTreeSet::new();
        for &o in added {
            touched.extend(
                self.overlap
                    .receivers_near(o, &self.pieces)
                    .into_iter()
                    .filter(|r| !new.contains(r)),
            );
        }
        let targets: Vec<(PieceId, bool)> = added
            .iter()
            .map(|&r| (r, true))
            .chain(touched.into_iter().map(|r| (r, false)))
            .filter(|(r, _)| self.receivers.get(*r).is_some_and(|dm| !dm.in_the_dark()))
            .collect();
        let (lights, pieces, overlap) = (&self.lights, &self.pieces, &self.overlap);
        targets
            .par_iter()
            .map(|&(r, fresh)| {
                // New receivers: every occluder the overlap structure pairs
                // them with. Old ones: the new occluders, appended.
                let candidates: Vec<PieceId> = if fresh {
                    overlap.occluders_near(r, pieces)
                } else {
                    added
                        .iter()
                        .copied()
                        .filter(|o| overlap.may_shadow(*o, r, pieces))
                        .collect()
                };
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
    /// illuminated) computes its vertices' irradiance again; the receivers
    /// in parallel, the biggest first (so that no thread is left with one
    /// at the end). `left` holds the pieces already gone whose units leave.
    fn apply(
        &mut self,
        mut removals: Removals,
        mut insertions: Insertions,
        left: &KeyMap<PieceId, Piece>,
    ) {
        // The receivers changed, taken out of the scene (looked up by key:
        // a walk over every receiver costs a tenth of a small move on the
        // 10k hall).
        let changed: BTreeSet<PieceId> =
            removals.keys().chain(insertions.keys()).copied().collect();
        let mut work: Vec<Work> = Vec::with_capacity(changed.len());
        for r in changed {
            if !self.receivers.contains_key(r) || !self.contacts.contains_key(r) {
                continue;
            }
            if let (Some(dm), Some(contact)) = (self.receivers.remove(r), self.contacts.remove(r)) {
                let illum = if self.lit { self.illum.remove(r) } else { None };
                work.push((
                    r,
                    dm,
                    contact,
                    removals.remove(&r),
                    insertions.remove(&r),
                    illum,
                ));
            }
        }
        let (lights, pieces, how) = (&self.lights, &self.pieces, self.options.deletion);
        let sources: Vec<AreaSource> = lights.iter().map(|l| l.source.clone()).collect();
        let run = |(r, dm, contact, out, into, illum): &mut Work| {
            let piece = |o: PieceId| left.get(&o).unwrap_or_else(|| &pieces[o]);
            let entering = into.iter().flat_map(|(_, order)| order.iter().copied());
            contact.add(&pieces[*r], &sources, entering, piece);
            let seen = &*contact;
            let planes = |occluder: PieceId, light: u8| {
                seen.get(occluder, light, unit_planes(pieces, left, occluder, light))
            };
            if let Some(units) = out {
                dm.remove_units(units, planes, how);
            }
            if let Some((depth, order)) = into {
                dm.insert_tiled(*depth, order, &planes);
            }
            if out.is_some() {
                contact.forget(|o| left.contains_key(&o));
            }
            illum.as_mut().map_or_else(IllumStats::default, |state| {
                illuminate_receiver(lights, pieces, *r, dm, state, &mut VisiblePart::new())
            })
        };
        let stats = if work.len() <= 2 {
            // A small change: no tasks to hand out.
            work.iter_mut()
                .map(run)
                .fold(IllumStats::default(), IllumStats::add)
        } else {
            work.sort_by_key(|(_, dm, _, out, into, _)| {
                let units = into.as_ref().map_or(0, |(_, order)| order.len());
                std::cmp::Reverse((dm.cell_count() + units * TILE_UNITS, out.is_some()))
            });
            // Each receiver a task of its own: a run of receivers split off
            // together would go on one thread, after the biggest, while the
            // other waits at the end (10k hall: the last 1.3-1.7 s of the
            // build on about one core).
            work.par_iter_mut()
                .with_max_len(1)
                .map(run)
                .reduce(IllumStats::default, IllumStats::add)
        };
        for (r, dm, contact, _, _, illum) in work {
            self.receivers.insert(r, dm);
            self.contacts.insert(r, contact);
            if let Some(illum) = illum {
                self.illum.insert(r, illum);
                self.unlit.remove(&r);
            }
        }
        self.lit_since = self.lit_since.add(stats);
        if self.lit {
            // New receivers that no unit reaches, not among the work.
            let rest = self.illuminate_pending();
            self.lit_since = self.lit_since.add(rest);
        }
    }
}

/// A body's penumbra volume under a light if it casts in place of its
/// polygons, and its umbra volume if it has one.
type BodyVolumes = (Option<Vec<Plane>>, Option<Vec<Plane>>);

/// A body of an object's polygons (convex, or a part of a flat union's
/// umbra), as [`DmScene::attach_body`] makes its occluder from it.
pub(super) struct BodyCast<'a> {
    /// Each polygon's plane, facing out of the body (a flat one's as it
    /// is).
    pub(super) outward: Vec<Plane>,
    /// Its polygons, with their surroundings when internal discontinuities
    /// are made.
    pub(super) members: &'a [(&'a ConvexPolygon, Option<&'a Surroundings>)],
    /// Their pieces.
    pub(super) keys: Vec<PieceId>,
    /// Per light, its volumes.
    pub(super) volumes: Vec<BodyVolumes>,
    /// Whether the polygons are the whole boundary of a convex polyhedron.
    pub(super) solid: bool,
}

/// One bit per light, set where `set` holds.
fn light_mask(set: impl Iterator<Item = bool>) -> u32 {
    set.enumerate()
        .filter(|(_, on)| *on)
        .fold(0, |mask, (l, _)| mask | 1 << l)
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
