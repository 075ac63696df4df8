//! The only module that decides a side.
//!
//! Two kinds of points are classified against planes:
//!
//! - **grid points** (input vertices, light positions): the sign of
//!   `a x + b y + c z + d`, exact in `i128`;
//! - **implicit points**, the intersection of three planes (vertices made by
//!   splitting). Their side of a fourth plane is the sign of a 4x4
//!   determinant of plane coefficients, below `2^235` in magnitude. A
//!   floating-point filter with a proven error bound answers almost every
//!   query; when it cannot, the determinant is evaluated exactly with 256-bit
//!   integers. [`exact_fallbacks`] counts how often that happens.
//!
//! # The filter's error bound
//!
//! The homogeneous coordinates `X` of the intersection are 3x3 minors of the
//! 3x4 matrix of plane coefficients, so that `q · X` is the 4x4 determinant
//! with `q` as its last row. Every quantity is a polynomial in the
//! coefficients, evaluated as a tree of `+`, `-` and `*` in which each
//! coefficient is rounded once (only `d` can need it: normal components are
//! below `2^53`) and each operation rounds once. For such a tree of depth `D`
//! (roundings on the longest path from a leaf to the root) the computed value
//! `v'` satisfies `|v' - v| <= gamma_D * P` where `P` is the same tree
//! evaluated on absolute values with every subtraction made an addition (the
//! *permanent*), and `gamma_D = D u / (1 - D u)`, `u = 2^-53` (Higham,
//! *Accuracy and Stability of Numerical Algorithms*, ch. 3). The minors have
//! depth 6 (conversion, product, difference; conversion, product, two sums);
//! `q · X` adds a product and three sums: depth 10. The permanent is computed
//! alongside in floating point, with relative error at most `gamma_10`
//! (all its terms are positive). Hence `|s'| > 12 u P'` implies
//! `|s'| > gamma_10 P >= |s' - s|`, and the sign of `s'` is the sign of `s`.
//! A point keeps each coordinate's permanent rounded up to a power of two
//! ([`PointFilter`]): a larger `P'` only widens the band left to the exact
//! path.
//! Integers leave no room for underflow, and `2^240` is far from overflow.

use crate::{Error, GridPoint, Plane};
use ethnum::I256;
use std::sync::atomic::{AtomicU64, Ordering};

mod pencil;

use pencil::dot_sign;
pub use pencil::{Pencil, in_pencil};

/// Which side of an oriented plane a point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Side {
    /// Strictly behind: the plane's expression is negative.
    Back,
    /// On the plane.
    On,
    /// Strictly in front: the plane's expression is positive.
    Front,
}

impl Side {
    /// The side of a value's sign.
    #[inline]
    pub fn of_sign<T: PartialOrd + Default>(v: T) -> Self {
        let zero = T::default();
        if v > zero {
            Side::Front
        } else if v < zero {
            Side::Back
        } else {
            Side::On
        }
    }

    /// Front for Back and Back for Front.
    #[inline]
    pub fn flipped(self) -> Self {
        match self {
            Side::Back => Side::Front,
            Side::On => Side::On,
            Side::Front => Side::Back,
        }
    }
}

static EXACT_FALLBACKS: AtomicU64 = AtomicU64::new(0);

/// How many implicit-point queries the floating-point filter could not
/// decide, so far, in this process (all threads).
pub fn exact_fallbacks() -> u64 {
    EXACT_FALLBACKS.load(Ordering::Relaxed)
}

/// Unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;
/// Filter coefficient for `q · X` (depth 10, see the module docs).
const SIDE_BOUND: f64 = 12.0 * U;
/// Filter coefficient for a 3x3 minor (depth 6).
const MINOR_BOUND: f64 = 8.0 * U;

/// Side of a grid point. Exact: every term fits `i128`.
#[inline]
pub fn side_of_point(plane: &Plane, p: GridPoint) -> Side {
    Side::of_sign(plane_value_at(plane, p))
}

