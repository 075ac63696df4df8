//! The order in which occluders are merged into a receiver's tree.
//!
//! Cells' occluder lists are sets: which occluders' penumbra volumes hold
//! the cell does not depend on the order, so the light is never split to
//! make a front-to-back order exist (the paper's "offending" polygons). The
//! order only decides how much umbra culling saves: an occluder is not
//! merged into cells already in another's umbra. As in area-shadow's
//! `AreaTrees::build`, units go nearest the light's centroid first, a
//! stand-in for front-to-back that finds most of the culling.

use crate::scene::{DmLight, Piece, PieceId};
use slotmap::SlotMap;

/// The units (occluder, light) of `candidates` that cast any shadow, light
/// by light, each light's nearest first (ties by position in
/// `candidates`), bodies that cast only their umbra after the rest (such a
/// body hides the whole light only where its polygons hide it together;
/// merged last, it culls none of them).
pub(crate) fn unit_order(
    lights: &[DmLight],
    pieces: &SlotMap<PieceId, Piece>,
    candidates: &[PieceId],
) -> Vec<(PieceId, u8)> {
    let mut out = Vec::new();
    for (i, light) in lights.iter().enumerate() {
        let centre = light.source.centroid();
        let mut list: Vec<(bool, f64, usize)> = candidates
            .iter()
            .enumerate()
            .filter(|(_, k)| !pieces[**k].volumes[i].volumes.penumbra.is_empty())
            .map(|(n, k)| {
                let piece = &pieces[*k];
                (piece.umbra_only(i), distance2(piece.centre(), centre), n)
            })
            .collect();
        list.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2)));
        out.extend(list.into_iter().map(|(_, _, n)| (candidates[n], i as u8)));
    }
    out
}

fn distance2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}
