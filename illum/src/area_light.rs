//! A validated convex polygonal Lambertian light.

use crate::contour_integral::integrate_front_with_edges;
use crate::error::IllumError;
use crate::point_light::Sidedness;
use crate::vec3::{Vec3, area_normal, cross, dot, norm, scale, sub};
use smallvec::SmallVec;

/// Relative tolerance (times the light's size) of the planarity and
/// convexity checks.
const SHAPE_TOLERANCE: f64 = 1e-9;

/// A convex planar polygonal light of uniform radiance.
///
/// It emits on the side its counter-clockwise normal points to (vertices
/// counter-clockwise seen from the lit side); a point behind its plane, or on
/// it, receives nothing.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaLight {
    /// The vertices, then the edge vectors `vertices[i] - vertices[i - 1]`
    /// (cyclically) for the contour integral: one buffer, so that a quad
    /// light stays inline in a value no larger than before.
    points: SmallVec<[Vec3; 8]>,
    /// Unit normal, towards the emitting side.
    normal: Vec3,
    /// Mean of the vertices (a point of the plane).
    center: Vec3,
    radiance: f64,
}

impl AreaLight {
    /// Validates a light polygon: at least 3 finite vertices, a non-zero
    /// area, planar and convex within `1e-9` times its size, and a finite
    /// non-negative radiance.
    pub fn new(vertices: &[Vec3], radiance: f64) -> Result<Self, IllumError> {
        if vertices.len() < 3 {
            return Err(IllumError::TooFewVertices {
                count: vertices.len(),
            });
        }
        if let Some(index) = vertices
            .iter()
            .position(|v| v.iter().any(|c| !c.is_finite()))
        {
            return Err(IllumError::NonFinite { index });
        }
        if !(radiance.is_finite() && radiance >= 0.0) {
            return Err(IllumError::BadStrength { value: radiance });
        }
        let size = vertices
            .iter()
            .map(|v| norm(sub(*v, vertices[0])))
            .fold(0.0_f64, f64::max);
        let twice_area = area_normal(vertices);
        let len = norm(twice_area);
        if size == 0.0 || len <= 1e-12 * size * size {
            return Err(IllumError::Degenerate);
        }
        let normal = scale(twice_area, 1.0 / len);
        let tol = SHAPE_TOLERANCE * size;
        for (index, v) in vertices.iter().enumerate() {
            let distance = dot(normal, sub(*v, vertices[0]));
            if distance.abs() > tol {
                return Err(IllumError::NonPlanar { index, distance });
            }
        }
        let n = vertices.len();
        for edge in 0..n {
            let a = vertices[edge];
            let b = vertices[(edge + 1) % n];
            let e = sub(b, a);
            let e_len = norm(e);
            if e_len == 0.0 {
                continue;
            }
            for (index, v) in vertices.iter().enumerate() {
                // Signed distance of v to the edge's line, inside positive.
                let d = dot(cross(e, sub(*v, a)), normal) / e_len;
                if d < -tol {
                    return Err(IllumError::NonConvex { edge, index });
                }
            }
        }
        let mut center = [0.0; 3];
        for v in vertices {
            for k in 0..3 {
                center[k] += v[k];
            }
        }
        let center = scale(center, 1.0 / n as f64);
        let mut points = SmallVec::from_slice(vertices);
        points.extend((0..n).map(|i| sub(vertices[i], vertices[(i + n - 1) % n])));
        Ok(Self {
            points,
            normal,
            center,
            radiance,
        })
    }

    /// The polygon, counter-clockwise seen from the lit side.
    pub fn vertices(&self) -> &[Vec3] {
        &self.points[..self.points.len() / 2]
    }

    /// Unit normal pointing to the emitting side.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// Radiance.
    pub fn radiance(&self) -> f64 {
        self.radiance
    }

    /// Area of the polygon.
    pub fn area(&self) -> f64 {
        0.5 * norm(area_normal(self.vertices()))
    }

    /// Signed distance of `p` to the light's plane, positive on the lit side.
    pub fn height(&self, p: Vec3) -> f64 {
        dot(self.normal, sub(p, self.center))
    }

    /// Whether `p` is strictly on the emitting side of the light's plane.
    pub fn lights_side_of(&self, p: Vec3) -> bool {
        self.height(p) > 0.0
    }

    /// Unoccluded irradiance at `p` on a receiver of unit normal `n`.
    ///
    /// One-sided: only light above the receiver's tangent plane (the side `n`
    /// points to) counts. Two-sided: both sides of the receiver count,
    /// `E(n) + E(-n)`, which for a small light is `|cos|` times the one-sided
    /// value.
    pub fn irradiance(&self, p: Vec3, n: Vec3, sidedness: Sidedness) -> f64 {
        if !self.lights_side_of(p) {
            return 0.0;
        }
        let (vertices, edges) = self.points.split_at(self.points.len() / 2);
        let e = match sidedness {
            Sidedness::OneSided => integrate_front_with_edges(vertices, edges, p, n),
            Sidedness::TwoSided => {
                integrate_front_with_edges(vertices, edges, p, n)
                    + integrate_front_with_edges(vertices, edges, p, scale(n, -1.0))
            }
        };
        self.radiance * e
    }
}
