//! Joint bodies: closed convex bodies of different objects (or of one)
//! that touch face to face and together make one convex body, casting
//! that body's umbra ([`area_shadow::convex_unions`]).
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

use super::update::BodyCast;
use super::{DmScene, ObjectId, PieceId};
use area_shadow::{AreaSource, ConvexGroup, convex_unions};
use bsp_core::ConvexPolygon;
use std::collections::{BTreeMap, BTreeSet};

/// A joint body's members: (object, index into its solids), ascending.
type Members = Vec<(ObjectId, u32)>;

impl DmScene {
    /// Keeps an object's groups (pieces indices into its pieces), and
    /// lists the faces of its closed bodies.
    pub(super) fn list_faces(&mut self, id: ObjectId, solids: Vec<ConvexGroup>) {
        for face in solids.iter().flat_map(ConvexGroup::faces) {
            self.solid_faces.entry(*face).or_default().insert(id);
        }
        self.objects[id].solids = solids;
    }

    /// Takes an object's faces out of the list ([`Self::list_faces`]).
    pub(super) fn forget_faces(&mut self, id: ObjectId, solids: &[ConvexGroup]) {
        for face in solids.iter().flat_map(ConvexGroup::faces) {
            if let Some(holders) = self.solid_faces.get_mut(face) {
                holders.remove(&id);
                if holders.is_empty() {
                    self.solid_faces.remove(face);
                }
            }
        }
    }

    /// The objects (`id` among them, if it has bodies) with a body face in
    /// a plane where one of `id`'s bodies has a face turned the other way.
    pub(super) fn touching(&self, id: ObjectId) -> BTreeSet<ObjectId> {
        let Some(object) = self.objects.get(id) else {
            return BTreeSet::new();
        };
        object
            .solids
            .iter()
            .flat_map(ConvexGroup::faces)
            .filter_map(|face| self.solid_faces.get(&face.flipped()))
            .flatten()
            .copied()
            .collect()
    }

    /// Drops a joint body from the lists of the objects it joins (its
    /// piece stays, for its units to leave the receivers).
    pub(super) fn unlist_joint(&mut self, joint: PieceId) {
        for (object, _) in self.joints.remove(&joint).unwrap_or_default() {
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
        let mut owners: Members = Vec::new();
        let mut groups: Vec<&ConvexGroup> = Vec::new();
        for &o in &set {
            for (k, group) in self.objects[o].solids.iter().enumerate() {
                owners.push((o, k as u32));
                groups.push(group);
            }
        }
        let mut wanted: BTreeMap<Members, ConvexGroup> = convex_unions(&groups)
            .into_iter()
            .map(|(members, union)| (members.iter().map(|&i| owners[i]).collect(), union))
            .collect();
        let mut parted = Vec::new();
        let held: BTreeSet<PieceId> = set
            .iter()
            .flat_map(|&o| self.objects[o].joints.iter().copied())
            .collect();
        for joint in held {
            if wanted.remove(&self.joints[&joint]).is_none() {
                self.unlist_joint(joint);
                parted.push(joint);
            }
        }
        let joined = wanted
            .into_iter()
            .map(|(members, union)| self.attach_joint(members, &union))
            .collect();
        (joined, parted)
    }

    /// Creates the occluder of a joint body with only the union's umbra,
    /// and lists it with the objects it joins.
    fn attach_joint(&mut self, members: Members, union: &ConvexGroup) -> PieceId {
        let sources: Vec<AreaSource> = self.lights.iter().map(|l| l.source.clone()).collect();
        let mut polygons: Vec<ConvexPolygon> = Vec::new();
        let mut keys = Vec::new();
        let mut outward = Vec::new();
        for &(o, k) in &members {
            let object = &self.objects[o];
            let group = &object.solids[k as usize];
            for &i in &group.pieces {
                let key = object.pieces[i as usize];
                let polygon = &self.pieces[key].polygon;
                outward.push(group.outward(polygon.support()));
                polygons.push(polygon.clone());
                keys.push(key);
            }
        }
        let (owner, _) = members[0];
        let flags = self.pieces[keys[0]].flags;
        let listed: Vec<(&ConvexPolygon, _)> = polygons.iter().map(|p| (p, None)).collect();
        let cast = BodyCast {
            outward,
            members: &listed,
            keys,
            volumes: sources
                .iter()
                .map(|light| (None, union.umbra_planes(light)))
                .collect(),
        };
        let joint = self.attach_body(owner, flags, cast, &sources);
        let objects: BTreeSet<ObjectId> = members.iter().map(|(o, _)| *o).collect();
        for o in objects {
            self.objects[o].joints.push(joint);
        }
        self.joints.insert(joint, members);
        joint
    }
}
