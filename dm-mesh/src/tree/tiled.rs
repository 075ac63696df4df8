//! Building a busy receiver tile by tile, the tiles side by side.
//!
//! A receiver that many units reach starts as a balanced tree of tiles
//! ([`ReceiverDm::tile`]), whose lines are never removed. Below its tile, a
//! unit's single tree only ever meets the cells of that tile, so each
//! tile's subtree can be grown on its own: in a mesh of the tile's polygon,
//! with the pieces of the units' regions that reach the tile, in the
//! units' order. The tiles are grown in parallel, a batch at a time, and
//! grafted into the receiver's tree and mesh ([`bsp_core::WingedMesh::graft`]
//! sews each tile's outline to its neighbours'), in tile order, so the
//! result does not depend on the number of threads; a batch is grafted
//! while the next one grows. It is the tree that inserting the units one by
//! one makes, up to the numbering of nodes and faces.

use super::arena::UNLISTED;
use super::{Node, Reach, ReceiverDm, clip};
use crate::cell::Cell;
use crate::critical::UnitPlanes;
use bsp_core::{ConvexPolygon, FaceKey, Plane, WingedMesh};
use rayon::prelude::*;

/// Units from which on a new receiver's tiles are grown apart (below, a
/// mesh per tile and the grafting cost more than they save).
const APART_UNITS: usize = 256;

/// Tiles grown side by side before they are grafted (the 10k hall floor's
/// 512 tiles in 8 batches: each batch's tile meshes are dropped soon, which
/// keeps the hall's peak memory during the build at 2.0 GB instead of 3.2
/// GB).
const TILE_BATCH: usize = 64;

/// What reaches one tile: per unit, in order, the pieces of its penumbra
/// regions (unit, penumbra part, piece).
type TileJobs = Vec<(u32, u8, ConvexPolygon)>;

impl<K: Copy + Ord + Send + Sync> ReceiverDm<K> {
    /// Cuts a receiver that has no unit yet into about `2^depth` tiles and
    /// merges `units` (occluder and light) in, in order, as
    /// [`insert`](Self::insert) one by one would, each tile grown apart
    /// and in parallel when there are many; `planes` gives a unit's volume
    /// planes.
    pub(crate) fn insert_tiled<'p>(
        &mut self,
        depth: u32,
        units: &[(K, u8)],
        planes: &(dyn Fn(K, u8) -> &'p UnitPlanes + Sync),
    ) {
        self.insert_tiles_apart(depth, units, planes, APART_UNITS, TILE_BATCH);
    }

