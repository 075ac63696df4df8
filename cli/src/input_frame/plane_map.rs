//! The maps from a snapped polygon onto its input polygon: affine,
//! bilinear and projective, in a coordinate plane.

use smallvec::SmallVec;

use super::{centroid, planar_normal};
use crate::vec3::{dot, norm, sub};

/// A map between two nearly equal planar polygons, worked in the
/// coordinate plane of axes `u`, `v` (the input plane's normal is largest
/// along the third axis `k`).
#[derive(Debug, Clone)]
pub(super) struct PlaneMap {
    u: usize,
    v: usize,
    k: usize,
    /// Snapped corner 0 in the coordinate plane: points are mapped relative
    /// to it, so that the map's entries stay well scaled.
    from_origin: [f64; 2],
    /// Input corner 0.
    to_origin: [f64; 3],
    /// The input plane `normal . x = offset` (unit normal).
    normal: [f64; 3],
    offset: f64,
    kind: MapKind,
}

#[derive(Debug, Clone)]
enum MapKind {
    /// A projective map (affine for a triangle): homogeneous 3 x 3 matrix
    /// from coordinates relative to `from_origin` to coordinates (`u`,
    /// `v`) relative to `to_origin`.
    Projective([[f64; 3]; 3]),
    /// Bilinear interpolation of the input corners (relative to
    /// `to_origin`) at the snapped quad's bilinear coordinates of a point:
    /// each point moves by an average of the corners' moves, however thin
    /// the quad (a projective map can move a thin quad's middle by many
    /// grid steps).
    Bilinear {
        from: [[f64; 2]; 4],
        to: [[f64; 3]; 4],
    },
}

impl PlaneMap {
    /// The map taking the corners `from` (a snapped polygon, possibly bent
    /// along a diagonal) to `to` (a planar polygon), 3 or 4 of each in the
    /// same order: affine for a triangle, bilinear for a convex quad,
    /// projective for a concave one. `None` when `to` is not planar, either
    /// is degenerate, the two turn differently at some corner, or the map
    /// would move some point much farther than the corners moved.
    pub(super) fn new(from: &[[f64; 3]], to: &[[f64; 3]]) -> Option<Self> {
        let n = to.len();
        let normal = planar_normal(to)?;
        let size = (0..n)
            .map(|i| norm(sub(to[i], to[(i + 1) % n])))
            .fold(0.0, f64::max);
        let k = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs()))?;
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        let from_origin = [from[0][u], from[0][v]];
        let flat = |p: &[f64; 3], o: [f64; 2]| [p[u] - o[0], p[v] - o[1]];
        let a: SmallVec<[[f64; 2]; 4]> = from.iter().map(|p| flat(p, from_origin)).collect();
        let b: SmallVec<[[f64; 2]; 4]> = to.iter().map(|p| flat(p, [to[0][u], to[0][v]])).collect();
        // Same non-zero turn at every corner: the same shape, so the map
        // keeps the side each fragment faces.
        let turn = |q: &[[f64; 2]], i: usize| {
            let (p0, p1, p2) = (q[i], q[(i + 1) % n], q[(i + 2) % n]);
            (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0])
        };
        let turns: SmallVec<[f64; 4]> = (0..n).map(|i| turn(&b, i)).collect();
        if (0..n).any(|i| {
            let (s, t) = (turn(&a, i), turns[i]);
            s == 0.0 || t == 0.0 || (s > 0.0) != (t > 0.0)
        }) {
            return None;
        }
        let convex = turns.iter().all(|&t| (t > 0.0) == (turns[0] > 0.0));
        let kind = if n == 3 {
            MapKind::Projective(mul(
                &affine_from_triangle(&b)?,
                &inverse(&affine_from_triangle(&a)?)?,
            ))
        } else if convex {
            let relative = |p: &[f64; 3]| sub(*p, to[0]);
            MapKind::Bilinear {
                from: [a[0], a[1], a[2], a[3]],
                to: [
                    relative(&to[0]),
                    relative(&to[1]),
                    relative(&to[2]),
                    relative(&to[3]),
                ],
            }
        } else {
            MapKind::Projective(mul(
                &from_unit_square(&b)?,
                &inverse(&from_unit_square(&a)?)?,
            ))
        };
        let map = Self {
            u,
            v,
            k,
            from_origin,
            to_origin: to[0],
            normal,
            offset: dot(normal, centroid(to)),
            kind,
        };
        // The corners land where they belong (a projective map keeps them
        // on its side of the line at infinity: then all of the polygon,
        // their convex hull, stays there), and the middle of the polygon
        // and of its sides move about as far as the corners did.
        let moved = from
            .iter()
            .zip(to)
            .map(|(p, q)| norm(sub(*p, *q)))
            .fold(0.0, f64::max);
        let sign = map.weight(from[0]).signum();
        let lands = from.iter().zip(to).all(|(p, q)| {
            map.weight(*p) * sign > 0.0 && norm(sub(map.apply(*p), *q)) <= 1e-6 * size
        });
        let middles = (0..n)
            .map(|i| mid(from[i], from[(i + 1) % n]))
            .chain([centroid(from)]);
        let tame = middles
            .into_iter()
            .all(|p| norm(sub(map.apply(p), p)) <= 4.0 * moved + 1e-9 * size);
        (lands && tame).then_some(map)
    }

    /// The homogeneous weight of the point `p` (1 for a bilinear map).
    fn weight(&self, p: [f64; 3]) -> f64 {
        match &self.kind {
            MapKind::Projective(h) => {
                let x = self.flat(p);
                h[2][0] * x[0] + h[2][1] * x[1] + h[2][2]
            }
            MapKind::Bilinear { .. } => 1.0,
        }
    }

    /// `p` in the coordinate plane, relative to `from_origin`.
    pub(super) fn flat(&self, p: [f64; 3]) -> [f64; 2] {
        [
            p[self.u] - self.from_origin[0],
            p[self.v] - self.from_origin[1],
        ]
    }

    /// The image of `p` on the input plane.
    pub(super) fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let x = self.flat(p);
        match &self.kind {
            MapKind::Projective(h) => {
                let y = [0, 1, 2].map(|r| h[r][0] * x[0] + h[r][1] * x[1] + h[r][2]);
                let a = self.to_origin[self.u] + y[0] / y[2];
                let b = self.to_origin[self.v] + y[1] / y[2];
                let mut q = [0.0; 3];
                q[self.u] = a;
                q[self.v] = b;
                q[self.k] = (self.offset - self.normal[self.u] * a - self.normal[self.v] * b)
                    / self.normal[self.k];
                q
            }
            MapKind::Bilinear { from, to } => {
                let [s, t] = bilinear_coordinates(from, x);
                let q = [0, 1, 2].map(|c| {
                    let (q0, q1, q2, q3) = (to[0][c], to[1][c], to[2][c], to[3][c]);
                    q0 + s * (q1 - q0) + t * (q3 - q0) + s * t * (q0 - q1 + q2 - q3)
                });
                [0, 1, 2].map(|c| self.to_origin[c] + q[c])
            }
        }
    }
}

