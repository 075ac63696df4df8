//! Where a segment crosses a shadow polygon, and whether a point lies in a
//! polygon's shadow frustum: every answer is a sign of `orient3d` on
//! explicit points ([`bsp_core::predicates::orient3d_f64`]), exact.
//!
//! Ties are decided one way, documented here: a segment that ends on a
//! shadow polygon's plane, or whose line meets the polygon's boundary, does
//! not cross it; a point on a frustum's boundary is not inside it. Such
//! segments graze a shadow boundary, where either answer shows the same
//! picture.

use bsp_core::predicates::{Side, orient3d_f64};

use super::apex::Apex;

/// One polygon of a shadow volume's boundary, with its depth increment.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowPolygon {
    /// Its corners, a convex planar polygon (exact `f64`, grid units). A
    /// side polygon is `[a, b, b', a']`: the contour edge `ab` and its far
    /// copy; a cap is a model polygon's far copy.
    pub vertices: Vec<[f64; 3]>,
    /// Bergeron's `Nb_C`: what crossing it adds to the depth count, going
    /// from the back of `vertices[0..3]`'s orientation to its front
    /// ([`Side::Back`] to [`Side::Front`] of `orient3d_f64(v0, v1, v2, x)`),
    /// minus that going the other way. `±2` for a contour edge shared by two
    /// polygons, `±1` for an open edge or a cap.
    pub weight: i32,
    /// Which depth count it adds to: 0 for the models' shared count, `1 +
    /// k` for the `k`-th L-twisted polygon's own count.
    pub counter: u32,
}

impl ShadowPolygon {
    /// What the segment from `e` to `p` adds to the depth count by crossing
    /// this polygon: `±weight`, or 0 if it does not cross.
    pub fn crossing(&self, e: [f64; 3], p: [f64; 3]) -> i32 {
        let v = &self.vertices;
        let side_e = orient3d_f64(v[0], v[1], v[2], e);
        let side_p = orient3d_f64(v[0], v[1], v[2], p);
        if side_e == Side::On || side_p == Side::On || side_e == side_p {
            return 0;
        }
        // The line ep passes inside the polygon iff it turns the same way
        // around every edge.
        let first = orient3d_f64(e, p, v[0], v[1]);
        if first == Side::On {
            return 0;
        }
        for i in 1..v.len() {
            if orient3d_f64(e, p, v[i], v[(i + 1) % v.len()]) != first {
                return 0;
            }
        }
        if side_e == Side::Back {
            self.weight
        } else {
            -self.weight
        }
    }
}

/// Whether `x` lies strictly inside the shadow frustum of the convex planar
/// polygon `v` (grid points, exact): beyond its plane from the light,
/// inside the cone of rays from the light through it, and, when `cap` (the
/// polygon's far copy) is given, on the light's side of the cap. A polygon
/// whose plane holds the light has an empty frustum.
pub(crate) fn in_frustum(
    apex: &Apex,
    v: &[[f64; 3]],
    cap: Option<&[[f64; 3]]>,
    x: [f64; 3],
) -> bool {
    let light_side = orient3d_f64(v[0], v[1], v[2], apex.beside(v[0]));
    if light_side == Side::On || orient3d_f64(v[0], v[1], v[2], x) != light_side.flipped() {
        return false;
    }
    let inside = orient3d_f64(apex.beside(v[0]), v[0], v[1], v[2]);
    for i in 0..v.len() {
        let (a, b) = (v[i], v[(i + 1) % v.len()]);
        if orient3d_f64(apex.beside(a), a, b, x) != inside {
            return false;
        }
    }
    match cap {
        Some(c) => {
            let light_side = orient3d_f64(c[0], c[1], c[2], apex.beside(c[0]));
            light_side != Side::On && orient3d_f64(c[0], c[1], c[2], x) == light_side
        }
        None => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_is_crossed_once_each_way() {
        let square = ShadowPolygon {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
            ],
            weight: 2,
            counter: 0,
        };
        // orient3d(v0, v1, v2, x) is positive below a counter-clockwise
        // triangle: z < 0 is the front.
        let above = [1.0, 1.0, 1.0];
        let below = [1.0, 1.0, -1.0];
        assert_eq!(square.crossing(above, below), 2);
        assert_eq!(square.crossing(below, above), -2);
        // Beside it, or stopping on it: no crossing.
        assert_eq!(square.crossing([3.0, 1.0, 1.0], [3.0, 1.0, -1.0]), 0);
        assert_eq!(square.crossing(above, [1.0, 1.0, 0.0]), 0);
        // Through an edge's line: not counted.
        assert_eq!(square.crossing([2.0, 1.0, 1.0], [2.0, 1.0, -1.0]), 0);
    }

    #[test]
    fn frustum_of_a_triangle_under_a_point_light() {
        let apex = Apex::Point([0.0, 10.0, 0.0]);
        let t = [[-1.0, 5.0, -1.0], [1.0, 5.0, -1.0], [0.0, 5.0, 2.0]];
        assert!(in_frustum(&apex, &t, None, [0.0, 0.0, 0.0]));
        assert!(!in_frustum(&apex, &t, None, [0.0, 7.0, 0.0]));
        assert!(!in_frustum(&apex, &t, None, [5.0, 0.0, 0.0]));
        // Either orientation of the triangle.
        let r = [t[0], t[2], t[1]];
        assert!(in_frustum(&apex, &r, None, [0.0, 0.0, 0.0]));
        // A cap at y = -5 (ratio 3): beyond it is outside.
        let cap: Vec<[f64; 3]> = t.iter().map(|&v| apex.far(v, 3.0)).collect();
        assert!(in_frustum(&apex, &t, Some(&cap), [0.0, 0.0, 0.0]));
        assert!(!in_frustum(&apex, &t, Some(&cap), [0.0, -6.0, 0.0]));
        // A directional light straight down.
        let sun = Apex::Direction([0.0, -1.0, 0.0]);
        assert!(in_frustum(&sun, &t, None, [0.0, -100.0, 0.0]));
        assert!(!in_frustum(&sun, &t, None, [1.5, -100.0, 0.0]));
    }
}