/// `a x + b y + c z + d` at a grid point, exactly.
#[inline]
pub fn plane_value_at(plane: &Plane, p: GridPoint) -> i128 {
    let [a, b, c] = plane.normal();
    i128::from(a) * i128::from(p.x)
        + i128::from(b) * i128::from(p.y)
        + i128::from(c) * i128::from(p.z)
        + plane.offset()
}

/// Side of the point at infinity in direction `dir` (a viewer infinitely far
/// away, such as a directional light): the sign of `normal · dir`.
///
/// Exact: a normal component below `2^51` times an `i32` fits `i128`.
#[inline]
pub fn side_of_direction(plane: &Plane, dir: [i32; 3]) -> Side {
    let [a, b, c] = plane.normal();
    Side::of_sign(
        i128::from(a) * i128::from(dir[0])
            + i128::from(b) * i128::from(dir[1])
            + i128::from(c) * i128::from(dir[2]),
    )
}

/// Whether three grid points are collinear (exact).
pub fn collinear(p: GridPoint, q: GridPoint, r: GridPoint) -> bool {
    cross_of_differences(p, q, r) == [0, 0, 0]
}

/// `(q - p) x (r - p)`, exact in `i64` (components below `2^51`).
pub fn cross_of_differences(p: GridPoint, q: GridPoint, r: GridPoint) -> [i64; 3] {
    let [px, py, pz] = p.to_i64();
    let [qx, qy, qz] = q.to_i64();
    let [rx, ry, rz] = r.to_i64();
    let (ux, uy, uz) = (qx - px, qy - py, qz - pz);
    let (vx, vy, vz) = (rx - px, ry - py, rz - pz);
    [uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx]
}

/// Exact dot product of two vectors with components below `2^62`.
pub fn dot_i128(u: [i64; 3], v: [i64; 3]) -> i128 {
    i128::from(u[0]) * i128::from(v[0])
        + i128::from(u[1]) * i128::from(v[1])
        + i128::from(u[2]) * i128::from(v[2])
}

/// Orientation of four explicit `f64` points: the sign of
/// `det[a - d, b - d, c - d]`, exactly (Shewchuk's adaptive predicate, the
/// `robust` crate). [`Side::Front`] when `d` lies below the plane through
/// `a`, `b`, `c`, that is when `a`, `b`, `c` turn counter-clockwise seen
/// from above it; [`Side::On`] when the four are coplanar.
///
/// For points that are not grid points: a camera's eye, a pixel's visible
/// point, a far vertex of a shadow polygon. Its answer is exact for the
/// `f64` values given, whatever rounding made them.
#[inline]
pub fn orient3d_f64(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> Side {
    let p = |v: [f64; 3]| robust::Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    };
    Side::of_sign(robust::orient3d(p(a), p(b), p(c), p(d)))
}

/// Floating-point filter data of an implicit point: approximate homogeneous
/// coordinates (scaled so that the true `w` is positive) and, per
/// coordinate, the permanent that bounds its error.
///
/// Each permanent is kept as the power of two just above it (its biased
/// `f64` exponent, 0 for a zero permanent): a bound at most twice the
/// permanent serves the filter as well, and the point takes 40 bytes, not
/// 64 (polygons and meshes hold millions).
///
/// It does not store the three planes: whoever owns it (an
/// [`ImplicitPoint`], a polygon's vertex) keeps them, for the exact path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointFilter {
    coords: [f64; 4],
    magnitude_exponents: [u16; 4],
}

/// The biased exponent of a power of two at least `m` (`m` zero, or at
/// least 1 and below `2^1023`: a permanent of integer coefficients).
#[inline]
fn power_above(m: f64) -> u16 {
    if m == 0.0 {
        0
    } else {
        // 2^(E + 1) > m for m = 1.f * 2^E.
        ((m.to_bits() >> 52) & 0x7ff) as u16 + 1
    }
}

/// The power of two a [`power_above`] exponent stands for (0 for 0).
#[inline]
fn power(exponent: u16) -> f64 {
    f64::from_bits(u64::from(exponent) << 52)
}

