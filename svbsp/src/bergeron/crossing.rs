//! Where a segment crosses a shadow polygon, and whether a point lies in a
//! polygon's shadow frustum: every answer is a sign of `orient3d` on
//! explicit points ([`bsp_core::predicates::orient3d_f64`]), exact.
//!
//! Ties are broken so that every answer stays consistent:
//!
//! - the **eye** (a segment's start, a point whose depth counts are asked
//!   for) is perturbed symbolically to `e + ε x + ε² y + ε³ z` (`ε` positive
//!   and infinitely small): every orientation with it is affine in it, so
//!   when one is zero its sign is that of the first non-zero change along
//!   `x`, then `y`, then `z`, each read exactly by moving one coordinate up
//!   by one unit (an affine function's change has the same sign for any
//!   step, and a unit keeps the point where the exact orientation does not
//!   underflow). An eye that lies on a shadow polygon (on the
//!   boundary of a volume) is thus inside or outside the volume the same
//!   way for its own count and for every segment it starts;
//! - the **visible point** is not perturbed: a segment that ends on a
//!   shadow polygon's plane does not cross it (the count just before the
//!   point), and neither does one whose line meets the polygon's boundary
//!   only degenerately. Such segments graze a shadow edge.

use bsp_core::predicates::{Side, orient3d_f64};

use super::apex::Apex;

/// One polygon of a shadow volume's boundary, with its depth increment.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowPolygon {
    /// Its corners, a convex planar polygon (exact `f64`, grid units). A
    /// side polygon is `[a', a, b, b']`: the contour edge `ab` between the
    /// two rays from the light through its ends, `a'` and `b'` on them; a
    /// cap is a model polygon's far copy.
    pub vertices: Vec<[f64; 3]>,
    /// Whether the polygon is closed by the edge from its last corner back
    /// to its first. An open one is unbounded: that edge lies at infinity,
    /// and its first and last corners only give the rays' directions.
    pub closed: bool,
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
        let side_e = perturbed(e, |e| orient3d_f64(v[0], v[1], v[2], e));
        let side_p = orient3d_f64(v[0], v[1], v[2], p);
        if side_e == Side::On || side_p == Side::On || side_e == side_p {
            return 0;
        }
        // The line ep passes inside the polygon iff it turns around every
        // edge the way a line from the back of `v[0..3]` to its front
        // turns around a convex polygon's edges: orient3d(e, p, v_i,
        // v_i+1) has the sign opposite to e's side. Of an open polygon only
        // the finite edges are tested: it is the intersection of their
        // half-planes (asking for the sign, not only for equal signs, keeps
        // out the intersection of the other half-planes, the cone opposite).
        let edges = if self.closed { v.len() } else { v.len() - 1 };
        let inside = side_e.flipped();
        let around = |i: usize| perturbed(e, |e| orient3d_f64(e, p, v[i], v[(i + 1) % v.len()]));
        if (0..edges).any(|i| around(i) != inside) {
            return 0;
        }
        if side_e == Side::Back {
            self.weight
        } else {
            -self.weight
        }
    }
}

/// The side `orient(e)` gives for the symbolically perturbed point
/// `e + ε x + ε² y + ε³ z`, where `orient` is affine in its point (every
/// orientation is): its sign at `e` or, if zero, that of its change as one
/// coordinate moves up, `x` first. [`Side::On`] only if `orient` does not
/// depend on the point at all.
fn perturbed(e: [f64; 3], orient: impl Fn([f64; 3]) -> Side) -> Side {
    let side = orient(e);
    if side != Side::On {
        return side;
    }
    for axis in 0..3 {
        let mut moved = e;
        moved[axis] = step_up(e[axis]);
        let side = orient(moved);
        if side != Side::On {
            return side;
        }
    }
    Side::On
}

/// A coordinate above `x`, for reading the sign of an affine function's
/// change along an axis: any point above gives it, as long as the exact
/// orientation can be evaluated there. A step of one (rounded) keeps the
/// point at the scale of the input: the next `f64` above 0 is subnormal,
/// where the products of an orientation underflow and its sign is lost.
fn step_up(x: f64) -> f64 {
    let up = x + 1.0;
    if up > x { up } else { next_up(x) }
}

