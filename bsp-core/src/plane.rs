//! Planes through three grid points, with exact integer coefficients.

use crate::GridPoint;
use std::hash::{Hash, Hasher};

/// Largest magnitude of a normal component of a [`Plane`]: `2^51`.
///
/// With grid coordinates of magnitude at most `2^24`, coordinate differences
/// are below `2^25` and each component of a cross product is below `2^51`.
pub const NORMAL_LIMIT: i64 = 1 << 51;

/// Largest magnitude of a plane offset: `2^77` (three products of `2^51` by
/// `2^24`, summed).
pub const OFFSET_LIMIT: i128 = 1 << 77;

/// An oriented plane `a x + b y + c z + d = 0` through three grid points.
///
/// The normal `(a, b, c)` follows the right-hand rule over the three points;
/// the **front** is the side the normal points to, where `a x + b y + c z + d`
/// is positive. Coefficients are divided by their greatest common divisor, so
/// two planes are equal (same set, same orientation) exactly when their
/// coefficients are equal. The `f64` copies of the coefficients serve the
/// floating-point filter in [`predicates`](crate::predicates).
#[derive(Debug, Clone, Copy)]
pub struct Plane {
    normal: [i64; 3],
    /// `offset` rounded to `f64`, kept because converting an `i128` is slow
    /// on the filter's hot path (the normal converts exactly and quickly).
    approx_offset: f64,
    /// The exact offset as two 64-bit halves, so that a plane is aligned
    /// like its other fields (8 bytes, not the 16 of an `i128`): polygons
    /// and tree nodes hold planes by the thousand and pad less.
    offset: SplitI128,
}

/// An `i128` stored as two 64-bit words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct SplitI128 {
    low: u64,
    high: i64,
}

impl SplitI128 {
    #[inline]
    fn new(v: i128) -> Self {
        Self {
            low: v as u64,
            high: (v >> 64) as i64,
        }
    }

    #[inline]
    fn get(self) -> i128 {
        (i128::from(self.high) << 64) | i128::from(self.low)
    }
}

impl Plane {
    /// The plane through `p`, `q`, `r`, oriented by the right-hand rule
    /// (counter-clockwise seen from the front). `None` if they are collinear.
    pub fn through(p: GridPoint, q: GridPoint, r: GridPoint) -> Option<Self> {
        let ([a, b, c], d) = Self::coefficients(p, q, r)?;
        Some(Self::normalized(a, b, c, d))
    }

    /// The normal and offset of the plane through `p`, `q`, `r`, not
    /// reduced; `None` if they are collinear.
    fn coefficients(p: GridPoint, q: GridPoint, r: GridPoint) -> Option<([i64; 3], i128)> {
        let normal = crate::predicates::cross_of_differences(p, q, r);
        if normal == [0, 0, 0] {
            return None;
        }
        let [px, py, pz] = p.to_i64();
        let d = -(i128::from(normal[0]) * i128::from(px)
            + i128::from(normal[1]) * i128::from(py)
            + i128::from(normal[2]) * i128::from(pz));
        Some((normal, d))
    }

    /// [`Self::through`] without dividing out the coefficients' common
    /// factor: the same oriented plane, with the same sides, for planes
    /// made for a few side tests and dropped (the common factor is most of
    /// the cost of making one). Its coefficients are within the kernel's
    /// bounds all the same; it may compare unequal to the reduced plane.
    pub fn through_unreduced(p: GridPoint, q: GridPoint, r: GridPoint) -> Option<Self> {
        let (normal, d) = Self::coefficients(p, q, r)?;
        Some(Self {
            normal,
            approx_offset: d as f64,
            offset: SplitI128::new(d),
        })
    }

    /// The plane with the given normal through the grid point `p`.
    ///
    /// The normal must have components within [`NORMAL_LIMIT`] for the
    /// kernel's bounds to hold; this is the case for any normal of a plane
    /// through three grid points (such as a cross product of two differences
    /// of grid points). Returns `None` for a zero or out-of-range normal.
    pub fn with_normal_through(normal: [i64; 3], p: GridPoint) -> Option<Self> {
        if normal == [0, 0, 0] || normal.iter().any(|c| c.abs() > NORMAL_LIMIT) {
            return None;
        }
        let [px, py, pz] = p.to_i64();
        let d = -(i128::from(normal[0]) * i128::from(px)
            + i128::from(normal[1]) * i128::from(py)
            + i128::from(normal[2]) * i128::from(pz));
        Some(Self::normalized(normal[0], normal[1], normal[2], d))
    }

