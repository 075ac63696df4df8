//! The visible part of an area light from a point, as convex pieces.
//!
//! Each occluder (a convex planar polygon) hides, as seen from `p`, the part
//! of the light that lies inside its shadow pyramid (apex `p`, through the
//! occluder's edges) *and* beyond the occluder's plane: a point `x` of the
//! light is hidden exactly when the segment from `p` to `x` crosses the
//! occluder. That region is convex, the intersection of `k + 1` half-spaces
//! for an occluder of `k` edges, so subtracting it from a convex piece leaves
//! at most `k + 1` convex pieces. Occluders block whichever of their sides
//! faces the light.
//!
//! Everything here is plain `f64` clipping: a vertex is sent to a side by the
//! sign of a computed distance, and a piece is split only when it has
//! vertices strictly on both sides. It never decides topology (nothing here
//! is used to classify fragments as lit, penumbra or umbra; that is the exact
//! kernel's job): rounding can only create or drop slivers whose contour
//! integrals are negligible, because the integral is continuous in the
//! vertices.

use crate::area_light::AreaLight;
use crate::contour_integral::integrate_front;
use crate::point_light::Sidedness;
use crate::vec3::{Vec3, area_normal, cross, dot, lerp, scale, sub};
use smallvec::SmallVec;
use std::ops::Range;

/// Convex pieces of the visible part of an area light, reusable between
/// queries: after the first few calls, [`VisiblePart::compute`] does not
/// allocate.
#[derive(Debug, Clone, Default)]
pub struct VisiblePart {
    verts: Vec<Vec3>,
    pieces: Vec<Range<u32>>,
    next_verts: Vec<Vec3>,
    next_pieces: Vec<Range<u32>>,
}

/// A half-space `m . (x - q) > 0` of the blocked region.
#[derive(Clone, Copy)]
struct HalfSpace {
    m: Vec3,
    q: Vec3,
}

/// Where a convex piece lies with respect to a plane.
enum Split {
    /// Wholly outside the half-space (or on its plane): untouched.
    Outside,
    /// Wholly inside.
    Inside,
    /// On both sides: the inside and outside parts were written out.
    Both,
}

type Buf = SmallVec<[Vec3; 16]>;

/// Where convex `poly` lies with respect to `h`: whether some vertex is
/// strictly inside, and whether some vertex is strictly outside.
#[inline(always)]
fn classify(poly: &[Vec3], h: &HalfSpace) -> (bool, bool) {
    let mut pos = false;
    let mut neg = false;
    for v in poly {
        let s = dot(h.m, sub(*v, h.q));
        pos |= s > 0.0;
        neg |= s < 0.0;
    }
    (pos, neg)
}

/// Splits convex `poly` by `h`; on [`Split::Both`], `inside` and `outside`
/// hold the two parts.
fn split(poly: &[Vec3], h: &HalfSpace, inside: &mut Buf, outside: &mut Buf) -> Split {
    match classify(poly, h) {
        (false, _) => Split::Outside,
        (true, false) => Split::Inside,
        (true, true) => {
            inside.clear();
            outside.clear();
            let mut prev = poly[poly.len() - 1];
            let mut sp = dot(h.m, sub(prev, h.q));
            for &v in poly {
                let sv = dot(h.m, sub(v, h.q));
                if (sp > 0.0 && sv < 0.0) || (sp < 0.0 && sv > 0.0) {
                    let x = lerp(prev, v, sp / (sp - sv));
                    inside.push(x);
                    outside.push(x);
                }
                if sv >= 0.0 {
                    inside.push(v);
                }
                if sv <= 0.0 {
                    outside.push(v);
                }
                prev = v;
                sp = sv;
            }
            Split::Both
        }
    }
}

