//! Irradiance at the vertices of the DM cells, by the paper's three cases.
//!
//! For each light, a vertex looks at the cells around it:
//!
//! 1. one of them lists no occluder for the light: the vertex is in the
//!    closure of a region that sees all of it, so it is unoccluded;
//! 2. one of them is in umbra (or the light does not reach it): the vertex
//!    is in the closure of a region that sees none of the light, and gets
//!    none, unless every occluder making that umbra lies on the vertex
//!    (below);
//! 3. otherwise only the occluders listed by *every* cell around it can
//!    hide any of the light from it (an occluder missing from one cell's
//!    list has the vertex on its penumbra volume's boundary, where it hides
//!    nothing of positive area): `illum` computes the visible part of the
//!    light past exactly those.
//!
//! A vertex in a light's plane sees that light edge-on and gets none of
//! it, whatever its cells say (decided exactly, before the cases).
//! Irradiance is continuous except where an occluder touches or pierces
//! the receiver; a vertex on such a line gets its own value, the light it
//! sees past occluders it lies on (so case 1 comes first, as in the paper).
//! So case 2 holds only for an umbra made by an occluder off the vertex;
//! where each one making it lies on the vertex, the vertex sees what the
//! cells on their other side see, past the occluders every cell around
//! lists or culled (a convex solid the light lies behind at the vertex
//! still hides it all).
//! A vertex whose cases and covering occluders are unchanged since the last
//! call keeps its value: after a move only new vertices and those whose
//! covering set changed are evaluated again.

use crate::cell::{Cell, Sides};
use crate::error::Error;
use crate::hash::KeySet;
use crate::marks::{SharedMarks, slot};
use crate::scene::{DmLight, DmScene, Hider, Piece, PieceId};
use crate::tree::ReceiverDm;
use area_shadow::dark::DARK_FRACTION;
use bsp_core::{FaceKey, Side, VertexKey, VertexPosition, WingedMesh};
use illum::{AreaLight, Occluder, Sidedness, VisiblePart, visible_irradiance};
use rayon::prelude::*;
use slotmap::SecondaryMap;
use slotmap::SlotMap;
use smallvec::SmallVec;
use std::collections::BTreeSet;

/// Vertices of one receiver to look at from which on they are shared out
/// among threads (a quarter as many per task; one costs a few
/// microseconds, so a move's few thousand on a big receiver are worth
/// sharing).
const PARALLEL_VERTICES: usize = 512;

/// Faces touched on one receiver from which on their vertices are gathered
/// and evaluated together, a chunk of a quarter as many faces per task:
/// walking the faces for their vertices mostly waits on memory, and the
/// walks beside the evaluations (a few thousand faces on the 10k hall floor
/// after a small move) cost 0.15-0.2 ms less of its 3.0-3.2 ms than walking
/// them all first, on one thread (in parallel that walk was no faster).
const GATHER_FACES: usize = 512;

/// What covers a vertex from one light.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Cover {
    /// Case 1: all of the light is visible.
    Free,
    /// Case 2: no light arrives.
    Dark,
    /// Case 3: these units (occluders) may hide part of it.
    Occluders(SmallVec<[u32; 4]>),
}

/// The covers of a vertex's lights as its value keeps them, to tell
/// whether they changed: per light in order, [`Self::FREE`], [`Self::DARK`],
/// or the number of occluders and then their units. Inline up to six
/// words (two lights with four occluders between them): 32 bytes, where a
/// list of [`Cover`]s took 72 (a value per vertex, over a million on a big
/// receiver).
#[derive(Debug, Clone, PartialEq, Eq)]
struct CoverKey(SmallVec<[u32; 6]>);

impl CoverKey {
    /// Case 1 for a light.
    const FREE: u32 = u32::MAX;
    /// Case 2 for a light.
    const DARK: u32 = u32::MAX - 1;

    fn of(covers: &[Cover]) -> Self {
        let mut words = SmallVec::new();
        for cover in covers {
            match cover {
                Cover::Free => words.push(Self::FREE),
                Cover::Dark => words.push(Self::DARK),
                Cover::Occluders(units) => {
                    // (Fewer units than a unit number: no clash with the
                    // two cases.)
                    words.push(units.len() as u32);
                    words.extend_from_slice(units);
                }
            }
        }
        Self(words)
    }

