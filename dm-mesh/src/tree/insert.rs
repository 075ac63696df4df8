//! Merging one unit's single tree into a receiver's DM-tree.

use super::{Reach, ReceiverDm, clip};
use crate::cell::{Entry, Sides};
use crate::critical::{Critical, UnitPlanes};
use bsp_core::{Chord, ConvexPolygon, FaceKey, Plane, PolygonSide, Side};
use smallvec::SmallVec;
use std::borrow::Cow;
use std::ops::Range;

/// The chords through a cell of the unit's internal discontinuities that
/// cross it, each with the discontinuity's index, in order.
type CellChords = Vec<(u32, Chord)>;

thread_local! {
    /// The chords a unit's region carries down a tree ([`ReceiverDm::merge_region`]),
    /// kept from one region to the next on each thread: grown anew each
    /// time, the list (240 bytes a chord, a few thousand on a big
    /// receiver) was copied over and over as it grew, 4 % of a move.
    static CHORDS: std::cell::Cell<Vec<(u32, Chord)>> = const { std::cell::Cell::new(Vec::new()) };
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Appends a unit (occluder `key` under light `light`, with its volume
    /// planes) and merges its single tree in. Returns its unit number.
    pub(crate) fn insert(&mut self, key: K, light: u8, planes: &UnitPlanes) -> u32 {
        let unit = self.units.len() as u32;
        self.units.push(Some((key, light)));
        self.seeds.push(FaceKey::default());
        self.merge_unit(self.root, None, unit, light, planes);
        unit
    }

    /// Merges unit `unit`'s single tree into the subtree at `node`, within
    /// `cell` (`None`: all of the node's cell). Cells that already list the
    /// unit, or culled it and are still in umbra, are left alone, so merging
    /// a unit again where it already is changes nothing.
    pub(super) fn merge_unit(
        &mut self,
        node: u32,
        cell: Option<&ConvexPolygon>,
        unit: u32,
        light: u8,
        planes: &UnitPlanes,
    ) {
        if self.reach[usize::from(light)] == Reach::None {
            return;
        }
        for part in &planes.volumes.penumbra {
            // The quick reject: the receiver (or cell) clipped by the
            // penumbra planes, exactly.
            let Some(mut region) = clip(&self.polygon, part) else {
                continue;
            };
            if let Some(cell) = cell {
                let Some(inside) = clip(&region, cell.edges()) else {
                    continue;
                };
                region = inside;
            }
            let exact = cell.is_none();
            self.merge_region(node, region, exact, part, unit, light, planes);
        }
    }

    /// Grows unit `unit`'s single tree in the cells of the subtree at
    /// `node` that `region` (the receiver clipped by the penumbra planes
    /// `part`, inside the node's cell) reaches. `exact`: the region is all
    /// of the unit's region there, so each leaf's piece is the leaf's part
    /// of it; otherwise (a region restricted to a cell, when a removal
    /// merges freed units again) a piece may be smaller than that part.
    #[allow(clippy::too_many_arguments)] // (the unit's region and its whole context)
    pub(super) fn merge_region(
        &mut self,
        node: u32,
        region: ConvexPolygon,
        exact: bool,
        part: &[Plane],
        unit: u32,
        light: u8,
        planes: &UnitPlanes,
    ) {
        // With the whole region, the cells that come to list the unit lie
        // in its leaves' pieces: an internal discontinuity that does not
        // cross a piece crosses none of them, and is not tried on each.
        // A piece that misses one has parts that miss it too, so they are
        // sorted out on the way down, at the cuts: each discontinuity that
        // crosses a piece is kept with its chord through it, divided at
        // each cut between the parts (two exact sides of the chord's ends,
        // where trying each part anew took a polygon's sides to each of the
        // discontinuity's planes); each piece carries the range of
        // `chords` that holds its own.
        let support = *self.polygon.support();
        let mut chords = CHORDS.take();
        chords.clear();
        if exact {
            chords.extend(
                planes.internal.iter().enumerate().filter_map(|(k, c)| {
                    Some((k as u32, region.chord_inside(&c.plane, &c.wedge)?))
                }),
            );
        }
        // Likewise the umbra: where the whole region misses it, so do its
        // pieces, and only the umbra planes that bound the region's umbra
        // part can cut a piece's.
        let umbra: Option<Cow<'_, [Plane]>> = match planes.volumes.umbra.as_deref() {
            Some(all) if exact => {
                clip(&region, all).map(|core| Cow::Owned(bounding(all, &core).copied().collect()))
            }
            other => other.map(Cow::Borrowed),
        };
        let whole = 0..chords.len() as u32;
        // A piece that is all of its node's cell (no edge on the region's
        // planes), crossed by no internal discontinuity and wholly in or
        // out of the umbra grows every leaf under the node alike: the
        // leaves are listed, not reached by cutting the piece further
        // (most of a region's leaves lie in such subtrees).
        let settled = |piece: &ConvexPolygon, range: &Range<u32>| {
            exact
                && range.is_empty()
                && !piece.edges().any(|e| part.contains(e))
                && umbra
                    .as_deref()
                    .is_none_or(|u| umbra_cover(piece, u).is_some())
        };
        let reached = self.descend_with(
            node,
            region,
            whole,
            |range, line| {
                // The back parts' chords first, then the front parts'.
                let mut ahead: SmallVec<[(u32, Chord); 8]> = SmallVec::new();
                let start = chords.len() as u32;
                for k in range {
                    let (critical, (back, front)) = {
                        let (critical, chord) = &chords[k as usize];
                        (*critical, chord.split(&support, line))
                    };
                    chords.extend(back.map(|chord| (critical, chord)));
                    ahead.extend(front.map(|chord| (critical, chord)));
                }
                let middle = chords.len() as u32;
                chords.extend(ahead);
                (start..middle, middle..chords.len() as u32)
            },
            settled,
        );
        for (n, piece, range) in reached {
            if !self.is_leaf(n) {
                let sides = match umbra.as_deref().and_then(|u| umbra_cover(&piece, u)) {
                    Some(UmbraCover::Whole) => planes.umbra_sides,
                    _ => Sides::NONE,
                };
                self.grow_settled(n, sides, unit, light, planes);
                continue;
            }
            let leaf = n;
            let umbra = umbra.as_deref().map(|u| (u, planes.umbra_sides));
            let grown = self.grow_leaf(leaf, &piece, exact, part, umbra, unit, light);
            if planes.internal.is_empty() {
                continue;
            }
            match grown {
                Some(grown) if exact => {
                    if range.is_empty() {
                        continue;
                    }
                    let own = &chords[range.start as usize..range.end as usize];
                    let crossing: SmallVec<[&Critical; 16]> = own
                        .iter()
                        .map(|(k, _)| &planes.internal[*k as usize])
                        .collect();
                    let crossing = crossing.as_slice();
                    match grown {
                        // (No face polygon to make: the cell is the piece,
                        // its chords those it carried down.)
                        Grown::Whole(inner) => {
                            let carried = own
                                .iter()
                                .enumerate()
                                .map(|(k, (_, c))| (k as u32, c.clone()))
                                .collect();
                            self.split_by_internal(vec![(inner, carried)], crossing, unit)
                        }
                        Grown::Parts => self.grow_internal(leaf, crossing, unit),
                    }
                }
                _ => self.grow_all_internal(leaf, planes, unit),
            }
        }
        CHORDS.set(chords);
    }

    /// Grows the unit's single tree in a settled subtree at `node` (its
    /// cell inside the unit's penumbra region, crossed by none of its
    /// internal discontinuities, in its umbra on `sides` or out of it):
    /// each leaf lists the unit as [`Self::grow_leaf`] would have it, with
    /// no cut.
    fn grow_settled(&mut self, node: u32, sides: Sides, unit: u32, light: u8, planes: &UnitPlanes) {
        for leaf in self.leaves(node) {
            if self.claim(leaf, unit, light) {
                self.cell_mut(leaf).add(Entry {
                    unit,
                    light,
                    umbra: sides,
                });
                self.seeds[unit as usize] = self.face_of(leaf);
            } else {
                self.grow_all_internal(leaf, planes, unit);
            }
        }
    }

    /// Splits the cells of the subtree at `node` that list `unit` outside
    /// its umbra by all of its internal discontinuities.
    fn grow_all_internal(&mut self, node: u32, planes: &UnitPlanes, unit: u32) {
        if !planes.internal.is_empty() {
            let all: SmallVec<[&Critical; 32]> = planes.internal.iter().collect();
            self.grow_internal(node, &all, unit);
        }
    }

    /// Whether a leaf whose cell the unit's penumbra region meets is to
    /// grow: not if it lists the unit already, or culled it, or the light
    /// does not reach it; not either if it is in umbra already (the
    /// occluder changes nothing there unless the occluder making the umbra
    /// goes: it is remembered for then, as culled).
    fn claim(&mut self, leaf: u32, unit: u32, light: u8) -> bool {
        let cell = self.cell(leaf);
        if cell.has_unit(unit) || cell.culled.contains(&unit) || cell.unreached(usize::from(light))
        {
            return false;
        }
        if cell.in_umbra(usize::from(light)) {
            self.cell_mut(leaf).culled.push(unit);
            self.seeds[unit as usize] = self.face_of(leaf);
            return false;
        }
        true
    }

    /// Grows the unit's single tree at one leaf whose cell meets the
    /// unit's penumbra region in `piece` (with area; `exact`: `piece` is
    /// all of the leaf's part of the region). Whether it did (the leaf did
    /// not list the unit yet, and its cells inside the region now do: the
    /// part outside the umbra, if any), and how.
    #[allow(clippy::too_many_arguments)] // (the leaf, the unit's region and its context)
    fn grow_leaf(
        &mut self,
        leaf: u32,
        piece: &ConvexPolygon,
        exact: bool,
        penumbra: &[Plane],
        umbra: Option<(&[Plane], Sides)>,
        unit: u32,
        light: u8,
    ) -> Option<Grown> {
        if !self.claim(leaf, unit, light) {
            return None;
        }
        // Only the planes that bound the cell's part of the region cut the
        // cell where it matters: the others are redundant there (the cell
        // and the bounding ones already keep the part inside them), and
        // splitting by them would only make cells that change nothing. A
        // piece smaller than that part (`!exact`) may lack some of them:
        // then every plane is tried.
        let inner = if exact {
            self.chain(leaf, bounding(penumbra, piece), unit)
        } else {
            self.chain(leaf, penumbra, unit)
        };
        let inner = inner?;
        self.cell_mut(inner).add(Entry {
            unit,
            light,
            umbra: Sides::NONE,
        });
        self.seeds[unit as usize] = self.face_of(inner);
        // The inner cell is `piece` when it is exact, until the umbra cuts it.
        let whole = if exact {
            Grown::Whole(inner)
        } else {
            Grown::Parts
        };
        let Some((umbra, sides)) = umbra else {
            return Some(whole);
        };
        let core = if exact {
            // The inner cell is `piece`: its umbra part is the piece's.
            let Some(core) = clip(piece, umbra) else {
                return Some(whole);
            };
            self.chain(inner, bounding(umbra, &core), unit)
        } else {
            // The inner cell may reach past `piece`, and meet the umbra
            // where the piece does not.
            let meets = self
                .mesh
                .face_polygon(self.face_of(inner), 0)
                .is_ok_and(|cell| clip(&cell, umbra).is_some());
            if !meets {
                return Some(Grown::Parts);
            }
            self.chain(inner, umbra, unit)
        };
        if let Some(core) = core {
            self.cell_mut(core).add(Entry {
                unit,
                light,
                umbra: sides,
            });
        }
        Some(Grown::Parts)
    }

    /// Splits the cells of the subtree at `node` that list `unit` outside
    /// its umbra by its internal discontinuities, each where its wedge
    /// crosses the cell.
    pub(super) fn grow_internal(&mut self, node: u32, internal: &[&Critical], unit: u32) {
        let cells: Vec<(u32, CellChords)> = self
            .leaves(node)
            .into_iter()
            .filter(|&n| {
                self.cell(n)
                    .entries
                    .iter()
                    .any(|e| e.unit == unit && e.umbra.is_none())
            })
            .filter_map(|n| {
                let polygon = self.mesh.face_polygon(self.face_of(n), 0).ok()?;
                let chords = internal
                    .iter()
                    .enumerate()
                    .filter_map(|(k, c)| {
                        Some((k as u32, polygon.chord_inside(&c.plane, &c.wedge)?))
                    })
                    .collect();
                Some((n, chords))
            })
            .collect();
        self.split_by_internal(cells, internal, unit);
    }

    /// Splits `cells` (leaves listing `unit` outside its umbra, each with
    /// the chords through it of those of the unit's internal
    /// discontinuities `internal` that cross it) by those discontinuities,
    /// each where its wedge crosses a cell: a cell split by one divides the
    /// later ones' chords between its parts (no polygon is made or asked
    /// again).
    fn split_by_internal(
        &mut self,
        cells: Vec<(u32, CellChords)>,
        internal: &[&Critical],
        unit: u32,
    ) {
        let support = *self.polygon.support();
        // Each cell's chords are a run of `chords`, by discontinuity; a
        // split appends its parts' runs. (Runs of every discontinuity,
        // crossing or not, made each split copy and allocate two lists of
        // mostly empty slots.)
        let mut chords: Vec<(u32, Chord)> = Vec::new();
        let mut cells: Vec<(u32, Range<usize>)> = cells
            .into_iter()
            .map(|(leaf, own)| {
                let start = chords.len();
                chords.extend(own);
                (leaf, start..chords.len())
            })
            .collect();
        for (k, critical) in internal.iter().enumerate() {
            let k = k as u32;
            let mut next = Vec::with_capacity(cells.len());
            for (leaf, mut run) in cells {
                // (The runs hold the discontinuities from `k` on.)
                if run.is_empty() || chords[run.start].0 != k {
                    next.push((leaf, run));
                    continue;
                }
                run.start += 1;
                let Ok((back, front)) = self.split_leaf(leaf, &critical.plane, unit) else {
                    next.push((leaf, run));
                    continue;
                };
                let mut ahead: SmallVec<[(u32, Chord); 8]> = SmallVec::new();
                let start = chords.len();
                for i in run {
                    let (j, (b, f)) = {
                        let (j, chord) = &chords[i];
                        (*j, chord.split(&support, &critical.plane))
                    };
                    chords.extend(b.map(|chord| (j, chord)));
                    ahead.extend(f.map(|chord| (j, chord)));
                }
                let middle = chords.len();
                chords.extend(ahead);
                next.extend([(back, start..middle), (front, middle..chords.len())]);
            }
            cells = next;
        }
    }

    /// Splits the cell at `leaf` by `planes` in turn, following the back;
    /// the innermost leaf, or `None` if a plane leaves the cell in front.
    fn chain<'a>(
        &mut self,
        leaf: u32,
        planes: impl IntoIterator<Item = &'a Plane>,
        unit: u32,
    ) -> Option<u32> {
        let mut cur = leaf;
        for plane in planes {
            match self.split_leaf(cur, plane, unit) {
                Ok((back, _)) => cur = back,
                Err(Side::Front) => return None,
                Err(_) => {}
            }
        }
        Some(cur)
    }
}