    /// [`insert_tiled`](Self::insert_tiled), the tiles grown apart from
    /// `apart` units on, `batch` at a time.
    pub(super) fn insert_tiles_apart<'p>(
        &mut self,
        depth: u32,
        units: &[(K, u8)],
        planes: &(dyn Fn(K, u8) -> &'p UnitPlanes + Sync),
        apart: usize,
        batch: usize,
    ) {
        let fresh = self.units.is_empty() && !self.tracking;
        self.tile(depth);
        let tiles = if fresh && depth > 0 && units.len() >= apart {
            self.leaves(self.root)
        } else {
            Vec::new()
        };
        if tiles.len() < 2 {
            for &(key, light) in units {
                self.insert(key, light, planes(key, light));
            }
            return;
        }
        // Number the units, and send each piece of their regions to its
        // tile.
        let mut position = vec![usize::MAX; self.nodes.len()];
        for (i, &t) in tiles.iter().enumerate() {
            position[t as usize] = i;
        }
        let mut jobs: Vec<TileJobs> = vec![Vec::new(); tiles.len()];
        for &(key, light) in units {
            let unit = self.units.len() as u32;
            self.units.push(Some((key, light)));
            self.seeds.push(FaceKey::default());
            if self.reach[usize::from(light)] == Reach::None {
                continue;
            }
            for (part, plane_list) in planes(key, light).volumes.penumbra.iter().enumerate() {
                let Some(region) = clip(&self.polygon, plane_list) else {
                    continue;
                };
                for (leaf, piece) in self.descend(self.root, region) {
                    jobs[position[leaf as usize]].push((unit, part as u8, piece));
                }
            }
        }
        let starts: Vec<(ConvexPolygon, Cell)> = tiles
            .iter()
            .map(|&t| {
                let polygon = self
                    .mesh
                    .face_polygon(self.face_of(t), 0)
                    .expect("a tile is a convex cell");
                (polygon, self.cell(t).clone())
            })
            .collect();
        // Tiles are grown and grafted a batch at a time, a batch grafted
        // while the next grows: the tile meshes of a batch are copied into
        // the receiver's mesh and dropped before the one after next is
        // grown, so that the memory they free is taken again (the tile
        // meshes together are as big as the receiver's), and the grafting,
        // one thread's work, runs beside the growing.
        let (reach, count) = (self.reach.clone(), self.units.len());
        let grow = |next: Vec<((ConvexPolygon, Cell), TileJobs)>| -> Vec<ReceiverDm<K>> {
            next.into_par_iter()
                .map(|((polygon, cell), jobs)| {
                    let mut tile = Self::tile_part(polygon, cell, reach.clone(), count);
                    for (unit, part, piece) in jobs {
                        let (key, light) = units[unit as usize];
                        let own = planes(key, light);
                        let penumbra = &own.volumes.penumbra[usize::from(part)];
                        tile.merge_region(tile.root, piece, true, penumbra, unit, light, own);
                    }
                    tile
                })
                .collect()
        };
        let mut pieces_left: usize = jobs.iter().map(Vec::len).sum();
        let mut jobs = jobs.into_iter();
        let mut starts = starts.into_iter();
        let mut tiles = tiles.into_iter();
        // The batch grown last, with its pieces.
        let mut grown: Option<(Vec<ReceiverDm<K>>, usize)> = None;
        loop {
            let next: Vec<((ConvexPolygon, Cell), TileJobs)> = starts
                .by_ref()
                .zip(jobs.by_ref())
                .take(batch.max(1))
                .collect();
            let pieces: usize = next.iter().map(|(_, jobs)| jobs.len()).sum();
            let ready = grown.take();
            if ready.is_none() && next.is_empty() {
                break;
            }
            let ((), now) = rayon::join(
                || {
                    if let Some((ready, pieces)) = ready {
                        pieces_left -= pieces;
                        self.graft_batch(ready, &mut tiles, pieces, pieces_left);
                    }
                },
                || (!next.is_empty()).then(|| grow(next)),
            );
            grown = now.map(|tiles| (tiles, pieces));
        }
    }

    /// Grafts a batch of grown tiles, made from `pieces` pieces, in place
    /// of the next leaves of `tiles`; `left` pieces are still to be grafted
    /// after them.
    fn graft_batch(
        &mut self,
        grown: Vec<ReceiverDm<K>>,
        tiles: &mut impl Iterator<Item = u32>,
        pieces: usize,
        left: usize,
    ) {
        let counts = grown.iter().fold([0; 4], |[v, e, f, n], tile| {
            let (tv, te, tf) = tile.mesh.counts();
            [v + tv, e + te, f + tf, n + tile.nodes.len()]
        });
        self.make_room(counts, pieces, left);
        // (`grown` first: a zip asks its first iterator first.)
        for (tile, t) in grown.into_iter().zip(tiles) {
            self.graft_tile(t, tile);
        }
    }

    /// Makes room for a batch of grown tiles with `grown` vertices, edges,
    /// faces and nodes from `pieces` pieces, `left` pieces still to come.
    /// Where the batch does not fit, room is made at once for it and,
    /// guessed from its share of the pieces (and a quarter more), for the
    /// batches to come: growing the receiver's arrays batch by batch would
    /// copy them again and again (a second of the 10k hall's build), while
    /// room never used costs address space only.
    fn make_room(&mut self, grown: [usize; 4], pieces: usize, left: usize) {
        // (An eighth more for the vertices and edges that sewing the tiles'
        // outlines adds.)
        let [v, e, f, n] = grown.map(|x| x + x / 8);
        let (len_v, len_e, len_f) = self.mesh.counts();
        let (cap_v, cap_e, cap_f) = self.mesh.capacity();
        let fits = len_v + v <= cap_v
            && len_e + e <= cap_e
            && len_f + f <= cap_f
            && self.nodes.len() + n <= self.nodes.capacity();
        let room = |x: usize| {
            if fits {
                x
            } else {
                x + x * left / pieces.max(1) * 5 / 4
            }
        };
        self.mesh.reserve(room(v), room(e), room(f));
        self.nodes.reserve(room(n));
        self.parent.reserve(room(n));
        self.slot.reserve(room(n));
    }