impl PointFilter {
    /// The filter of `p1 ∩ p2 ∩ p3`; `None` if the planes do not meet in a
    /// single point (decided exactly).
    pub fn new(p1: &Plane, p2: &Plane, p3: &Plane) -> Option<Self> {
        let (mut coords, magnitudes) = homogeneous_f64(&p1.approx(), &p2.approx(), &p3.approx());
        let w_sign = if coords[3].abs() > MINOR_BOUND * magnitudes[3] {
            coords[3].signum() as i32
        } else {
            EXACT_FALLBACKS.fetch_add(1, Ordering::Relaxed);
            exact_homogeneous(p1, p2, p3)[3].signum128() as i32
        };
        match w_sign {
            0 => None,
            s => {
                if s < 0 {
                    coords = coords.map(|c| -c);
                }
                Some(Self {
                    coords,
                    magnitude_exponents: magnitudes.map(power_above),
                })
            }
        }
    }

    /// The approximate homogeneous coordinates `(x, y, z, w)`, `w > 0` in
    /// exact arithmetic.
    pub fn coords(&self) -> [f64; 4] {
        self.coords
    }

    /// The filter's verdict: `Some(side)` if certain, `None` if the exact
    /// path must decide.
    #[inline]
    pub fn side(&self, q: &Plane) -> Option<Side> {
        let a = q.approx();
        let x = &self.coords;
        let m = self.magnitude_exponents.map(power);
        let s = a[0] * x[0] + a[1] * x[1] + a[2] * x[2] + a[3] * x[3];
        let t = a[0].abs() * m[0] + a[1].abs() * m[1] + a[2].abs() * m[2] + a[3].abs() * m[3];
        let bound = SIDE_BOUND * t;
        if s > bound {
            Some(Side::Front)
        } else if s < -bound {
            Some(Side::Back)
        } else if t == 0.0 {
            // Every term of the permanent is zero, so is every term of s.
            Some(Side::On)
        } else {
            None
        }
    }

    /// Coordinates in grid units if the filter data is accurate enough
    /// (absolute error below `2^-20` grid units), else `None`.
    fn to_f64_if_accurate(self) -> Option<[f64; 3]> {
        let [x, y, z, w] = self.coords;
        let m = self.magnitude_exponents.map(power);
        let ew = MINOR_BOUND * m[3];
        if w <= 2.0 * ew {
            return None;
        }
        let p = [x / w, y / w, z / w];
        for j in 0..3 {
            // |x/w - x'/w'| <= (e_x + |x'/w'| e_w) / (w' - e_w), plus rounding.
            let err = (MINOR_BOUND * m[j] + p[j].abs() * ew) / (w - ew) + p[j].abs() * U;
            if !err.is_finite() || err > 1.0 / (1u64 << 20) as f64 {
                return None;
            }
        }
        Some(p)
    }
}

/// Side of the implicit point `p1 ∩ p2 ∩ p3` (with its filter data) with
/// respect to `q`.
#[inline]
pub fn side_of_implicit(filter: &PointFilter, planes: [&Plane; 3], q: &Plane) -> Side {
    match filter.side(q) {
        Some(side) => side,
        None => exact_side_of_implicit(planes, q),
    }
}

