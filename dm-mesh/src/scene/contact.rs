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
//! reaches on both sides receives each part of the light on its side: the
//! body hides, from the side it lies on, the part of the light there, and
//! nothing from the other; its umbra there is marked as hiding that side
//! only ([`Sides`]), and a cell is umbra where the bodies on either side
//! hide both (two boxes standing face to face, the receiver between them:
//! area-shadow finds it in the interior of the union of their volumes).
//!
//! So per receiver a body unit's planes are adapted before any tree code
//! sees them: a plane of the receiver's own, facing it, is dropped (the
//! receiver is behind it); one facing away empties the volume there.

use super::{Piece, PieceId, PieceKind};
use crate::cell::Sides;
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
    match light.side_of(support) {
        SourceSide::Back => Some(adapted(planes, support, &support.flipped())),
        SourceSide::Both if receiver.flags.two_sided => Some(from_one_side(planes, support)),
        _ => Some(adapted(planes, support, support)),
    }
    .map(|(volumes, sides)| {
        if volumes.penumbra.is_empty() {
            // No region here: an empty unit merges nothing.
            UnitPlanes::default()
        } else {
            UnitPlanes::new(volumes, planes.internal.clone()).hiding_from(sides)
        }
    })
}

/// The planes of a body unit as a two-sided receiver in `support` sees
/// them, the light on both sides of it: as seen from the side, if any,
/// where the receiver is inside the volume (the body's side), the umbra
/// hiding that side's part of the light only; else no volume.
fn from_one_side(planes: &UnitPlanes, support: &Plane) -> (VolumePlanes, Sides) {
    let sides = [(*support, Sides::FRONT), (support.flipped(), Sides::BACK)];
    let seen = sides.map(|(facing, side)| {
        let (volumes, hidden) = adapted(planes, support, &facing);
        let sides = if hidden.is_both() { side } else { Sides::NONE };
        (volumes, sides)
    });
    let [front, back] = seen;
    match (front.0.penumbra.is_empty(), back.0.penumbra.is_empty()) {
        (true, true) => (VolumePlanes::default(), Sides::NONE),
        (false, true) => front,
        (true, false) => back,
        // The penumbra is the same from either side (none of its planes
        // lies in `support`); the umbra is that of the side that keeps it.
        (false, false) => match (&front.0.umbra, &back.0.umbra) {
            (Some(_), None) => front,
            (None, Some(_)) => back,
            _ => front,
        },
    }
}

/// A body unit's planes seen from the side that `facing` faces (the
/// receiver in `support`), and the sides its umbra hides (`BOTH`, or
/// `NONE` where that side has no umbra). A plane holds its volume behind
/// it: a plane in `support` facing the other way is dropped (the receiver,
/// facing its back, is inside), one facing the same way empties the volume
/// there (the receiver looks away from it).
fn adapted(planes: &UnitPlanes, support: &Plane, facing: &Plane) -> (VolumePlanes, Sides) {
    let adapt = |list: &[Plane]| -> Option<Vec<Plane>> {
        let mut out = Vec::with_capacity(list.len());
        for p in list {
            if !p.is_coincident(support) {
                out.push(*p);
            } else if p == facing {
                return None;
            }
        }
        Some(out)
    };
    let Some(penumbra) = planes.volumes.penumbra.iter().map(|l| adapt(l)).collect() else {
        return (VolumePlanes::default(), Sides::NONE);
    };
    let umbra = planes.volumes.umbra.as_deref().and_then(adapt);
    let sides = if umbra.is_some() {
        Sides::BOTH
    } else {
        Sides::NONE
    };
    (VolumePlanes { penumbra, umbra }, sides)
}