    /// How many lights are in cases 1, 2 and 3.
    fn cases(&self) -> [usize; 3] {
        let mut counts = [0; 3];
        let mut words = self.0.iter();
        while let Some(&word) = words.next() {
            match word {
                Self::FREE => counts[0] += 1,
                Self::DARK => counts[1] += 1,
                units => {
                    counts[2] += 1;
                    for _ in 0..units {
                        words.next();
                    }
                }
            }
        }
        counts
    }
}

#[derive(Debug, Clone)]
struct VertexValue {
    covers: CoverKey,
    irradiance: f64,
    /// Bit `i`: light `i` gives the vertex nothing.
    dark: u32,
}

/// A receiver's vertex irradiance cache.
#[derive(Debug, Clone, Default)]
pub(crate) struct ReceiverIllum {
    /// Whether every vertex has been evaluated once.
    fresh: bool,
    values: SecondaryMap<VertexKey, VertexValue>,
    /// The unit normal light falls on, when not the polygon's own
    /// ([`DmScene::set_receiver_normal`]).
    pub(crate) normal: Option<[f64; 3]>,
}

/// Figures of one [`DmScene::illuminate`] call.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct IllumStats {
    /// Vertices of the receivers looked at (all of them on a first call,
    /// those of changed receivers afterwards).
    pub vertices: usize,
    /// Vertices whose value was computed (not kept from before).
    pub evaluated: usize,
    /// Vertex-light pairs that see all of the light (case 1).
    pub unoccluded: usize,
    /// Vertex-light pairs in umbra (case 2).
    pub dark: usize,
    /// Vertex-light pairs whose visible part was computed (case 3).
    pub visibility: usize,
    /// Light/occluder comparisons made by those visibility computations
    /// (occluders clipped against the light: a polygon, a convex solid's
    /// silhouette, or each polygon of another body that can hide it from
    /// the vertex), summed.
    pub comparisons: usize,
}

impl IllumStats {
    /// Comparisons per evaluated vertex (the paper reports 1.3 to 2.1).
    pub fn comparisons_per_vertex(&self) -> f64 {
        if self.evaluated == 0 {
            0.0
        } else {
            self.comparisons as f64 / self.evaluated as f64
        }
    }
}

fn cover(cells: &[&Cell], light: usize) -> Cover {
    if cells
        .iter()
        .any(|c| !c.occluded(light) && !c.unreached(light))
    {
        return Cover::Free;
    }
    if cells.iter().any(|c| c.in_umbra(light)) {
        return Cover::Dark;
    }
    let mut units: SmallVec<[u32; 4]> = cells[0]
        .entries()
        .iter()
        .filter(|e| usize::from(e.light) == light)
        .map(|e| e.unit)
        .collect();
    for c in &cells[1..] {
        units.retain(|u| c.entries().iter().any(|e| e.unit == *u));
    }
    units.sort_unstable();
    Cover::Occluders(units)
}

/// Case 2 at a vertex at `position` with cells `cells`: whether the umbra
/// of `light` in one of them leaves the vertex dark. It does when the
/// light does not reach a cell, and when an occluder making the umbra does
/// not lie on the vertex (the closure argument). Where every such occluder
/// lies on it, the vertex lies where they touch or pierce the receiver,
/// the irradiance jumps there, and the vertex sees past them what the
/// cells on their other side see, unless one is a convex solid that hides
/// all of the light from its own boundary there. An umbra hiding the light
/// from one side of a two-sided receiver leaves that side dark: the
/// vertex is when both are.
fn dark_by_umbra(
    cells: &[&Cell],
    light: usize,
    dm: &ReceiverDm<PieceId>,
    pieces: &SlotMap<PieceId, Piece>,
    position: &VertexPosition,
) -> bool {
    if cells.iter().any(|c| c.unreached(light)) {
        return true;
    }
    let mut umbrae: SmallVec<[(u32, Sides); 4]> = cells
        .iter()
        .flat_map(|c| c.entries())
        .filter(|e| !e.umbra.is_none() && usize::from(e.light) == light)
        .map(|e| (e.unit, e.umbra))
        .collect();
    umbrae.sort_unstable_by_key(|&(u, _)| u);
    umbrae.dedup();
    let within = dm.polygon().support();
    let at = position.to_f64();
    let mut dark = Sides::NONE;
    for &(u, sides) in &umbrae {
        if dark.contains(sides) {
            continue;
        }
        let Some((o, _)) = dm.unit(u) else {
            continue;
        };
        let occluder = &pieces[o];
        let hides = occluder
            .holding(position, at, within)
            .is_none_or(|held| occluder.hides_all_past(&held, light));
        if hides {
            dark |= sides;
            if dark.is_both() {
                return true;
            }
        }
    }
    false
}