/// The coordinates `(s, t)` of `x` in the bilinear patch of the convex
/// quad `q` (corner 0 at `(0, 0)`, 1 at `(1, 0)`, 2 at `(1, 1)`, 3 at
/// `(0, 1)`): Newton's method from the parallelogram of corners 0, 1, 3,
/// which a nearly parallelogram quad (a snapped one) all but is.
fn bilinear_coordinates(q: &[[f64; 2]; 4], x: [f64; 2]) -> [f64; 2] {
    let e = [q[1][0] - q[0][0], q[1][1] - q[0][1]];
    let f = [q[3][0] - q[0][0], q[3][1] - q[0][1]];
    let g = [
        q[0][0] - q[1][0] + q[2][0] - q[3][0],
        q[0][1] - q[1][1] + q[2][1] - q[3][1],
    ];
    let h = [x[0] - q[0][0], x[1] - q[0][1]];
    let solve = |a: [f64; 2], b: [f64; 2], r: [f64; 2]| {
        let det = a[0] * b[1] - a[1] * b[0];
        [
            (r[0] * b[1] - r[1] * b[0]) / det,
            (a[0] * r[1] - a[1] * r[0]) / det,
        ]
    };
    let mut st = solve(e, f, h);
    for _ in 0..16 {
        let [s, t] = st;
        let residual = [0, 1].map(|c| e[c] * s + f[c] * t + g[c] * s * t - h[c]);
        let step = solve(
            [e[0] + g[0] * t, e[1] + g[1] * t],
            [f[0] + g[0] * s, f[1] + g[1] * s],
            residual,
        );
        if !(step[0].is_finite() && step[1].is_finite()) {
            break;
        }
        st = [s - step[0], t - step[1]];
        if step[0].abs() + step[1].abs() <= 4.0 * f64::EPSILON * (1.0 + s.abs() + t.abs()) {
            break;
        }
    }
    st
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|c| 0.5 * (a[c] + b[c]))
}

type Matrix = [[f64; 3]; 3];

