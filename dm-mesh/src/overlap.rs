//! Which occluders can shadow which receivers: a conservative
//! floating-point reject before any tree is touched.
//!
//! A receiver is paired with an occluder under a light unless its bounding
//! box lies strictly in front of one of the occluder's penumbra-volume
//! planes by more than the rounding error of the test; the exact clip of
//! the receiver by those planes (in the tree) decides the rest. This is a
//! linear scan per added or removed piece: the paper's shadow overlap cube,
//! or a hierarchy of penumbra volumes, would make it sublinear.

use crate::scene::{DmLight, Piece, PieceId};
use slotmap::{SecondaryMap, SlotMap};

/// Bounding boxes of the receivers.
#[derive(Debug, Clone, Default)]
pub(crate) struct Overlap {
    boxes: SecondaryMap<PieceId, [[f64; 3]; 2]>,
}

impl Overlap {
    pub(crate) fn new(_lights: &[DmLight]) -> Self {
        Self::default()
    }

    pub(crate) fn insert(&mut self, key: PieceId, piece: &Piece) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &piece.outline {
            for a in 0..3 {
                lo[a] = lo[a].min(v[a]);
                hi[a] = hi[a].max(v[a]);
            }
        }
        self.boxes.insert(key, [lo, hi]);
    }

    pub(crate) fn remove(&mut self, key: PieceId) {
        self.boxes.remove(key);
    }

    /// Whether occluder `o` may shadow receiver `r` under some light.
    pub(crate) fn may_shadow(
        &self,
        o: PieceId,
        r: PieceId,
        pieces: &SlotMap<PieceId, Piece>,
    ) -> bool {
        if o == r {
            return false;
        }
        let Some(bx) = self.boxes.get(r) else {
            return false;
        };
        pieces[o].volumes.iter().any(|v| {
            v.volumes
                .penumbra
                .iter()
                .any(|planes| planes.iter().all(|p| !box_in_front(bx, p.approx())))
        })
    }

    /// Occluders that may shadow receiver `r`, in the pieces' order.
    pub(crate) fn occluders_near(
        &self,
        r: PieceId,
        pieces: &SlotMap<PieceId, Piece>,
    ) -> Vec<PieceId> {
        pieces
            .keys()
            .filter(|&o| self.may_shadow(o, r, pieces))
            .collect()
    }

    /// Receivers that occluder `o` may shadow, in the pieces' order.
    pub(crate) fn receivers_near(
        &self,
        o: PieceId,
        pieces: &SlotMap<PieceId, Piece>,
    ) -> Vec<PieceId> {
        pieces
            .keys()
            .filter(|&r| self.may_shadow(o, r, pieces))
            .collect()
    }
}

/// Whether every corner of the box is strictly in front of the plane
/// `(a, b, c, d)` by more than the evaluation's rounding error.
fn box_in_front(bx: &[[f64; 3]; 2], [a, b, c, d]: [f64; 4]) -> bool {
    // The corner that minimises the plane's value.
    let pick = |n: f64, axis: usize| if n >= 0.0 { bx[0][axis] } else { bx[1][axis] };
    let (x, y, z) = (pick(a, 0), pick(b, 1), pick(c, 2));
    let value = a * x + b * y + c * z + d;
    let magnitude = (a * x).abs() + (b * y).abs() + (c * z).abs() + d.abs();
    value > magnitude * 1e-12
}
