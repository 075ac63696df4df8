//! The visible part of an area light as outlines: the light minus the
//! union of the occluders' images on its plane, one polygon boolean.
//!
//! Seen from `p`, an occluder hides the points of the light whose segments
//! to `p` cross it. Clipped to the pyramid from `p` to the light, an
//! occluder lies between `p` and the light's plane, so what it hides is
//! its central projection from `p` onto that plane: a convex polygon inside
//! the light. The visible part is the light minus the union of those
//! images, a polygon with holes, found by `i_overlay` (exact integer
//! arithmetic on coordinates scaled to 61 bits, finer than `f64`'s own);
//! its outlines, counter-clockwise around what is visible and clockwise
//! around holes, add up to the irradiance by the contour integral. Unlike
//! convex pieces, the outlines do not multiply where neighbouring
//! occluders (a mesh's triangles) meet: their shared edges vanish in the
//! union.

use super::{HalfSpace, light_pyramid};
use crate::area_light::AreaLight;
use crate::contour_integral::{ClipBuf, clip_above, integrate_front_signed};
use crate::point_light::Sidedness;
use crate::vec3::{Vec3, cross, dot, norm, scale, sub};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::core::solver::Solver;
use i_overlay::float::overlay::{FloatOverlay, OverlayOptions};
use i_overlay::i_shape::flat::float::FloatFlatContoursBuffer;

/// A point of the light's plane in the light's frame.
type Point2 = [f64; 2];

/// The working storage of the outline computation, reused between calls.
#[derive(Default)]
pub(super) struct Outline {
    /// The polygon boolean engine, made at the first call.
    engine: Option<FloatOverlay<Point2, i64>>,
    light: Vec<Point2>,
    images: FloatFlatContoursBuffer<Point2>,
    visible: FloatFlatContoursBuffer<Point2>,
    outline: Vec<Vec3>,
}

// The engine holds only scratch space: a copy starts without one, and
// printing shows none.
impl Clone for Outline {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for Outline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Outline").finish_non_exhaustive()
    }
}

/// The light's plane as a frame: origin, two unit axes in the plane
/// (counter-clockwise seen from the emitting side) and the unit normal.
struct Frame {
    origin: Vec3,
    u: Vec3,
    v: Vec3,
    normal: Vec3,
}

impl Frame {
    fn of(light: &AreaLight) -> Option<Self> {
        let verts = light.vertices();
        let normal = light.normal();
        let first = sub(verts[1], verts[0]);
        let length = norm(first);
        if length.is_nan() || length <= 0.0 {
            return None;
        }
        let u = scale(first, 1.0 / length);
        Some(Self {
            origin: verts[0],
            u,
            v: cross(normal, u),
            normal,
        })
    }

    fn to_plane(&self, x: Vec3) -> Point2 {
        let d = sub(x, self.origin);
        [dot(d, self.u), dot(d, self.v)]
    }

    fn to_space(&self, [a, b]: Point2) -> Vec3 {
        let o = self.origin;
        let (u, v) = (self.u, self.v);
        [
            o[0] + a * u[0] + b * v[0],
            o[1] + a * u[1] + b * v[1],
            o[2] + a * u[2] + b * v[2],
        ]
    }
}

impl Outline {
    /// Irradiance at `p` (unit normal `n`, `p` on the light's emitting
    /// side) from the part of `light` visible past `occluders` (convex
    /// planar polygons), or `None` where the outlines cannot be made (a
    /// point not finite): then the caller cuts pieces instead.
    pub(super) fn irradiance<'o>(
        &mut self,
        light: &AreaLight,
        occluders: impl Iterator<Item = &'o [Vec3]>,
        p: Vec3,
        n: Vec3,
        sidedness: Sidedness,
    ) -> Option<f64> {
        let frame = Frame::of(light)?;
        let height = dot(sub(p, frame.origin), frame.normal);
        if height.is_nan() || height <= 0.0 {
            return None;
        }
        let pyramid = light_pyramid(light, p);
        if pyramid.is_empty() {
            return None;
        }
        self.light.clear();
        self.light
            .extend(light.vertices().iter().map(|&x| frame.to_plane(x)));
        self.images.clear_and_reserve(0, 0);
        for occ in occluders {
            let clipped = clip_to(occ, &pyramid);
            if clipped.len() < 3 {
                continue;
            }
            // The image of each corner: where the ray from p through it
            // meets the light's plane (beyond the corner: inside the
            // pyramid a corner is nearer the plane than p is).
            let start = self.images.points.len();
            for &x in &clipped {
                let below = height - dot(sub(x, frame.origin), frame.normal);
                if below.is_nan() || below <= 0.0 {
                    return None;
                }
                let image = sub(scale(sub(x, p), height / below), sub(frame.origin, p));
                let point = [dot(image, frame.u), dot(image, frame.v)];
                if !(point[0].is_finite() && point[1].is_finite()) {
                    return None;
                }
                self.images.points.push(point);
            }
            let image = &mut self.images.points[start..];
            // Counter-clockwise, so that the images' union is where their
            // winding is not zero.
            if signed_area(image) < 0.0 {
                image.reverse();
            }
            let end = self.images.points.len();
            self.images.ranges.push(start..end);
        }
        let engine = self.engine.get_or_insert_with(|| {
            FloatOverlay::new_empty(OverlayOptions::default(), Solver::default(), 64)
        });
        engine.reinit_with_subj_and_clip(&self.light, &self.images);
        engine.overlay_into(
            OverlayRule::Difference,
            FillRule::NonZero,
            &mut self.visible,
        );
        let mut sum = |n: Vec3| -> f64 {
            let mut total = 0.0;
            for range in &self.visible.ranges {
                self.outline.clear();
                self.outline.extend(
                    self.visible.points[range.clone()]
                        .iter()
                        .map(|&x| frame.to_space(x)),
                );
                total += integrate_front_signed(&self.outline, p, n);
            }
            // The visible part is above the horizon, so the true value is
            // not negative (rounding can leave a few ulps below zero).
            total.max(0.0)
        };
        let e = match sidedness {
            Sidedness::OneSided => sum(n),
            Sidedness::TwoSided => sum(n) + sum(scale(n, -1.0)),
        };
        Some(light.radiance() * e)
    }
}

/// Twice the signed area of a polygon of the plane (positive when
/// counter-clockwise).
fn signed_area(points: &[Point2]) -> f64 {
    let Some(&last) = points.last() else {
        return 0.0;
    };
    let mut prev = last;
    let mut sum = 0.0;
    for &q in points {
        sum += prev[0] * q[1] - q[0] * prev[1];
        prev = q;
    }
    sum
}

/// Convex polygon `poly` clipped to the half-spaces `planes` (their closed
/// insides), one after the other as the horizon clips a light.
fn clip_to(poly: &[Vec3], planes: &[HalfSpace]) -> ClipBuf {
    let mut out: ClipBuf = poly.iter().copied().collect();
    for h in planes {
        if out.len() < 3 {
            break;
        }
        out = clip_above(&out, h.q, h.m);
    }
    out
}