/// The affine map taking (0, 0), (1, 0), (0, 1) to the corners `t`.
fn affine_from_triangle(t: &[[f64; 2]]) -> Option<Matrix> {
    let [p0, p1, p2] = [t[0], t[1], t[2]];
    Some([
        [p1[0] - p0[0], p2[0] - p0[0], p0[0]],
        [p1[1] - p0[1], p2[1] - p0[1], p0[1]],
        [0.0, 0.0, 1.0],
    ])
}

/// The projective map taking the unit square's corners (0, 0), (1, 0),
/// (1, 1), (0, 1) to the corners `q` (Heckbert's closed form).
fn from_unit_square(q: &[[f64; 2]]) -> Option<Matrix> {
    let [p0, p1, p2, p3] = [q[0], q[1], q[2], q[3]];
    let sx = p0[0] - p1[0] + p2[0] - p3[0];
    let sy = p0[1] - p1[1] + p2[1] - p3[1];
    let (dx1, dx2) = (p1[0] - p2[0], p3[0] - p2[0]);
    let (dy1, dy2) = (p1[1] - p2[1], p3[1] - p2[1]);
    let den = dx1 * dy2 - dx2 * dy1;
    if den == 0.0 || !den.is_finite() {
        return None;
    }
    let g = (sx * dy2 - dx2 * sy) / den;
    let h = (dx1 * sy - sx * dy1) / den;
    Some([
        [p1[0] - p0[0] + g * p1[0], p3[0] - p0[0] + h * p3[0], p0[0]],
        [p1[1] - p0[1] + g * p1[1], p3[1] - p0[1] + h * p3[1], p0[1]],
        [g, h, 1.0],
    ])
}

fn mul(a: &Matrix, b: &Matrix) -> Matrix {
    let mut m = [[0.0; 3]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = (0..3).map(|i| a[r][i] * b[i][c]).sum();
        }
    }
    m
}

