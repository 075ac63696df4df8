//! A convex solid given by its silhouette hides what its faces seen from
//! the point hide together: random boxes under a light, seen from random
//! points, the silhouette found independently as the convex hull of the
//! corners' images on a screen facing the box.

use crate::{cross, dot, rect_light, sub, unit};
use illum::{Occluder, Sidedness::OneSided, Vec3, VisiblePart, visible_irradiance};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// A box: centre, three orthogonal half-axes.
struct Cuboid {
    centre: Vec3,
    axes: [Vec3; 3],
}

impl Cuboid {
    fn random(rng: &mut Pcg64, centre: Vec3, size: f64) -> Self {
        let a = unit([
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        ]);
        let b = unit(cross(
            a,
            unit([
                rng.random_range(-1.0..1.0),
                1.0,
                rng.random_range(-1.0..1.0),
            ]),
        ));
        let c = cross(a, b);
        let half = |v: Vec3, rng: &mut Pcg64| {
            let s = size * rng.random_range(0.2..1.0);
            [v[0] * s, v[1] * s, v[2] * s]
        };
        Self {
            centre,
            axes: [half(a, rng), half(b, rng), half(c, rng)],
        }
    }

    fn corner(&self, signs: [f64; 3]) -> Vec3 {
        let mut out = self.centre;
        for (axis, s) in self.axes.iter().zip(signs) {
            for k in 0..3 {
                out[k] += s * axis[k];
            }
        }
        out
    }

    /// Its faces, counter-clockwise seen from outside, with their outward
    /// normals.
    fn faces(&self) -> Vec<(Vec3, Vec<Vec3>)> {
        let mut out = Vec::new();
        for axis in 0..3 {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            for s in [1.0, -1.0] {
                let at = |a: f64, b: f64| {
                    let mut signs = [0.0; 3];
                    signs[axis] = s;
                    signs[u] = a;
                    signs[v] = b;
                    self.corner(signs)
                };
                let mut corners = vec![at(-1.0, -1.0), at(1.0, -1.0), at(1.0, 1.0), at(-1.0, 1.0)];
                if s < 0.0 {
                    corners.reverse();
                }
                let n = self.axes[axis];
                out.push(([s * n[0], s * n[1], s * n[2]], corners));
            }
        }
        out
    }

    /// Its faces with `p` strictly in front.
    fn faces_seen(&self, p: Vec3) -> Vec<Vec<Vec3>> {
        self.faces()
            .into_iter()
            .filter(|(n, corners)| dot(*n, sub(p, corners[0])) > 0.0)
            .map(|(_, corners)| corners)
            .collect()
    }

    /// Its silhouette from `p` (outside its bounding sphere),
    /// counter-clockwise seen from `p`: the corners whose images on a
    /// screen facing the box make the convex hull of them all.
    fn silhouette(&self, p: Vec3) -> Vec<Vec3> {
        let corners: Vec<Vec3> = (0..8)
            .map(|i| {
                let s = |bit: usize| if i >> bit & 1 == 1 { 1.0 } else { -1.0 };
                self.corner([s(0), s(1), s(2)])
            })
            .collect();
        // Looking along d with the screen's axes u (right) and v = u x d
        // (up), counter-clockwise on the screen is counter-clockwise seen
        // from p.
        let d = unit(sub(self.centre, p));
        let u = unit(cross(d, [0.3, 0.5, 0.7]));
        let v = cross(u, d);
        let image: Vec<[f64; 2]> = corners
            .iter()
            .map(|&c| {
                let q = sub(c, p);
                [dot(q, u) / dot(q, d), dot(q, v) / dot(q, d)]
            })
            .collect();
        // Gift wrapping from the leftmost image.
        let first = (0..8)
            .min_by(|&a, &b| image[a][0].total_cmp(&image[b][0]))
            .unwrap();
        let mut hull = vec![first];
        loop {
            let at = *hull.last().unwrap();
            let mut next = (at + 1) % 8;
            for k in 0..8 {
                let (a, b, c) = (image[at], image[next], image[k]);
                let turn = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
                // Keep the candidate with every image on its left.
                if turn < 0.0 {
                    next = k;
                }
            }
            if next == first {
                break;
            }
            hull.push(next);
        }
        hull.into_iter().map(|i| corners[i]).collect()
    }
}