/// The units of `light` that every one of `cells` lists or culled: every
/// occluder that can hide light of positive area from a vertex of them
/// without lying on it (such a one hides some from all the points around
/// the vertex, so each cell there lists it, or culled it under another's
/// umbra).
fn occluders_around(cells: &[&Cell], light: usize, dm: &ReceiverDm<PieceId>) -> Cover {
    let reaching = |cell: &Cell| -> SmallVec<[u32; 4]> {
        let listed = cell
            .entries()
            .iter()
            .filter(|e| usize::from(e.light) == light)
            .map(|e| e.unit);
        let culled = cell
            .culled
            .iter()
            .copied()
            .filter(|&u| dm.unit(u).is_some_and(|(_, l)| usize::from(l) == light));
        listed.chain(culled).collect()
    };
    let mut units = reaching(cells[0]);
    for cell in &cells[1..] {
        let other = reaching(cell);
        units.retain(|u| other.contains(u));
    }
    units.sort_unstable();
    Cover::Occluders(units)
}

impl IllumStats {
    /// The figures of evaluating one vertex with `covers`, clipping
    /// `comparisons` occluder polygons (kept apart from the values: a first
    /// call evaluates millions of vertices).
    fn of_evaluation(covers: &CoverKey, comparisons: usize) -> Self {
        let [unoccluded, dark, visibility] = covers.cases();
        Self {
            evaluated: 1,
            unoccluded,
            dark,
            visibility,
            comparisons,
            ..Self::default()
        }
    }

    pub(crate) fn add(mut self, other: Self) -> Self {
        self.vertices += other.vertices;
        self.evaluated += other.evaluated;
        self.unoccluded += other.unoccluded;
        self.dark += other.dark;
        self.visibility += other.visibility;
        self.comparisons += other.comparisons;
        self
    }
}

impl DmScene {
    /// Sets the normal that light falls on at receiver `piece` in place of
    /// its polygon's: the input polygon's, say, of which the polygon is a
    /// copy snapped to the grid (a thin one's plane turns by up to a grid
    /// step over its width). Only irradiance changes; the receiver's
    /// values are computed anew at the next [`Self::illuminate`]. A move
    /// keeps it for a polygon whose plane keeps its orientation.
    ///
    /// Errors: [`Error::UnknownPiece`] for no such receiver,
    /// [`Error::BadNormal`] for a zero or non-finite `normal`.
    pub fn set_receiver_normal(&mut self, piece: PieceId, normal: [f64; 3]) -> Result<(), Error> {
        let length = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(length > 0.0 && length.is_finite()) {
            return Err(Error::BadNormal);
        }
        let state = self.illum.get_mut(piece).ok_or(Error::UnknownPiece)?;
        state.normal = Some(normal.map(|x| x / length));
        state.values.clear();
        state.fresh = false;
        self.unlit.insert(piece);
        self.revision += 1;
        self.changed_at.insert(piece, self.revision);
        Ok(())
    }

    /// Computes the irradiance at the vertices of every receiver changed
    /// since the last call (all of them the first time), keeping the value
    /// of every vertex whose covering occluders did not change. Receivers
    /// are worked on in parallel; the values do not depend on the number of
    /// threads.
    ///
    /// Once it has run, every change (adding, removing or moving an
    /// object) illuminates the receivers it touched as it updates them, so
    /// that their vertex irradiance is current right after the change;
    /// this call then has little left to do, and its figures include the
    /// work those changes did since the last call.
    pub fn illuminate(&mut self) -> IllumStats {
        self.revision += 1;
        self.lit = true;
        let since = std::mem::take(&mut self.lit_since);
        since.add(self.illuminate_pending())
    }