    /// The edge plane of the directed segment `p -> q` in the plane
    /// `support`: it holds the segment and the support normal's dominant
    /// axis (so its coefficients stay small), and what lies on the left of
    /// `p -> q`, seen from the support's front, is behind it. This is how
    /// polygon edges and receiver lines are cut. `None` if `p == q`.
    pub fn edge_plane(support: &Plane, p: GridPoint, q: GridPoint) -> Option<Self> {
        let axis = support.dominant_axis();
        let d = [
            i64::from(q.x) - i64::from(p.x),
            i64::from(q.y) - i64::from(p.y),
            i64::from(q.z) - i64::from(p.z),
        ];
        let mut e = [0_i64; 3];
        e[axis] = support.normal()[axis].signum();
        // d x (sign e_axis): with (d x e) . (d x n) = |d|^2 |n_axis| > 0 the
        // right-hand side of the edge, d x n, is in front.
        let normal = [
            d[1] * e[2] - d[2] * e[1],
            d[2] * e[0] - d[0] * e[2],
            d[0] * e[1] - d[1] * e[0],
        ];
        Self::with_normal_through(normal, p)
    }

    fn normalized(a: i64, b: i64, c: i64, d: i128) -> Self {
        // The normal's gcd first, in 64 bits; it is usually 1, and then so
        // is the whole gcd.
        let gn = match gcd_u64(a.unsigned_abs(), b.unsigned_abs()) {
            1 => 1,
            g => gcd_u64(g, c.unsigned_abs()),
        };
        let g = if gn == 1 {
            1
        } else {
            // gcd(gn, d) = gcd(gn, d mod gn), with gn >= 1 (normal not zero).
            u128::from(gcd_u64(gn, (d.unsigned_abs() % u128::from(gn)) as u64))
        };
        // g >= 1 because the normal is not zero, and g <= gn fits in 64
        // bits. Usually g = 1: no division at all (a 128-bit one is a
        // library call).
        let (a, b, c, d) = if g == 1 {
            (a, b, c, d)
        } else {
            let g64 = g as i64;
            (a / g64, b / g64, c / g64, d / g as i128)
        };
        Self {
            normal: [a, b, c],
            approx_offset: d as f64,
            offset: SplitI128::new(d),
        }
    }

    /// The normal `(a, b, c)`.
    #[inline]
    pub fn normal(&self) -> [i64; 3] {
        self.normal
    }

    /// The offset `d`.
    #[inline]
    pub fn offset(&self) -> i128 {
        self.offset.get()
    }

    /// `(a, b, c, d)` rounded to `f64`; `a`, `b`, `c` are exact (below
    /// `2^53`), `d` is correctly rounded.
    #[inline]
    pub fn approx(&self) -> [f64; 4] {
        let [a, b, c] = self.normal;
        [a as f64, b as f64, c as f64, self.approx_offset]
    }

    /// The same plane with the opposite orientation (front and back swapped).
    #[inline]
    pub fn flipped(&self) -> Self {
        Self {
            normal: [-self.normal[0], -self.normal[1], -self.normal[2]],
            approx_offset: -self.approx_offset,
            offset: SplitI128::new(-self.offset()),
        }
    }

    /// Whether `other` is the same set of points with the opposite
    /// orientation.
    #[inline]
    pub fn is_opposite(&self, other: &Plane) -> bool {
        self.normal[0] == -other.normal[0]
            && self.normal[1] == -other.normal[1]
            && self.normal[2] == -other.normal[2]
            && self.offset() == -other.offset()
    }

    /// Whether `other` is the same set of points, whatever its orientation.
    #[inline]
    pub fn is_coincident(&self, other: &Plane) -> bool {
        self == other || self.is_opposite(other)
    }

