//! Tiles: construction lines that start a busy receiver as a balanced tree.

use super::{LIGHT_UNIT, ReceiverDm};
use bsp_core::predicates::{self, Side};
use bsp_core::{GridPoint, Plane};

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Splits a receiver that has no unit yet into about `2^depth` tiles
    /// by construction lines (the receiver cut by axis-aligned planes
    /// through grid points, halving the longer side of the receiver's box
    /// each time), so that the tree starts balanced: a unit's discontinuity
    /// nodes then stay within the tiles its region meets, and removing it
    /// changes only those. The tile nodes are never removed, like the light
    /// planes' splits.
    pub(crate) fn tile(&mut self, depth: u32) {
        if depth == 0 || !self.units.is_empty() {
            return;
        }
        let n = self.polygon.support().normal();
        // Cut across the axes other than the normal's dominant one.
        let dominant = (0..3)
            .max_by_key(|&a| (n[a].unsigned_abs(), std::cmp::Reverse(a)))
            .unwrap_or(1);
        let axes = [(dominant + 1) % 3, (dominant + 2) % 3];
        let mut lo = [i64::MAX; 2];
        let mut hi = [i64::MIN; 2];
        for k in 0..self.polygon.len() {
            let Some(g) = self.polygon.vertex_grid_point(k) else {
                return;
            };
            let g = g.to_i64();
            for (i, &a) in axes.iter().enumerate() {
                lo[i] = lo[i].min(g[a]);
                hi[i] = hi[i].max(g[a]);
            }
        }
        for leaf in self.leaves(self.root) {
            self.tile_leaf(leaf, axes, lo, hi, depth);
        }
    }

    fn tile_leaf(&mut self, leaf: u32, axes: [usize; 2], lo: [i64; 2], hi: [i64; 2], depth: u32) {
        let mut stack = vec![(leaf, lo, hi, depth)];
        while let Some((leaf, lo, hi, depth)) = stack.pop() {
            if depth == 0 {
                continue;
            }
            let i = if hi[0] - lo[0] >= hi[1] - lo[1] { 0 } else { 1 };
            if hi[i] - lo[i] < 2 {
                continue;
            }
            let c = lo[i] + (hi[i] - lo[i]) / 2;
            // The plane x_a = c through three grid points, with the lower
            // half behind it.
            let at = |da: i32, db: i32| {
                let mut p = [0_i32; 3];
                p[axes[i]] = c as i32;
                p[axes[1 - i]] = da;
                p[3 - axes[0] - axes[1]] = db;
                GridPoint {
                    x: p[0],
                    y: p[1],
                    z: p[2],
                }
            };
            let Some(plane) = Plane::through(at(0, 0), at(1, 0), at(0, 1)) else {
                continue;
            };
            let mut below = at(0, 0);
            match axes[i] {
                0 => below.x -= 1,
                1 => below.y -= 1,
                _ => below.z -= 1,
            }
            let plane = if predicates::side_of_point(&plane, below) == Side::Front {
                plane.flipped()
            } else {
                plane
            };
            let (mut lower_hi, mut upper_lo) = (hi, lo);
            lower_hi[i] = c;
            upper_lo[i] = c;
            match self.split_leaf(leaf, &plane, LIGHT_UNIT) {
                Ok((back, front)) => {
                    stack.push((back, lo, lower_hi, depth - 1));
                    stack.push((front, upper_lo, hi, depth - 1));
                }
                Err(Side::Back) => stack.push((leaf, lo, lower_hi, depth - 1)),
                Err(_) => stack.push((leaf, upper_lo, hi, depth - 1)),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use area_shadow::AreaSource;
    use bsp_core::ConvexPolygon;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    #[test]
    fn tiles_partition_the_receiver() {
        let floor = ConvexPolygon::from_grid_points(
            &[g(-40, 0, 40), g(40, 0, 40), g(40, 0, -40), g(-40, 0, -40)],
            0,
        )
        .unwrap();
        let light =
            AreaSource::from_grid_points(&[g(-1, 10, -1), g(1, 10, -1), g(1, 10, 1), g(-1, 10, 1)])
                .unwrap();
        let mut dm: ReceiverDm<u32> = ReceiverDm::new(floor.clone(), false, &[light]);
        dm.tile(3);
        dm.check_invariants().unwrap();
        assert_eq!(dm.cell_count(), 8);
        let total: f64 = dm
            .cells()
            .map(|(f, _)| dm.mesh().face_polygon(f, 0).unwrap().area())
            .sum();
        assert!((total - floor.area()).abs() <= 1e-9 * floor.area());
        // The tiles are equal quarters and eighths of the floor.
        for (f, _) in dm.cells() {
            let area = dm.mesh().face_polygon(f, 0).unwrap().area();
            assert!((area - floor.area() / 8.0).abs() <= 1e-9 * floor.area());
        }
    }
}