/// How [`ReceiverDm::grow_leaf`] grew a leaf.
enum Grown {
    /// Its part of the region is one cell listing the unit outside its
    /// umbra, this leaf, whose polygon is the piece.
    Whole(u32),
    /// Its part is in cells of the leaf's subtree, to be looked up.
    Parts,
}

/// How a piece of a unit's penumbra region lies in its umbra.
enum UmbraCover {
    /// All of it in.
    Whole,
    /// None of it (with area).
    Clear,
}

/// How `piece` lies in the umbra bounded by `umbra`; `None` when partly.
fn umbra_cover(piece: &ConvexPolygon, umbra: &[Plane]) -> Option<UmbraCover> {
    // As `clip(piece, umbra)` would find: none of it where a plane leaves
    // the piece in front (or holds it), all of it where none cuts it.
    let mut cut = false;
    for plane in umbra {
        match piece.classify(plane) {
            PolygonSide::Back => {}
            PolygonSide::Both => cut = true,
            PolygonSide::Front | PolygonSide::Coplanar(_) => return Some(UmbraCover::Clear),
        }
    }
    if !cut {
        Some(UmbraCover::Whole)
    } else if clip(piece, umbra).is_none() {
        Some(UmbraCover::Clear)
    } else {
        None
    }
}

/// The planes of `planes` (in their order) that hold an edge of `part`, a
/// convex polygon inside all of them: those that bound it.
fn bounding<'a>(planes: &'a [Plane], part: &'a ConvexPolygon) -> impl Iterator<Item = &'a Plane> {
    planes.iter().filter(|p| part.edges().any(|e| e == *p))
}

