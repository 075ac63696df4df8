//! The visible part of an area light from a point, as convex pieces.
//!
//! Each occluder (a convex planar polygon) hides, as seen from `p`, the part
//! of the light that lies inside its shadow pyramid (apex `p`, through the
//! occluder's edges) *and* beyond the occluder's plane: a point `x` of the
//! light is hidden exactly when the segment from `p` to `x` crosses the
//! occluder. That region is convex, the intersection of `k + 1` half-spaces
//! for an occluder of `k` edges, so subtracting it from a convex piece leaves
//! at most `k + 1` convex pieces. Occluders block whichever of their sides
//! faces the light. A convex solid wholly on the lit side of the light's
//! plane hides what its cone from `p` holds: given by its silhouette from
//! `p` ([`Occluder::Silhouette`]) it makes one region of one half-space
//! per silhouette edge, where its faces seen from `p` would make one
//! each, cutting the light along their shared edges as well.
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
pub use occluder::{AsOccluder, Occluder};
use outline::Outline;
use smallvec::SmallVec;
use std::ops::Range;

mod occluder;
mod outline;

/// Occluders cutting the light from which on [`visible_irradiance`] takes
/// the outlines of the visible part instead of its convex pieces: each
/// piece is checked against every later occluder, and the pieces multiply
/// as small occluders (a dense mesh's triangles) slice the light along
/// their edges' lines (a thousand-triangle blob: 140 pieces past 100
/// triangles on average). The polygon boolean costs some 30 us however
/// few they are; past a patch of triangles over half the light's view
/// (one core): 18 triangles, pieces 19-21 us, outlines 33-57 us; 32: both
/// 42-46 us; 72: 147-169 against 64-71 us; 200: 973-1105 against 119-134 us.
const OUTLINE_FROM: usize = 24;

/// Convex pieces of the visible part of an area light, reusable between
/// queries: after the first few calls, [`VisiblePart::compute`] does not
/// allocate.
#[derive(Debug, Clone, Default)]
pub struct VisiblePart {
    verts: Vec<Vec3>,
    pieces: Vec<Range<u32>>,
    scratch: Scratch,
    outline: Outline,
}

/// Working storage of [`VisiblePart::compute`].
#[derive(Debug, Clone, Default)]
struct Scratch {
    /// The half-spaces of the occluders that cut the light, in runs, and
    /// the occluders' indices.
    planes: Vec<HalfSpace>,
    runs: Vec<Range<u32>>,
    cutting: Vec<u32>,
    /// Pieces still to be checked against occluders `next..`: a stack of
    /// runs of `stack_verts` with their `next`.
    stack_verts: Vec<Vec3>,
    stack: Vec<(Range<u32>, u32)>,
    cur: Vec<Vec3>,
    dist: Vec<f64>,
    inside: Vec<Vec3>,
    outside: Vec<Vec3>,
}

/// A half-space `m . (x - q) > 0` of the blocked region.
#[derive(Debug, Clone, Copy)]
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
    /// On both sides: the inside and outside parts were written out, with
    /// these numbers of vertices.
    Both(usize, usize),
}

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

/// Splits convex `poly` by `h`; on [`Split::Both`]`(ni, no)`, `inside[..ni]`
/// and `outside[..no]` hold the two parts (the buffers are only grown,
/// never shrunk). `dist` is scratch for the signed distances, each computed
/// once.
///
/// The split has no data-dependent branch: every vertex and crossing point
/// is written to the next slot of both outputs, and each output's length
/// advances by whether it keeps it (the side of a vertex is as hard to
/// predict as a coin toss).
fn split(
    poly: &[Vec3],
    h: &HalfSpace,
    dist: &mut Vec<f64>,
    inside: &mut Vec<Vec3>,
    outside: &mut Vec<Vec3>,
) -> Split {
    dist.clear();
    dist.extend(poly.iter().map(|v| dot(h.m, sub(*v, h.q))));
    let mut pos = false;
    let mut neg = false;
    for &s in dist.iter() {
        pos |= s > 0.0;
        neg |= s < 0.0;
    }
    match (pos, neg) {
        (false, _) => Split::Outside,
        (true, false) => Split::Inside,
        (true, true) => {
            // At most two slots per vertex.
            let cap = 2 * poly.len();
            if inside.len() < cap {
                inside.resize(cap, [0.0; 3]);
            }
            if outside.len() < cap {
                outside.resize(cap, [0.0; 3]);
            }
            let (mut ni, mut no) = (0, 0);
            let mut prev = poly[poly.len() - 1];
            let mut sp = dist[dist.len() - 1];
            for (&v, &sv) in poly.iter().zip(dist.iter()) {
                let crosses = (sp > 0.0 && sv < 0.0) | (sp < 0.0 && sv > 0.0);
                // Used only when the edge crosses, so sp != sv.
                let x = lerp(prev, v, sp / (sp - sv));
                inside[ni] = x;
                outside[no] = x;
                ni += crosses as usize;
                no += crosses as usize;
                inside[ni] = v;
                outside[no] = v;
                ni += (sv >= 0.0) as usize;
                no += (sv <= 0.0) as usize;
                prev = v;
                sp = sv;
            }
            Split::Both(ni, no)
        }
    }
}

