//! The shadow volume of a lit piece: one plane per edge through the light,
//! and the piece's own plane as a cap.
//!
//! The 1989 paper needs no cap: in front-to-back order nothing filtered
//! later lies between the light and a piece inside its pyramid. Overlapping
//! coplanar polygons break that (each lies in the other's pyramid, in its
//! plane, and neither hides the other), so umbra caps every volume; the
//! cap also sends pieces lying in it to the light's side.
//!
//! Every plane must pass through grid points (DESIGN.md), so a shadow
//! plane is built only from an edge the kernel can name exactly: an edge of
//! the original input piece (two grid points), or an edge that lies on a
//! plane through the light already (an SVBSP split made it, and that plane
//! is its own shadow plane). A piece with any other edge (made by a
//! scene-BSP cut or by another light's shadow plane) casts the capped
//! volume of its whole original piece instead: the cap keeps that larger
//! volume from reaching anything in front of the piece's plane, and what it
//! adds behind the plane lies in the shadow of the original piece, which is
//! in shadow or casts it too.

use crate::LightSource;
use bsp_core::predicates::Side;
use bsp_core::{ConvexPolygon, Plane};
use smallvec::SmallVec;

/// The planes of a shadow volume.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowVolume {
    /// One plane per edge, each with the occluder behind it.
    pub shadow_planes: SmallVec<[Plane; 6]>,
    /// The occluder's plane with the light in front.
    pub cap: Plane,
    /// Whether the whole original piece's volume was used.
    pub whole_piece: bool,
}

/// The capped shadow volume of `piece` (a fragment of `original`, whose
/// vertices are grid points). `None` if the light lies in the piece's plane:
/// it casts no shadow.
pub fn shadow_volume(
    piece: &ConvexPolygon,
    original: &ConvexPolygon,
    light: LightSource,
) -> Option<ShadowVolume> {
    if light.lies_in(piece.support()) {
        return None;
    }
    match planes_of_edges(piece, original, light) {
        Some(planes) => Some(ShadowVolume {
            shadow_planes: planes,
            cap: cap(piece, light),
            whole_piece: false,
        }),
        None => Some(ShadowVolume {
            shadow_planes: planes_of_edges(original, original, light)?,
            cap: cap(original, light),
            whole_piece: true,
        }),
    }
}

fn cap(piece: &ConvexPolygon, light: LightSource) -> Plane {
    let support = *piece.support();
    if light.side(&support) == Side::Back {
        support.flipped()
    } else {
        support
    }
}

/// Shadow planes of every edge of `piece`, oriented with the piece behind;
/// `None` if some edge is neither original nor on a plane through the light.
fn planes_of_edges(
    piece: &ConvexPolygon,
    original: &ConvexPolygon,
    light: LightSource,
) -> Option<SmallVec<[Plane; 6]>> {
    let n = piece.len();
    let mut planes = SmallVec::with_capacity(n);
    for (i, edge) in piece.edges().enumerate() {
        let plane = if light.lies_in(edge) {
            *edge
        } else {
            let j = original.edges().position(|e| e == edge)?;
            let m = original.len();
            let p = original.vertex_grid_point(j)?;
            let q = original.vertex_grid_point((j + 1) % m)?;
            light.shadow_plane(p, q)?
        };
        // The vertex after the edge's end is off the edge's line and, as the
        // light is not in the piece's plane, off the shadow plane.
        match piece.vertex_side((i + 2) % n, &plane) {
            Side::Back => planes.push(plane),
            Side::Front => planes.push(plane.flipped()),
            Side::On => return None,
        }
    }
    Some(planes)
}