/// The half-spaces whose intersection is the part of space an occluder hides
/// from `p`: beyond its plane first, then one per edge. `None` when it hides
/// nothing of positive area (fewer than 3 vertices, no area, or `p` in its
/// plane).
fn blocked_region(occ: &[Vec3], p: Vec3, out: &mut SmallVec<[HalfSpace; 9]>) -> bool {
    out.clear();
    if occ.len() < 3 {
        return false;
    }
    let nrm = area_normal(occ);
    let side = dot(nrm, sub(p, occ[0]));
    if side == 0.0 || !side.is_finite() {
        return false;
    }
    // sigma = +1 when p is on the occluder's counter-clockwise side.
    let sigma = if side > 0.0 { 1.0 } else { -1.0 };
    out.push(HalfSpace {
        m: scale(nrm, -sigma),
        q: occ[0],
    });
    let mut prev = occ[occ.len() - 1];
    for &v in occ {
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

impl VisiblePart {
    /// An empty set of pieces.
    pub fn new() -> Self {
        Self::default()
    }

    /// Replaces the pieces by the part of `light` visible from `p` past the
    /// convex planar `occluders`.
    pub fn compute<O: AsRef<[Vec3]>>(&mut self, light: &AreaLight, occluders: &[O], p: Vec3) {
        self.verts.clear();
        self.pieces.clear();
        self.verts.extend_from_slice(light.vertices());
        self.pieces.push(0..self.verts.len() as u32);
        let mut planes = SmallVec::<[HalfSpace; 9]>::new();
        let mut active = SmallVec::<[HalfSpace; 9]>::new();
        for occ in occluders {
            if self.pieces.is_empty() {
                break;
            }
            if !blocked_region(occ.as_ref(), p, &mut planes) {
                continue;
            }
            // The pieces lie in the light: an occluder whose blocked region
            // misses the whole light leaves them as they are, and a
            // half-space that holds the whole light holds every piece, so
            // only the others can split them.
            active.clear();
            let mut misses = false;
            for h in &planes {
                match classify(light.vertices(), h) {
                    (false, _) => {
                        misses = true;
                        break;
                    }
                    (true, false) => {}
                    (true, true) => active.push(*h),
                }
            }
            if misses {
                continue;
            }
            if active.is_empty() {
                // The whole light is hidden.
                self.pieces.clear();
                break;
            }
            self.next_verts.clear();
            self.next_pieces.clear();
            for r in &self.pieces {
                let piece = &self.verts[r.start as usize..r.end as usize];
                subtract(piece, &active, &mut self.next_verts, &mut self.next_pieces);
            }
            std::mem::swap(&mut self.verts, &mut self.next_verts);
            std::mem::swap(&mut self.pieces, &mut self.next_pieces);
        }
    }

    /// Number of convex pieces.
    pub fn len(&self) -> usize {
        self.pieces.len()
    }

    /// Whether nothing of the light is visible.
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// The convex pieces, each oriented like the light.
    pub fn pieces(&self) -> impl ExactSizeIterator<Item = &[Vec3]> + '_ {
        self.pieces
            .iter()
            .map(|r| &self.verts[r.start as usize..r.end as usize])
    }

    /// Total area of the pieces.
    pub fn area(&self) -> f64 {
        self.pieces()
            .map(|piece| 0.5 * crate::vec3::norm(area_normal(piece)))
            .sum()
    }

    /// Irradiance at `p` (unit normal `n`) from the pieces, with `light`'s
    /// radiance and emitting side (`light` must be the one they were
    /// computed from).
    pub fn irradiance(&self, light: &AreaLight, p: Vec3, n: Vec3, sidedness: Sidedness) -> f64 {
        if !light.lights_side_of(p) {
            return 0.0;
        }
        let one = |n: Vec3| -> f64 { self.pieces().map(|pc| integrate_front(pc, p, n)).sum() };
        let e = match sidedness {
            Sidedness::OneSided => one(n),
            Sidedness::TwoSided => one(n) + one(scale(n, -1.0)),
        };
        light.radiance() * e
    }
}

/// Appends to `verts`/`pieces` the parts of convex `piece` outside the
/// intersection of `planes`.
///
/// A piece wholly outside one of the half-spaces is kept whole, and one
/// wholly inside them all is dropped, before any splitting; otherwise it is
/// split only by the planes it straddles, so that no piece is cut where the
/// blocked region does not reach it.
fn subtract(
    piece: &[Vec3],
    planes: &[HalfSpace],
    verts: &mut Vec<Vec3>,
    pieces: &mut Vec<Range<u32>>,
) {
    let mut push = |poly: &[Vec3]| {
        if poly.len() >= 3 {
            let start = verts.len() as u32;
            verts.extend_from_slice(poly);
            pieces.push(start..verts.len() as u32);
        }
    };
    // Bit k: the piece straddles planes[k] (at most 9 half-spaces).
    let mut straddled = 0u32;
    for (k, h) in planes.iter().enumerate() {
        match classify(piece, h) {
            (false, _) => {
                push(piece);
                return;
            }
            (true, false) => {}
            (true, true) => straddled |= 1 << k,
        }
    }
    // What is left to split: the piece itself, then bufs[0] or bufs[1] in
    // turn (no copy of the piece, no swap of buffers).
    let mut bufs = [Buf::new(), Buf::new()];
    let mut outside = Buf::new();
    let mut cur: Option<usize> = None;
    while straddled != 0 {
        let h = &planes[straddled.trailing_zeros() as usize];
        straddled &= straddled - 1;
        let [b0, b1] = &mut bufs;
        let (src, dst): (&[Vec3], &mut Buf) = match cur {
            None => (piece, b0),
            Some(0) => (b0.as_slice(), b1),
            Some(_) => (b1.as_slice(), b0),
        };
        match split(src, h, dst, &mut outside) {
            Split::Outside => {
                push(src);
                return;
            }
            Split::Inside => {}
            Split::Both => {
                push(&outside);
                cur = Some(cur.map_or(0, |i| 1 - i));
            }
        }
    }
    // What is left lies inside every half-space: hidden.
}

/// Irradiance at `p` (unit normal `n`) from the part of `light` visible past
/// `occluders`, using `scratch` for the pieces (no allocation once warm).
///
/// Skips the visibility computation when `p` is behind the light or the
/// light is wholly below the receiver's horizon.
pub fn visible_irradiance<O: AsRef<[Vec3]>>(
    light: &AreaLight,
    occluders: &[O],
    p: Vec3,
    n: Vec3,
    sidedness: Sidedness,
    scratch: &mut VisiblePart,
) -> f64 {
    if !light.lights_side_of(p) {
        return 0.0;
    }
    if sidedness == Sidedness::OneSided
        && light.vertices().iter().all(|v| dot(sub(*v, p), n) <= 0.0)
    {
        return 0.0;
    }
    scratch.compute(light, occluders, p);
    scratch.irradiance(light, p, n, sidedness)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light() -> AreaLight {
        AreaLight::new(
            &[
                [-1.0, -1.0, 2.0],
                [-1.0, 1.0, 2.0],
                [1.0, 1.0, 2.0],
                [1.0, -1.0, 2.0],
            ],
            1.0,
        )
        .unwrap()
    }

    #[test]
    fn no_occluder_gives_whole_light() {
        let mut vp = VisiblePart::new();
        vp.compute::<[Vec3; 3]>(&light(), &[], [0.0; 3]);
        assert_eq!(vp.len(), 1);
        assert!((vp.area() - 4.0).abs() < 1e-15);
    }

    #[test]
    fn big_occluder_hides_everything_either_orientation() {
        let mut vp = VisiblePart::new();
        let ccw = [
            [-5.0, -5.0, 1.0],
            [5.0, -5.0, 1.0],
            [5.0, 5.0, 1.0],
            [-5.0, 5.0, 1.0],
        ];
        let mut cw = ccw;
        cw.reverse();
        for occ in [ccw, cw] {
            vp.compute(&light(), &[occ], [0.0; 3]);
            assert!(vp.is_empty(), "{:?}", vp.pieces().collect::<Vec<_>>());
        }
    }

    #[test]
    fn occluder_beyond_light_or_behind_point_blocks_nothing() {
        let mut vp = VisiblePart::new();
        let far = [
            [-5.0, -5.0, 3.0],
            [5.0, -5.0, 3.0],
            [5.0, 5.0, 3.0],
            [-5.0, 5.0, 3.0],
        ];
        let behind = [
            [-5.0, -5.0, -1.0],
            [5.0, -5.0, -1.0],
            [5.0, 5.0, -1.0],
            [-5.0, 5.0, -1.0],
        ];
        vp.compute(&light(), &[far, behind], [0.0; 3]);
        assert!((vp.area() - 4.0).abs() < 1e-12);
    }

    #[test]
    fn half_occluder_hides_half() {
        // Occluder at height 1 covering x < 0 as seen from the origin.
        let occ = [
            [-5.0, -5.0, 1.0],
            [0.0, -5.0, 1.0],
            [0.0, 5.0, 1.0],
            [-5.0, 5.0, 1.0],
        ];
        let mut vp = VisiblePart::new();
        vp.compute(&light(), &[occ], [0.0; 3]);
        assert!((vp.area() - 2.0).abs() < 1e-12, "{}", vp.area());
        let e = vp.irradiance(&light(), [0.0; 3], [0.0, 0.0, 1.0], Sidedness::OneSided);
        let full = light().irradiance([0.0; 3], [0.0, 0.0, 1.0], Sidedness::OneSided);
        assert!((e - 0.5 * full).abs() < 1e-14);
    }

    #[test]
    fn small_occluder_leaves_a_hole_as_pieces() {
        let occ = [
            [-0.1, -0.1, 1.0],
            [0.1, -0.1, 1.0],
            [0.1, 0.1, 1.0],
            [-0.1, 0.1, 1.0],
        ];
        let mut vp = VisiblePart::new();
        vp.compute(&light(), &[occ], [0.0; 3]);
        assert_eq!(vp.len(), 4);
        // The hole is the occluder scaled by 2 (twice as far): 0.4 x 0.4.
        assert!((vp.area() - (4.0 - 0.16)).abs() < 1e-12, "{}", vp.area());
    }
}