/// Side of the implicit point `p1 ∩ p2 ∩ p3` with respect to `q`, in exact
/// 256-bit arithmetic (counted in [`exact_fallbacks`]) unless `q` is one of
/// the three planes. The planes must meet in one point.
#[cold]
pub fn exact_side_of_implicit(planes: [&Plane; 3], q: &Plane) -> Side {
    // A point lies on its own planes: the commonest zero, decided for free.
    if planes.iter().any(|p| p.is_coincident(q)) {
        return Side::On;
    }
    EXACT_FALLBACKS.fetch_add(1, Ordering::Relaxed);
    // side = sign(det[p1; p2; p3; q]) * sign(w), w = det of the three
    // normals. The 4x4 determinant is expanded in the 2x2 minors of rows
    // (p1, p2) and (p3, q) (Laplace): the minors of normal components fit
    // `i128`, the others usually do, and only six products need 256 bits.
    let row = |p: &Plane| {
        let [a, b, c] = p.normal();
        [i128::from(a), i128::from(b), i128::from(c), p.offset()]
    };
    let (r0, r1, r2, r3) = (row(planes[0]), row(planes[1]), row(planes[2]), row(q));
    let m = |j: usize, k: usize| minor(r0[j], r1[k], r0[k], r1[j]);
    let n = |j: usize, k: usize| minor(r2[j], r3[k], r2[k], r3[j]);
    let (m01, m02, m12) = (m(0, 1), m(0, 2), m(1, 2));
    let w = dot3(
        [Wide::Small(r2[0]), Wide::Small(-r2[1]), Wide::Small(r2[2])],
        [m12, m02, m01],
    );
    let det = dot3(
        [m(0, 3), m(1, 3).neg(), m(2, 3)],
        [n(1, 2), n(0, 2), n(0, 1)],
    )
    .cmp_sum(dot3([m01, m02.neg(), m12], [n(2, 3), n(1, 3), n(0, 3)]));
    Side::of_sign(det * w.signum_i32())
}

/// Whether the implicit point `p1 ∩ p2 ∩ p3` lies on every plane of `qs`,
/// exact. The determinants share the 2x2 minors of `p1` and `p2`: testing
/// two points for equality (three planes each) costs about half of three
/// [`exact_side_of_implicit`] calls. The planes must meet in one point.
pub fn lies_on_all(planes: [&Plane; 3], qs: &[&Plane]) -> bool {
    let row = |p: &Plane| {
        let [a, b, c] = p.normal();
        [i128::from(a), i128::from(b), i128::from(c), p.offset()]
    };
    let (r0, r1, r2) = (row(planes[0]), row(planes[1]), row(planes[2]));
    let m = |j: usize, k: usize| minor(r0[j], r1[k], r0[k], r1[j]);
    let (m01, m02, m12, m03, m13, m23) = (m(0, 1), m(0, 2), m(1, 2), m(0, 3), m(1, 3), m(2, 3));
    qs.iter().all(|q| {
        if planes.iter().any(|p| p.is_coincident(q)) {
            return true;
        }
        EXACT_FALLBACKS.fetch_add(1, Ordering::Relaxed);
        let r3 = row(q);
        let n = |j: usize, k: usize| minor(r2[j], r3[k], r2[k], r3[j]);
        // The 4x4 determinant of exact_side_of_implicit, tested for zero.
        dot3([m03, m13.neg(), m23], [n(1, 2), n(0, 2), n(0, 1)])
            .cmp_sum(dot3([m01, m02.neg(), m12], [n(2, 3), n(1, 3), n(0, 3)]))
            == 0
    })
}

/// A signed 256-bit sum, kept as `i128` while it fits.
#[derive(Clone, Copy)]
enum Wide {
    Small(i128),
    Big(I256),
}

impl Wide {
    fn big(self) -> I256 {
        match self {
            Wide::Small(v) => I256::from(v),
            Wide::Big(v) => v,
        }
    }

    fn neg(self) -> Wide {
        match self {
            Wide::Small(v) => v
                .checked_neg()
                .map_or(Wide::Big(-I256::from(v)), Wide::Small),
            Wide::Big(v) => Wide::Big(-v),
        }
    }

    fn signum_i32(self) -> i32 {
        match self {
            Wide::Small(v) => v.signum() as i32,
            Wide::Big(v) => v.signum128() as i32,
        }
    }

    /// The sign of `self + other`, as an `i32`.
    fn cmp_sum(self, other: Wide) -> i32 {
        if let (Wide::Small(a), Wide::Small(b)) = (self, other)
            && let Some(s) = a.checked_add(b)
        {
            return s.signum() as i32;
        }
        (self.big() + other.big()).signum128() as i32
    }
}