    /// The receivers changed and not illuminated yet, illuminated: those
    /// of [`DmScene::unlit`] (a change illuminates the others it touches
    /// as it goes).
    pub(crate) fn illuminate_pending(&mut self) -> IllumStats {
        let pending: BTreeSet<PieceId> = std::mem::take(&mut self.unlit)
            .into_iter()
            .filter(|&r| {
                self.receivers.get(r).is_some_and(|dm| {
                    dm.has_touched() || self.illum.get(r).is_some_and(|s| !s.fresh)
                })
            })
            .collect();
        let (lights, pieces) = (&self.lights, &self.pieces);
        if pending.len() <= 2 {
            // A small update: no tasks to hand out.
            let mut scratch = VisiblePart::new();
            let mut stats = IllumStats::default();
            for r in pending {
                if let (Some(dm), Some(state)) = (self.receivers.get_mut(r), self.illum.get_mut(r))
                {
                    stats = stats.add(illuminate_receiver(
                        lights,
                        pieces,
                        r,
                        dm,
                        state,
                        &mut scratch,
                    ));
                    self.changed_at.insert(r, self.revision);
                }
            }
            return stats;
        }
        // The receivers taken out of the scene by key (a walk over every
        // receiver would cost more than a few small ones' illumination),
        // and put back after.
        let mut work: Vec<(PieceId, ReceiverDm<PieceId>, ReceiverIllum)> = Vec::new();
        for r in pending {
            if !self.illum.contains_key(r) || !self.receivers.contains_key(r) {
                continue;
            }
            if let (Some(dm), Some(state)) = (self.receivers.remove(r), self.illum.remove(r)) {
                work.push((r, dm, state));
            }
        }
        // Big receivers first, so that no thread is left with one at the
        // end; each receiver a task of its own, so that while one thread
        // works on the biggest the other can take any of the rest (a run of
        // receivers split off together goes on one thread, and would hold
        // the other idle at the end).
        work.sort_by_key(|(_, dm, _)| std::cmp::Reverse(dm.cell_count()));
        let (lights, pieces) = (&self.lights, &self.pieces);
        let stats = work
            .par_iter_mut()
            .with_max_len(1)
            .map_init(VisiblePart::new, |scratch, (r, dm, state)| {
                illuminate_receiver(lights, pieces, *r, dm, state, scratch)
            })
            .reduce(IllumStats::default, IllumStats::add);
        for (r, dm, state) in work {
            self.receivers.insert(r, dm);
            self.illum.insert(r, state);
            self.changed_at.insert(r, self.revision);
        }
        stats
    }

    /// The irradiance at a vertex of a receiver's mesh (all lights, grid
    /// units; ambient excluded), once [`illuminate`](Self::illuminate) ran.
    pub fn vertex_irradiance(&self, receiver: PieceId, vertex: VertexKey) -> Option<f64> {
        self.illum
            .get(receiver)?
            .values
            .get(vertex)
            .map(|v| v.irradiance)
    }

    /// The lights that give a vertex of a receiver's mesh no irradiance,
    /// or at most [`DARK_FRACTION`] of what all of the light would give, a
    /// trace that rounding leaves (bit `i` for light `i`), once [`illuminate`](Self::illuminate) ran.
    pub fn vertex_dark_lights(&self, receiver: PieceId, vertex: VertexKey) -> Option<u32> {
        self.illum.get(receiver)?.values.get(vertex).map(|v| v.dark)
    }
}

