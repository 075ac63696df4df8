//! Two occluders that share an edge, blocking as one across their seam.
//!
//! Where occluders `A` and `B` meet along an edge `e` (the pieces of a
//! concave polygon, the two halves of a bent quad, a fold), the parts of
//! the light each hides from a point meet along the seam's image with no
//! overlap, so no proof that takes them one at a time gets across it.
//! Together they do, by one observation.
//!
//! Let `A'` be `A`'s plane inside its edges other than `e`, and `Π_l` the
//! plane through `e` and a light point `l`. A segment from `k` to `l` that
//! crosses `A'` at `x` crosses `A` itself exactly when `x` is on `A`'s side
//! of `e`'s line, and since `x` lies between `k` and `l`, with `l` on `Π_l`
//! (which meets `A`'s plane in that line), that is when `k` is on the side
//! of `Π_l` of `A`'s corners off `e`. The same holds for `B`. So where
//! `Π_l` has the two occluders strictly on opposite sides (the light seen
//! along `e` within the hinge's angle, or within the angle opposite it),
//! a segment from anywhere to `l` that crosses both `A'` and `B'` crosses
//! `A` or `B`: `k` is on one side of `Π_l`, or on it, and then the segment
//! lies in `Π_l` and meets `A'` on `e` itself.
//!
//! That condition on `l` says that `l` lies within one of the two angles
//! (wedges of space about `e`'s line, each bounded by half of each
//! occluder's plane). When it holds for every light corner, it holds for
//! the whole light piece: the light lies on one side of each occluder's
//! plane (else no pair crosses), so its corners all lie in the same angle,
//! which is convex. And a segment set crosses `A'` (convex, in a plane) as
//! soon as the corner pairs do (the module's docs). So when every corner
//! pair crosses both `A'` and `B'`, every segment from the region to the
//! light piece is blocked.

use super::{Occluder, Pairs};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, Plane};
use smallvec::SmallVec;

/// Two occluders (indices into the prover's) that share an edge.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Hinge {
    /// The occluders, and for each the index of the shared edge (from that
    /// corner to the next).
    pub(super) occluders: [OnEdge; 2],
    /// The shared edge's ends.
    pub(super) axis: [GridPoint; 2],
    /// A corner of each occluder off the shared edge.
    off: [GridPoint; 2],
}

/// An occluder (index) and the index of one of its edges.
type OnEdge = (u32, usize);

/// The hinges among `occluders`: each pair that shares a whole edge (the
/// same two corners, one after the other in both), in order of their
/// first occluder, then their second.
pub(super) fn hinges(occluders: &[Occluder]) -> Vec<Hinge> {
    // Each edge by its ends in increasing order, with its occluder and
    // its index there; sorted, so that the occluders sharing an edge
    // follow each other (a hash map of them was a fiftieth of a dense
    // mesh's proofs).
    let mut edges: Vec<((GridPoint, GridPoint), OnEdge)> = Vec::new();
    for (k, o) in occluders.iter().enumerate() {
        let m = o.corners.len();
        for e in 0..m {
            let (p, q) = (o.corners[e], o.corners[(e + 1) % m]);
            edges.push((if p < q { (p, q) } else { (q, p) }, (k as u32, e)));
        }
    }
    edges.sort_unstable();
    let mut out: Vec<Hinge> = Vec::new();
    for sharing in edges.chunk_by(|a, b| a.0 == b.0) {
        let (p, q) = sharing[0].0;
        for (i, &(_, a)) in sharing.iter().enumerate() {
            for &(_, b) in &sharing[i + 1..] {
                if a.0 != b.0 {
                    out.extend(Hinge::of(occluders, [a, b], [p, q]));
                }
            }
        }
    }
    out.sort_unstable_by_key(|h| h.occluders.map(|(k, e)| (k, e)));
    out
}

/// Per occluder (of `count`), the indices of the `hinges` it is the first
/// occluder of, ascending.
pub(super) fn hinges_from(hinges: &[Hinge], count: usize) -> Vec<SmallVec<[u32; 4]>> {
    let mut from = vec![SmallVec::new(); count];
    for (h, hinge) in hinges.iter().enumerate() {
        from[hinge.occluders[0].0 as usize].push(h as u32);
    }
    from
}

impl Hinge {
    /// The hinge of two occluders (with their edges) that share the edge
    /// from `p` to `q`; `None` when one has no corner off its line.
    fn of(occluders: &[Occluder], ends: [OnEdge; 2], [p, q]: [GridPoint; 2]) -> Option<Self> {
        // A corner of each off the edge's line (welded corners may lie on
        // it).
        let off = |(k, _): OnEdge| {
            occluders[k as usize]
                .corners
                .iter()
                .copied()
                .find(|&c| Plane::through_unreduced(p, q, c).is_some())
        };
        Some(Self {
            occluders: ends,
            axis: [p, q],
            off: [off(ends[0])?, off(ends[1])?],
        })
    }

    /// Whether every light corner of `light` sees the two occluders
    /// strictly on opposite sides of the plane through the shared edge and
    /// it (the light within the hinge's angle or the one opposite).
    pub(super) fn folds_apart(&self, light: &[GridPoint]) -> bool {
        light.iter().all(|&l| {
            Plane::through_unreduced(self.axis[0], self.axis[1], l).is_some_and(|plane| {
                let sides = self.off.map(|p| side_of_point(&plane, p));
                !sides.contains(&Side::On) && sides[0] != sides[1]
            })
        })
    }

    /// The corner pairs (as [`Occluder::candidate_pairs`]) that cross both
    /// occluders with the shared edge taken away, when every light corner
    /// sees the two on opposite sides of the plane through the shared edge
    /// and it; `None` otherwise, or when the region and the light are not
    /// on opposite sides of both occluders' planes. Every pair crossing:
    /// every segment from the region to the light crosses one of them (see
    /// the module's docs).
    pub(super) fn candidate_pairs(
        &self,
        occluders: &[Occluder],
        region: &ConvexPolygon,
        light: &[GridPoint],
    ) -> Option<Pairs> {
        if !self.folds_apart(light) {
            return None;
        }
        let crossed = self
            .occluders
            .map(|(k, edge)| occluders[k as usize].candidate_pairs_past(region, light, &[edge]));
        let [Some(a), Some(b)] = crossed else {
            return None;
        };
        let both: SmallVec<[bool; 32]> = a.iter().zip(&b).map(|(&x, &y)| x && y).collect();
        Some(both)
    }
}
