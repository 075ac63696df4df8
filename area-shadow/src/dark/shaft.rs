//! The shaft between a region and a part of a light: a floating-point cull
//! of the blockers that cannot meet a segment between the two.
//!
//! Only to skip work: a blocker culled by mistake can only make a proof
//! fail, never make one succeed, so the test need not be exact (its margin
//! keeps blockers that touch the shaft).

use super::vector::{cross, dot, sub};

/// The convex hull of two convex polygons, by the planes through an edge
/// of one and a corner of the other that have both on one side.
#[derive(Debug, Clone)]
pub struct Shaft {
    /// Unit normals and offsets, the hull behind.
    planes: Vec<([f64; 3], f64)>,
    /// The box around both.
    bounds: [[f64; 3]; 2],
    margin: f64,
}

impl Shaft {
    /// The shaft between the polygons with corners `a` and `b` (in order
    /// around each).
    pub fn new(a: &[[f64; 3]], b: &[[f64; 3]]) -> Self {
        let all = || a.iter().chain(b);
        let extent = all()
            .flat_map(|p| p.iter().map(|c| c.abs()))
            .fold(1.0, f64::max);
        let margin = 1e-6 * extent;
        let mut bounds = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
        for p in all() {
            for k in 0..3 {
                bounds[0][k] = bounds[0][k].min(p[k] - margin);
                bounds[1][k] = bounds[1][k].max(p[k] + margin);
            }
        }
        let mut planes = Vec::new();
        for (edges, corners) in [(a, b), (b, a)] {
            for (i, &p) in edges.iter().enumerate() {
                let q = edges[(i + 1) % edges.len()];
                for &c in corners {
                    let n = cross(sub(q, p), sub(c, p));
                    let length = dot(n, n).sqrt();
                    if length == 0.0 {
                        continue;
                    }
                    let n = n.map(|x| x / length);
                    let d = -dot(n, p);
                    let sides = all().map(|&x| dot(n, x) + d);
                    if sides.clone().all(|v| v <= margin) {
                        planes.push((n, d));
                    } else if sides.clone().all(|v| v >= -margin) {
                        planes.push((n.map(|x| -x), -d));
                    }
                }
            }
        }
        Self {
            planes,
            bounds,
            margin,
        }
    }

    /// Whether the points (the corners of something convex) lie all beyond
    /// one of the hull's planes, or beyond a side of its box: then nothing
    /// in their hull meets a segment between the two polygons.
    pub fn misses(&self, points: &[[f64; 3]]) -> bool {
        let [lo, hi] = self.bounds;
        (0..3).any(|k| points.iter().all(|p| p[k] < lo[k]) || points.iter().all(|p| p[k] > hi[k]))
            || self
                .planes
                .iter()
                .any(|(n, d)| points.iter().all(|&p| dot(*n, p) + d > 4.0 * self.margin))
    }

    /// As [`Shaft::misses`], for the box `[low, high]`.
    pub fn misses_box(&self, [lo, hi]: &[[f64; 3]; 2]) -> bool {
        let corners: [[f64; 3]; 8] = std::array::from_fn(|c| {
            std::array::from_fn(|k| if c >> k & 1 == 0 { lo[k] } else { hi[k] })
        });
        self.misses(&corners)
    }
}

#[cfg(test)]
mod tests {
    use super::Shaft;

    #[test]
    fn culls_what_lies_beside_and_keeps_what_lies_between() {
        // A unit square on the floor, a unit square light 10 above it.
        let floor = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let light = floor.map(|[x, y, _]| [x, y, 10.0]);
        let shaft = Shaft::new(&floor, &light);
        let at = |x: f64, y: f64, z: f64, r: f64| [[x - r, y - r, z - r], [x + r, y + r, z + r]];
        assert!(!shaft.misses_box(&at(0.5, 0.5, 5.0, 0.1)));
        // Touching the shaft's side counts as meeting it.
        assert!(!shaft.misses_box(&at(1.1, 0.5, 5.0, 0.1)));
        assert!(shaft.misses_box(&at(1.2, 0.5, 5.0, 0.1)));
        assert!(shaft.misses_box(&at(0.5, 0.5, 10.2, 0.1)));
        // Between a tilted pair: beside both boxes' overlap in x, yet in
        // the box around them, it is culled by a plane.
        let shifted = floor.map(|[x, y, _]| [x + 5.0, y, 10.0]);
        let slanted = Shaft::new(&floor, &shifted);
        assert!(!slanted.misses_box(&at(2.5, 0.5, 5.0, 0.1)));
        assert!(slanted.misses_box(&at(4.5, 0.5, 2.0, 0.1)));
    }
}