/// [`DmScene::illuminate`] on one receiver.
pub(crate) fn illuminate_receiver(
    lights: &[DmLight],
    pieces: &SlotMap<PieceId, Piece>,
    r: PieceId,
    dm: &mut ReceiverDm<PieceId>,
    state: &mut ReceiverIllum,
    scratch: &mut VisiblePart,
) -> IllumStats {
    let mut stats = IllumStats::default();
    let everything = !state.fresh;
    let touched = if everything {
        dm.start_tracking();
        Vec::new()
    } else {
        dm.take_touched()
    };
    if !everything && touched.is_empty() {
        return stats;
    }
    let dm = &*dm;
    let piece = &pieces[r];
    let normal = state
        .normal
        .unwrap_or_else(|| piece.polygon.support().unit_normal_f64());
    let sided = if piece.flags.two_sided {
        Sidedness::TwoSided
    } else {
        Sidedness::OneSided
    };
    let mesh = dm.mesh();
    let values = &state.values;
    // The cases at a vertex, and its value if they changed: each depends on
    // its vertex only, so a big receiver's vertices go in parallel chunks.
    let work = |v: VertexKey, scratch: &mut VisiblePart| {
        let cells: SmallVec<[&Cell; 6]> = mesh
            .faces_around(v)
            .flatten()
            .filter_map(|f| mesh.face(f).map(|face| &face.data))
            .collect();
        let position = mesh.vertex(v).expect("face vertex").position;
        let covers: SmallVec<[Cover; 2]> = lights
            .iter()
            .enumerate()
            .map(|(i, light)| {
                // In the light's plane the light is seen edge-on (exactly
                // decided; f64 would be ill-conditioned where a receiver
                // pierces the light).
                if position.side(light.source.support()) == Side::On {
                    return Cover::Dark;
                }
                match cover(&cells, i) {
                    Cover::Dark if !dark_by_umbra(&cells, i, dm, pieces, &position) => {
                        occluders_around(&cells, i, dm)
                    }
                    other => other,
                }
            })
            .collect();
        let key = CoverKey::of(&covers);
        if values.get(v).is_some_and(|value| value.covers == key) {
            return None;
        }
        let (irradiance, dark, comparisons) = evaluate(
            lights, pieces, dm, &position, normal, sided, &covers, scratch,
        );
        let value = VertexValue {
            covers: key,
            irradiance,
            dark,
        };
        Some((v, value, comparisons))
    };
    // Each vertex once, taken in the order of their keys: on a big
    // receiver they are scattered over its arenas, and taken in memory
    // order they are evaluated a quarter faster (10k hall floor after a
    // move, one thread), their values and neighbours sharing cache lines.
    let in_order = |vertices: &[VertexKey], scratch: &mut VisiblePart| {
        if vertices.len() >= PARALLEL_VERTICES {
            vertices
                .par_iter()
                .with_min_len(PARALLEL_VERTICES / 4)
                .map_init(VisiblePart::new, |scratch, &v| work(v, scratch))
                .collect()
        } else {
            vertices.iter().map(|&v| work(v, scratch)).collect()
        }
    };
    // (In chunks, as found.)
    let results: Vec<Vec<_>> = if everything {
        // All of them the first time.
        let vertices: Vec<VertexKey> = mesh.vertices().map(|(v, _)| v).collect();
        stats.vertices = vertices.len();
        vec![in_order(&vertices, scratch)]
    } else if touched.len() >= GATHER_FACES {
        // After a big change, those of the faces touched, gathered and
        // evaluated a chunk of faces at a time, the chunks in parallel
        // (each vertex marked by the chunk that finds it first), in the
        // order of their keys within a chunk.
        let (vertex_slots, ..) = mesh.capacity();
        let seen = SharedMarks::new(vertex_slots + 1);
        let chunks: Vec<(usize, Vec<_>)> = touched
            .par_chunks(GATHER_FACES / 4)
            .map_init(VisiblePart::new, |scratch, faces| {
                let mut each: Vec<VertexKey> = corners(mesh, faces)
                    .filter(|&v| seen.insert(slot(v)))
                    .collect();
                each.sort_unstable();
                let values = each.iter().map(|&v| work(v, scratch)).collect();
                (each.len(), values)
            })
            .collect();
        stats.vertices = chunks.iter().map(|(n, _)| n).sum();
        chunks.into_iter().map(|(_, values)| values).collect()
    } else {
        // After a small one, those of the faces touched, once each (by a
        // hash set: sorting them all with their repeats costs more).
        let mut seen: KeySet<VertexKey> = KeySet::default();
        seen.reserve(4 * touched.len());
        let mut each: Vec<VertexKey> = corners(mesh, &touched)
            .filter(|&v| seen.insert(v))
            .collect();
        each.sort_unstable();
        stats.vertices = each.len();
        vec![in_order(&each, scratch)]
    };
    let values = &mut state.values;
    for (v, value, comparisons) in results.into_iter().flatten().flatten() {
        stats = stats.add(IllumStats::of_evaluation(&value.covers, comparisons));
        values.insert(v, value);
    }
    // Values of vertices gone since are dropped now and then.
    let (live, _, _) = mesh.counts();
    if values.len() > 2 * live + 64 {
        values.retain(|v, _| mesh.contains_vertex(v));
    }
    state.fresh = true;
    stats
}

/// The corners of `faces`, with repeats.
fn corners<'a>(
    mesh: &'a WingedMesh<Cell, ()>,
    faces: &'a [FaceKey],
) -> impl Iterator<Item = VertexKey> + 'a {
    faces
        .iter()
        .flat_map(|&f| mesh.face_sides(f).map(|side| side.start))
}

