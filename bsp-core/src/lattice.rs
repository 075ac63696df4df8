//! The grid points of a plane, as a 2D lattice: `origin + i u + j v` for
//! integers `i`, `j`, with a short (reduced) basis `u`, `v`.
//!
//! Whatever a plane's tilt, its grid points form such a lattice, so work
//! that must stay on grid points in a tilted plane can count in lattice
//! steps: a joint-umbra proof halves an area light into lattice
//! parallelograms; snapping a tilted light puts its corners on the nearest
//! lattice points of one plane (a plane in an axis-aligned plane gets the
//! plain axes).

use crate::{GridPoint, Plane};

/// A plane's grid points as the integer combinations of two vectors.
#[derive(Debug, Clone, Copy)]
pub struct PlaneLattice {
    origin: [i64; 3],
    u: [i64; 3],
    v: [i64; 3],
    /// The plane's primitive normal.
    normal: [i64; 3],
    /// `(u x v) . normal`: the divisor of the coordinates (nonzero).
    det: i128,
}

impl PlaneLattice {
    /// The lattice of the plane `support` through its grid point `on`;
    /// `None` if a vector is out of range.
    pub fn of(support: &Plane, on: GridPoint) -> Option<Self> {
        let n = support.normal();
        let g = gcd(gcd(n[0], n[1]), n[2]);
        if g == 0 {
            return None;
        }
        let normal = n.map(|c| c / g);
        let (u, v) = match (0..3).find(|&k| (0..3).all(|m| m == k || normal[m] == 0)) {
            // An axis-aligned plane: the other two axes, in the order the
            // rest of the module has always used.
            Some(k) => (unit((k + 1) % 3), unit((k + 2) % 3)),
            None => reduced(basis(normal)?)?,
        };
        let det = dot(cross(u, v), normal);
        if det == 0 {
            return None;
        }
        Some(Self {
            origin: on.to_i64(),
            u,
            v,
            normal,
            det,
        })
    }

    /// The coordinates `(i, j)` of a grid point of the plane.
    pub fn coords(&self, p: GridPoint) -> [i64; 2] {
        let d = sub(p.to_i64(), self.origin);
        // d = i u + j v: d x v = i (u x v), u x d = j (u x v).
        let i = dot(cross(d, self.v), self.normal) / self.det;
        let j = dot(cross(self.u, d), self.normal) / self.det;
        [i as i64, j as i64]
    }

    /// The grid point with coordinates `(i, j)`, if in range.
    pub fn point(&self, [i, j]: [i64; 2]) -> Option<GridPoint> {
        let c = |k: usize| -> Option<i64> {
            let v = i128::from(self.origin[k])
                + i128::from(i) * i128::from(self.u[k])
                + i128::from(j) * i128::from(self.v[k]);
            i64::try_from(v).ok()
        };
        GridPoint::new(c(0)?, c(1)?, c(2)?).ok()
    }

    /// The lattice point nearest to `q` (grid units, anywhere in space),
    /// if in range: `q`'s lattice coordinates rounded (close to nearest, as
    /// the basis is reduced), then the nearest of that point and its eight
    /// neighbours.
    pub fn nearest(&self, q: [f64; 3]) -> Option<GridPoint> {
        let f = |a: [i64; 3]| a.map(|c| c as f64);
        let d = [0, 1, 2].map(|k| q[k] - self.origin[k] as f64);
        let (u, v, n) = (f(self.u), f(self.v), f(self.normal));
        let det = self.det as f64;
        let i = dot_f64(cross_f64(d, v), n) / det;
        let j = dot_f64(cross_f64(u, d), n) / det;
        if !(i.is_finite() && j.is_finite()) {
            return None;
        }
        let (i, j) = (i.round() as i64, j.round() as i64);
        let mut best: Option<(f64, GridPoint)> = None;
        for di in -1..=1 {
            for dj in -1..=1 {
                let Some(p) = self.point([i + di, j + dj]) else {
                    continue;
                };
                let g = p.to_f64();
                let distance = (0..3).map(|k| (g[k] - q[k]).powi(2)).sum::<f64>();
                if best.is_none_or(|(b, _)| distance < b) {
                    best = Some((distance, p));
                }
            }
        }
        best.map(|(_, p)| p)
    }

    /// Where the plane `cut` meets the lattice's plane in a line of
    /// constant `i` (`(0, i)`) or constant `j` (`(1, j)`), if it does.
    pub fn line_of(&self, cut: &Plane) -> Option<(usize, i64)> {
        let r = cut.normal();
        let (ru, rv) = (dot(r, self.u), dot(r, self.v));
        // On the line origin + c u + j v (all j) when r . v = 0 and
        // r . (origin + c u) + offset = 0; likewise with u and v swapped.
        let (side, along) = match (ru, rv) {
            (0, 0) => return None,
            (_, 0) => (0, ru),
            (0, _) => (1, rv),
            _ => return None,
        };
        let at = -(dot(r, self.origin) + cut.offset());
        (at % along == 0)
            .then(|| i64::try_from(at / along).ok())
            .flatten()
            .map(|c| (side, c))
    }
}

