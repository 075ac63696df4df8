//! Lambert's contour integral: irradiance from a convex polygonal Lambertian
//! emitter, clipped by the receiver's horizon (Chin & Feiner 1992).
//!
//! For a receiver at `p` with unit normal `n` and a polygon of radiance `L`
//! counter-clockwise seen from `p`,
//!
//! ```text
//! E = (L / 2) * sum_i angle_i * (n . unit(b_i x a_i)),   a_i = v_i - p, b_i = v_{i+1} - p,
//! angle_i = atan2(|a_i x b_i|, a_i . b_i)
//! ```
//!
//! which is the irradiance itself (not divided by pi). Each term is computed
//! as `(n . c) * atan2(|c|, a . b) / |c|` with `c = (v_{i+1} - v_i) x a`:
//! the edge vector is taken from the vertices (no cancellation when `p` is
//! far away), and an edge collinear with `p` (`c = 0`) contributes 0 with no
//! division. Before summing, the polygon is clipped by the receiver's tangent
//! plane, keeping `(x - p) . n > 0` (Sutherland–Hodgman on one plane, in a
//! fixed-size buffer).

use crate::angle::angle_over;
use crate::vec3::{Vec3, area_normal, cross, dot, lerp, norm, sub};
use smallvec::SmallVec;

/// A convex polygon clipped by one plane; 16 vertices before spilling.
pub(crate) type ClipBuf = SmallVec<[Vec3; 16]>;

/// Irradiance for unit radiance of a convex polygon, counter-clockwise as
/// seen from `p` (the caller has checked that `p` is on its emitting side),
/// on a receiver of unit normal `n`, clipped by the receiver's horizon.
///
/// The edges are summed in the same pass that finds which side of the
/// horizon each vertex is on: the sum stands when none is below, and the
/// clipped polygon is summed instead when some is.
#[inline]
pub(crate) fn integrate_front(poly: &[Vec3], p: Vec3, n: Vec3) -> f64 {
    integrate_front_by(poly, |i, prev| sub(poly[i], prev), p, n)
}

/// [`integrate_front`] with the edge vectors given: `edges[i] = poly[i] -
/// poly[i - 1]` (cyclically), as [`AreaLight`](crate::AreaLight) keeps them.
#[inline]
pub(crate) fn integrate_front_with_edges(poly: &[Vec3], edges: &[Vec3], p: Vec3, n: Vec3) -> f64 {
    debug_assert_eq!(poly.len(), edges.len());
    integrate_front_by(poly, |i, _| edges[i], p, n)
}

/// [`integrate_front`] with `edge(i, poly[i - 1])` giving `poly[i] -
/// poly[i - 1]`.
#[inline(always)]
fn integrate_front_by(poly: &[Vec3], edge: impl Fn(usize, Vec3) -> Vec3, p: Vec3, n: Vec3) -> f64 {
    finish(half_sum_front_by(poly, edge, p, n))
}

/// The signed integral for unit radiance of a closed polygon, not
/// necessarily convex, as seen from `p` on a receiver of unit normal `n`,
/// clipped by the receiver's horizon: positive for a counter-clockwise
/// polygon, negative for a clockwise one (a hole). The outlines of a region
/// add up to the region's irradiance.
///
/// Clipping a non-convex polygon by the horizon joins its parts above by
/// segments along the horizon that run to and fro; their terms cancel, as
/// the terms of the parts of a great-circle arc add up to the arc's.
pub(crate) fn integrate_front_signed(poly: &[Vec3], p: Vec3, n: Vec3) -> f64 {
    half_sum_front_by(poly, |i, prev| sub(poly[i], prev), p, n)
}

/// Half the sum of the edge terms of `poly` clipped by the horizon
/// (`edge(i, poly[i - 1])` gives `poly[i] - poly[i - 1]`), unclamped.
#[inline(always)]
fn half_sum_front_by(poly: &[Vec3], edge: impl Fn(usize, Vec3) -> Vec3, p: Vec3, n: Vec3) -> f64 {
    let Some(&last) = poly.last() else {
        return 0.0;
    };
    let mut above = false;
    let mut below = false;
    let mut prev = last;
    let mut a = sub(prev, p);
    let mut sum = 0.0;
    for (i, &v) in poly.iter().enumerate() {
        let b = sub(v, p);
        let s = dot(b, n);
        above |= s > 0.0;
        below |= s < 0.0;
        sum += edge_term(edge(i, prev), a, b, n);
        a = b;
        prev = v;
    }
    if !above {
        return 0.0;
    }
    if !below {
        return 0.5 * sum;
    }
    let clipped = clip_above(poly, p, n);
    half_sum_edges(&clipped, p, n)
}

/// The part of a polygon with `(x - p) . n >= 0` (of a non-convex one, its
/// parts above joined along the horizon: the same integral).
pub(crate) fn clip_above(poly: &[Vec3], p: Vec3, n: Vec3) -> ClipBuf {
    let mut out = ClipBuf::new();
    let Some(&last) = poly.last() else {
        return out;
    };
    let mut prev = last;
    let mut sp = dot(sub(prev, p), n);
    for &v in poly {
        let sv = dot(sub(v, p), n);
        if (sp > 0.0 && sv < 0.0) || (sp < 0.0 && sv > 0.0) {
            out.push(lerp(prev, v, sp / (sp - sv)));
        }
        if sv >= 0.0 {
            out.push(v);
        }
        prev = v;
        sp = sv;
    }
    out
}

