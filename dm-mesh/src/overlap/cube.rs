//! [`OverlapKind::Cube`](super::OverlapKind::Cube): Chrysanthou & Slater's
//! shadow overlap cube. Around each light's centroid `c` a cube, each face
//! cut into `TILES_PER_SIDE`² tiles: a tile stands for the directions from
//! `c` through it, so the cube bounds no region and every place an object
//! may move to is covered. Each receiver is scan-converted into the tiles
//! of the directions from `c` to its points, each occluder into those of
//! its penumbra volumes; an occluder can shadow a receiver only if they
//! share a tile. Every piece keeps its tile lists, so removing it touches
//! only its own tiles.
//!
//! The directions of a convex polygon from `c` are the cone spanned by its
//! vertices' directions. A penumbra volume is made of points
//! `x + t (y - x)`, `x` on the light, `y` on the occluder, `t >= 1`, that is
//! `y + (t - 1) (y - x)`: within the occluder plus the cone of the
//! differences `o_j - l_i` of its and the light's vertices; so its
//! directions lie in the cone spanned by the `o_j - c` and the
//! `o_j - l_i`. An occluder that touches or crosses the light's plane gets
//! every tile.
//!
//! Scan conversion of a cone spanned by directions `g_k` onto the face
//! whose axis is `a` (sign `s`): with `g' = s g_a`, the generators with
//! `g' > 0` project to `(g_b, g_c) / g'`; a generator `q` with `q' <= 0`
//! takes the cone's projection to infinity along
//! `e = p' (q_b, q_c) - q' (p_b, p_c)` from each projected `p` (the
//! projection of `p + λ q` moves from that of `p` along `e`). The face gets
//! the tiles of the box around the projected points, opened to infinity
//! along every such `e`, a little widened against rounding: conservative.

use super::{Box3, bounding_box, light_plane};
use crate::scene::{DmLight, Piece, PieceId};
use slotmap::{SecondaryMap, SlotMap};
use std::collections::BTreeSet;

/// Tiles along each side of a cube face.
const TILES_PER_SIDE: usize = 32;

/// Tiles of one cube.
const TILES: usize = 6 * TILES_PER_SIDE * TILES_PER_SIDE;

/// A piece's tiles on one light's cube: some, or every one.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Tiles {
    Some(Vec<u32>),
    All,
}

/// One light's cube: per tile, the receivers and the shadows in it.
#[derive(Debug, Clone)]
struct LightCube {
    centre: [f64; 3],
    vertices: Vec<[f64; 3]>,
    plane: [f64; 4],
    receivers: Vec<Vec<PieceId>>,
    shadows: Vec<Vec<PieceId>>,
    /// Pieces in every tile, as receivers and as shadows.
    every_receiver: BTreeSet<PieceId>,
    every_shadow: BTreeSet<PieceId>,
    /// Every piece casting a shadow of this light.
    casters: BTreeSet<PieceId>,
}

/// The shadow overlap cubes of a scene's lights.
#[derive(Debug, Clone, Default)]
pub(crate) struct Cube {
    cubes: Vec<LightCube>,
    boxes: SecondaryMap<PieceId, Box3>,
    /// Per piece, per light, its tiles as a receiver.
    receiver_tiles: SecondaryMap<PieceId, Vec<Tiles>>,
    /// Per piece, per light, its shadow's tiles (none when it casts none).
    shadow_tiles: SecondaryMap<PieceId, Vec<Option<Tiles>>>,
    /// Pieces whose shadows are still to be scan-converted.
    pending: Vec<PieceId>,
}

impl Cube {
    pub(crate) fn new(lights: &[DmLight]) -> Self {
        let cubes = lights
            .iter()
            .map(|l| {
                let vertices: Vec<[f64; 3]> = l.source.vertices().map(|g| g.to_f64()).collect();
                LightCube {
                    centre: l.source.centroid(),
                    plane: light_plane(&vertices),
                    vertices,
                    receivers: vec![Vec::new(); TILES],
                    shadows: vec![Vec::new(); TILES],
                    every_receiver: BTreeSet::new(),
                    every_shadow: BTreeSet::new(),
                    casters: BTreeSet::new(),
                }
            })
            .collect();
        Self {
            cubes,
            ..Self::default()
        }
    }