#[cfg(test)]
mod tests {
    use super::{UmbraCover, clip, umbra_cover};
    use bsp_core::{ConvexPolygon, GridPoint, Plane};
    use proptest::prelude::*;

    fn g(x: i32, z: i32) -> GridPoint {
        GridPoint { x, y: 0, z }
    }

    /// A square of the floor (y = 0), and the vertical planes through
    /// two floor points (some through its corners, along its edges, or
    /// beside it), as a unit's umbra planes would cut it.
    fn square() -> impl Strategy<Value = ConvexPolygon> {
        (-8_i32..8, -8_i32..8, 1_i32..8).prop_map(|(x, z, s)| {
            ConvexPolygon::from_grid_points(
                &[g(x, z), g(x, z + s), g(x + s, z + s), g(x + s, z)],
                0,
            )
            .expect("a square")
        })
    }

    fn vertical_plane() -> impl Strategy<Value = Option<Plane>> {
        (-12_i32..12, -12_i32..12, -12_i32..12, -12_i32..12).prop_map(|(a, b, c, d)| {
            Plane::through(g(a, b), g(c, d), GridPoint { x: a, y: 1, z: b })
        })
    }

    proptest! {
        /// `umbra_cover` answers what clipping the piece by the planes
        /// finds: all of it kept (Whole), nothing (Clear), or a part
        /// (`None`), by area.
        #[test]
        fn umbra_cover_agrees_with_clipping(
            piece in square(),
            planes in prop::collection::vec(vertical_plane(), 1..5),
        ) {
            let planes: Vec<Plane> = planes.into_iter().flatten().collect();
            prop_assume!(!planes.is_empty());
            let kept = clip(&piece, &planes).map_or(0.0, |p| p.area());
            match umbra_cover(&piece, &planes) {
                Some(UmbraCover::Whole) => prop_assert!((kept - piece.area()).abs() <= 1e-9),
                Some(UmbraCover::Clear) => prop_assert_eq!(kept, 0.0),
                None => prop_assert!(kept > 0.0 && kept < piece.area() - 1e-9),
            }
        }
    }
}