    /// Index of the normal's component of largest magnitude (0, 1 or 2):
    /// the axis to project along for a 2D view of the plane.
    pub fn dominant_axis(&self) -> usize {
        let m = self.normal.map(i64::unsigned_abs);
        if m[0] >= m[1] && m[0] >= m[2] {
            0
        } else if m[1] >= m[2] {
            1
        } else {
            2
        }
    }

    /// The normal as `f64`, unit length (for shading and output only).
    pub fn unit_normal_f64(&self) -> [f64; 3] {
        let [a, b, c, _] = self.approx();
        let len = (a * a + b * b + c * c).sqrt();
        [a / len, b / len, c / len]
    }
}

impl PartialEq for Plane {
    fn eq(&self, other: &Self) -> bool {
        self.normal == other.normal && self.offset == other.offset
    }
}

impl Eq for Plane {}

impl Hash for Plane {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.normal.hash(state);
        self.offset().hash(state);
    }
}

fn gcd_u64(mut a: u64, mut b: u64) -> u64 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    if a == 1 || b == 1 {
        return 1;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gp(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    #[test]
    fn orientation_follows_the_right_hand_rule() {
        let p = Plane::through(gp(0, 0, 0), gp(1, 0, 0), gp(0, 1, 0)).unwrap();
        assert_eq!(p.normal(), [0, 0, 1]);
        assert_eq!(p.offset(), 0);
        let q = Plane::through(gp(0, 0, 5), gp(0, 7, 5), gp(3, 0, 5)).unwrap();
        assert_eq!(q.normal(), [0, 0, -1]);
        assert_eq!(q.offset(), 5);
        assert!(q.is_opposite(&Plane::through(gp(0, 0, 5), gp(3, 0, 5), gp(0, 7, 5)).unwrap()));
    }

    #[test]
    fn equal_planes_have_equal_coefficients() {
        let a = Plane::through(gp(0, 0, 2), gp(4, 0, 2), gp(0, 6, 2)).unwrap();
        let b = Plane::through(gp(10, 10, 2), gp(-3, 10, 2), gp(10, -30, 2)).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.flipped().flipped(), a);
        assert!(a.flipped().is_opposite(&a));
        assert!(a.is_coincident(&a.flipped()));
        assert_ne!(a, a.flipped());
    }

    #[test]
    fn coefficients_are_divided_by_their_gcd() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        for _ in 0..2000 {
            let k: i64 = rng.random_range(1..50);
            let n: [i64; 3] = std::array::from_fn(|_| k * rng.random_range(-1000..1000));
            let p = gp(rng.random_range(-99..99), rng.random_range(-99..99), 0);
            let Some(plane) = Plane::with_normal_through(n, p) else {
                continue;
            };
            let [a, b, c] = plane.normal().map(|v| v.unsigned_abs() as u128);
            // Euclid's algorithm: an oracle independent of the binary gcd.
            let gcd = |mut x: u128, mut y: u128| {
                while y != 0 {
                    (x, y) = (y, x % y);
                }
                x
            };
            let g = gcd(gcd(gcd(a, b), c), plane.offset().unsigned_abs());
            assert_eq!(g, 1);
            // The same plane from a scaled normal.
            let m = n.map(|v| v / k);
            assert_eq!(Plane::with_normal_through(m, p), Some(plane));
        }
    }

    #[test]
    fn collinear_points_make_no_plane() {
        assert!(Plane::through(gp(0, 0, 0), gp(1, 1, 1), gp(2, 2, 2)).is_none());
    }

    #[test]
    fn extreme_coordinates_stay_within_bounds() {
        let l = crate::GRID_LIMIT;
        let p = Plane::through(gp(-l, -l, l), gp(l, -l, -l), gp(-l, l, -l)).unwrap();
        assert!(p.normal().iter().all(|c| c.abs() <= NORMAL_LIMIT));
        assert!(p.offset().abs() < OFFSET_LIMIT);
        let q = Plane::through(gp(-l, l, -l), gp(l, -l + 1, l), gp(l - 1, l, -l + 2)).unwrap();
        assert!(q.normal().iter().all(|c| c.abs() <= NORMAL_LIMIT));
        assert!(q.offset().abs() < OFFSET_LIMIT);
    }
}
