//! Object transforms: scale, then rotate about X, Y, Z, then translate.

/// An object's placement in the scene, as written in the scene file.
///
/// Applied to a point in this order: `scale`, then `rotate_deg` about X,
/// then Y, then Z (right-handed, degrees), then `translate`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    /// Per-axis scale factors (non-zero).
    pub scale: [f64; 3],
    /// Rotation angles about X, Y and Z in degrees, applied in that order.
    pub rotate_deg: [f64; 3],
    /// Translation.
    pub translate: [f64; 3],
}

impl Default for Transform {
    fn default() -> Self {
        Self {
            scale: [1.0; 3],
            rotate_deg: [0.0; 3],
            translate: [0.0; 3],
        }
    }
}

impl Transform {
    /// The rotation as a matrix `Rz * Ry * Rx` (rows).
    pub fn rotation(&self) -> [[f64; 3]; 3] {
        let [ax, ay, az] = self.rotate_deg.map(f64::to_radians);
        let (sx, cx) = ax.sin_cos();
        let (sy, cy) = ay.sin_cos();
        let (sz, cz) = az.sin_cos();
        let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
        let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
        let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
        mul(rz, mul(ry, rx))
    }

    /// Maps a point of the object to the scene.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        self.apply_with(&self.rotation(), p)
    }

    /// Maps a point with a rotation computed once by [`Transform::rotation`].
    pub fn apply_with(&self, rotation: &[[f64; 3]; 3], p: [f64; 3]) -> [f64; 3] {
        let s = [
            p[0] * self.scale[0],
            p[1] * self.scale[1],
            p[2] * self.scale[2],
        ];
        let mut out = self.translate;
        for (row, o) in rotation.iter().zip(out.iter_mut()) {
            *o += row[0] * s[0] + row[1] * s[1] + row[2] * s[2];
        }
        out
    }

    /// Whether the transform mirrors space (an odd number of negative scale
    /// factors), which reverses the winding of every polygon.
    pub fn mirrors(&self) -> bool {
        self.scale.iter().filter(|&&s| s < 0.0).count() % 2 == 1
    }
}

fn mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
    }

    #[test]
    fn right_handed_quarter_turns() {
        let about = |r: [f64; 3]| Transform {
            rotate_deg: r,
            ..Transform::default()
        };
        assert!(close(
            about([90.0, 0.0, 0.0]).apply([0.0, 1.0, 0.0]),
            [0.0, 0.0, 1.0]
        ));
        assert!(close(
            about([0.0, 90.0, 0.0]).apply([0.0, 0.0, 1.0]),
            [1.0, 0.0, 0.0]
        ));
        assert!(close(
            about([0.0, 0.0, 90.0]).apply([1.0, 0.0, 0.0]),
            [0.0, 1.0, 0.0]
        ));
    }

    #[test]
    fn order_is_scale_rotate_x_y_z_translate() {
        let t = Transform {
            scale: [2.0, 3.0, 4.0],
            rotate_deg: [90.0, 90.0, 0.0],
            translate: [10.0, 20.0, 30.0],
        };
        // (1,1,1) -> scale (2,3,4) -> Rx90 (2,-4,3) -> Ry90 (3,-4,-2) -> +t.
        assert!(close(t.apply([1.0, 1.0, 1.0]), [13.0, 16.0, 28.0]));
        assert!(!t.mirrors());
        let m = Transform {
            scale: [-1.0, 1.0, 1.0],
            ..Transform::default()
        };
        assert!(m.mirrors());
    }
}
