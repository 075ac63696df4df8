//! Joint bodies: closed convex bodies of different objects (or of one)
//! that touch face to face and together make one convex body (or nearly,
//! when the grid bent them), casting that body's umbra
//! ([`area_shadow::convex_unions`]), and coplanar
//! polygons of several objects sharing whole edges, casting the umbra of
//! the polygon they cover ([`area_shadow::flat_joints`]).
//!
//! Beside the seam of two boxes side by side each hides only part of the
//! light, and together all of it: without the joint body those cells
//! would be penumbra with no light. A joint body is an occluder of kind
//! [`PieceKind::Body`](super::PieceKind) with only the union's umbra;
//! every object it joins lists it, and it leaves with any of them. After
//! each change the joint bodies of the touching sets the changed object
//! left and entered are found again from the bodies' shapes and compared
//! with those there: the scene holds the same joint bodies whatever the
//! history of changes, as a rebuild would.

use super::attach::BodyCast;
use super::{DmScene, ObjectId, PieceId};
use area_shadow::{
    AreaSource, ConvexGroup, FlatUnion, convex_unions, edge_contact, flat_joints, one_way,
};
use bsp_core::{ConvexPolygon, Plane};
use std::collections::{BTreeMap, BTreeSet};

/// A joint body's members: its polygons' pieces, ascending.
type Members = Vec<PieceId>;

/// What a joint body is.
enum Joint {
    /// A convex body or a flat convex polygon: one umbra volume.
    Body(ConvexGroup),
    /// A flat union that is no convex polygon: an umbra in parts.
    FlatUnion(FlatUnion),
}

impl DmScene {
    /// Keeps an object's groups (pieces indices into its pieces), and
    /// lists the faces of its closed bodies and the planes of its
    /// shadow-casting polygons.
    pub(super) fn list_planes(&mut self, id: ObjectId, solids: Vec<ConvexGroup>) {
        for solid in &solids {
            let outline: Vec<[f64; 3]> = solid
                .pieces
                .iter()
                .flat_map(|&k| {
                    self.pieces[self.objects[id].pieces[k as usize]]
                        .outline
                        .iter()
                })
                .copied()
                .collect();
            let around = bounds(&outline);
            let mut faces: Vec<Plane> = Vec::with_capacity(solid.faces().len());
            for face in solid.faces() {
                if !faces.contains(face) {
                    faces.push(*face);
                }
            }
            for face in faces {
                self.solid_faces.entry(face).or_default().push((id, around));
            }
            for corner in solid.joining_corners() {
                let holders = self.solid_corners.entry(corner).or_default();
                if !holders.contains(&id) {
                    holders.push(id);
                }
            }
        }
        for &key in &self.objects[id].pieces {
            let piece = &self.pieces[key];
            if piece.flags.casts_shadows {
                let plane = one_way(piece.polygon.support());
                let entry = (key, bounds(&piece.outline));
                self.flat_planes.entry(plane).or_default().push(entry);
            }
        }
        self.objects[id].solids = solids;
    }

    /// Takes an object's planes out of the lists ([`Self::list_planes`]),
    /// its groups and polygons (`pieces`, still in the scene) given.
    pub(super) fn forget_planes(
        &mut self,
        id: ObjectId,
        solids: &[ConvexGroup],
        pieces: &[PieceId],
    ) {
        for face in solids.iter().flat_map(ConvexGroup::faces) {
            if let Some(holders) = self.solid_faces.get_mut(face) {
                holders.retain(|(o, _)| *o != id);
                if holders.is_empty() {
                    self.solid_faces.remove(face);
                }
            }
        }
        for corner in solids.iter().flat_map(ConvexGroup::joining_corners) {
            if let Some(holders) = self.solid_corners.get_mut(&corner) {
                holders.retain(|o| *o != id);
                if holders.is_empty() {
                    self.solid_corners.remove(&corner);
                }
            }
        }
        for &key in pieces {
            let Some(piece) = self.pieces.get(key) else {
                continue;
            };
            let plane = one_way(piece.polygon.support());
            if let Some(holders) = self.flat_planes.get_mut(&plane) {
                holders.retain(|(k, _)| *k != key);
                if holders.is_empty() {
                    self.flat_planes.remove(&plane);
                }
            }
        }
    }