#[test]
fn a_box_by_its_silhouette_hides_what_its_faces_hide() {
    let light = rect_light(-1.0, 1.0, -1.0, 1.0, 4.0, 1.0);
    let up = [0.0, 0.0, 1.0];
    let mut rng = Pcg64::seed_from_u64(11);
    let (mut scratch, mut partial) = (VisiblePart::new(), 0);
    for _ in 0..2000 {
        let centre = [
            rng.random_range(-1.5..1.5),
            rng.random_range(-1.5..1.5),
            rng.random_range(1.0..3.0),
        ];
        let cuboid = Cuboid::random(&mut rng, centre, 0.6);
        // Below the box, outside its bounding sphere (at most 0.6 sqrt 3).
        let p = [
            rng.random_range(-2.5..2.5),
            rng.random_range(-2.5..2.5),
            centre[2] - 1.1,
        ];
        let faces = cuboid.faces_seen(p);
        let loop_ = cuboid.silhouette(p);
        assert!((4..=6).contains(&loop_.len()), "{loop_:?}");
        let by_faces = visible_irradiance(&light, &faces, p, up, OneSided, &mut scratch);
        let by_silhouette = visible_irradiance(
            &light,
            &[Occluder::Silhouette(&loop_)],
            p,
            up,
            OneSided,
            &mut scratch,
        );
        let full = light.irradiance(p, up, OneSided);
        assert!(
            (by_faces - by_silhouette).abs() <= 1e-12 * full,
            "{by_faces} vs {by_silhouette} (all {full}) at {p:?}"
        );
        if by_faces > 1e-3 * full && by_faces < full * (1.0 - 1e-3) {
            partial += 1;
        }
    }
    assert!(partial > 500, "{partial} of 2000 partly shadowed");
}

#[test]
fn many_boxes_by_their_silhouettes_hide_what_their_faces_hide() {
    // Past 24 occluders cutting the light the outlines of the visible
    // part are taken: a row of small boxes under the light.
    let light = rect_light(-1.0, 1.0, -1.0, 1.0, 4.0, 1.0);
    let up = [0.0, 0.0, 1.0];
    let mut rng = Pcg64::seed_from_u64(12);
    let mut scratch = VisiblePart::new();
    for _ in 0..50 {
        let boxes: Vec<Cuboid> = (0..40)
            .map(|i| {
                let x = -0.5 + 0.025 * f64::from(i);
                let centre = [x, rng.random_range(-0.5..0.5), 2.0];
                Cuboid::random(&mut rng, centre, 0.05)
            })
            .collect();
        let p = [
            rng.random_range(-0.5..0.5),
            rng.random_range(-0.5..0.5),
            0.0,
        ];
        let faces: Vec<Vec<Vec3>> = boxes.iter().flat_map(|b| b.faces_seen(p)).collect();
        let loops: Vec<Vec<Vec3>> = boxes.iter().map(|b| b.silhouette(p)).collect();
        let silhouettes: Vec<Occluder> = loops.iter().map(|l| Occluder::Silhouette(l)).collect();
        let by_faces = visible_irradiance(&light, &faces, p, up, OneSided, &mut scratch);
        let by_silhouette = visible_irradiance(&light, &silhouettes, p, up, OneSided, &mut scratch);
        let full = light.irradiance(p, up, OneSided);
        assert!(
            by_faces < 0.9 * full,
            "{by_faces} of {full}: the boxes hide some"
        );
        assert!(
            (by_faces - by_silhouette).abs() <= 1e-9 * full,
            "{by_faces} vs {by_silhouette} (all {full}) at {p:?}"
        );
    }
}