/// The least `f64` above `x` (finite `x`; `f64::next_up` needs Rust 1.86).
fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// Whether `x`, perturbed as an eye is, lies inside the shadow frustum of
/// the convex planar polygon `v` (grid points, exact): beyond its plane from
/// the light, inside the cone of rays from the light through it, and, when
/// `cap` (the polygon's far copy) is given, on the light's side of the cap.
/// A polygon whose plane holds the light has an empty frustum.
pub(crate) fn in_frustum(
    apex: &Apex,
    v: &[[f64; 3]],
    cap: Option<&[[f64; 3]]>,
    x: [f64; 3],
) -> bool {
    let light_side = orient3d_f64(v[0], v[1], v[2], apex.beside(v[0]));
    if light_side == Side::On
        || perturbed(x, |x| orient3d_f64(v[0], v[1], v[2], x)) != light_side.flipped()
    {
        return false;
    }
    let inside = orient3d_f64(apex.beside(v[0]), v[0], v[1], v[2]);
    for i in 0..v.len() {
        let (a, b) = (v[i], v[(i + 1) % v.len()]);
        if perturbed(x, |x| orient3d_f64(apex.beside(a), a, b, x)) != inside {
            return false;
        }
    }
    match cap {
        Some(c) => {
            let light_side = orient3d_f64(c[0], c[1], c[2], apex.beside(c[0]));
            light_side != Side::On
                && perturbed(x, |x| orient3d_f64(c[0], c[1], c[2], x)) == light_side
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
            closed: true,
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
        // Through an edge's line: decided by the eye's perturbation (+x:
        // outside the square's edge x = 2, then the edge y = 0 at x = 0:
        // +x is inside).
        assert_eq!(square.crossing([2.0, 1.0, 1.0], [2.0, 1.0, -1.0]), 0);
        assert_eq!(square.crossing([0.0, 1.0, 1.0], [0.0, 1.0, -1.0]), 2);
        // Starting on its plane, inside it: the eye counts as just beside
        // it (+x does not leave the plane; +y neither; +z is above).
        assert_eq!(square.crossing([1.0, 1.0, 0.0], below), 2);
    }

    #[test]
    fn an_open_polygon_reaches_to_infinity() {
        // The wedge under the edge (-1, 5, 0) - (1, 5, 0) from a light at
        // (0, 10, 0): rays through (-2, 0, 0) and (2, 0, 0).
        let wedge = ShadowPolygon {
            vertices: vec![
                [-2.0, 0.0, 0.0],
                [-1.0, 5.0, 0.0],
                [1.0, 5.0, 0.0],
                [2.0, 0.0, 0.0],
            ],
            closed: false,
            weight: 1,
            counter: 0,
        };
        let far = |x: f64, z: f64| [x, -1e6, z];
        assert_eq!(wedge.crossing(far(0.0, 1.0), far(0.0, -1.0)).abs(), 1);
        assert_eq!(wedge.crossing(far(1e5, 1.0), far(1e5, -1.0)).abs(), 1);
        assert_eq!(wedge.crossing(far(3e5, 1.0), far(3e5, -1.0)), 0);
        // Above the edge, or in the opposite cone above the light: no.
        assert_eq!(wedge.crossing([0.0, 7.0, 1.0], [0.0, 7.0, -1.0]), 0);
        assert_eq!(wedge.crossing([0.0, 20.0, 1.0], [0.0, 20.0, -1.0]), 0);
    }

    /// An eye on a polygon's plane at the origin (an integer point, as
    /// eyes often are; the polygon's corners fractions, as those of shadow
    /// polygons are): the perturbed side is the sign of the orientation's
    /// change along x, then y, then z, read exactly from the plane's
    /// integer normal. (Moving 0 to the next `f64`, a subnormal, lost it to
    /// underflow: cargo-fuzz `bergeron` found an eye whose counts
    /// disagreed with the crossings of its segments.)
    #[test]
    fn an_eye_at_the_origin_is_perturbed_exactly() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = |range: i64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % (2 * range as u64 + 1)) as i64 - range
        };
        let mut checked = 0;
        for _ in 0..2000 {
            let a = [next(9), next(9), next(9)];
            let b = [next(9), next(9), next(9)];
            // a, b and a + b span a plane through the origin.
            let c = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
            let n = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            let Some(&first) = n.iter().find(|&&k| k != 0) else {
                continue;
            };
            // orient3d(a, b, c, x) = det[a - x, b - x, c - x] decreases
            // along (b - a) x (c - a) = -(a x b).
            let expected = Side::of_sign(first);
            // In 64ths (exact): the orientation's change for a subnormal
            // step is below the least subnormal.
            let f = |v: [i64; 3]| v.map(|k| k as f64 / 64.0);
            let (a, b, c) = (f(a), f(b), f(c));
            let side = perturbed([0.0; 3], |x| orient3d_f64(a, b, c, x));
            assert_eq!(side, expected, "{a:?} {b:?} {c:?}");
            checked += 1;
        }
        assert!(checked > 1500, "{checked} planes");
    }

    #[test]
    fn next_up_is_the_next_float() {
        assert_eq!(next_up(1.0), 1.0 + f64::EPSILON);
        assert_eq!(next_up(-1.0), -1.0 + f64::EPSILON / 2.0);
        assert!(next_up(0.0) > 0.0);
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
