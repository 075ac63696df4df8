//! [`OverlapKind::Grid`](super::OverlapKind::Grid): a uniform grid over
//! the scene holding each receiver's bounding box and each occluder's
//! *penumbra box*, a box around its penumbra volumes within the scene.
//!
//! The penumbra box: every point `p` of a penumbra volume lies on a ray from
//! a light point `x` through an occluder point `y`, `p = x + t (y - x)` with
//! `t >= 1`. If the occluder is at least `h > 0` in front of the light's
//! plane, `p` is at least `t h` in front of it, so a `p` inside the scene's
//! box (with the light), whose corners are at most `depth` in front, has
//! `t <= depth / h`. For a fixed `t`, `p` is a convex
//! combination of the points `l_i + t (o_j - l_i)` over the light's and the
//! occluder's vertices, and those are linear in `t`: so the volume within
//! the scene lies in the box of those points at `t = 1` and `t = depth / h`.
//! An occluder touching or crossing the light's plane gets the whole scene.
//!
//! Lists of pieces are returned in key order, so results do not depend on
//! the grid.

use super::{Box3, grow, light_plane};
use crate::hash::KeyMap;
use crate::scene::{DmLight, Piece, PieceId};
use slotmap::{SecondaryMap, SlotMap};
use std::collections::BTreeSet;

/// A box spanning more grid cells than this is kept in a list of its own.
const BIG: i64 = 4096;

/// The grid of receivers' boxes and occluders' penumbra boxes.
#[derive(Debug, Clone, Default)]
pub(crate) struct Grid {
    /// Light vertices, grid units.
    lights: Vec<Vec<[f64; 3]>>,
    /// Box of every piece and light so far (it only grows).
    bounds: Option<Box3>,
    /// Side of a grid cell (grid units), fixed at the first refresh.
    cell: f64,
    boxes: SecondaryMap<PieceId, Box3>,
    shadow_boxes: SecondaryMap<PieceId, Box3>,
    receivers: KeyMap<[i64; 3], Vec<PieceId>>,
    shadows: KeyMap<[i64; 3], Vec<PieceId>>,
    big_receivers: BTreeSet<PieceId>,
    big_shadows: BTreeSet<PieceId>,
    /// Pieces whose penumbra box is still to be made.
    pending: Vec<PieceId>,
    /// Whether the bounds grew since the penumbra boxes were made.
    stale: bool,
}

impl Grid {
    pub(crate) fn new(lights: &[DmLight]) -> Self {
        let lights: Vec<Vec<[f64; 3]>> = lights
            .iter()
            .map(|l| l.source.vertices().map(|g| g.to_f64()).collect())
            .collect();
        let mut bounds = None;
        for p in lights.iter().flatten() {
            grow(&mut bounds, *p);
        }
        Self {
            lights,
            bounds,
            ..Self::default()
        }
    }

    /// Registers a new piece's receiver box (if it `receives`); its
    /// penumbra box is made at the next [`refresh`](Self::refresh).
    pub(crate) fn insert(&mut self, key: PieceId, piece: &Piece, receives: bool) {
        let mut b = None;
        for v in &piece.outline {
            grow(&mut b, *v);
            self.stale |= grow(&mut self.bounds, *v);
        }
        if receives {
            let b = b.unwrap_or_default();
            self.boxes.insert(key, b);
            if self.cell > 0.0 {
                self.place(key, b, false);
            }
        }
        self.pending.push(key);
    }

    /// Forgets a piece.
    pub(crate) fn remove(&mut self, key: PieceId) {
        if let Some(b) = self.boxes.remove(key) {
            self.unplace(key, b, false);
        }
        if let Some(b) = self.shadow_boxes.remove(key) {
            self.unplace(key, b, true);
        }
        self.pending.retain(|k| *k != key);
    }

    /// Makes the penumbra boxes of new pieces (all of them, and the grid
    /// anew, when the scene grew).
    pub(crate) fn refresh(&mut self, pieces: &SlotMap<PieceId, Piece>) {
        let Some(bounds) = self.bounds else { return };
        if self.cell == 0.0 || self.stale {
            if self.cell == 0.0 {
                let extent = (0..3)
                    .map(|a| bounds[1][a] - bounds[0][a])
                    .fold(1.0, f64::max);
                self.cell = (extent / 32.0).max(1.0);
            }
            self.receivers.clear();
            self.shadows.clear();
            self.big_receivers.clear();
            self.big_shadows.clear();
            self.shadow_boxes.clear();
            let boxes: Vec<(PieceId, Box3)> = self.boxes.iter().map(|(k, b)| (k, *b)).collect();
            for (k, b) in boxes {
                self.place(k, b, false);
            }
            self.pending = pieces.keys().collect();
            self.stale = false;
        }
        for key in std::mem::take(&mut self.pending) {
            let Some(piece) = pieces.get(key) else {
                continue;
            };
            if let Some(b) = self.penumbra_box(piece, bounds) {
                self.shadow_boxes.insert(key, b);
                self.place(key, b, true);
            }
        }
    }

