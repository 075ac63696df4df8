//! The scene camera as a perspective projection: world point to pixel
//! coordinates and depth.

use crate::scene::Camera;
use crate::vec3::{cross, dot, normalize, sub};

/// A [`Camera`] ready to project: an orthonormal right-handed view frame
/// (right, up, forward) at the eye, and the focal length in pixels.
///
/// Pixel coordinates run from the image's top-left corner, `x` to the right
/// and `y` down; pixel `(i, j)` covers `[i, i + 1] x [j, j + 1]`, so the
/// image centre is `(width / 2, height / 2)`. Pixels are square: the
/// vertical field of view is `fov_deg` and the horizontal one follows from
/// the aspect ratio.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    eye: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    /// Pixels per unit of `x / depth`: `(height / 2) / tan(fov / 2)`.
    focal: f64,
    width: f64,
    height: f64,
}

impl Projection {
    /// The projection of a validated camera (eye and target distinct, `up`
    /// not parallel to the view, `0 < fov_deg < 180`).
    pub fn new(camera: &Camera) -> Self {
        let forward = normalize(sub(camera.target, camera.eye));
        let right = normalize(cross(forward, camera.up));
        let up = cross(right, forward);
        let height = f64::from(camera.height);
        let focal = 0.5 * height / (0.5 * camera.fov_deg.to_radians()).tan();
        Self {
            eye: camera.eye,
            right,
            up,
            forward,
            focal,
            width: f64::from(camera.width),
            height,
        }
    }

    /// `p` in the view frame: `[x right, y up, depth along the view]`.
    pub fn to_view(&self, p: [f64; 3]) -> [f64; 3] {
        let d = sub(p, self.eye);
        [dot(d, self.right), dot(d, self.up), dot(d, self.forward)]
    }

    /// A view-frame point with positive depth to pixel coordinates.
    pub fn view_to_pixel(&self, v: [f64; 3]) -> [f64; 2] {
        [
            0.5 * self.width + self.focal * v[0] / v[2],
            0.5 * self.height - self.focal * v[1] / v[2],
        ]
    }

    /// The direction (world frame, unit depth along the view) of the ray
    /// from the eye through pixel coordinates `[x, y]`.
    pub fn pixel_ray(&self, x: f64, y: f64) -> [f64; 3] {
        let right = (x - 0.5 * self.width) / self.focal;
        let up = (0.5 * self.height - y) / self.focal;
        [0, 1, 2].map(|i| self.forward[i] + right * self.right[i] + up * self.up[i])
    }

    /// `p` in pixel coordinates with its depth, `[x, y, depth]`; `None` for
    /// points on or behind the eye's plane.
    pub fn project(&self, p: [f64; 3]) -> Option<[f64; 3]> {
        let v = self.to_view(p);
        if v[2] <= 0.0 {
            return None;
        }
        let [x, y] = self.view_to_pixel(v);
        Some([x, y, v[2]])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    /// Looking down -Z from the origin, 90 degrees vertically, 200 x 100:
    /// the focal length is 50 pixels, the centre (100, 50).
    #[test]
    fn projects_hand_computed_points() {
        let camera = Camera {
            eye: [0.0, 0.0, 0.0],
            target: [0.0, 0.0, -1.0],
            up: [0.0, 1.0, 0.0],
            fov_deg: 90.0,
            width: 200,
            height: 100,
        };
        let p = Projection::new(&camera);
        assert!(close(
            p.project([0.0, 0.0, -5.0]).unwrap(),
            [100.0, 50.0, 5.0]
        ));
        // x = 100 + 50 * 1 / 4, y = 50 - 50 * 2 / 4.
        assert!(close(
            p.project([1.0, 2.0, -4.0]).unwrap(),
            [112.5, 25.0, 4.0]
        ));
        // The top edge of the view at depth 2 is y = 2: pixel row 0.
        assert!(close(
            p.project([-2.0, 2.0, -2.0]).unwrap(),
            [50.0, 0.0, 2.0]
        ));
        assert_eq!(p.project([0.0, 0.0, 1.0]), None);
        // The ray through a pixel reaches the point that projects there.
        let ray = p.pixel_ray(112.5, 25.0);
        assert!(close(ray.map(|c| 4.0 * c), [1.0, 2.0, -4.0]));
        assert_eq!(p.project([3.0, 0.0, 0.0]), None);
    }

    /// An eye above and in front of the origin, looking at it: right-handed
    /// with +Y up, so +X is to the right of the image and up is up.
    #[test]
    fn a_tilted_camera_keeps_right_and_up() {
        let camera = Camera {
            eye: [0.0, 3.0, 4.0],
            target: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_deg: 60.0,
            width: 640,
            height: 480,
        };
        let p = Projection::new(&camera);
        // The target is 5 away, in the centre.
        assert!(close(
            p.project([0.0, 0.0, 0.0]).unwrap(),
            [320.0, 240.0, 5.0]
        ));
        // One unit along +X at the target: x = 320 + f / 5 with
        // f = 240 / tan(30 degrees).
        let f = 240.0 / (30f64.to_radians()).tan();
        assert!(close(
            p.project([1.0, 0.0, 0.0]).unwrap(),
            [320.0 + f / 5.0, 240.0, 5.0]
        ));
        // A point above the target shows above the centre.
        assert!(p.project([0.0, 1.0, 0.0]).unwrap()[1] < 240.0);
    }
}
