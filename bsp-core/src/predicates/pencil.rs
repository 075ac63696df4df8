//! Pencils of planes: whether a plane holds the line where two others
//! meet, exactly and without the 4x4 determinant (the commonest exact
//! zero after a point's own planes).

use super::{Side, U};
use crate::Plane;
use ethnum::I256;

/// Whether `q` contains the line where `a` and `b` meet (`a`, `b` not
/// parallel): the three planes lie in one pencil, their 3x4 coefficient
/// matrix has rank 2, and all its 3x3 minors vanish. Exact.
///
/// A vertex on the line `a ∩ b` then lies on `q` without its 4x4
/// determinant: the commonest exact zero after a point's own planes (two
/// shadow planes through one occluder vertex meet in the ray from the
/// light through it, which every other such plane holds; the shadow plane
/// of an edge holds the edge's line).
pub fn in_pencil(a: &Plane, b: &Plane, q: &Plane) -> bool {
    let (na, nb, nq) = (
        a.normal().map(i128::from),
        b.normal().map(i128::from),
        q.normal().map(i128::from),
    );
    let direction = cross_i128(na, nb);
    if dot_sign(nq, direction) != Side::On {
        return false;
    }
    let Some(pivot) = (0..3).find(|&k| direction[k] != 0) else {
        return false;
    };
    let (alpha, beta) = combination([na, nb], nq, pivot);
    offset_combines(q, direction[pivot], [alpha, beta], [a.offset(), b.offset()])
}

/// The `(alpha, beta)`, scaled by `(na x nb)[pivot]`, with `nq = alpha na +
/// beta nb` (Cramer's rule on the two coordinates other than the pivot,
/// whose 2x2 determinant is that nonzero component), for `nq` orthogonal
/// to `na x nb`.
fn combination(normals: [[i128; 3]; 2], nq: [i128; 3], pivot: usize) -> (i128, i128) {
    let [na, nb] = normals;
    let (i, j) = ((pivot + 1) % 3, (pivot + 2) % 3);
    (nq[i] * nb[j] - nq[j] * nb[i], na[i] * nq[j] - na[j] * nq[i])
}

/// Whether `q`'s offset is the combination of `offsets` that its normal
/// is of the normals (scaled by `scale`): then it holds their line.
fn offset_combines(q: &Plane, scale: i128, combination: [i128; 2], offsets: [i128; 2]) -> bool {
    let wide = I256::from;
    wide(q.offset()) * wide(scale)
        == wide(combination[0]) * wide(offsets[0]) + wide(combination[1]) * wide(offsets[1])
}