    /// Scan-converts a new receiver; its shadow waits for
    /// [`refresh`](Self::refresh).
    pub(crate) fn insert(&mut self, key: PieceId, piece: &Piece, receives: bool) {
        if !receives {
            self.pending.push(key);
            return;
        }
        self.boxes.insert(key, bounding_box(&piece.outline));
        let mut all = Vec::with_capacity(self.cubes.len());
        for cube in &mut self.cubes {
            let directions: Vec<[f64; 3]> =
                piece.outline.iter().map(|v| sub(*v, cube.centre)).collect();
            let tiles = scan(&directions);
            match &tiles {
                Tiles::All => {
                    cube.every_receiver.insert(key);
                }
                Tiles::Some(list) => {
                    for &t in list {
                        cube.receivers[t as usize].push(key);
                    }
                }
            }
            all.push(tiles);
        }
        self.receiver_tiles.insert(key, all);
        self.pending.push(key);
    }

    /// Forgets a piece: only its own tiles are looked at.
    pub(crate) fn remove(&mut self, key: PieceId) {
        self.boxes.remove(key);
        if let Some(all) = self.receiver_tiles.remove(key) {
            for (cube, tiles) in self.cubes.iter_mut().zip(all) {
                match tiles {
                    Tiles::All => {
                        cube.every_receiver.remove(&key);
                    }
                    Tiles::Some(list) => {
                        for t in list {
                            cube.receivers[t as usize].retain(|k| *k != key);
                        }
                    }
                }
            }
        }
        if let Some(all) = self.shadow_tiles.remove(key) {
            for (cube, tiles) in self.cubes.iter_mut().zip(all) {
                cube.casters.remove(&key);
                match tiles {
                    None => {}
                    Some(Tiles::All) => {
                        cube.every_shadow.remove(&key);
                    }
                    Some(Tiles::Some(list)) => {
                        for t in list {
                            cube.shadows[t as usize].retain(|k| *k != key);
                        }
                    }
                }
            }
        }
        self.pending.retain(|k| *k != key);
    }

    /// Scan-converts the penumbra volumes of the pieces inserted since.
    pub(crate) fn refresh(&mut self, pieces: &SlotMap<PieceId, Piece>) {
        for key in std::mem::take(&mut self.pending) {
            let Some(piece) = pieces.get(key) else {
                continue;
            };
            let mut all = Vec::with_capacity(self.cubes.len());
            for (i, cube) in self.cubes.iter_mut().enumerate() {
                if piece.volumes[i].volumes.penumbra.is_empty() {
                    all.push(None);
                    continue;
                }
                cube.casters.insert(key);
                let [a, b, c, d] = cube.plane;
                let scale = cube
                    .vertices
                    .iter()
                    .chain(&piece.outline)
                    .map(|v| v.iter().map(|x| x.abs()).sum::<f64>())
                    .fold(1.0, f64::max);
                let in_front = piece
                    .outline
                    .iter()
                    .all(|v| a * v[0] + b * v[1] + c * v[2] + d > 1e-9 * scale);
                let tiles = if in_front {
                    let mut directions: Vec<[f64; 3]> =
                        piece.outline.iter().map(|v| sub(*v, cube.centre)).collect();
                    for l in &cube.vertices {
                        directions.extend(piece.outline.iter().map(|v| sub(*v, *l)));
                    }
                    scan(&directions)
                } else {
                    Tiles::All
                };
                match &tiles {
                    Tiles::All => {
                        cube.every_shadow.insert(key);
                    }
                    Tiles::Some(list) => {
                        for &t in list {
                            cube.shadows[t as usize].push(key);
                        }
                    }
                }
                all.push(Some(tiles));
            }
            self.shadow_tiles.insert(key, all);
        }
    }

    /// A receiver's box.
    pub(crate) fn receiver_box(&self, r: PieceId) -> Option<&Box3> {
        self.boxes.get(r)
    }

    /// Occluders whose shadows share a tile with receiver `r`.
    pub(crate) fn occluders_of(&self, r: PieceId) -> BTreeSet<PieceId> {
        let mut out = BTreeSet::new();
        let Some(all) = self.receiver_tiles.get(r) else {
            return out;
        };
        for (cube, tiles) in self.cubes.iter().zip(all) {
            match tiles {
                Tiles::All => out.extend(cube.casters.iter().copied()),
                Tiles::Some(list) => {
                    out.extend(cube.every_shadow.iter().copied());
                    for &t in list {
                        out.extend(cube.shadows[t as usize].iter().copied());
                    }
                }
            }
        }
        out
    }