impl VisiblePart {
    /// An empty set of pieces.
    pub fn new() -> Self {
        Self::default()
    }

    /// Replaces the pieces by the part of `light` visible from `p` past
    /// `occluders` (convex polygons, or convex solids by their
    /// silhouettes: [`Occluder`]).
    ///
    /// The occluders that cut the light are found first (an occluder
    /// outside the pyramid from `p` to the light, or whose blocked region
    /// misses the light, is skipped); then each piece goes down the list
    /// depth first, and is split only by an occluder it straddles.
    pub fn compute<O: AsOccluder>(&mut self, light: &AreaLight, occluders: &[O], p: Vec3) {
        if self.find_cutting(light, occluders, p) {
            self.cut_pieces(light);
        }
    }

    /// Clears the pieces and finds the occluders whose blocked regions cut
    /// the light (their planes that do in `scratch.runs`, their indices in
    /// `scratch.cutting`); `false` when one hides all of it.
    fn find_cutting<O: AsOccluder>(&mut self, light: &AreaLight, occluders: &[O], p: Vec3) -> bool {
        self.verts.clear();
        self.pieces.clear();
        let sc = &mut self.scratch;
        sc.planes.clear();
        sc.runs.clear();
        sc.cutting.clear();
        let cone = light_pyramid(light, p);
        let mut planes = SmallVec::<[HalfSpace; 9]>::new();
        for (index, occ) in occluders.iter().enumerate() {
            let occ = occ.occluder();
            // Outside the pyramid from p to the light: hides none of it.
            let corners = occ.corners();
            if cone
                .iter()
                .any(|h| corners.iter().all(|v| dot(h.m, sub(*v, h.q)) <= 0.0))
            {
                continue;
            }
            if !occ.blocked_region(p, &mut planes) {
                continue;
            }
            // The pieces lie in the light: an occluder whose blocked region
            // misses the whole light leaves them as they are, and a
            // half-space that holds the whole light holds every piece, so
            // only the others can split them.
            let start = sc.planes.len() as u32;
            let mut misses = false;
            for h in &planes {
                match classify(light.vertices(), h) {
                    (false, _) => {
                        misses = true;
                        break;
                    }
                    (true, false) => {}
                    (true, true) => sc.planes.push(*h),
                }
            }
            if misses {
                sc.planes.truncate(start as usize);
                continue;
            }
            if sc.planes.len() as u32 == start {
                // The whole light is hidden.
                return false;
            }
            sc.runs.push(start..sc.planes.len() as u32);
            sc.cutting.push(index as u32);
        }
        true
    }