/// `(1/2) sum angle_i (n . unit(b_i x a_i))` over the edges of `poly`.
#[inline]
fn half_sum_edges(poly: &[Vec3], p: Vec3, n: Vec3) -> f64 {
    let Some(&last) = poly.last() else {
        return 0.0;
    };
    let mut prev = last;
    let mut a = sub(prev, p);
    let mut sum = 0.0;
    for &v in poly {
        let b = sub(v, p);
        sum += edge_term(sub(v, prev), a, b, n);
        a = b;
        prev = v;
    }
    0.5 * sum
}

/// One edge's `angle (n . unit(b x a))`, from the edge vector `e = b - a`
/// taken from the vertices: `b x a = (a + e) x a = e x a`.
#[inline(always)]
fn edge_term(e: Vec3, a: Vec3, b: Vec3, n: Vec3) -> f64 {
    let c = cross(e, a);
    let len = norm(c);
    if len > 0.0 {
        dot(n, c) * angle_over(len, dot(a, b))
    } else {
        0.0
    }
}

/// The value of a convex polygon from its half sum of edge terms.
#[inline(always)]
fn finish(half_sum: f64) -> f64 {
    // The clipped light is above the horizon, so the true value is not
    // negative; when the edge terms (each of order one) cancel, rounding
    // can leave a few ulps below zero.
    half_sum.max(0.0)
}

/// Irradiance at `p` (unit normal `n`) from a convex planar polygon of unit
/// radiance; multiply by the radiance.
///
/// The polygon emits on the side its counter-clockwise normal points to: a
/// point behind its plane or on it gets 0, as does a polygon with fewer than
/// three vertices or no area. The polygon is not validated (see
/// [`AreaLight::new`](crate::AreaLight::new) for that); a non-convex one
/// gives a meaningless value after horizon clipping.
pub fn contour_integral(polygon: &[Vec3], p: Vec3, n: Vec3) -> f64 {
    if polygon.len() < 3 {
        return 0.0;
    }
    if dot(area_normal(polygon), sub(p, polygon[0])) <= 0.0 {
        return 0.0;
    }
    integrate_front(polygon, p, n)
}

/// Sum of [`contour_integral`] over the convex pieces of a region, such as
/// the visible part of a light (all pieces oriented like the light).
pub fn contour_integral_sum<'a, I>(pieces: I, p: Vec3, n: Vec3) -> f64
where
    I: IntoIterator<Item = &'a [Vec3]>,
{
    pieces
        .into_iter()
        .map(|piece| contour_integral(piece, p, n))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(a: f64, h: f64) -> [Vec3; 4] {
        // Counter-clockwise seen from below: normal -z.
        [[-a, -a, h], [-a, a, h], [a, a, h], [a, -a, h]]
    }

    #[test]
    fn on_axis_square_matches_closed_form() {
        let (a, h) = (0.7_f64, 1.3_f64);
        let e = contour_integral(&square(a, h), [0.0; 3], [0.0, 0.0, 1.0]);
        let s = a / (a * a + h * h).sqrt();
        let want = 4.0 * s * s.atan();
        assert!((e - want).abs() < 1e-14, "{e} vs {want}");
    }

    #[test]
    fn behind_or_on_the_plane_is_zero() {
        let sq = square(1.0, 1.0);
        assert_eq!(
            contour_integral(&sq, [0.0, 0.0, 2.0], [0.0, 0.0, -1.0]),
            0.0
        );
        assert_eq!(contour_integral(&sq, [5.0, 0.0, 1.0], [0.0, 0.0, 1.0]), 0.0);
        assert_eq!(contour_integral(&sq, [0.3, 0.2, 1.0], [0.0, 0.0, 1.0]), 0.0);
    }

    #[test]
    fn below_horizon_is_zero() {
        let sq = square(1.0, 1.0);
        assert_eq!(contour_integral(&sq, [0.0; 3], [0.0, 0.0, -1.0]), 0.0);
    }

    #[test]
    fn clip_keeps_upper_part() {
        let sq = square(1.0, 1.0);
        let c = clip_above(&sq, [0.0; 3], [1.0, 0.0, 0.0]);
        assert_eq!(c.len(), 4);
        assert!(c.iter().all(|v| v[0] >= 0.0));
        let area = 0.5 * norm(area_normal(&c));
        assert!((area - 2.0).abs() < 1e-15);
    }

    #[test]
    fn collinear_edge_contributes_nothing() {
        // p on the extension of the edge (-1,-1,1)-(-1,1,1): that edge's
        // term is exactly 0 and the others stay finite.
        let sq = square(1.0, 1.0);
        let e = integrate_front(&sq, [-1.0, 3.0, 1.0], [0.0, 0.0, -1.0]);
        assert!(e.is_finite() && e.abs() < 1e-15, "{e}");
        // Just in front of the plane, outside the light: E ~ h^2, tiny.
        let e = contour_integral(&sq, [-1.0, 3.0, 1.0 - 1e-9], [0.0, 0.0, 1.0]);
        assert!(e.is_finite() && e.abs() < 1e-15, "{e}");
        // Facing the light's plane edge-on there, a finite positive value.
        let e = contour_integral(&sq, [-1.0, 3.0, 1.0 - 1e-9], [0.0, -1.0, 0.0]);
        assert!(e.is_finite() && e > 0.0, "{e}");
    }

    #[test]
    fn far_away_matches_point_source() {
        // A unit square at distance d acts like intensity L * A.
        let d = 1e7;
        let sq = square(0.5, d);
        let e = contour_integral(&sq, [0.0; 3], [0.0, 0.0, 1.0]);
        let want = 1.0 / (d * d);
        assert!(((e - want) / want).abs() < 1e-9, "{e} vs {want}");
    }
}