    /// Receivers sharing a tile with occluder `o`'s shadow.
    pub(crate) fn receivers_of(&self, o: PieceId) -> BTreeSet<PieceId> {
        let mut out = BTreeSet::new();
        let Some(all) = self.shadow_tiles.get(o) else {
            return out;
        };
        for (cube, tiles) in self.cubes.iter().zip(all) {
            match tiles {
                None => {}
                Some(Tiles::All) => out.extend(self.boxes.keys()),
                Some(Tiles::Some(list)) => {
                    out.extend(cube.every_receiver.iter().copied());
                    for &t in list {
                        out.extend(cube.receivers[t as usize].iter().copied());
                    }
                }
            }
        }
        out
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The tiles of the cone spanned by `directions` (see the module docs).
fn scan(directions: &[[f64; 3]]) -> Tiles {
    let scale = directions
        .iter()
        .map(|g| g.iter().map(|x| x.abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    if scale == 0.0
        || directions
            .iter()
            .any(|g| g.iter().all(|x| x.abs() <= 1e-12 * scale))
    {
        // A point at the centre sees every direction.
        return Tiles::All;
    }
    let n = TILES_PER_SIDE;
    let mut out = Vec::new();
    for face in 0..6 {
        let a = face / 2;
        let s = if face % 2 == 0 { 1.0 } else { -1.0 };
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        let tiny = 1e-9 * scale;
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let mut any = false;
        for p in directions {
            let pa = s * p[a];
            if pa <= tiny {
                continue;
            }
            any = true;
            for (k, &axis) in [b, c].iter().enumerate() {
                let x = p[axis] / pa;
                lo[k] = lo[k].min(x);
                hi[k] = hi[k].max(x);
            }
            for q in directions {
                let qa = s * q[a];
                if qa > tiny {
                    continue;
                }
                for (k, &axis) in [b, c].iter().enumerate() {
                    let e = pa * q[axis] - qa * p[axis];
                    let bound = 1e-9 * (pa.abs() + qa.abs()) * scale;
                    if e >= -bound {
                        hi[k] = f64::INFINITY;
                    }
                    if e <= bound {
                        lo[k] = f64::NEG_INFINITY;
                    }
                }
            }
        }
        if !any {
            continue;
        }
        let pad = 1e-6;
        let range = |lo: f64, hi: f64| -> Option<(usize, usize)> {
            let (lo, hi) = ((lo - pad).max(-1.0), (hi + pad).min(1.0));
            if lo > hi {
                return None;
            }
            let at = |x: f64| (((x + 1.0) / 2.0 * n as f64).floor() as usize).min(n - 1);
            Some((at(lo), at(hi)))
        };
        let (Some((i0, i1)), Some((j0, j1))) = (range(lo[0], hi[0]), range(lo[1], hi[1])) else {
            continue;
        };
        for i in i0..=i1 {
            for j in j0..=j1 {
                out.push((face * n * n + i * n + j) as u32);
            }
        }
    }
    Tiles::Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Directions sampled from the cone of `generators` fall in its tiles.
    #[test]
    fn scan_covers_the_cone() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let sets: [&[[f64; 3]]; 4] = [
            &[[1.0, 0.2, 0.1], [1.0, -0.3, 0.4], [0.9, 0.5, -0.2]],
            &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            &[[1.0, 0.1, 0.1], [-1.0, 0.2, 0.1], [0.0, 1.0, 0.3]],
            &[
                [0.3, -2.0, 0.1],
                [0.2, -2.0, -0.4],
                [-0.1, -1.5, 0.2],
                [0.4, -1.0, 5.0],
            ],
        ];
        for gens in sets {
            let Tiles::Some(tiles) = scan(gens) else {
                panic!("finite generators");
            };
            let n = TILES_PER_SIDE;
            for _ in 0..400 {
                // Positive combinations with pseudo-random weights.
                let weights: Vec<f64> = (0..gens.len())
                    .map(|_| rng.random_range(0.0..1.0))
                    .collect();
                let d: [f64; 3] = std::array::from_fn(|x| {
                    gens.iter()
                        .zip(&weights)
                        .map(|(g, w)| g[x] * w)
                        .sum::<f64>()
                });
                let a = (0..3)
                    .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
                    .unwrap();
                if d[a] == 0.0 {
                    continue;
                }
                let face = 2 * a + usize::from(d[a] < 0.0);
                let s = d[a].abs();
                let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                let at = |x: f64| (((x / s + 1.0) / 2.0 * n as f64).floor() as usize).min(n - 1);
                let tile = (face * n * n + at(d[b]) * n + at(d[c])) as u32;
                assert!(tiles.contains(&tile), "{d:?} outside the tiles of {gens:?}");
            }
        }
    }
}
