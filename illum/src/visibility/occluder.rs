//! What hides light from a point: a convex polygon, or a convex solid seen
//! by its silhouette.

use super::HalfSpace;
use crate::vec3::{Vec3, area_normal, cross, dot, scale, sub};
use smallvec::SmallVec;

/// An occluder as [`visible_irradiance`](super::visible_irradiance) takes
/// it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Occluder<'a> {
    /// A convex planar polygon (either orientation): it hides the points
    /// of the light whose segments to the point cross it.
    Polygon(&'a [Vec3]),
    /// A convex solid that lies wholly on the lit side of the light's
    /// plane, given by its silhouette from the point: the closed loop of
    /// its edges between the faces the point sees and the others,
    /// counter-clockwise as seen from the point. It hides every point of
    /// the light inside the cone from the point over the loop (a segment
    /// to one enters the solid, and leaves it before the light's plane).
    /// One region where its faces that the point sees make one each (two
    /// or three of a box), cutting the light along their shared edges too.
    Silhouette(&'a [Vec3]),
}

impl<'a> Occluder<'a> {
    /// Its corners: the polygon's, or the silhouette's.
    pub fn corners(&self) -> &'a [Vec3] {
        match *self {
            Self::Polygon(corners) | Self::Silhouette(corners) => corners,
        }
    }

    /// The half-spaces whose intersection is the part of space it hides
    /// from `p`: a polygon's plane (beyond it) first, then one per edge
    /// (inside the pyramid from `p`). `false` when it hides nothing of
    /// positive area (fewer than 3 corners, a polygon of no area or with
    /// `p` in its plane).
    pub(super) fn blocked_region(&self, p: Vec3, out: &mut SmallVec<[HalfSpace; 9]>) -> bool {
        out.clear();
        let corners = self.corners();
        if corners.len() < 3 {
            return false;
        }
        // sigma = +1 when p sees the corners counter-clockwise.
        let sigma = match self {
            Self::Polygon(occ) => {
                let nrm = area_normal(occ);
                let side = dot(nrm, sub(p, occ[0]));
                if side == 0.0 || !side.is_finite() {
                    return false;
                }
                let sigma = if side > 0.0 { 1.0 } else { -1.0 };
                out.push(HalfSpace {
                    m: scale(nrm, -sigma),
                    q: occ[0],
                });
                sigma
            }
            // Nothing of the solid lies beyond the light's plane: the cone
            // alone bounds what it hides there.
            Self::Silhouette(_) => 1.0,
        };
        let mut prev = corners[corners.len() - 1];
        for &v in corners {
            let a = sub(prev, p);
            // (v_i - p) x (v_{i+1} - p) = a x e; the pyramid's inside is where
            // sigma * m . (x - p) < 0.
            let m = cross(a, sub(v, prev));
            if m != [0.0; 3] {
                out.push(HalfSpace {
                    m: scale(m, -sigma),
                    q: p,
                });
            }
            prev = v;
        }
        true
    }
}

/// Anything [`visible_irradiance`](super::visible_irradiance) takes as an
/// occluder: an [`Occluder`], or a convex polygon's corners.
pub trait AsOccluder {
    /// The occluder.
    fn occluder(&self) -> Occluder<'_>;
}

impl AsOccluder for Occluder<'_> {
    fn occluder(&self) -> Occluder<'_> {
        *self
    }
}

impl<T: AsRef<[Vec3]> + ?Sized> AsOccluder for T {
    fn occluder(&self) -> Occluder<'_> {
        Occluder::Polygon(self.as_ref())
    }
}