/// The irradiance at a vertex at `position` (receiver normal `normal`)
/// with the covers `covers` of the lights, the lights that give it nothing
/// (bit `i` for light `i`), and the number of occluder polygons clipped
/// against a light for it.
#[allow(clippy::too_many_arguments)] // (the receiver's fixed context, and the vertex)
fn evaluate(
    lights: &[DmLight],
    pieces: &SlotMap<PieceId, Piece>,
    dm: &ReceiverDm<PieceId>,
    position: &VertexPosition,
    normal: [f64; 3],
    sided: Sidedness,
    covers: &[Cover],
    scratch: &mut VisiblePart,
) -> (f64, u32, usize) {
    let p = position.to_f64();
    let mut irradiance = 0.0;
    let mut dark = 0;
    let mut comparisons = 0;
    for (i, (light, cover)) in lights.iter().zip(covers).enumerate() {
        let value = match cover {
            Cover::Dark => 0.0,
            Cover::Free => light.illum.irradiance(p, normal, sided),
            Cover::Occluders(units) => {
                let mut hiders: SmallVec<[Hider; 8]> = SmallVec::new();
                let mut loops = SmallVec::new();
                for (o, _) in units.iter().filter_map(|u| dm.unit(*u)) {
                    pieces[o].hiders(pieces, i, position, &mut hiders, &mut loops);
                }
                comparisons += hiders.len();
                let occluders: SmallVec<[Occluder; 8]> =
                    hiders.iter().map(|h| h.occluder(&loops)).collect();
                visible_irradiance(&light.illum, &occluders, p, normal, sided, scratch)
            }
        };
        // Rounding leaves a vertex that sees nothing a trace of light
        // (1e-18 of it, say): dark below a billionth of the whole light.
        if value == 0.0
            || (matches!(cover, Cover::Occluders(_))
                && is_trace(value, &light.illum, p, normal, sided))
        {
            dark |= 1 << i;
        }
        irradiance += value;
    }
    (irradiance, dark, comparisons)
}

/// Whether `value`, the irradiance from the part of `light` a vertex at
/// `p` sees (unit normal `normal`), is a trace that rounding leaves: at
/// most [`DARK_FRACTION`] of what all of the light gives there. That
/// whole light's irradiance (a contour integral, the cost of a vertex that
/// sees all of the light) is computed only when `value` is below that
/// fraction of a bound on it, `4 pi` radiance: a side's projected solid
/// angle is at most `pi`, and a two-sided receiver has two (the bound
/// doubled again for rounding). A vertex in penumbra sees far more.
fn is_trace(
    value: f64,
    light: &AreaLight,
    p: [f64; 3],
    normal: [f64; 3],
    sided: Sidedness,
) -> bool {
    let bound = 4.0 * std::f64::consts::PI * light.radiance();
    value <= DARK_FRACTION * bound && value <= DARK_FRACTION * light.irradiance(p, normal, sided)
}

#[cfg(test)]
mod tests {
    use super::{Cover, CoverKey, IllumStats, VertexValue};
    use smallvec::smallvec;

    /// Covers kept as words tell the same cases apart as the covers, and
    /// changes of them, and a vertex's value stays within 48 bytes.
    #[test]
    fn cover_keys_keep_what_tells_covers_apart() {
        let lists: Vec<Vec<Cover>> = vec![
            vec![Cover::Free, Cover::Dark],
            vec![Cover::Dark, Cover::Free],
            vec![Cover::Occluders(smallvec![]), Cover::Free],
            vec![Cover::Occluders(smallvec![3]), Cover::Free],
            vec![Cover::Occluders(smallvec![3, 7]), Cover::Dark],
            vec![
                Cover::Occluders(smallvec![3]),
                Cover::Occluders(smallvec![7]),
            ],
            vec![
                Cover::Occluders(smallvec![3, 7]),
                Cover::Occluders(smallvec![]),
            ],
            vec![Cover::Occluders(smallvec![1, 2, 3, 4, 5, 6, 7, 8])],
        ];
        for (i, a) in lists.iter().enumerate() {
            let key = CoverKey::of(a);
            for (j, b) in lists.iter().enumerate() {
                assert_eq!(key == CoverKey::of(b), i == j, "{a:?} against {b:?}");
            }
            let stats = IllumStats::of_evaluation(&key, 0);
            let count = |f: fn(&Cover) -> bool| a.iter().filter(|c| f(c)).count();
            assert_eq!(stats.unoccluded, count(|c| matches!(c, Cover::Free)));
            assert_eq!(stats.dark, count(|c| matches!(c, Cover::Dark)));
            assert_eq!(
                stats.visibility,
                count(|c| matches!(c, Cover::Occluders(_)))
            );
        }
        assert!(std::mem::size_of::<VertexValue>() <= 48);
    }
}
