//! The maps from a snapped polygon onto its input polygon, in a
//! coordinate plane: bilinear for a convex quad in one piece, affine on
//! each triangle of the polygon's convex pieces (fanned) otherwise. Either
//! moves each point by an average of the corners' moves.

use smallvec::SmallVec;

use super::planar_normal;
use crate::vec3::sub;

/// A map between two nearly equal planar polygons, worked in the
/// coordinate plane of axes `u`, `v` (the input plane's normal is largest
/// along the third axis).
#[derive(Debug, Clone)]
pub(super) struct PlaneMap {
    u: usize,
    v: usize,
    /// Snapped corner 0 in the coordinate plane: points are mapped relative
    /// to it, so that differences stay exact.
    from_origin: [f64; 2],
    /// Input corner 0.
    to_origin: [f64; 3],
    /// The snapped corners in the coordinate plane, relative to
    /// `from_origin`.
    from: SmallVec<[[f64; 2]; 4]>,
    /// The input corners, relative to `to_origin`.
    to: SmallVec<[[f64; 3]; 4]>,
    kind: MapKind,
}

#[derive(Debug, Clone)]
enum MapKind {
    /// Bilinear interpolation of the input corners at the snapped quad's
    /// bilinear coordinates of a point: smooth across the quad, sides
    /// onto sides. (The projective map through the same corners, which
    /// would keep every line straight, moves the middle of a thin quad by
    /// hundreds of grid steps.)
    Bilinear,
    /// Affine on each triangle (corner indices), which the snapped and the
    /// input polygon both turn the same way.
    Triangles(SmallVec<[[u16; 3]; 2]>),
}

/// The most corners a mapped polygon has (locating a point takes time
/// linear in them).
const MOST_CORNERS: usize = 1024;

impl PlaneMap {
    /// The map taking the corners `from` (a snapped polygon, possibly bent
    /// along a diagonal) to `to` (a planar polygon), in the same order.
    /// `None` when `to` is not planar, either is degenerate, or the two
    /// turn differently at some corner.
    pub(super) fn new(
        from: &[[f64; 3]],
        to: &[[f64; 3]],
        pieces: &[SmallVec<[u16; 4]>],
    ) -> Option<Self> {
        let n = to.len();
        if !(3..=MOST_CORNERS).contains(&n) || from.len() != n {
            return None;
        }
        let normal = planar_normal(to)?;
        let k = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs()))?;
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        let from_origin = [from[0][u], from[0][v]];
        let a: SmallVec<[[f64; 2]; 4]> = from
            .iter()
            .map(|p| [p[u] - from_origin[0], p[v] - from_origin[1]])
            .collect();
        let b: SmallVec<[[f64; 2]; 4]> = to
            .iter()
            .map(|p| [p[u] - to[0][u], p[v] - to[0][v]])
            .collect();
        // The same turn at every corner, or none in one of them (a corner
        // welded onto an input side lies on it; its snapped copy, half a
        // step off): the same shape.
        let turn = |q: &[[f64; 2]], i: usize| {
            let (p0, p1, p2) = (q[i], q[(i + 1) % n], q[(i + 2) % n]);
            let t = orient(p0, p1, p2);
            let scale = norm2(sub2(p1, p0)).sqrt() * norm2(sub2(p2, p1)).sqrt();
            if t.abs() <= 1e-12 * scale { 0.0 } else { t }
        };
        let turns: SmallVec<[f64; 4]> = (0..n).map(|i| turn(&b, i)).collect();
        if (0..n).any(|i| turn(&a, i) * turns[i] < 0.0) {
            return None;
        }
        let convex = turns
            .iter()
            .all(|&t| t != 0.0 && (t > 0.0) == (turns[0] > 0.0));
        let kind = if n == 4 && convex && pieces.len() == 1 && pieces[0].len() == 4 {
            MapKind::Bilinear
        } else {
            MapKind::Triangles(fans(pieces, &a, &b)?)
        };
        Some(Self {
            u,
            v,
            from_origin,
            to_origin: to[0],
            from: a,
            to: to.iter().map(|p| sub(*p, to[0])).collect(),
            kind,
        })
    }

    /// `p` in the coordinate plane, relative to `from_origin`.
    pub(super) fn flat(&self, p: [f64; 3]) -> [f64; 2] {
        [
            p[self.u] - self.from_origin[0],
            p[self.v] - self.from_origin[1],
        ]
    }

    /// The image of `p` on the input polygon.
    pub(super) fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let x = self.flat(p);
        let (q, to) = (&self.from, &self.to);
        let relative = match &self.kind {
            MapKind::Bilinear => {
                let [s, t] = bilinear_coordinates([q[0], q[1], q[2], q[3]], x);
                [0, 1, 2].map(|c| {
                    let (q0, q1, q2, q3) = (to[0][c], to[1][c], to[2][c], to[3][c]);
                    q0 + s * (q1 - q0) + t * (q3 - q0) + s * t * (q0 - q1 + q2 - q3)
                })
            }
            MapKind::Triangles(triangles) => {
                // The triangle the point is deepest inside (near a shared
                // side either gives all but the same place).
                let (weights, corners) = triangles
                    .iter()
                    .map(|t| {
                        let [i, j, l] = t.map(usize::from);
                        (barycentric([q[i], q[j], q[l]], x), [i, j, l])
                    })
                    .max_by(|(w, _), (z, _)| {
                        let least = |w: &[f64; 3]| w.iter().fold(f64::INFINITY, |m, &c| m.min(c));
                        least(w).total_cmp(&least(z))
                    })
                    .unwrap_or(([1.0, 0.0, 0.0], [0, 0, 0]));
                [0, 1, 2].map(|c| (0..3).map(|m| weights[m] * to[corners[m]][c]).sum())
            }
        };
        [0, 1, 2].map(|c| self.to_origin[c] + relative[c])
    }
}