/// `x0 y1 - x1 y0` exactly, for entries below `2^78` in magnitude.
#[inline]
fn minor(x0: i128, y1: i128, x1: i128, y0: i128) -> Wide {
    if let (Some(p), Some(q)) = (x0.checked_mul(y1), x1.checked_mul(y0))
        && let Some(d) = p.checked_sub(q)
    {
        return Wide::Small(d);
    }
    Wide::Big(I256::from(x0) * I256::from(y1) - I256::from(x1) * I256::from(y0))
}

/// `u · v` exactly (each product below `2^250` in magnitude).
fn dot3(u: [Wide; 3], v: [Wide; 3]) -> Wide {
    let small = || {
        let mut acc = 0_i128;
        for k in 0..3 {
            let (Wide::Small(uk), Wide::Small(vk)) = (u[k], v[k]) else {
                return None;
            };
            acc = acc.checked_add(uk.checked_mul(vk)?)?;
        }
        Some(acc)
    };
    match small() {
        Some(s) => Wide::Small(s),
        None => Wide::Big((0..3).fold(I256::ZERO, |acc, k| acc + u[k].big() * v[k].big())),
    }
}

/// Side of a point of the line `support ∩ edge` that lies at a grid point
/// `g` on `q` moved along the line's direction `support.normal ×
/// edge.normal` (`forward`) or against it, with `g` itself on `q`: the sign
/// of `±q.normal · (support.normal × edge.normal)`, exact.
///
/// This decides, without the 4x4 determinant, a polygon vertex whose
/// neighbour along an edge is a grid point on `q` (a cut vertex on a mesh
/// edge tested against the neighbouring face, a commonest zero).
pub fn side_along_line(q: &Plane, support: &Plane, edge: &Plane, forward: bool) -> Side {
    EXACT_FALLBACKS.fetch_add(1, Ordering::Relaxed);
    let [a, b, c] = support.normal().map(i128::from);
    let [d, e, f] = edge.normal().map(i128::from);
    // Components below 2^103.
    let dir = [b * f - c * e, c * d - a * f, a * e - b * d];
    let s = dot_sign(q.normal().map(i128::from), dir);
    if forward { s } else { s.flipped() }
}

/// Exact homogeneous coordinates of `p1 ∩ p2 ∩ p3` (the 3x3 minors of the
/// coefficient matrix, signed as the cofactors of a fourth row).
pub fn exact_homogeneous(p1: &Plane, p2: &Plane, p3: &Plane) -> [I256; 4] {
    let row = |p: &Plane| {
        let [a, b, c] = p.normal();
        [
            I256::from(a),
            I256::from(b),
            I256::from(c),
            I256::from(p.offset()),
        ]
    };
    cofactors(
        &row(p1),
        &row(p2),
        &row(p3),
        |a, b| a * b,
        |a, b| a - b,
        |a, b| a + b,
    )
}

/// Approximate homogeneous coordinates and their permanents.
fn homogeneous_f64(r0: &[f64; 4], r1: &[f64; 4], r2: &[f64; 4]) -> ([f64; 4], [f64; 4]) {
    let coords = cofactors(r0, r1, r2, |a, b| a * b, |a, b| a - b, |a, b| a + b);
    let abs = |r: &[f64; 4]| r.map(f64::abs);
    let magnitudes = cofactors(
        &abs(r0),
        &abs(r1),
        &abs(r2),
        |a, b| a * b,
        |a, b| a + b,
        |a, b| a + b,
    );
    // The permanents carry no sign: cofactor signs are irrelevant there.
    (coords, magnitudes.map(f64::abs))
}