/// `u x v` for normals (components at most 2^51; the product's below
/// 2^103).
fn cross_i128(u: [i128; 3], v: [i128; 3]) -> [i128; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

/// The line where two planes meet, set up once to ask of many planes
/// whether they hold it ([`in_pencil`] with its first two planes fixed:
/// the line's direction and the pivot are computed once).
#[derive(Debug, Clone, Copy)]
pub struct Pencil {
    normals: [[i128; 3]; 2],
    offsets: [i128; 2],
    /// The line's direction (components below 2^103).
    direction: [i128; 3],
    /// `direction`, `normals` and `offsets` rounded (the normals exactly),
    /// for the filters of [`Self::holds`].
    rounded: [f64; 3],
    rounded_normals: [[f64; 3]; 2],
    rounded_offsets: [f64; 2],
    /// A coordinate in which `direction` is not zero.
    pivot: usize,
}

impl Pencil {
    /// The line `a ∩ b`; `None` when the planes are parallel.
    pub fn new(a: &Plane, b: &Plane) -> Option<Self> {
        let (na, nb) = (a.normal().map(i128::from), b.normal().map(i128::from));
        let direction = cross_i128(na, nb);
        let pivot = (0..3).find(|&k| direction[k] != 0)?;
        Some(Self {
            normals: [na, nb],
            offsets: [a.offset(), b.offset()],
            direction,
            rounded: direction.map(|d| d as f64),
            rounded_normals: [a.normal().map(|c| c as f64), b.normal().map(|c| c as f64)],
            rounded_offsets: [a.approx()[3], b.approx()[3]],
            pivot,
        })
    }

    /// `false` when no plane with normal `normal` (a plane's normal
    /// converted to `f64`, which is exact) can hold the line: its normal
    /// is certainly not orthogonal to the line. The first test of
    /// [`Self::holds`], for callers that keep normals apart from their
    /// planes to scan many quickly.
    #[inline]
    pub fn may_hold(&self, normal: [f64; 3]) -> bool {
        // The filter of `dot_sign`, the direction rounded once: most
        // planes do not hold the line, and are told so here.
        let (mut estimate, mut permanent) = (0.0_f64, 0.0_f64);
        for (&n, &d) in normal.iter().zip(&self.rounded) {
            let term = n * d;
            estimate += term;
            permanent += term.abs();
        }
        estimate.abs() <= 8.0 * U * permanent
    }

    /// Whether `q` holds the line, exactly.
    pub fn holds(&self, q: &Plane) -> bool {
        let normal = q.normal().map(|c| c as f64);
        if !self.may_hold(normal) {
            return false;
        }
        // Past the filter `|nq . direction| < 2^110` (see `dot_sign`): the
        // wrapping sum is the exact value.
        let nq = q.normal().map(i128::from);
        if wrapping_dot(nq, self.direction) != 0 {
            return false;
        }
        // Planes whose lines on the receiver are parallel to this one end
        // here, most of them: the offset test in f64. The combination's
        // products are exact below 2^102 and rounded once, its difference
        // once more (within 2u of |p1| + |p2|); each term below is then
        // within 4u of |combination| |offset| (the offset rounded, one
        // product), the first within 3u of its value, the sum and the
        // difference within 2u more: in all within 6u of `permanent`, so
        // beyond 8u the offsets do not combine.
        let k = self.pivot;
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let [na, nb] = self.rounded_normals;
        let [oa, ob] = self.rounded_offsets;
        let (p1, p2) = (normal[i] * nb[j], normal[j] * nb[i]);
        let (p3, p4) = (na[i] * normal[j], na[j] * normal[i]);
        let t1 = q.approx()[3] * self.rounded[k];
        let (t2, t3) = ((p1 - p2) * oa, (p3 - p4) * ob);
        let permanent =
            t1.abs() + (p1.abs() + p2.abs()) * oa.abs() + (p3.abs() + p4.abs()) * ob.abs();
        if (t1 - (t2 + t3)).abs() > 8.0 * U * permanent {
            return false;
        }
        let (alpha, beta) = combination(self.normals, nq, k);
        offset_combines(q, self.direction[k], [alpha, beta], self.offsets)
    }
}

/// The sign of `u · v`, exactly, for `|u_k| < 2^53` and `|v_k| < 2^103`
/// (a normal and a cross product of two normals), without 256-bit
/// products.
///
/// The `f64` estimate `s'` of the dot product is within `5 u P'` of the
/// true `s` (depth 4: `v_k` rounded, product, two sums; `P'` the computed
/// permanent, itself within `gamma_4`), so `|s'| > 8 u P'` gives the sign.
/// Otherwise `|s| < 13 u P' < 2^110`, and the dot product taken modulo
/// `2^128` (wrapping `i128` arithmetic) is `s` itself.
#[inline]
pub(super) fn dot_sign(u: [i128; 3], v: [i128; 3]) -> Side {
    let (mut estimate, mut permanent) = (0.0_f64, 0.0_f64);
    for k in 0..3 {
        let term = u[k] as f64 * v[k] as f64;
        estimate += term;
        permanent += term.abs();
    }
    if estimate.abs() > 8.0 * U * permanent {
        return Side::of_sign(estimate);
    }
    Side::of_sign(wrapping_dot(u, v))
}

/// `u · v` modulo `2^128`: the value itself where it is known to be below
/// `2^127` in magnitude (past the filters of `dot_sign` and
/// [`Pencil::holds`]).
fn wrapping_dot(u: [i128; 3], v: [i128; 3]) -> i128 {
    (0..3).fold(0_i128, |acc, k| acc.wrapping_add(u[k].wrapping_mul(v[k])))
}
