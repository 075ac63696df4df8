//! Which occluders can shadow which receivers, without looking at every
//! pair. Two structures, chosen by [`OverlapKind`]:
//!
//! - [`OverlapKind::Grid`] (module `grid`, the default): a uniform grid of
//!   receivers' bounding boxes and occluders' penumbra boxes over the
//!   scene;
//! - [`OverlapKind::Cube`] (module `cube`): the paper's shadow overlap
//!   cube, a cube of direction tiles around each light into which every
//!   receiver and every penumbra volume is scan-converted, with tile lists
//!   kept per polygon.
//!
//! Pairs either finds are filtered by the same conservative floating-point
//! test (the receiver's box strictly in front of a penumbra plane by more
//! than the rounding error). Then the tree's quick reject, before any node
//! is made, decides exactly: the receiver clipped by the penumbra volume's
//! planes (the paper casts the volume's vertices on the receiver's plane
//! and tests them against the receiver; clipping is the same test, exact).
//!
//! Measured on the benchmark scenes (`overlap-pairs` and `dm-cost`, 2
//! cores, shared with other work): pairs after the box test, pairs that
//! pass the exact quick reject, instructions (callgrind, 1 thread) of
//! loading, building and illuminating, and of one move (re-illumination
//! included); the hall (9995 polygons, outer discontinuities only) by the
//! clock, median of a few runs on the loaded machine:
//!
//! | scene | grid pairs | cube pairs | shadowing | grid build / move | cube build / move |
//! | --- | --- | --- | --- | --- | --- |
//! | office (monitor_1) | 821 | 837 | 494 | 147.2M / 17.6M | 141.6M / 17.3M |
//! | cubes (cube_1) | 1184 | 1204 | 640 | 323.2M / 84.3M | 266.6M / 79.5M |
//! | hall (box0) | 184906 | 193166 | 135627 | 11.8 s / 40 ms | 14.1 s / 112 ms |
//!
//! The grid localises better everywhere (its boxes separate depths along a
//! light's rays, the cube's direction tiles cannot), and on the 10k hall
//! that decides: a box's move is almost three times slower through the
//! cube, whose tiles hold every piece along their rays. On the small scenes
//! the cube's simpler bookkeeping wins a few per cent. The grid stays the
//! default.

use crate::scene::{DmLight, Piece, PieceId};
use slotmap::SlotMap;

mod cube;
mod grid;

/// Which structure pairs occluders with the receivers they may shadow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OverlapKind {
    /// A uniform grid of receiver boxes and penumbra boxes (the default).
    #[default]
    Grid,
    /// Chrysanthou & Slater's shadow overlap cube: direction tiles on a
    /// cube around each light.
    Cube,
}

/// How well an overlap structure localises, for a scene as it is
/// ([`DmScene::overlap_figures`](crate::DmScene::overlap_figures)).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct OverlapFigures {
    /// Occluder / receiver pairs the structure gives (after the box test).
    pub candidates: usize,
    /// Those that pass the exact quick reject: the receiver clipped by one
    /// of the occluder's penumbra volumes keeps some area.
    pub shadowing: usize,
}

/// An axis-aligned box: low and high corners.
pub(crate) type Box3 = [[f64; 3]; 2];

/// Grows `b` to hold `p`; whether it grew.
pub(crate) fn grow(b: &mut Option<Box3>, p: [f64; 3]) -> bool {
    match b {
        None => {
            *b = Some([p, p]);
            true
        }
        Some([lo, hi]) => {
            let mut grew = false;
            for a in 0..3 {
                if p[a] < lo[a] {
                    lo[a] = p[a];
                    grew = true;
                }
                if p[a] > hi[a] {
                    hi[a] = p[a];
                    grew = true;
                }
            }
            grew
        }
    }
}

/// The box around `points`.
pub(crate) fn bounding_box(points: &[[f64; 3]]) -> Box3 {
    let mut b = None;
    for p in points {
        grow(&mut b, *p);
    }
    b.unwrap_or_default()
}

/// Whether the occluder `piece` may shadow a receiver inside `bx` under
/// some light: no plane of one of its penumbra volumes has the whole box
/// strictly in front.
pub(crate) fn may_shadow_box(bx: &Box3, piece: &Piece) -> bool {
    piece.volumes.iter().any(|v| {
        v.volumes
            .penumbra
            .iter()
            .any(|planes| planes.iter().all(|p| !box_in_front(bx, p.approx())))
    })
}

