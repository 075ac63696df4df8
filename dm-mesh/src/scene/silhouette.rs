//! A convex solid's silhouette from a point outside it.
//!
//! The faces of a convex solid that a point sees (those with the point in
//! front) make one patch of its boundary; seen from the point, the patch
//! covers the solid, and its outline is the silhouette: the edges of those
//! faces that no other of them shares. Directed counter-clockwise as seen
//! from the point, each shared edge comes once in each direction, and the
//! rest chain into one loop. `illum` hides by the cone over that loop what
//! the faces would each hide (`Occluder::Silhouette`), in one region.
//!
//! The corners are numbered, and each face edge knows the face across it,
//! once, when the solid is made: a silhouette, asked for at every vertex a
//! solid may shadow, is then a scan of the seen faces' edges and a walk
//! along small numbers.

use crate::hash::KeyMap;
use smallvec::SmallVec;

type Point = [f64; 3];

/// No corner (in [`SolidCorners::silhouette`]'s chain).
const NONE: u8 = u8::MAX;

/// A closed convex solid's corners, each once, and its faces as loops of
/// corner numbers, each edge with the face across it.
#[derive(Debug, Clone)]
pub(crate) struct SolidCorners {
    points: Vec<Point>,
    /// Per face, per corner: its number, and the face across the edge from
    /// it to the next corner.
    faces: Vec<SmallVec<[(u8, u8); 4]>>,
}

impl SolidCorners {
    /// The corners of a closed convex solid's faces (each face's
    /// counter-clockwise seen from outside), numbered: corners of several
    /// faces are one where their coordinates are equal. `None` past 255
    /// corners or faces, and where an edge is not one other face's edge
    /// run the other way (faces whose shared corners were rounded apart,
    /// vertices made by cuts off the grid, or an edge cut in two on one
    /// side only): its silhouette is not sought.
    pub(crate) fn new<'a>(faces: impl ExactSizeIterator<Item = &'a [Point]>) -> Option<Self> {
        if faces.len() >= usize::from(NONE) {
            return None;
        }
        let mut number: KeyMap<[u64; 3], u8> = KeyMap::default();
        let mut points = Vec::new();
        let mut numbered: Vec<SmallVec<[u8; 4]>> = Vec::new();
        for corners in faces {
            let mut face = SmallVec::new();
            for &point in corners {
                // (-0.0 and 0.0 are one point.)
                let key = point.map(|x| (x + 0.0).to_bits());
                let n = match number.get(&key) {
                    Some(&n) => n,
                    None => {
                        let n = u8::try_from(points.len()).ok().filter(|&n| n != NONE)?;
                        number.insert(key, n);
                        points.push(point);
                        n
                    }
                };
                face.push(n);
            }
            numbered.push(face);
        }
        // Each directed edge's face; every edge is met once each way.
        let mut owner: KeyMap<(u8, u8), u8> = KeyMap::default();
        for (i, face) in numbered.iter().enumerate() {
            for edge in edges_of(face) {
                if owner.insert(edge, i as u8).is_some() {
                    return None;
                }
            }
        }
        let faces = numbered
            .iter()
            .map(|face| {
                edges_of(face)
                    .map(|(a, b)| Some((a, *owner.get(&(b, a))?)))
                    .collect::<Option<SmallVec<[(u8, u8); 4]>>>()
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Self { points, faces })
    }

    /// Appends to `out` the silhouette from a point outside the solid,
    /// given which faces the point sees (by number, `seen`): the edges from
    /// a seen face to one not seen, chained counter-clockwise as seen from
    /// the point. Returns whether it did (where they make no single loop,
    /// a point nearly in a face's plane seen by rounding, `out` is as it
    /// was: the faces are to be taken one by one).
    pub(crate) fn silhouette(
        &self,
        seen: impl Fn(usize) -> bool,
        out: &mut SmallVec<[Point; 24]>,
    ) -> bool {
        // next[a]: the corner the silhouette edge from corner a runs to.
        let mut next = [NONE; 256];
        let (mut first, mut count) = (NONE, 0);
        for (i, face) in self.faces.iter().enumerate() {
            if !seen(i) {
                continue;
            }
            let n = face.len();
            for k in 0..n {
                let (a, across) = face[k];
                if seen(usize::from(across)) {
                    continue;
                }
                if next[usize::from(a)] != NONE {
                    return false;
                }
                next[usize::from(a)] = face[(k + 1) % n].0;
                first = a;
                count += 1;
            }
        }
        if count < 3 {
            return false;
        }
        let start = out.len();
        let mut at = first;
        loop {
            out.push(self.points[usize::from(at)]);
            at = next[usize::from(at)];
            if at == first || at == NONE || out.len() - start > count {
                break;
            }
        }
        if at != first || out.len() - start != count {
            out.truncate(start);
            return false;
        }
        true
    }
}