    /// The box around `piece`'s penumbra volumes within `bounds`, if it
    /// casts any.
    fn penumbra_box(&self, piece: &Piece, bounds: Box3) -> Option<Box3> {
        let diagonal = (0..3)
            .map(|a| (bounds[1][a] - bounds[0][a]).powi(2))
            .sum::<f64>()
            .sqrt();
        let mut out: Option<Box3> = None;
        for (i, unit) in piece.volumes.iter().enumerate() {
            if unit.volumes.penumbra.is_empty() {
                continue;
            }
            let light = &self.lights[i];
            // The occluder's least distance in front of the light's plane.
            let plane = light_plane(light);
            let h = piece
                .outline
                .iter()
                .map(|v| plane[0] * v[0] + plane[1] * v[1] + plane[2] * v[2] + plane[3])
                .fold(f64::INFINITY, f64::min);
            if h.is_nan() || h <= 1e-6 * diagonal {
                return Some(bounds);
            }
            // A point of the scene is at most `depth` in front of the
            // light's plane, and a point on a ray at `t` is at least
            // `t h` in front: `t <= depth / h` (a little beyond, against
            // rounding).
            let depth = (0..8)
                .map(|k| {
                    let c: [f64; 3] = std::array::from_fn(|a| bounds[(k >> a) & 1][a]);
                    plane[0] * c[0] + plane[1] * c[1] + plane[2] * c[2] + plane[3]
                })
                .fold(h, f64::max);
            let t_far = depth / h * (1.0 + 1e-9) + 1e-9;
            for l in light {
                for o in &piece.outline {
                    for t in [1.0, t_far] {
                        grow(&mut out, std::array::from_fn(|a| l[a] + t * (o[a] - l[a])));
                    }
                }
            }
        }
        let [lo, hi] = out?;
        let pad = 1e-9 * diagonal + 1.0;
        let clipped: Box3 = [
            std::array::from_fn(|a| (lo[a] - pad).max(bounds[0][a] - pad)),
            std::array::from_fn(|a| (hi[a] + pad).min(bounds[1][a] + pad)),
        ];
        (0..3)
            .all(|a| clipped[0][a] <= clipped[1][a])
            .then_some(clipped)
    }

    fn range(&self, b: Box3) -> ([i64; 3], [i64; 3]) {
        let lo = b[0].map(|x| (x / self.cell).floor() as i64);
        let hi = b[1].map(|x| (x / self.cell).floor() as i64);
        (lo, hi)
    }

    fn cells(&self, b: Box3) -> Option<Vec<[i64; 3]>> {
        let (lo, hi) = self.range(b);
        // (Counted without overflow, a wrapped count being small.)
        let span = (0..3)
            .try_fold(1_i64, |count, a| {
                hi[a].checked_sub(lo[a])?.checked_add(1)?.checked_mul(count)
            })
            .filter(|&span| span <= BIG)?;
        let mut out = Vec::with_capacity(span as usize);
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    out.push([x, y, z]);
                }
            }
        }
        Some(out)
    }

    fn place(&mut self, key: PieceId, b: Box3, shadow: bool) {
        match self.cells(b) {
            None if shadow => {
                self.big_shadows.insert(key);
            }
            None => {
                self.big_receivers.insert(key);
            }
            Some(cells) => {
                let map = if shadow {
                    &mut self.shadows
                } else {
                    &mut self.receivers
                };
                for c in cells {
                    map.entry(c).or_default().push(key);
                }
            }
        }
    }

    fn unplace(&mut self, key: PieceId, b: Box3, shadow: bool) {
        if self.cell == 0.0 {
            return;
        }
        match self.cells(b) {
            None if shadow => {
                self.big_shadows.remove(&key);
            }
            None => {
                self.big_receivers.remove(&key);
            }
            Some(cells) => {
                let map = if shadow {
                    &mut self.shadows
                } else {
                    &mut self.receivers
                };
                for c in cells {
                    if let Some(list) = map.get_mut(&c) {
                        list.retain(|k| *k != key);
                    }
                }
            }
        }
    }

    /// The pieces registered (as receivers or as shadows) in the cells `b`
    /// covers, and the big ones.
    fn near(&self, b: Box3, shadow: bool) -> BTreeSet<PieceId> {
        let (map, big) = if shadow {
            (&self.shadows, &self.big_shadows)
        } else {
            (&self.receivers, &self.big_receivers)
        };
        let mut out = big.clone();
        match self.cells(b) {
            Some(cells) => {
                for c in cells {
                    if let Some(list) = map.get(&c) {
                        out.extend(list.iter().copied());
                    }
                }
            }
            None => {
                for list in map.values() {
                    out.extend(list.iter().copied());
                }
            }
        }
        out
    }

    /// A receiver's box.
    pub(crate) fn receiver_box(&self, r: PieceId) -> Option<&Box3> {
        self.boxes.get(r)
    }

    /// Occluders whose penumbra boxes share a cell with receiver `r`'s box.
    pub(crate) fn occluders_of(&self, r: PieceId) -> BTreeSet<PieceId> {
        self.boxes
            .get(r)
            .map(|b| self.near(*b, true))
            .unwrap_or_default()
    }

    /// Receivers whose boxes share a cell with occluder `o`'s penumbra box.
    pub(crate) fn receivers_of(&self, o: PieceId) -> BTreeSet<PieceId> {
        self.shadow_boxes
            .get(o)
            .map(|b| self.near(*b, false))
            .unwrap_or_default()
    }
}
