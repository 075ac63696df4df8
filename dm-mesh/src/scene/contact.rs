//! A body's umbra volume as one receiver sees it.
//!
//! A receiver can lie in a plane of a body's umbra volume: a face in
//! contact with the body (a box standing against another), or one in a
//! plane through a light vertex and the body's edge. The receiver sees
//! light past the points just off it on the side it receives on, so that
//! is where it is inside or outside the volume: in contact with the body
//! and facing it, the body covers it; facing away, the body hides nothing
//! from it. area-shadow's body tree decides the same way
//! (`VolumeTree::partition_facing`). A two-sided receiver that the light
//! reaches on both sides has no one such side: lying in a plane of the
//! volume, it is outside (area-shadow: inside only in the interior of the
//! union, which differs only where two bodies' volumes meet in that plane
//! from either side).
//!
//! So per receiver a body unit's planes are adapted before any tree code
//! sees them: a plane of the receiver's own, facing it, is dropped (the
//! receiver is behind it); one facing away empties the volume there.

use super::{Piece, PieceId, PieceKind};
use crate::critical::UnitPlanes;
use crate::hash::KeyMap;
use area_shadow::{AreaSource, SourceSide, VolumePlanes};
use bsp_core::Plane;

/// Body units whose planes a receiver sees adapted.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactPlanes(KeyMap<(PieceId, u8), UnitPlanes>);

impl ContactPlanes {
    /// The adapted planes of the body units among `units` on `receiver`;
    /// `piece` finds a unit's occluder.
    pub(crate) fn new<'p>(
        receiver: &Piece,
        lights: &[AreaSource],
        units: impl Iterator<Item = (PieceId, u8)>,
        piece: impl Fn(PieceId) -> &'p Piece,
    ) -> Self {
        let mut contact = Self::default();
        contact.add(receiver, lights, units, piece);
        contact
    }

    /// Adds the adapted planes of the body units among `units` (units
    /// entering `receiver`). A receiver keeps its contact planes from
    /// change to change, so that a change looks at its own units only,
    /// not at every unit of the receiver (a floor lists thousands).
    pub(crate) fn add<'p>(
        &mut self,
        receiver: &Piece,
        lights: &[AreaSource],
        units: impl Iterator<Item = (PieceId, u8)>,
        piece: impl Fn(PieceId) -> &'p Piece,
    ) {
        for (key, light) in units {
            let occluder = piece(key);
            if occluder.kind != PieceKind::Body {
                continue;
            }
            let planes = &occluder.volumes[usize::from(light)];
            let light_source = &lights[usize::from(light)];
            if let Some(seen) = seen_from(receiver, light_source, planes) {
                self.0.insert((key, light), seen);
            }
        }
    }

    /// Forgets the units of the occluders for which `gone` holds (once
    /// their units left the receiver).
    pub(crate) fn forget(&mut self, gone: impl Fn(PieceId) -> bool) {
        if !self.0.is_empty() {
            self.0.retain(|(key, _), _| !gone(*key));
        }
    }

    /// The planes of unit `(key, light)` as the receiver sees them.
    pub(crate) fn get<'a>(
        &'a self,
        key: PieceId,
        light: u8,
        planes: &'a UnitPlanes,
    ) -> &'a UnitPlanes {
        self.0.get(&(key, light)).unwrap_or(planes)
    }
}

/// A body unit's planes as `receiver` sees them, if they differ.
fn seen_from(receiver: &Piece, light: &AreaSource, planes: &UnitPlanes) -> Option<UnitPlanes> {
    let support = receiver.polygon.support();
    let all = planes
        .volumes
        .penumbra
        .iter()
        .flatten()
        .chain(planes.volumes.umbra.iter().flatten());
    if !all.into_iter().any(|p| p.is_coincident(support)) {
        return None;
    }
    // The side the receiver receives on (none: both).
    let facing = match light.side_of(support) {
        SourceSide::Back => Some(support.flipped()),
        SourceSide::Both if receiver.flags.two_sided => None,
        _ => Some(*support),
    };
    // A plane holds its volume behind it: the receiver is inside when it
    // faces the plane's back.
    let adapt = |list: &[Plane]| -> Option<Vec<Plane>> {
        let mut out = Vec::with_capacity(list.len());
        for p in list {
            if !p.is_coincident(support) {
                out.push(*p);
            } else if facing.is_none_or(|f| f == *p) {
                return None;
            }
        }
        Some(out)
    };
    let Some(penumbra) = planes.volumes.penumbra.iter().map(|l| adapt(l)).collect() else {
        // No region here: no volume (an empty unit merges nothing).
        return Some(UnitPlanes::default());
    };
    let volumes = VolumePlanes {
        penumbra,
        umbra: planes.volumes.umbra.as_deref().and_then(adapt),
    };
    Some(UnitPlanes::new(volumes, planes.internal.clone()))
}