/// A face's edges, as pairs of corner numbers.
fn edges_of(face: &[u8]) -> impl Iterator<Item = (u8, u8)> + '_ {
    let n = face.len();
    (0..n).map(move |k| (face[k], face[(k + 1) % n]))
}

#[cfg(test)]
mod tests {
    use super::SolidCorners;
    use smallvec::SmallVec;

    /// The unit cube's faces, counter-clockwise seen from outside, with
    /// their outward normals.
    fn cube() -> Vec<([f64; 3], Vec<[f64; 3]>)> {
        let c = |x: u8, y: u8, z: u8| [f64::from(x), f64::from(y), f64::from(z)];
        vec![
            (
                [-1.0, 0.0, 0.0],
                vec![c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)],
            ),
            (
                [1.0, 0.0, 0.0],
                vec![c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)],
            ),
            (
                [0.0, -1.0, 0.0],
                vec![c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)],
            ),
            (
                [0.0, 1.0, 0.0],
                vec![c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)],
            ),
            (
                [0.0, 0.0, -1.0],
                vec![c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)],
            ),
            (
                [0.0, 0.0, 1.0],
                vec![c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)],
            ),
        ]
    }

    /// The silhouette of the unit cube from `p`, its faces starting at
    /// their corner `first`.
    fn from(p: [f64; 3], first: usize) -> Option<Vec<[f64; 3]>> {
        let faces: Vec<([f64; 3], Vec<[f64; 3]>)> = cube()
            .into_iter()
            .map(|(n, mut corners)| {
                corners.rotate_left(first);
                (n, corners)
            })
            .collect();
        let solid = SolidCorners::new(faces.iter().map(|(_, c)| c.as_slice())).expect("8 corners");
        let seen = |i: usize| {
            let (n, corners) = &faces[i];
            let d: f64 = (0..3).map(|a| n[a] * (p[a] - corners[0][a])).sum();
            d > 0.0
        };
        let mut out = SmallVec::new();
        solid.silhouette(seen, &mut out).then(|| out.to_vec())
    }

    /// Whether `loop_` runs counter-clockwise seen from `p` (each corner
    /// turning left).
    fn counter_clockwise_from(p: [f64; 3], loop_: &[[f64; 3]]) -> bool {
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let n = loop_.len();
        (0..n).all(|i| {
            let (a, b, c) = (loop_[i], loop_[(i + 1) % n], loop_[(i + 2) % n]);
            let (u, v, w) = (sub(a, p), sub(b, p), sub(c, p));
            // The triple product of the three rays: negative when the turn
            // at b is to the left seen from p.
            let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]);
            det < 0.0
        })
    }

    #[test]
    fn one_face_seen_is_its_own_outline() {
        let p = [0.5, 0.5, 3.0];
        let out = from(p, 0).expect("a loop");
        assert_eq!(out.len(), 4);
        assert!(counter_clockwise_from(p, &out));
    }

    #[test]
    fn two_faces_seen_give_a_hexagon() {
        let p = [0.5, 3.0, 3.0];
        for first in 0..4 {
            let out = from(p, first).expect("a loop");
            assert_eq!(out.len(), 6, "{out:?}");
            assert!(counter_clockwise_from(p, &out), "{out:?}");
        }
    }

    #[test]
    fn three_faces_seen_give_a_hexagon_without_the_near_corner() {
        let p = [3.0, 3.0, 3.0];
        let out = from(p, 2).expect("a loop");
        assert_eq!(out.len(), 6, "{out:?}");
        assert!(!out.contains(&[1.0, 1.0, 1.0]), "{out:?}");
        assert!(counter_clockwise_from(p, &out));
    }

    #[test]
    fn corners_rounded_apart_make_no_solid() {
        let mut faces: Vec<Vec<[f64; 3]>> = cube().into_iter().map(|(_, c)| c).collect();
        assert!(SolidCorners::new(faces.iter().map(|f| f.as_slice())).is_some());
        // The corner (1, 1, 1) of the top face an ulp apart from the
        // others'.
        faces[5][2][0] = 1.0 + f64::EPSILON;
        assert!(SolidCorners::new(faces.iter().map(|f| f.as_slice())).is_none());
    }

    #[test]
    fn a_face_cut_in_two_shares_its_cut() {
        // The top face as two triangles: their shared diagonal runs both
        // ways, and is no silhouette edge when both are seen.
        let mut faces: Vec<Vec<[f64; 3]>> = cube().into_iter().map(|(_, c)| c).collect();
        let top = faces.pop().expect("six faces");
        faces.push(vec![top[0], top[1], top[2]]);
        faces.push(vec![top[0], top[2], top[3]]);
        let solid = SolidCorners::new(faces.iter().map(|f| f.as_slice())).expect("closed");
        let mut out = SmallVec::new();
        assert!(solid.silhouette(|i| i >= 5, &mut out));
        assert_eq!(out.len(), 4, "{out:?}");
    }

    #[test]
    fn a_seen_set_no_point_sees_makes_no_loop() {
        // Two opposite faces: two loops, not one.
        let faces: Vec<Vec<[f64; 3]>> = cube().into_iter().map(|(_, c)| c).collect();
        let solid = SolidCorners::new(faces.iter().map(|f| f.as_slice())).expect("closed");
        let mut out: SmallVec<[[f64; 3]; 24]> = SmallVec::new();
        out.push([9.0; 3]);
        assert!(!solid.silhouette(|i| i == 0 || i == 1, &mut out));
        assert_eq!(out.as_slice(), &[[9.0; 3]], "left as it was");
    }

    /// A prism over a regular `n`-gon: its faces, counter-clockwise seen
    /// from outside.
    fn prism(n: usize) -> Vec<Vec<[f64; 3]>> {
        let at = |i: usize, z: f64| {
            let t = std::f64::consts::TAU * (i % n) as f64 / n as f64;
            [t.cos(), t.sin(), z]
        };
        let mut faces = vec![
            (0..n).map(|i| at(i, 1.0)).collect::<Vec<_>>(),
            (0..n).rev().map(|i| at(i, 0.0)).collect(),
        ];
        faces.extend((0..n).map(|i| vec![at(i, 0.0), at(i + 1, 0.0), at(i + 1, 1.0), at(i, 1.0)]));
        faces
    }

    #[test]
    fn past_255_corners_there_are_no_numbers() {
        let numbered = |n: usize| {
            let faces = prism(n);
            SolidCorners::new(faces.iter().map(|f| f.as_slice())).is_some()
        };
        assert!(numbered(100), "200 corners");
        assert!(!numbered(128), "256 corners");
    }

    #[test]
    fn a_prism_seen_from_above_and_aside() {
        let faces = prism(12);
        let solid = SolidCorners::new(faces.iter().map(|f| f.as_slice())).expect("24 corners");
        // From above, beside the side face 0: the top and the side faces
        // facing the point.
        let p = [3.0, 0.4, 2.0];
        let seen = |i: usize| {
            let f = &faces[i];
            let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            let (u, v) = (sub(f[1], f[0]), sub(f[2], f[0]));
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let d = sub(p, f[0]);
            n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0.0
        };
        let mut out = SmallVec::new();
        assert!(solid.silhouette(seen, &mut out));
        assert!(counter_clockwise_from(p, &out), "{out:?}");
        // The far part of the top's rim and the near sides' bottom edges.
        let top = out.iter().filter(|q| q[2] == 1.0).count();
        let bottom = out.iter().filter(|q| q[2] == 0.0).count();
        assert!(
            top >= 7 && bottom >= 2 && top + bottom == out.len(),
            "{out:?}"
        );
    }
}