    /// The light cut by the occluders [`Self::find_cutting`] found, into
    /// the pieces none of them hides.
    fn cut_pieces(&mut self, light: &AreaLight) {
        let sc = &mut self.scratch;
        sc.stack_verts.clear();
        sc.stack.clear();
        sc.stack_verts.extend_from_slice(light.vertices());
        sc.stack.push((0..sc.stack_verts.len() as u32, 0));
        while let Some((r, mut next)) = sc.stack.pop() {
            // The run popped is the last one of stack_verts; it is read in
            // place until it must be split (or is done with), then moved to
            // cur.
            let r = r.start as usize..r.end as usize;
            let mut in_stack = true;
            'occluders: loop {
                let piece = if in_stack {
                    &sc.stack_verts[r.clone()]
                } else {
                    &sc.cur[..]
                };
                let Some(run) = sc.runs.get(next as usize) else {
                    // Past every occluder: visible.
                    let start = self.verts.len() as u32;
                    self.verts.extend_from_slice(piece);
                    self.pieces.push(start..self.verts.len() as u32);
                    break;
                };
                next += 1;
                let planes = &sc.planes[run.start as usize..run.end as usize];
                // The planes the piece straddles (as many as the occluder
                // has edges: a polygon may have dozens).
                let mut straddled: SmallVec<[&HalfSpace; 12]> = SmallVec::new();
                for h in planes {
                    match classify(piece, h) {
                        (false, _) => continue 'occluders,
                        (true, false) => {}
                        (true, true) => straddled.push(h),
                    }
                }
                if !straddled.is_empty() && in_stack {
                    sc.cur.clear();
                    sc.cur.extend_from_slice(&sc.stack_verts[r.clone()]);
                    sc.stack_verts.truncate(r.start);
                    in_stack = false;
                }
                for h in straddled {
                    match split(&sc.cur, h, &mut sc.dist, &mut sc.inside, &mut sc.outside) {
                        // Once cut, what is left may be outside a later plane.
                        Split::Outside => continue 'occluders,
                        Split::Inside => {}
                        Split::Both(ni, no) => {
                            if no >= 3 {
                                let start = sc.stack_verts.len() as u32;
                                sc.stack_verts.extend_from_slice(&sc.outside[..no]);
                                sc.stack.push((start..sc.stack_verts.len() as u32, next));
                            }
                            std::mem::swap(&mut sc.cur, &mut sc.inside);
                            sc.cur.truncate(ni);
                        }
                    }
                }
                // What is left lies inside every half-space: hidden.
                break;
            }
            if in_stack {
                sc.stack_verts.truncate(r.start);
            }
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

/// The pyramid from `p` to the light, as half-spaces `m . (x - q) > 0`: one
/// per light edge, and the light's plane. Empty when `p` is not strictly on
/// the lit side (then nothing is skipped on its account).
fn light_pyramid(light: &AreaLight, p: Vec3) -> SmallVec<[HalfSpace; 9]> {
    let mut out = SmallVec::new();
    if !light.lights_side_of(p) {
        return out;
    }
    let n = light.normal();
    let lv = light.vertices();
    // The lit side of the light's plane, where p is.
    out.push(HalfSpace { m: n, q: lv[0] });
    let mut prev = lv[lv.len() - 1];
    for &v in lv {
        // Counter-clockwise seen from p: (v_i - p) x (v_{i+1} - p) = a x e
        // points away from the pyramid's inside.
        let m = cross(sub(prev, p), sub(v, prev));
        out.push(HalfSpace {
            m: scale(m, -1.0),
            q: p,
        });
        prev = v;
    }
    out
}

/// Irradiance at `p` (unit normal `n`) from the part of `light` visible past
/// `occluders` (convex polygons' corners, or [`Occluder`]s), using
/// `scratch` for the pieces (no allocation once warm).
///
/// Skips the visibility computation when `p` is behind the light or the
/// light is wholly below the receiver's horizon. Past many occluders that
/// cut the light (the triangles of a dense mesh), it integrates the
/// outlines of the visible part instead, the light minus the union of the
/// occluders' images on its plane (module `outline`): the pieces would
/// multiply along the occluders' edges. `scratch` then holds no pieces.
pub fn visible_irradiance<O: AsOccluder>(
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
    if !scratch.find_cutting(light, occluders, p) {
        return 0.0;
    }
    if scratch.scratch.cutting.len() >= OUTLINE_FROM {
        let cutting = &scratch.scratch.cutting;
        let cut = cutting
            .iter()
            .map(|&i| occluders[i as usize].occluder().corners());
        // (`find_cutting` left no pieces.)
        if let Some(e) = scratch.outline.irradiance(light, cut, p, n, sidedness) {
            return e;
        }
    }
    scratch.cut_pieces(light);
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

    /// A regular `n`-gon of radius `r` around the z axis at height `z`,
    /// counter-clockwise seen from above.
    fn regular(n: usize, r: f64, z: f64) -> Vec<Vec3> {
        (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                [r * t.cos(), r * t.sin(), z]
            })
            .collect()
    }

    #[test]
    fn occluder_of_many_edges_across_the_light() {
        // Its image on the light (twice as far from the origin) is a
        // 100-gon of radius 1.1 whose edges near the light's corners cut
        // the light, about 60 of them; it hides that image clipped to the
        // light.
        let n = 100;
        let occ = regular(n, 0.55, 1.0);
        let image: Vec<[f64; 2]> = occ.iter().map(|v| [2.0 * v[0], 2.0 * v[1]]).collect();
        let inside = clip_square(&image);
        let mut vp = VisiblePart::new();
        vp.compute(&light(), &[occ], [0.0; 3]);
        let hidden = polygon_area(&inside);
        assert!(hidden > 3.5 && hidden < 3.8, "{hidden}");
        assert!(
            (vp.area() - (4.0 - hidden)).abs() < 1e-12,
            "{} {}",
            vp.area(),
            hidden
        );
    }

    /// The part of a convex polygon of the plane inside the square
    /// [-1, 1]^2 (Sutherland-Hodgman).
    fn clip_square(poly: &[[f64; 2]]) -> Vec<[f64; 2]> {
        let mut out = poly.to_vec();
        for (axis, sign) in [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)] {
            let inside = |p: &[f64; 2]| sign * p[axis] <= 1.0;
            let input = std::mem::take(&mut out);
            for (i, cur) in input.iter().enumerate() {
                let prev = input[(i + input.len() - 1) % input.len()];
                if inside(cur) != inside(&prev) {
                    let t = (sign - prev[axis]) / (cur[axis] - prev[axis]);
                    out.push([
                        prev[0] + t * (cur[0] - prev[0]),
                        prev[1] + t * (cur[1] - prev[1]),
                    ]);
                }
                if inside(cur) {
                    out.push(*cur);
                }
            }
        }
        out
    }

    fn polygon_area(poly: &[[f64; 2]]) -> f64 {
        let n = poly.len();
        (0..n)
            .map(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum::<f64>()
            / 2.0
    }
}