    /// A tile's own tree: one cell, `cell`, over `polygon`, before any unit
    /// (`units` of the receiver numbered so far).
    fn tile_part(polygon: ConvexPolygon, cell: Cell, reach: Vec<Reach>, units: usize) -> Self {
        let mesh = WingedMesh::from_polygon(&polygon, Cell { leaf: 0, ..cell }, ());
        let face = mesh.faces().next().map(|(k, _)| k).expect("one face");
        Self {
            polygon,
            mesh,
            nodes: vec![Node::Leaf(face)],
            parent: vec![0],
            slot: vec![UNLISTED],
            free: Vec::new(),
            unit_nodes: Vec::new(),
            seeds: vec![FaceKey::default(); units],
            root: 0,
            reach,
            units: Vec::new(),
            touched: Vec::new(),
            tracking: false,
        }
    }

    /// Puts tile `tile`'s tree and mesh in place of leaf `t`.
    fn graft_tile(&mut self, t: u32, tile: ReceiverDm<K>) {
        // The tile's lines are held in its mesh's table, which goes with
        // the graft: by value, to be held in this one's.
        let lines: Vec<Option<Plane>> = tile
            .nodes
            .iter()
            .map(|node| match node {
                Node::Split { line, .. } => Some(*tile.mesh.plane(*line)),
                _ => None,
            })
            .collect();
        let faces = self
            .mesh
            .graft(self.face_of(t), tile.mesh)
            .expect("a tile's mesh has the tile's outline");
        // The tile's root takes the leaf's place, its other nodes go after
        // the receiver's.
        let base = self.nodes.len() as u32;
        let at = |k: u32| if k == tile.root { t } else { base + k };
        for _ in 0..tile.nodes.len() {
            self.nodes.push(Node::Free);
            self.parent.push(0);
            self.slot.push(UNLISTED);
        }
        self.free.push(base + tile.root);
        for (k, node) in tile.nodes.iter().enumerate() {
            let (k, n) = (k as u32, at(k as u32));
            if k != tile.root {
                self.parent[n as usize] = at(tile.parent[k as usize]);
            }
            match (*node, &lines[k as usize]) {
                (Node::Leaf(f), _) => self.set_node(n, Node::Leaf(faces[f])),
                (
                    Node::Split {
                        unit, back, front, ..
                    },
                    Some(line),
                ) => self.set_split(n, line, unit, at(back), at(front)),
                _ => self.free.push(n),
            }
        }
        for (u, &seed) in tile.seeds.iter().enumerate() {
            if let Some(&f) = faces.get(seed) {
                self.seeds[u] = f;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::tree::testing::{fresh, fresh_tiled, numbered, occluders, same_regions};
    use rand::SeedableRng;
    use rand_pcg::Pcg64;

    #[test]
    fn tiles_grown_apart_make_the_tree_insertion_makes() {
        for seed in 0..6 {
            let mut rng = Pcg64::seed_from_u64(100 + seed);
            let planes = occluders(&mut rng, 24);
            let units = numbered(&planes);
            let depth = 1 + seed as u32 % 4;
            let (one, apart) = (fresh(&units, depth), fresh_tiled(&units, depth));
            apart.check_invariants().unwrap();
            apart.check_lists(|k, _| &planes[k as usize]).unwrap();
            assert_eq!(one.cell_count(), apart.cell_count());
            assert_eq!(one.node_count(), apart.node_count());
            assert_eq!(one.mesh().counts(), apart.mesh().counts());
            same_regions(&one, &apart);
        }
    }
}