    /// The objects (`id` among them) with a body face in a plane where one
    /// of `id`'s bodies has a face turned the other way (their bounding
    /// boxes meeting), with a body that shares a surface corner with one
    /// of `id`'s ([`ConvexGroup::joining_corners`]: bodies the grid bent
    /// join so), or with a
    /// shadow-casting polygon in the plane of one of `id`'s in contact with
    /// it along their edges ([`edge_contact`]; a floor and the bottoms of
    /// the boxes on it lie in one plane, but do not touch so).
    pub(super) fn touching(&self, id: ObjectId) -> BTreeSet<ObjectId> {
        let Some(object) = self.objects.get(id) else {
            return BTreeSet::new();
        };
        let faces = object.solids.iter().flat_map(|solid| {
            let outline: Vec<[f64; 3]> = solid
                .pieces
                .iter()
                .flat_map(|&k| self.pieces[object.pieces[k as usize]].outline.iter())
                .copied()
                .collect();
            let own = bounds(&outline);
            solid
                .faces()
                .iter()
                .filter_map(|face| self.solid_faces.get(&face.flipped()))
                .flatten()
                .filter(move |(_, other)| meet(&own, other))
                .map(|(o, _)| *o)
        });
        let planes = object
            .pieces
            .iter()
            .map(|&key| &self.pieces[key])
            .filter(|piece| piece.flags.casts_shadows)
            .flat_map(|piece| {
                let own = bounds(&piece.outline);
                self.flat_planes
                    .get(&one_way(piece.polygon.support()))
                    .into_iter()
                    .flatten()
                    .filter(move |(k, other)| {
                        meet(&own, other) && edge_contact(&piece.polygon, &self.pieces[*k].polygon)
                    })
                    .map(|(k, _)| self.pieces[*k].object)
            });
        let corners = object
            .solids
            .iter()
            .flat_map(ConvexGroup::joining_corners)
            .filter_map(|corner| self.solid_corners.get(&corner))
            .flatten()
            .copied();
        faces.chain(planes).chain(corners).collect()
    }

    /// Drops a joint body from the lists of the objects it joins (its
    /// piece stays, for its units to leave the receivers).
    pub(super) fn unlist_joint(&mut self, joint: PieceId) {
        let members = self.joints.remove(&joint).unwrap_or_default();
        let objects: BTreeSet<ObjectId> = members
            .iter()
            .filter_map(|&k| self.pieces.get(k))
            .map(|piece| piece.object)
            .collect();
        for object in objects {
            if let Some(object) = self.objects.get_mut(object) {
                object.joints.retain(|&j| j != joint);
            }
        }
    }

    /// Brings up to date the joint bodies of the touching sets that hold
    /// `seeds`: returns the joint bodies made (new pieces) and those that
    /// are no longer (their pieces, unlisted but still in the scene).
    pub(super) fn reconcile_joints(
        &mut self,
        seeds: &BTreeSet<ObjectId>,
    ) -> (Vec<PieceId>, Vec<PieceId>) {
        // The objects connected to the seeds through touching faces.
        let mut set: BTreeSet<ObjectId> = BTreeSet::new();
        let mut queue: Vec<ObjectId> = seeds.iter().copied().collect();
        while let Some(o) = queue.pop() {
            if self.objects.contains_key(o) && set.insert(o) {
                queue.extend(self.touching(o).into_iter().filter(|n| !set.contains(n)));
            }
        }
        let mut wanted = self.solid_joints(&set);
        wanted.append(&mut self.flat_joints(&set));
        let mut held: BTreeMap<Members, Vec<PieceId>> = BTreeMap::new();
        for &o in &set {
            for &joint in &self.objects[o].joints {
                let bodies = held.entry(self.joints[&joint].clone()).or_default();
                if !bodies.contains(&joint) {
                    bodies.push(joint);
                }
            }
        }
        let mut parted = Vec::new();
        for (members, bodies) in held {
            if wanted.remove(&members).is_none() {
                for joint in bodies {
                    self.unlist_joint(joint);
                    parted.push(joint);
                }
            }
        }
        let joined = wanted
            .into_iter()
            .flat_map(|(members, (outward, joint))| self.attach_joint(members, outward, &joint))
            .collect();
        (joined, parted)
    }

    /// The convex bodies that closed bodies of the objects `set` make
    /// touching face to face ([`convex_unions`]).
    fn solid_joints(&self, set: &BTreeSet<ObjectId>) -> BTreeMap<Members, (Vec<Plane>, Joint)> {
        let mut owners: Vec<(ObjectId, &ConvexGroup)> = Vec::new();
        for &o in set {
            for group in &self.objects[o].solids {
                owners.push((o, group));
            }
        }
        let groups: Vec<&ConvexGroup> = owners.iter().map(|(_, g)| *g).collect();
        convex_unions(&groups)
            .into_iter()
            .map(|(members, union)| {
                let mut pieces: Vec<(PieceId, Plane)> = members
                    .iter()
                    .flat_map(|&i| {
                        let (o, group) = owners[i];
                        group.pieces.iter().map(move |&k| {
                            let key = self.objects[o].pieces[k as usize];
                            (key, group.outward(self.pieces[key].polygon.support()))
                        })
                    })
                    .collect();
                pieces.sort_unstable_by_key(|(key, _)| *key);
                let (keys, outward) = pieces.into_iter().unzip();
                (keys, (outward, Joint::Body(union)))
            })
            .collect()
    }