/// Twice the signed area of the triangle `a`, `b`, `c`.
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The barycentric coordinates of `x` in the triangle `t`.
fn barycentric(t: [[f64; 2]; 3], x: [f64; 2]) -> [f64; 3] {
    let area = orient(t[0], t[1], t[2]);
    let w1 = orient(t[0], x, t[2]) / area;
    let w2 = orient(t[0], t[1], x) / area;
    [1.0 - w1 - w2, w1, w2]
}

/// The pieces (corner indices) cut into triangles fanned from their first
/// corners: each turning the way the polygon `a` does, and in `b` (the
/// same corners moved a little) the same way or not at all (corners on one
/// side of `b`). `None` for no pieces, or a triangle that `b` turns over.
fn fans(
    pieces: &[SmallVec<[u16; 4]>],
    a: &[[f64; 2]],
    b: &[[f64; 2]],
) -> Option<SmallVec<[[u16; 3]; 2]>> {
    let sense = |q: &[[f64; 2]]| {
        (0..q.len())
            .map(|i| orient([0.0; 2], q[i], q[(i + 1) % q.len()]))
            .sum::<f64>()
            .signum()
    };
    let (sa, sb) = (sense(a), sense(b));
    let shape = |q: &[[f64; 2]], s: f64, [i, j, l]: [usize; 3]| {
        let sides = norm2(sub2(q[i], q[j])) + norm2(sub2(q[j], q[l])) + norm2(sub2(q[l], q[i]));
        s * orient(q[i], q[j], q[l]) / sides
    };
    let mut out = SmallVec::new();
    for piece in pieces {
        for k in 1..piece.len().saturating_sub(1) {
            let t = [piece[0], piece[k], piece[k + 1]];
            let corners = t.map(usize::from);
            if corners.iter().any(|&c| c >= a.len()) {
                return None;
            }
            if !(shape(a, sa, corners) > 0.0 && shape(b, sb, corners) >= -1e-12) {
                return None;
            }
            out.push(t);
        }
    }
    (!out.is_empty()).then_some(out)
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn norm2(a: [f64; 2]) -> f64 {
    a[0] * a[0] + a[1] * a[1]
}

/// The coordinates `(s, t)` of `x` in the bilinear patch of the convex
/// quad `q` (corner 0 at `(0, 0)`, 1 at `(1, 0)`, 2 at `(1, 1)`, 3 at
/// `(0, 1)`): Newton's method from the parallelogram of corners 0, 1, 3,
/// which a nearly parallelogram quad (a snapped one) all but is.
fn bilinear_coordinates(q: [[f64; 2]; 4], x: [f64; 2]) -> [f64; 2] {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec3::{cross, dot, norm};

    /// One piece of `n` corners.
    fn whole(n: u16) -> [SmallVec<[u16; 4]>; 1] {
        [(0..n).collect()]
    }

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
    fn a_convex_quad_maps_bilinearly() {
        let (input, snapped) = quads(1e-3);
        let map = PlaneMap::new(&snapped, &input, &whole(4)).expect("a mappable quad");
        assert!(matches!(map.kind, MapKind::Bilinear));
        check_polygon(&map, &snapped, &input);
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
        let map = PlaneMap::new(&snapped, &input, &whole(4)).expect("a mappable needle");
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
    }

    /// Checks that `map` takes each corner of `snapped` to its input
    /// corner, each side onto its input side at the same fraction, and
    /// points inside into the input plane, moved no farther than a corner.
    fn check_polygon(map: &PlaneMap, snapped: &[[f64; 3]], input: &[[f64; 3]]) {
        let n = input.len();
        for (s, p) in snapped.iter().zip(input) {
            assert!(norm(sub(map.apply(*s), *p)) < 1e-14, "{s:?}");
        }
        let normal = newell(input);
        let moved = farthest(snapped, input);
        for i in 0..n {
            for t in [0.1, 0.37, 0.5, 0.93] {
                let side = between(snapped[i], snapped[(i + 1) % n], t);
                let q = map.apply(side);
                let want = between(input[i], input[(i + 1) % n], t);
                assert!(norm(sub(q, want)) < 1e-14, "side {i}, t = {t}");
            }
        }
        // Inside: points of the triangles (of a convex quad, towards the
        // corner two on).
        let triangles: Vec<[usize; 3]> = match &map.kind {
            MapKind::Triangles(ts) => ts.iter().map(|t| t.map(usize::from)).collect(),
            MapKind::Bilinear => vec![[0, 1, 2], [0, 2, 3], [1, 2, 3], [0, 1, 3]],
        };
        for [i, j, l] in triangles {
            for (s, t) in [(0.2, 0.3), (0.5, 0.5), (0.7, 0.1), (0.05, 0.9)] {
                let inner = between(between(snapped[i], snapped[j], s), snapped[l], t);
                let q = map.apply(inner);
                assert!(dot(sub(q, input[0]), normal).abs() < 1e-14);
                assert!(norm(sub(q, inner)) <= moved * (1.0 + 1e-9));
            }
        }
    }

    fn jiggled(input: &[[f64; 3]], jiggle: f64) -> Vec<[f64; 3]> {
        let moves = [
            [1.0, -0.5, 0.3],
            [-0.7, 0.2, 1.0],
            [0.4, 0.9, -1.0],
            [-1.0, -1.0, 0.6],
        ];
        input
            .iter()
            .enumerate()
            .map(|(i, p)| [0, 1, 2].map(|c| p[c] + jiggle * moves[i % 4][c]))
            .collect()
    }

    #[test]
    fn a_concave_quad_and_an_l_shape_map_on_their_pieces() {
        let at = |x: f64, z: f64| [x, 0.3 * x - 0.2 * z + 1.0, z];
        // A dart (corner 2 turns the other way), and an L.
        let dart = [at(0.0, 0.0), at(2.0, -1.0), at(0.8, 0.0), at(2.0, 1.0)];
        let l = [
            at(0.0, 0.0),
            at(0.0, 2.0),
            at(1.0, 2.0),
            at(1.0, 1.0),
            at(2.0, 1.0),
            at(2.0, 0.0),
        ];
        // Their convex pieces.
        let dart_pieces = [
            SmallVec::from_slice(&[0, 1, 2]),
            SmallVec::from_slice(&[0, 2, 3]),
        ];
        let l_pieces = [
            SmallVec::from_slice(&[0, 1, 2, 3]),
            SmallVec::from_slice(&[0, 3, 4, 5]),
        ];
        for (input, pieces) in [(&dart[..], &dart_pieces), (&l[..], &l_pieces)] {
            let snapped = jiggled(input, 1e-3);
            let map = PlaneMap::new(&snapped, input, pieces).expect("a mappable polygon");
            assert!(matches!(map.kind, MapKind::Triangles(_)));
            check_polygon(&map, &snapped, input);
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
        assert!(PlaneMap::new(&snapped, &input, &whole(4)).is_none());
        // A non-planar input is not mapped either.
        let mut bent = input;
        bent[2][1] += 1e-3;
        assert!(PlaneMap::new(&input, &bent, &whole(4)).is_none());
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
