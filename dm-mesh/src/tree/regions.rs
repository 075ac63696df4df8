//! Cells gathered by the tree into convex regions.
//!
//! Every node's cell is convex and is the union of the cells of its
//! leaves, so a question asked of a region and answered for all of it
//! (does it see any of a light?) answers it for each of those cells. A
//! joint umbra that discontinuities cut into many cells is then proven
//! dark once per subtree instead of once per cell.

use super::{Node, ReceiverDm};
use crate::cell::Cell;
use bsp_core::{ConvexPolygon, FaceKey, Split};

/// A subtree's region and its cells.
pub type Region = (ConvexPolygon, Vec<FaceKey>);

impl<K: Copy + Ord> ReceiverDm<K> {
    /// The cells for which `keep` holds, gathered into the largest
    /// subtrees of at most `most` cells (at least one) whose every cell it
    /// holds for: each subtree's cell (the union of its cells, convex,
    /// exact) with its cells, in the tree's order (back before front). A
    /// kept cell whose neighbours under its parent are not all kept comes
    /// alone, with its own polygon.
    pub fn kept_regions(&self, keep: impl Fn(FaceKey, &Cell) -> bool, most: usize) -> Vec<Region> {
        let most = most.max(1) as u32;
        // Per node, its cells and those kept (post-order: children first).
        let mut cells = vec![0_u32; self.nodes.len()];
        let mut kept = vec![0_u32; self.nodes.len()];
        let mut stack = vec![(self.root, false)];
        while let Some((n, children_done)) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf(f) => {
                    cells[n as usize] = 1;
                    let cell = self.mesh.face(*f).map(|face| &face.data);
                    kept[n as usize] = u32::from(cell.is_some_and(|c| keep(*f, c)));
                }
                Node::Split { back, front, .. } if children_done => {
                    let (b, f) = (*back as usize, *front as usize);
                    cells[n as usize] = cells[b] + cells[f];
                    kept[n as usize] = kept[b] + kept[f];
                }
                Node::Split { back, front, .. } => {
                    stack.extend([(n, true), (*front, false), (*back, false)]);
                }
                Node::Free => {}
            }
        }
        // Down from the root, each node's cell cut out of the receiver
        // along the way, to the subtrees wholly kept.
        let mut out = Vec::new();
        let mut stack = vec![(self.root, self.polygon.clone())];
        while let Some((n, polygon)) = stack.pop() {
            let (all, some) = (cells[n as usize], kept[n as usize]);
            if some == 0 {
                continue;
            }
            if some == all && all <= most {
                out.push((
                    polygon,
                    self.leaves(n).iter().map(|&l| self.face_of(l)).collect(),
                ));
                continue;
            }
            let Node::Split {
                line, back, front, ..
            } = &self.nodes[n as usize]
            else {
                continue;
            };
            // (A node's line cuts its cell; were the cell on one side, it
            // would all go there.)
            match polygon.split(self.mesh.plane(*line)) {
                Split::Both(b, f) => {
                    stack.push((*front, f));
                    stack.push((*back, b));
                }
                Split::Back => stack.push((*back, polygon)),
                Split::Front => stack.push((*front, polygon)),
                Split::Coplanar(_) => {}
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use crate::tree::testing::{fresh, numbered, occluders};
    use bsp_core::PolygonSide;
    use rand::SeedableRng;
    use rand_pcg::Pcg64;

    /// Every kept cell comes once, in one region, and a region is the
    /// union of its cells: their areas add up to its area, and each of
    /// them lies in it.
    #[test]
    fn regions_tile_the_kept_cells() {
        // Regions of several cells, over all seeds.
        let mut gathered = 0;
        for seed in 0..6 {
            let mut rng = Pcg64::seed_from_u64(700 + seed);
            let planes = occluders(&mut rng, 12);
            let dm = fresh(&numbered(&planes), (seed % 3) as u32);
            let keep =
                |_: bsp_core::FaceKey, cell: &crate::Cell| cell.entries().len().is_multiple_of(2);
            let wanted: Vec<bsp_core::FaceKey> = dm
                .cells()
                .filter(|(f, c)| keep(*f, c))
                .map(|(f, _)| f)
                .collect();
            for most in [1, 3, 1000] {
                let regions = dm.kept_regions(keep, most);
                if most > 1 {
                    gathered += regions.iter().filter(|(_, fs)| fs.len() > 1).count();
                }
                let mut found: Vec<bsp_core::FaceKey> = regions
                    .iter()
                    .flat_map(|(_, fs)| fs.iter().copied())
                    .collect();
                assert!(regions.iter().all(|(_, fs)| fs.len() <= most));
                found.sort_unstable();
                let mut sorted = wanted.clone();
                sorted.sort_unstable();
                assert_eq!(found, sorted, "seed {seed}, at most {most}");
                for (region, faces) in &regions {
                    let mut sum = 0.0;
                    for &f in faces {
                        let cell = dm.mesh().face_polygon(f, 0).expect("a cell");
                        sum += cell.area();
                        assert!(
                            region.edges().all(|e| !matches!(
                                cell.classify(e),
                                PolygonSide::Front | PolygonSide::Both
                            )),
                            "seed {seed}: a cell outside its region"
                        );
                    }
                    let area = region.area();
                    assert!(
                        (sum - area).abs() <= 1e-9 * area,
                        "seed {seed}: {sum} != {area}"
                    );
                }
            }
        }
        assert!(gathered > 0, "no region gathered several cells");
    }
}