    /// The flat groups and unions that coplanar shadow-casting polygons of
    /// two or more of the objects `set` make ([`flat_joints`]).
    fn flat_joints(&self, set: &BTreeSet<ObjectId>) -> BTreeMap<Members, (Vec<Plane>, Joint)> {
        let mut keys: Vec<PieceId> = Vec::new();
        let mut polygons: Vec<ConvexPolygon> = Vec::new();
        let mut objects: Vec<Option<u32>> = Vec::new();
        for (n, &o) in set.iter().enumerate() {
            for &key in &self.objects[o].pieces {
                let piece = &self.pieces[key];
                if piece.flags.casts_shadows {
                    keys.push(key);
                    polygons.push(piece.polygon.clone());
                    objects.push(Some(n as u32));
                }
            }
        }
        let (groups, unions) = flat_joints(&polygons, &objects);
        let members = |pieces: &[u32]| -> (Members, Vec<Plane>) {
            let mut found: Vec<(PieceId, Plane)> = pieces
                .iter()
                .map(|&k| (keys[k as usize], one_way(polygons[k as usize].support())))
                .collect();
            found.sort_unstable_by_key(|(key, _)| *key);
            found.into_iter().unzip()
        };
        let groups = groups.into_iter().map(|group| {
            let (keys, outward) = members(&group.pieces);
            (keys, (outward, Joint::Body(group)))
        });
        let unions = unions.into_iter().map(|union| {
            let (keys, outward) = members(&union.pieces);
            (keys, (outward, Joint::FlatUnion(union)))
        });
        groups.chain(unions).collect()
    }

    /// Creates the occluders of a joint body (of the pieces `members`, with
    /// their planes facing out `outward`): one with its umbra, or one per
    /// convex part of it (a flat union); lists them with the objects it
    /// joins.
    fn attach_joint(
        &mut self,
        members: Members,
        outward: Vec<Plane>,
        joint: &Joint,
    ) -> Vec<PieceId> {
        let sources: Vec<AreaSource> = self.lights.iter().map(|l| l.source.clone()).collect();
        let parts: Vec<Vec<Vec<Plane>>> = sources
            .iter()
            .map(|light| match joint {
                Joint::Body(group) => group.umbra_planes(light).into_iter().collect(),
                Joint::FlatUnion(union) => union.umbra_parts(light),
            })
            .collect();
        let polygons: Vec<ConvexPolygon> = members
            .iter()
            .map(|&key| self.pieces[key].polygon.clone())
            .collect();
        let listed: Vec<(&ConvexPolygon, _)> = polygons.iter().map(|p| (p, None)).collect();
        let owner = self.pieces[members[0]].object;
        let flags = self.pieces[members[0]].flags;
        let objects: BTreeSet<ObjectId> = members.iter().map(|&k| self.pieces[k].object).collect();
        // Per light its parts; body `i` takes each light's `i`-th.
        let count = parts.iter().map(Vec::len).max().unwrap_or(0).max(1);
        let mut made = Vec::with_capacity(count);
        for i in 0..count {
            let cast = BodyCast::umbra_part(outward.clone(), &listed, &parts, i);
            let mut piece = self.body_piece(owner, flags, cast, &sources);
            piece.movable = objects.iter().any(|&o| self.objects[o].movable);
            let joint = self.insert_body(piece, members.iter().copied());
            for &o in &objects {
                self.objects[o].joints.push(joint);
            }
            self.joints.insert(joint, members.clone());
            made.push(joint);
        }
        made
    }
}

/// The bounding box of grid-unit points (whole numbers: exact in `f64`).
pub(super) type Bounds = ([f64; 3], [f64; 3]);

/// The bounding box of `points`.
fn bounds(points: &[[f64; 3]]) -> Bounds {
    points.iter().fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|a| lo[a].min(p[a])),
                std::array::from_fn(|a| hi[a].max(p[a])),
            )
        },
    )
}

/// Whether two closed boxes meet (touching counts).
fn meet(a: &Bounds, b: &Bounds) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}