/// The cofactors of a fourth row of the 4x4 matrix with rows `r0`, `r1`,
/// `r2`: `X_j = (-1)^(j+1) det(columns other than j)`. `sub` is used for
/// every difference of products, so that passing `+` gives the permanent.
#[inline(always)]
fn cofactors<T: Copy>(
    r0: &[T; 4],
    r1: &[T; 4],
    r2: &[T; 4],
    mul: impl Fn(T, T) -> T,
    sub: impl Fn(T, T) -> T,
    add: impl Fn(T, T) -> T,
) -> [T; 4] {
    let m = |j: usize, k: usize| sub(mul(r0[j], r1[k]), mul(r0[k], r1[j]));
    let (m01, m02, m03, m12, m13, m23) = (m(0, 1), m(0, 2), m(0, 3), m(1, 2), m(1, 3), m(2, 3));
    // det of columns (j, k, l) expanded along r2.
    let det = |j: usize, k: usize, l: usize, mkl: T, mjl: T, mjk: T| {
        add(sub(mul(r2[j], mkl), mul(r2[k], mjl)), mul(r2[l], mjk))
    };
    // -det, written so that the signs of X0 and X2 come from the order of
    // the operands of one difference, which keeps `sub = +` a permanent.
    let neg_det = |j: usize, k: usize, l: usize, mkl: T, mjl: T, mjk: T| {
        sub(mul(r2[k], mjl), add(mul(r2[j], mkl), mul(r2[l], mjk)))
    };
    [
        neg_det(1, 2, 3, m23, m13, m12),
        det(0, 2, 3, m23, m03, m02),
        neg_det(0, 1, 3, m13, m03, m01),
        det(0, 1, 2, m12, m02, m01),
    ]
}

/// A point given as the intersection of three planes, with its filter data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImplicitPoint {
    planes: [Plane; 3],
    filter: PointFilter,
}

impl ImplicitPoint {
    /// The intersection of three planes; an error if they do not meet in a
    /// single point.
    pub fn new(p1: Plane, p2: Plane, p3: Plane) -> Result<Self, Error> {
        let filter = PointFilter::new(&p1, &p2, &p3).ok_or(Error::NoIntersection)?;
        Ok(Self {
            planes: [p1, p2, p3],
            filter,
        })
    }

    /// The point of three planes whose filter data was computed before
    /// (by [`Self::new`], from the same planes in the same order).
    pub(crate) fn from_parts(planes: [Plane; 3], filter: PointFilter) -> Self {
        Self { planes, filter }
    }

    /// The three planes that define the point.
    pub fn planes(&self) -> &[Plane; 3] {
        &self.planes
    }

    /// The filter data.
    pub fn filter(&self) -> &PointFilter {
        &self.filter
    }

    /// Side with respect to `q`, exact.
    #[inline]
    pub fn side(&self, q: &Plane) -> Side {
        let [a, b, c] = &self.planes;
        side_of_implicit(&self.filter, [a, b, c], q)
    }

    /// Whether this and `other` are the same point (exact).
    pub fn same_point(&self, other: &ImplicitPoint) -> bool {
        // The filter rejects most; the planes it cannot decide (the point
        // on them, most likely) go to one shared exact test.
        let mut undecided: [&Plane; 3] = [&other.planes[0]; 3];
        let mut count = 0;
        for q in &other.planes {
            if self.planes.iter().any(|p| p.is_coincident(q)) {
                continue;
            }
            match self.filter.side(q) {
                Some(Side::On) => {}
                Some(_) => return false,
                None => {
                    undecided[count] = q;
                    count += 1;
                }
            }
        }
        let [a, b, c] = &self.planes;
        count == 0 || lies_on_all([a, b, c], &undecided[..count])
    }

    /// Coordinates in grid units, for output and illumination only.
    pub fn to_f64(&self) -> [f64; 3] {
        implicit_to_f64(
            &self.filter,
            [&self.planes[0], &self.planes[1], &self.planes[2]],
        )
    }
}

/// Coordinates in grid units of an implicit point: from the filter when it
/// is accurate to `2^-20` grid units, else from the exact coordinates.
pub fn implicit_to_f64(filter: &PointFilter, planes: [&Plane; 3]) -> [f64; 3] {
    if let Some(p) = filter.to_f64_if_accurate() {
        return p;
    }
    let x = exact_homogeneous(planes[0], planes[1], planes[2]);
    let w = x[3].as_f64();
    [x[0].as_f64() / w, x[1].as_f64() / w, x[2].as_f64() / w]
}

#[cfg(test)]
mod tests;