/// The inverse matrix.
fn inverse(m: &Matrix) -> Option<Matrix> {
    let c =
        |r0: usize, r1: usize, c0: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let adj = [
        [c(1, 2, 1, 2), -c(0, 2, 1, 2), c(0, 1, 1, 2)],
        [-c(1, 2, 0, 2), c(0, 2, 0, 2), -c(0, 1, 0, 2)],
        [c(1, 2, 0, 1), -c(0, 2, 0, 1), c(0, 1, 0, 1)],
    ];
    let det = m[0][0] * adj[0][0] + m[0][1] * adj[1][0] + m[0][2] * adj[2][0];
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    Some(adj.map(|row| row.map(|x| x / det)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec3::cross;

    /// A convex quad in a tilted plane, and the same with each corner
    /// moved by up to `jiggle` (as snapping would).
    fn quads(jiggle: f64) -> ([[f64; 3]; 4], [[f64; 3]; 4]) {
        let at = |x: f64, z: f64| [x, 0.3 * x - 0.2 * z + 1.0, z];
        let input = [at(0.0, 0.0), at(0.0, 1.0), at(2.0, 1.3), at(1.7, -0.1)];
        let moves = [
            [1.0, -0.5, 0.3],
            [-0.7, 0.2, 1.0],
            [0.4, 0.9, -1.0],
            [-1.0, -1.0, 0.6],
        ];
        let mut snapped = input;
        for (s, m) in snapped.iter_mut().zip(moves) {
            *s = [0, 1, 2].map(|a| s[a] + jiggle * m[a]);
        }
        (input, snapped)
    }

    fn between(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
        [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]))
    }

    /// The largest distance between `a[i]` and `b[i]`.
    fn farthest(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(p, q)| norm(sub(*p, *q)))
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_convex_quad_maps_corner_to_corner_side_to_side_moving_no_point_farther() {
        let (input, snapped) = quads(1e-3);
        let map = PlaneMap::new(&snapped, &input).expect("a mappable quad");
        assert!(matches!(map.kind, MapKind::Bilinear { .. }));
        for (s, p) in snapped.iter().zip(&input) {
            assert!(norm(sub(map.apply(*s), *p)) < 1e-14, "{s:?}");
        }
        let normal = newell(&input);
        let moved = farthest(&snapped, &input);
        for i in 0..4 {
            let (s0, s1) = (snapped[i], snapped[(i + 1) % 4]);
            let (p0, p1) = (input[i], input[(i + 1) % 4]);
            for t in [0.1, 0.37, 0.5, 0.93] {
                // Along a side: onto the input side, at the same fraction.
                let q = map.apply(between(s0, s1, t));
                assert!(
                    norm(sub(q, between(p0, p1, t))) < 1e-14,
                    "side {i}, t = {t}"
                );
                // Inside: in the input plane, moved no farther than a corner.
                let inner = between(between(s0, s1, t), snapped[(i + 2) % 4], 0.6);
                let q = map.apply(inner);
                assert!(dot(sub(q, input[0]), normal).abs() < 1e-14);
                assert!(norm(sub(q, inner)) <= moved * (1.0 + 1e-9));
            }
        }
    }

    #[test]
    fn a_needle_moves_its_middle_no_farther_than_its_corners() {
        // 2000 long, 1 wide; the corners move by up to 0.005 across it.
        let input = [
            [0.0, 0.0, 0.0],
            [2000.0, 0.0, 0.0],
            [2000.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let moves = [
            [0.004, -0.003, 0.0],
            [-0.002, 0.005, 0.0],
            [0.003, -0.004, 0.0],
            [-0.005, 0.002, 0.0],
        ];
        let snapped: Vec<[f64; 3]> = input
            .iter()
            .zip(moves)
            .map(|(p, m)| [0, 1, 2].map(|c| p[c] + m[c]))
            .collect();
        let map = PlaneMap::new(&snapped, &input).expect("a mappable needle");
        let moved = farthest(&snapped, &input);
        for t in [0.25, 0.5, 0.75] {
            let p = between(
                between(snapped[0], snapped[1], t),
                between(snapped[3], snapped[2], t),
                0.5,
            );
            assert!(
                norm(sub(map.apply(p), p)) <= moved * (1.0 + 1e-9),
                "t = {t}"
            );
        }
        // The projective map through the same corners moves the middle by
        // hundreds of times as far.
        let flat = |q: &[[f64; 3]]| -> Vec<[f64; 2]> { q.iter().map(|p| [p[0], p[1]]).collect() };
        let h = mul(
            &from_unit_square(&flat(&input)).unwrap(),
            &inverse(&from_unit_square(&flat(&snapped)).unwrap()).unwrap(),
        );
        let p = between(
            between(snapped[0], snapped[1], 0.5),
            between(snapped[3], snapped[2], 0.5),
            0.5,
        );
        let y = [0, 1, 2].map(|r| h[r][0] * p[0] + h[r][1] * p[1] + h[r][2]);
        let q = [y[0] / y[2], y[1] / y[2], 0.0];
        assert!(norm(sub(q, p)) > 100.0 * moved, "{q:?}");
    }

    #[test]
    fn a_concave_quad_maps_projectively_lines_staying_lines() {
        // A dart: corner 2 turns the other way.
        let at = |x: f64, z: f64| [x, 0.3 * x - 0.2 * z + 1.0, z];
        let input = [at(0.0, 0.0), at(2.0, -1.0), at(0.8, 0.0), at(2.0, 1.0)];
        let moves = [
            [1.0, -0.5, 0.3],
            [-0.7, 0.2, 1.0],
            [0.4, 0.9, -1.0],
            [-1.0, -1.0, 0.6],
        ];
        let snapped: Vec<[f64; 3]> = input
            .iter()
            .zip(moves)
            .map(|(p, m)| [0, 1, 2].map(|c| p[c] + 1e-3 * m[c]))
            .collect();
        let map = PlaneMap::new(&snapped, &input).expect("a mappable dart");
        assert!(matches!(map.kind, MapKind::Projective(_)));
        for (s, p) in snapped.iter().zip(&input) {
            assert!(norm(sub(map.apply(*s), *p)) < 1e-14, "{s:?}");
        }
        // Points along the snapped line from corner 0 to corner 2 land on
        // the input line, in the input plane.
        let normal = newell(&input);
        for t in [0.1, 0.37, 0.5, 0.93] {
            let q = map.apply(between(snapped[0], snapped[2], t));
            let off = cross(sub(q, input[0]), sub(input[2], input[0]));
            assert!(norm(off) < 1e-14, "t = {t}: {off:?}");
            assert!(dot(sub(q, input[0]), normal).abs() < 1e-14);
        }
    }

    #[test]
    fn a_quad_that_turns_the_other_way_is_not_mapped() {
        let (input, _) = quads(0.0);
        // Corner 3 pushed across the line of corners 2 and 0: the snapped
        // copy is concave where the input is convex.
        let mut snapped = input;
        snapped[3] = between(input[0], input[2], 0.5);
        snapped[3] = [0, 1, 2].map(|k| snapped[3][k] + 0.01 * (snapped[3][k] - input[3][k]));
        assert!(PlaneMap::new(&snapped, &input).is_none());
        // A non-planar input is not mapped either.
        let mut bent = input;
        bent[2][1] += 1e-3;
        assert!(PlaneMap::new(&input, &bent).is_none());
    }

    fn newell(points: &[[f64; 3]]) -> [f64; 3] {
        let mut n = [0.0; 3];
        for i in 0..points.len() {
            let c = cross(points[i], points[(i + 1) % points.len()]);
            n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
        }
        n
    }
}
