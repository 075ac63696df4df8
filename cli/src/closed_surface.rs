//! Which pieces are parts of closed surfaces bounding their inside
//! ([`area_shadow::closed_parts`]), so that their faces turned away from a
//! light may skip the shadow pass, and which face the inside of a closed
//! surface wound inwards.
//!
//! From a light outside such a surface, a segment that reaches one of its
//! faces turned away from the light has crossed a face turned towards it
//! first: the faces towards the light cast the whole shadow. That needs
//! more than every edge being shared: the faces must face *out*. A closed
//! box wound inwards has its faces towards the light turned away by their
//! planes, and skipping those would light its inside.
//!
//! The faces of such a box face its inside: from a point just in front of
//! one, every segment to a light outside leaves the box through another of
//! its faces. They see none of any light; the shadow passes would find that
//! only where single occluders or convex bodies prove it (a box the grid
//! bends is no exact body), so the pipelines mark them in umbra outright.
//! (Both rules take each closed part to bound its inside once, as a solid's
//! surface does.)

use bsp_core::GridPoint;
use svbsp::PieceFlags;

use crate::decompose::{Pieces, SnappedLight};
use area_shadow::{AreaSource, closed_parts};

/// What each piece is part of as a surface.
pub(crate) struct Surfaces {
    /// Per piece: casts, two-sided, and whether it is part of a closed
    /// surface facing out ([`area_shadow::closed_parts`]: its corners on
    /// the grid, each edge walked once each way by the part's pieces and
    /// no other of the object's, a positive volume enclosed) that every
    /// light lies clear of.
    pub flags: Vec<PieceFlags>,
    /// Per piece: one-sided and casting shadows, of such a part but
    /// enclosing a negative volume (wound inwards): its front faces the
    /// part's inside, which no light outside reaches (the part's other
    /// faces block it).
    pub facing_inside: Vec<bool>,
}

/// The pieces as parts of surfaces (see [`Surfaces`]); `objects[k]` is
/// piece `k`'s object ([`piece_objects`](crate::shadow::piece_objects)).
/// Each closed part counts on its own: a closed mesh and a floor in one
/// object make one part closed and one open.
pub(crate) fn surfaces(pieces: &Pieces, objects: &[u32]) -> Surfaces {
    let count = pieces.polygons.len();
    // Per piece: the sign of its closed part's volume, the part being
    // clear of every light (a light on it or inside it shines into it,
    // and there its faces turned away from the light hide what its faces
    // towards the light do not).
    let mut volume_sign = vec![0_i8; count];
    for part in closed_parts(&pieces.polygons, objects) {
        let corners = part.corners(&pieces.polygons);
        if !pieces
            .lights
            .iter()
            .all(|light| light_clear_of(light, &corners))
        {
            continue;
        }
        let sign = part.six_volume.signum() as i8;
        for &k in &part.pieces {
            volume_sign[k as usize] = sign;
        }
    }
    Surfaces {
        flags: (0..count)
            .map(|k| PieceFlags {
                casts_shadows: pieces.casts_shadows[k],
                two_sided: pieces.two_sided[k],
                closed_surface: volume_sign[k] > 0,
            })
            .collect(),
        facing_inside: (0..count)
            .map(|k| pieces.casts_shadows[k] && !pieces.two_sided[k] && volume_sign[k] < 0)
            .collect(),
    }
}

/// Whether `light` lies clear of every solid whose surface has its
/// vertices among `points` (see [`AreaSource::clear_of`]): a point light
/// outside their bounding box; a directional light always (it comes from
/// infinity).
fn light_clear_of(light: &SnappedLight, points: &[GridPoint]) -> bool {
    match light {
        SnappedLight::Point(p) => {
            let outside = |c: fn(&GridPoint) -> i32| {
                points.iter().all(|q| c(q) < c(p)) || points.iter().all(|q| c(q) > c(p))
            };
            outside(|g| g.x) || outside(|g| g.y) || outside(|g| g.z)
        }
        SnappedLight::Directional(_) => true,
        SnappedLight::Area(polygon) => {
            AreaSource::new(polygon.clone()).is_ok_and(|light| light.clear_of(points))
        }
    }
}