fn unit(k: usize) -> [i64; 3] {
    let mut e = [0; 3];
    e[k] = 1;
    e
}

/// A basis of the integer vectors orthogonal to `n` (primitive, not along
/// an axis): `(b, -a, 0) / g` and `(-s c, -t c, g)` where `g = gcd(a, b) =
/// s a + t b`.
fn basis(n: [i64; 3]) -> Option<([i64; 3], [i64; 3])> {
    let [a, b, c] = n.map(i128::from);
    let (g, s, t) = extended_gcd(a, b);
    if g == 0 {
        return None;
    }
    let u = [b / g, -a / g, 0];
    let v = [-s * c, -t * c, g];
    let narrow = |w: [i128; 3]| -> Option<[i64; 3]> {
        Some([
            i64::try_from(w[0]).ok()?,
            i64::try_from(w[1]).ok()?,
            i64::try_from(w[2]).ok()?,
        ])
    };
    Some((narrow(u)?, narrow(v)?))
}

/// Lagrange-Gauss reduction: the shortest basis of the same lattice, so
/// that its parallelograms are as square as the lattice allows.
fn reduced((mut u, mut v): ([i64; 3], [i64; 3])) -> Option<([i64; 3], [i64; 3])> {
    loop {
        if dot(u, u) > dot(v, v) {
            std::mem::swap(&mut u, &mut v);
        }
        let (uv, uu) = (dot(u, v), dot(u, u));
        if uu == 0 {
            return None;
        }
        // The nearest integer to uv / uu.
        let m = (2 * uv + uu).div_euclid(2 * uu);
        if m == 0 {
            return Some((u, v));
        }
        let m = i64::try_from(m).ok()?;
        v = [0, 1, 2].map(|k| v[k] - m * u[k]);
    }
}

fn extended_gcd(a: i128, b: i128) -> (i128, i128, i128) {
    let (mut r0, mut r1, mut s0, mut s1, mut t0, mut t1) = (a, b, 1, 0, 0, 1);
    while r1 != 0 {
        let q = r0.div_euclid(r1);
        (r0, r1) = (r1, r0 - q * r1);
        (s0, s1) = (s1, s0 - q * s1);
        (t0, t1) = (t1, t0 - q * t1);
    }
    if r0 < 0 {
        (-r0, -s0, -t0)
    } else {
        (r0, s0, t0)
    }
}

fn gcd(a: i64, b: i64) -> i64 {
    let (mut a, mut b) = (a.unsigned_abs(), b.unsigned_abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a as i64
}

fn sub(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [0, 1, 2].map(|k| a[k] - b[k])
}

fn cross(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [i64; 3], b: [i64; 3]) -> i128 {
    (0..3).map(|k| i128::from(a[k]) * i128::from(b[k])).sum()
}

fn cross_f64(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot_f64(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint::new(x, y, z).unwrap()
    }

    #[test]
    fn a_tilted_planes_grid_points_are_its_lattice() {
        // The plane 3x + 5y + 7z = 39 through (2, 1, 4).
        let (p, q, r) = (g(2, 1, 4), g(7, -2, 4), g(9, 1, 1));
        let plane = Plane::through(p, q, r).unwrap();
        let lattice = PlaneLattice::of(&plane, p).unwrap();
        assert_eq!(lattice.det.abs(), 83, "u x v is the primitive normal");
        for point in [p, q, r, g(2, 8, -1), g(-3, 11, -1)] {
            let ij = lattice.coords(point);
            assert_eq!(lattice.point(ij), Some(point), "{point:?} at {ij:?}");
        }
        // The reduced basis is short: no longer than the lattice needs.
        assert!(dot(lattice.u, lattice.u) <= dot(lattice.v, lattice.v));
        assert!(dot(lattice.v, lattice.v) <= 2 * 83);
    }

    #[test]
    fn an_axis_plane_keeps_its_axes_and_meets_cuts_in_lines() {
        let plane = Plane::through(g(0, 10, 0), g(0, 10, 1), g(1, 10, 0)).unwrap();
        let lattice = PlaneLattice::of(&plane, g(3, 10, 4)).unwrap();
        assert_eq!(lattice.point([2, 5]), Some(g(3 + 5, 10, 4 + 2)));
        // The receiver x = 7 meets it in a line of constant j (along z).
        let wall = Plane::through(g(7, 0, 0), g(7, 1, 0), g(7, 0, 1)).unwrap();
        assert_eq!(lattice.line_of(&wall), Some((1, 4)));
        // A slanted receiver through the line x + y = 17: x = 7 too.
        let slant = Plane::through(g(7, 10, 0), g(7, 10, 1), g(8, 9, 0)).unwrap();
        assert_eq!(lattice.line_of(&slant), Some((1, 4)));
        // A plane parallel to the light's meets it nowhere.
        let ceiling = Plane::through(g(0, 11, 0), g(0, 11, 1), g(1, 11, 0)).unwrap();
        assert_eq!(lattice.line_of(&ceiling), None);
    }
}