/// Whether every corner of the box is strictly in front of the plane
/// `(a, b, c, d)` by more than the evaluation's rounding error.
fn box_in_front(bx: &Box3, [a, b, c, d]: [f64; 4]) -> bool {
    // The corner that minimises the plane's value.
    let pick = |n: f64, axis: usize| if n >= 0.0 { bx[0][axis] } else { bx[1][axis] };
    let (x, y, z) = (pick(a, 0), pick(b, 1), pick(c, 2));
    let value = a * x + b * y + c * z + d;
    let magnitude = (a * x).abs() + (b * y).abs() + (c * z).abs() + d.abs();
    value > magnitude * 1e-12
}

/// The light's plane `(a, b, c, d)` with a unit normal towards where it
/// emits, from its first three vertices (a convex light's vertices are
/// counter-clockwise seen from the front).
pub(crate) fn light_plane(v: &[[f64; 3]]) -> [f64; 4] {
    let u: [f64; 3] = std::array::from_fn(|a| v[1][a] - v[0][a]);
    let w: [f64; 3] = std::array::from_fn(|a| v[2][a] - v[0][a]);
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let n = n.map(|c| c / len);
    [
        n[0],
        n[1],
        n[2],
        -(n[0] * v[0][0] + n[1] * v[0][1] + n[2] * v[0][2]),
    ]
}

/// The overlap structure of a scene.
#[derive(Debug, Clone)]
pub(crate) enum Overlap {
    Grid(grid::Grid),
    Cube(cube::Cube),
}

impl Overlap {
    pub(crate) fn new(lights: &[DmLight], kind: OverlapKind) -> Self {
        match kind {
            OverlapKind::Grid => Self::Grid(grid::Grid::new(lights)),
            OverlapKind::Cube => Self::Cube(cube::Cube::new(lights)),
        }
    }

    /// Registers a new piece (its shadow is placed at the next
    /// [`refresh`](Self::refresh)); a receiver too when `receives`.
    pub(crate) fn insert(&mut self, key: PieceId, piece: &Piece, receives: bool) {
        match self {
            Self::Grid(g) => g.insert(key, piece, receives),
            Self::Cube(c) => c.insert(key, piece, receives),
        }
    }

    /// Forgets a piece.
    pub(crate) fn remove(&mut self, key: PieceId) {
        match self {
            Self::Grid(g) => g.remove(key),
            Self::Cube(c) => c.remove(key),
        }
    }

    /// Places the shadows of the pieces inserted since the last call.
    pub(crate) fn refresh(&mut self, pieces: &SlotMap<PieceId, Piece>) {
        match self {
            Self::Grid(g) => g.refresh(pieces),
            Self::Cube(c) => c.refresh(pieces),
        }
    }

    /// Whether occluder `o` may shadow receiver `r` under some light (the
    /// box test alone).
    pub(crate) fn may_shadow(
        &self,
        o: PieceId,
        r: PieceId,
        pieces: &SlotMap<PieceId, Piece>,
    ) -> bool {
        let bx = match self {
            Self::Grid(g) => g.receiver_box(r),
            Self::Cube(c) => c.receiver_box(r),
        };
        o != r && bx.is_some_and(|bx| may_shadow_box(bx, &pieces[o]))
    }

    /// Occluders that may shadow receiver `r`, in key order.
    pub(crate) fn occluders_near(
        &self,
        r: PieceId,
        pieces: &SlotMap<PieceId, Piece>,
    ) -> Vec<PieceId> {
        let near = match self {
            Self::Grid(g) => g.occluders_of(r),
            Self::Cube(c) => c.occluders_of(r),
        };
        near.into_iter()
            .filter(|&o| self.may_shadow(o, r, pieces))
            .collect()
    }

    /// Receivers that occluder `o` may shadow, in key order.
    pub(crate) fn receivers_near(
        &self,
        o: PieceId,
        pieces: &SlotMap<PieceId, Piece>,
    ) -> Vec<PieceId> {
        let near = match self {
            Self::Grid(g) => g.receivers_of(o),
            Self::Cube(c) => c.receivers_of(o),
        };
        near.into_iter()
            .filter(|&r| self.may_shadow(o, r, pieces))
            .collect()
    }
}
