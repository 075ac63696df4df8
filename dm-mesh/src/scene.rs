//! A scene of objects under area lights, with one DM-tree per receiving
//! polygon, kept up to date as objects are added, removed and moved.

use crate::critical::UnitPlanes;
use crate::error::Error;
use crate::hash::KeyMap;
use crate::illuminate::{IllumStats, ReceiverIllum};
use crate::overlap::{Overlap, OverlapFigures, OverlapKind};
use crate::tree::{Deletion, ReceiverDm};
use area_shadow::{AreaSource, ConvexGroup};
use bsp_core::{ConvexPolygon, GridPoint, Plane, Side, VertexPosition};
use contact::ContactPlanes;
use rayon::prelude::*;
use silhouette::SolidCorners;
use slotmap::{SecondaryMap, SlotMap, new_key_type};
use smallvec::SmallVec;
use std::collections::BTreeSet;
use svbsp::PieceFlags;

mod ahead;
mod attach;
mod contact;
mod joint;
mod silhouette;
#[cfg(test)]
pub(crate) mod testing;
mod update;

new_key_type! {
    /// Handle of an object (a group of polygons added, moved and removed
    /// together).
    pub struct ObjectId;
    /// Handle of one convex polygon of an object: a receiver and, if its
    /// object casts shadows, an occluder.
    pub struct PieceId;
}

/// Units (occluder, light) to merge into one receiver, in order, after
/// tiling it to that depth.
type Order = (u32, Vec<(PieceId, u8)>);

/// Units per tile of a new receiver (see [`ReceiverDm::tile`]). Tile lines
/// cut cells that no discontinuity would; one tile per 16 units rather
/// than 4 leaves 4-8 % fewer cells (10k hall 2.24M -> 2.07M, office 2438
/// -> 2329, cubes 3427 -> 3177) and rebuilds 2-5 % fewer instructions,
/// moves costing the same to 3 % (callgrind, one thread, `dm-cost`).
const TILE_UNITS: usize = 16;
/// At most `2^MAX_TILE_DEPTH` tiles per receiver.
const MAX_TILE_DEPTH: u32 = 12;

/// The bounding box of points (least and greatest corners).
pub(crate) fn bounds_of(points: &[[f64; 3]]) -> [[f64; 3]; 2] {
    points.iter().fold(
        [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]],
        |[lo, hi], p| {
            [
                std::array::from_fn(|a| lo[a].min(p[a])),
                std::array::from_fn(|a| hi[a].max(p[a])),
            ]
        },
    )
}

/// An area light: a convex polygon on the grid and its radiance.
#[derive(Debug, Clone)]
pub struct DmLight {
    pub(crate) source: AreaSource,
    pub(crate) illum: illum::AreaLight,
}

impl DmLight {
    /// A light of `radiance` over `source` (coordinates in grid units, as
    /// everything else here).
    pub fn new(source: AreaSource, radiance: f64) -> Result<Self, Error> {
        let vertices: Vec<[f64; 3]> = source.vertices().map(|g| g.to_f64()).collect();
        if !(radiance.is_finite() && radiance >= 0.0) {
            return Err(Error::BadRadiance(0));
        }
        let illum = illum::AreaLight::new(&vertices, radiance)
            .map_err(|e| Error::Light(0, e.to_string()))?;
        Ok(Self { source, illum })
    }

    /// The light's polygon.
    pub fn source(&self) -> &AreaSource {
        &self.source
    }
}

/// What a piece of the scene is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PieceKind {
    /// A convex polygon of an object: a receiver, and an occluder if its
    /// object casts shadows.
    Polygon,
    /// A convex body that several polygons of an object form
    /// ([`area_shadow::convex_groups`]), an occluder and no receiver: under
    /// a light where it is exactly convex and wholly in front of the light
    /// ([`area_shadow::ConvexGroup::penumbra_planes`]) it casts in place of
    /// its polygons (one unit with the body's penumbra, umbra and internal
    /// discontinuities); under the others its one volume is its umbra (its
    /// polygons may hide the whole light only together). The pieces of a
    /// flat union that is no convex polygon
    /// ([`area_shadow::flat_unions`]), and those of a body that holds a
    /// light in or is one face short
    /// ([`area_shadow::ConvexGroup::umbra_parts`]), make
    /// bodies of this kind too, one per convex part of the umbra they make
    /// together, with only that umbra.
    Body,
}

#[derive(Debug, Clone)]
pub(crate) struct Piece {
    /// The polygon; of a body, its first polygon's (it only places the
    /// body in the order units are merged in).
    pub(crate) polygon: ConvexPolygon,
    pub(crate) kind: PieceKind,
    pub(crate) object: ObjectId,
    pub(crate) flags: PieceFlags,
    /// Per light: the penumbra and umbra volume planes and the internal
    /// discontinuities (empty when the piece casts no shadow of that
    /// light).
    pub(crate) volumes: Vec<UnitPlanes>,
    /// Grid-unit vertices (of a body, all its polygons'), for illumination
    /// and the overlap structure.
    pub(crate) outline: Vec<[f64; 3]>,
    /// The outline's bounding box (least and greatest corners).
    pub(crate) bounds: [[f64; 3]; 2],
    /// Of a body: its polygons. Empty for a polygon.
    pub(crate) members: Vec<Member>,
    /// Of a body: the lights (bit per light) under which it casts in place
    /// of its polygons.
    pub(crate) whole: u32,
    /// Of a body: whether its polygons are the whole boundary of a convex
    /// polyhedron ([`ConvexGroup::is_closed_convex`]).
    pub(crate) solid: bool,
    /// Of such a solid: its members' corners, numbered, to find its
    /// silhouette from a vertex (`None` for others, past 255 corners, and
    /// where its members' edges do not pair up exactly).
    pub(crate) corners: Option<SolidCorners>,
    /// Whether it is of a movable object (of a joint body: of any), which
    /// puts its units after the static ones (module `order`).
    pub(crate) movable: bool,
}

/// What hides light from a vertex, as [`Piece::hiders`] gives it.
#[derive(Debug, Clone)]
pub(crate) enum Hider<'p> {
    /// A convex polygon's corners.
    Polygon(&'p [[f64; 3]]),
    /// A convex solid's silhouette: the corners at these positions of the
    /// silhouettes' list.
    Silhouette(std::ops::Range<usize>),
}

impl Hider<'_> {
    /// The occluder `illum` takes, the silhouettes' corners in `loops`.
    pub(crate) fn occluder<'a>(&'a self, loops: &'a [[f64; 3]]) -> illum::Occluder<'a> {
        match self {
            Self::Polygon(corners) => illum::Occluder::Polygon(corners),
            Self::Silhouette(range) => illum::Occluder::Silhouette(&loops[range.clone()]),
        }
    }
}

impl Piece {
    /// Appends what hides what this occluder hides of light `light` from a
    /// vertex at `position`: a polygon's own outline (none from its
    /// plane), or some of a body's polygons. From outside the body, those
    /// with the vertex strictly on their outer side (a segment from the
    /// light through the body leaves it through one of them: at most three
    /// of a box); of a convex solid wholly in front of the light, rather
    /// the loop they make, its silhouette from the vertex (one occluder,
    /// its corners appended to `loops`). From its boundary (a two-sided
    /// receiver of the body's own sees light from behind, through the
    /// body), those with some of the light in front that do not hold the
    /// vertex (the segment enters through one of them).
    pub(crate) fn hiders<'p>(
        &'p self,
        pieces: &'p SlotMap<PieceId, Piece>,
        light: usize,
        position: &VertexPosition,
        out: &mut SmallVec<[Hider<'p>; 8]>,
        loops: &mut SmallVec<[[f64; 3]; 24]>,
    ) {
        if self.kind == PieceKind::Polygon {
            // From its own plane (a receiver it touches along an edge: a
            // bent quad's other triangle) a polygon hides nothing of
            // positive area; decided exactly, as in floating point the
            // vertex lies a rounding error off the plane, and the blocked
            // region from a point on the polygon's edge came out as the
            // whole light.
            if position.side(self.polygon.support()) != Side::On {
                out.push(Hider::Polygon(&self.outline));
            }
            return;
        }
        let sides: SmallVec<[Side; 8]> = self
            .members
            .iter()
            .map(|m| position.side(&m.outward))
            .collect();
        let outside = sides.contains(&Side::Front);
        if outside
            && self.whole & (1 << light) != 0
            && let Some(solid) = &self.corners
        {
            let start = loops.len();
            if solid.silhouette(|i| sides[i] == Side::Front, loops) {
                out.push(Hider::Silhouette(start..loops.len()));
                return;
            }
        }
        let hiding = self.members.iter().zip(sides).filter(|(m, side)| {
            if outside {
                *side == Side::Front
            } else {
                *side != Side::On && m.facing & (1 << light) != 0
            }
        });
        out.extend(hiding.map(|(m, _)| Hider::Polygon(&pieces[m.piece].outline)));
    }

    /// The members of a body whose planes hold a point on its boundary
    /// (of a polygon, none), or `None` when the point is not on the piece:
    /// in a polygon's plane (where a polygon whose umbra reaches the point
    /// can only hold it), on a body's boundary (on a member's plane, in
    /// front of none). The point, at about `at`, is known to lie in plane
    /// `within` (a receiver's: the sides of a point on it are slow to
    /// decide exactly, and need not be).
    pub(crate) fn holding(
        &self,
        position: &VertexPosition,
        at: [f64; 3],
        within: &Plane,
    ) -> Option<SmallVec<[usize; 4]>> {
        if self.kind == PieceKind::Polygon {
            let on = self.polygon.support().is_coincident(within)
                || position.side(self.polygon.support()) == Side::On;
            return on.then(SmallVec::new);
        }
        // Outside the body's box the point is not on it: most points asked
        // about lie in the body's umbra, away from it. (A filter: `at` is
        // within `coordinate_error` of the exact point, so a coordinate
        // beyond the box by more than that is beyond it exactly.)
        let [lo, hi] = self.bounds;
        if (0..3).any(|a| {
            let slack = VertexPosition::coordinate_error(at[a]);
            at[a] < lo[a] - slack || at[a] > hi[a] + slack
        }) {
            return None;
        }
        let mut held = SmallVec::new();
        for (m, member) in self.members.iter().enumerate() {
            if member.outward.is_coincident(within) {
                held.push(m);
                continue;
            }
            match position.side(&member.outward) {
                Side::Front => return None,
                Side::On => held.push(m),
                Side::Back => {}
            }
        }
        (!held.is_empty()).then_some(held)
    }

    /// Whether a point on the piece sees none of light `light` past the
    /// piece's polygons `held` that hold it ([`Self::holding`]): the piece
    /// is a convex solid and the light lies on or behind the plane of each
    /// of them, so a segment to the light goes into the solid and out
    /// through another polygon.
    pub(crate) fn hides_all_past(&self, held: &[usize], light: usize) -> bool {
        self.solid
            && held
                .iter()
                .all(|&m| self.members[m].facing & (1 << light) == 0)
    }

    /// Whether under light `light` this piece is a body that casts its
    /// umbra only (its polygons casting their own units).
    pub(crate) fn umbra_only(&self, light: usize) -> bool {
        self.kind == PieceKind::Body && self.whole & (1 << light) == 0
    }

    /// Where the piece is, for the order units merge in: a polygon's
    /// centroid, the mean of a body's vertices.
    pub(crate) fn centre(&self) -> [f64; 3] {
        match self.kind {
            PieceKind::Polygon => self.polygon.centroid(),
            PieceKind::Body => {
                let n = self.outline.len().max(1) as f64;
                let sum = self.outline.iter().fold([0.0; 3], |acc, v| {
                    [acc[0] + v[0], acc[1] + v[1], acc[2] + v[2]]
                });
                sum.map(|c| c / n)
            }
        }
    }
}

/// A polygon of a body.
#[derive(Debug, Clone)]
pub(crate) struct Member {
    pub(crate) piece: PieceId,
    /// Its plane, facing out of the body.
    pub(crate) outward: Plane,
    /// The lights (bit per light) with some of their area in front of it.
    pub(crate) facing: u32,
}

#[derive(Debug, Clone, Default)]
pub(crate) struct Object {
    pub(crate) pieces: Vec<PieceId>,
    /// The convex bodies its polygons form (pieces of kind
    /// [`PieceKind::Body`]).
    pub(crate) bodies: Vec<PieceId>,
    /// The groups its polygons form, their pieces indices into
    /// [`Self::pieces`]: the closed convex ones may join other objects'
    /// (module `joint`).
    pub(crate) solids: Vec<ConvexGroup>,
    /// The joint bodies it is part of (module `joint`).
    pub(crate) joints: Vec<PieceId>,
    /// Whether it was declared movable ([`DmScene::build_movable`]).
    pub(crate) movable: bool,
}

/// How the discontinuity meshes are built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DmOptions {
    /// Whether the internal EV / VE discontinuities inside each penumbra
    /// cut the cells too (default); without them cells are bounded by
    /// penumbra and umbra edges only (fewer cells, faster; vertex
    /// irradiance is exact either way, but inside a cell it is no longer
    /// smooth).
    pub internal_discontinuities: bool,
    /// How removals (and moves) take an occluder's discontinuities out of
    /// the trees: by default the paper's local deletion.
    pub deletion: Deletion,
    /// Which structure pairs occluders with the receivers they may shadow:
    /// by default a uniform grid of boxes (it localises better than the
    /// paper's shadow overlap cube on the benchmark scenes).
    pub overlap: OverlapKind,
    /// Whether a closed, exactly convex body wholly in front of a light
    /// casts one unit under it in place of its polygons (default): its
    /// penumbra volume is one convex set of planes, so a box puts one
    /// region in each receiver's tree instead of one per face facing the
    /// light, and none of the faces' penumbra planes through edges the
    /// light sees on both sides. Off, each polygon casts its own unit and
    /// the body only its umbra (the paper's way).
    pub convex_bodies: bool,
}

impl Default for DmOptions {
    fn default() -> Self {
        Self {
            internal_discontinuities: true,
            deletion: Deletion::default(),
            overlap: OverlapKind::default(),
            convex_bodies: true,
        }
    }
}

/// Discontinuity meshes of a scene: one DM-tree per receiving polygon,
/// holding the discontinuities of every area light (occluder lists per
/// light in each cell).
#[derive(Debug, Clone)]
pub struct DmScene {
    pub(crate) lights: Vec<DmLight>,
    pub(crate) objects: SlotMap<ObjectId, Object>,
    pub(crate) pieces: SlotMap<PieceId, Piece>,
    pub(crate) receivers: SecondaryMap<PieceId, ReceiverDm<PieceId>>,
    pub(crate) illum: SecondaryMap<PieceId, ReceiverIllum>,
    /// Per receiver, the body units it sees adapted (kept as units come
    /// and go).
    pub(crate) contacts: SecondaryMap<PieceId, ContactPlanes>,
    pub(crate) overlap: Overlap,
    /// The objects with a convex body that has a face in each plane
    /// (facing out), with the body's bounding box, for finding the bodies
    /// that touch.
    pub(crate) solid_faces: KeyMap<Plane, Vec<(ObjectId, joint::Bounds)>>,
    /// The objects with a body that has a surface corner at each grid
    /// point ([`ConvexGroup::joining_corners`]), for finding the bodies the
    /// grid bent that touch others.
    pub(crate) solid_corners: KeyMap<GridPoint, Vec<ObjectId>>,
    /// The shadow-casting polygons in each plane (either way facing, under
    /// [`area_shadow::one_way`]), with their bounding boxes, for finding
    /// coplanar polygons of several objects side by side.
    pub(crate) flat_planes: KeyMap<Plane, Vec<(PieceId, joint::Bounds)>>,
    /// Each joint body's polygons' pieces, ascending.
    pub(crate) joints: KeyMap<PieceId, Vec<PieceId>>,
    pub(crate) options: DmOptions,
    /// Whether [`illuminate`](Self::illuminate) has run: from then on a
    /// change illuminates each receiver it touched right after updating
    /// it, in the same parallel pass (so the small receivers' illumination
    /// runs while a big one is still being updated).
    pub(crate) lit: bool,
    /// Figures of the illumination that changes did since the last
    /// [`illuminate`](Self::illuminate) call.
    pub(crate) lit_since: IllumStats,
    /// The receivers whose vertex irradiance may not be current: every
    /// receiver made since the last illumination (before the first one,
    /// all of them). A change that illuminates the receivers it touched
    /// looks only here for the rest, not at every receiver of the scene
    /// (the 10k hall's 10k: a tenth of a box's move).
    pub(crate) unlit: BTreeSet<PieceId>,
    /// The receivers of many cells, whose removals a small change floods
    /// ahead (module `ahead`), kept as changes put receivers back.
    pub(crate) big_receivers: BTreeSet<PieceId>,
    /// How many changes the scene has seen ([`Self::revision`]).
    pub(crate) revision: u64,
    /// Per receiver, the revision that last changed its cells or vertex
    /// irradiance ([`Self::receivers_changed_since`]).
    pub(crate) changed_at: SecondaryMap<PieceId, u64>,
    /// Removals flooded ahead so far (for tests to see that they were).
    #[cfg(test)]
    pub(crate) floods_ahead: usize,
}

impl DmScene {
    /// An empty scene under `lights` (at most 32), default options.
    pub fn new(lights: Vec<DmLight>) -> Result<Self, Error> {
        Self::with_options(lights, DmOptions::default())
    }

    /// An empty scene under `lights` (at most 32).
    pub fn with_options(lights: Vec<DmLight>, options: DmOptions) -> Result<Self, Error> {
        if lights.len() > 32 {
            return Err(Error::TooManyLights(lights.len()));
        }
        let overlap = Overlap::new(&lights, options.overlap);
        Ok(Self {
            lights,
            objects: SlotMap::with_key(),
            pieces: SlotMap::with_key(),
            receivers: SecondaryMap::new(),
            illum: SecondaryMap::new(),
            contacts: SecondaryMap::new(),
            overlap,
            solid_faces: KeyMap::default(),
            solid_corners: KeyMap::default(),
            flat_planes: KeyMap::default(),
            joints: KeyMap::default(),
            options,
            lit: false,
            lit_since: IllumStats::default(),
            unlit: BTreeSet::new(),
            big_receivers: BTreeSet::new(),
            revision: 0,
            changed_at: SecondaryMap::new(),
            #[cfg(test)]
            floods_ahead: 0,
        })
    }

    /// A scene built from scratch: every object added at once, default
    /// options.
    pub fn build(
        lights: Vec<DmLight>,
        objects: Vec<(Vec<ConvexPolygon>, PieceFlags)>,
    ) -> Result<(Self, Vec<ObjectId>), Error> {
        Self::build_with(lights, objects, DmOptions::default())
    }

    /// A scene built from scratch: every object added at once.
    pub fn build_with(
        lights: Vec<DmLight>,
        objects: Vec<(Vec<ConvexPolygon>, PieceFlags)>,
        options: DmOptions,
    ) -> Result<(Self, Vec<ObjectId>), Error> {
        Self::build_movable(lights, objects, &[], options)
    }

    /// [`Self::build_with`], the objects at the indices `movable` (into
    /// `objects`) declared movable: in every receiver's tree their
    /// discontinuities come after the static objects', where a move would
    /// put them, so that even their first move deletes only their own
    /// nodes. An object the build places among the others (front to back
    /// from the light) has its nodes high in the trees, and its first
    /// removal must rebuild what lies under them (a box of the 10k-polygon
    /// hall on 2 cores: 15-20 ms for its first move, 7-8 ms for the later
    /// ones; declared movable, 8-13 ms and 6.5-7 ms, the first move's
    /// extra now the first touch of memory the build left). The shadows
    /// are the same either way; only the trees' shapes differ.
    ///
    /// Errors: those of [`Self::build_with`], and an index past `objects`
    /// ([`Error::UnknownObject`]).
    pub fn build_movable(
        lights: Vec<DmLight>,
        objects: Vec<(Vec<ConvexPolygon>, PieceFlags)>,
        movable: &[usize],
        options: DmOptions,
    ) -> Result<(Self, Vec<ObjectId>), Error> {
        let mut scene = Self::with_options(lights, options)?;
        for (polygons, _) in &objects {
            Self::validate(polygons)?;
        }
        scene.revision = 1;
        if movable.iter().any(|&k| k >= objects.len()) {
            return Err(Error::UnknownObject);
        }
        let mut is_movable = vec![false; objects.len()];
        for &k in movable {
            is_movable[k] = true;
        }
        let ids: Vec<ObjectId> = is_movable
            .into_iter()
            .map(|movable| {
                scene.objects.insert(Object {
                    movable,
                    ..Object::default()
                })
            })
            .collect();
        // Every object's pieces made side by side, then put in the scene
        // in order.
        let prepared: Vec<_> = objects
            .into_par_iter()
            .zip(&ids)
            .map(|((polygons, flags), &id)| scene.prepare(id, polygons, flags))
            .collect();
        let mut added = Vec::new();
        for (prepared, &id) in prepared.into_iter().zip(&ids) {
            added.extend(scene.commit(id, prepared));
        }
        let (joined, _) = scene.reconcile_joints(&ids.iter().copied().collect());
        added.extend(joined);
        scene.cast(&added);
        Ok((scene, ids))
    }

    /// The options the scene was made with.
    pub fn options(&self) -> DmOptions {
        self.options
    }

    /// The lights.
    pub fn lights(&self) -> &[DmLight] {
        &self.lights
    }

    /// Adds an object of convex polygons with grid-point vertices (their
    /// `source` is kept as a tag) and casts its shadows; every receiver
    /// it reaches gets its discontinuities.
    ///
    /// `flags.closed_surface` says the object has closed parts facing out
    /// (all of it, or a closed mesh among other polygons): they are found
    /// ([`area_shadow::closed_parts`]), and the faces of each that every
    /// light is clear of ([`AreaSource::clear_of`]) cast nothing under a
    /// light they are turned away from (its faces towards the light cast
    /// its whole shadow; only a joint umbra of faces turned away, no
    /// single face's, is left to the bodies and proofs that find it).
    ///
    /// [`AreaSource::clear_of`]: area_shadow::AreaSource::clear_of
    pub fn add_object(
        &mut self,
        polygons: Vec<ConvexPolygon>,
        flags: PieceFlags,
    ) -> Result<ObjectId, Error> {
        Self::validate(&polygons)?;
        let id = self.objects.insert(Object::default());
        self.change(id, Some((polygons, flags)))?;
        Ok(id)
    }

    /// Removes an object: its receivers go, and its discontinuities leave
    /// every other receiver's tree.
    pub fn remove_object(&mut self, id: ObjectId) -> Result<(), Error> {
        self.change(id, None)?;
        self.objects.remove(id);
        Ok(())
    }

    /// Replaces an object's polygons (a move is a delete and an add; the
    /// handle stays valid).
    pub fn move_object(&mut self, id: ObjectId, polygons: Vec<ConvexPolygon>) -> Result<(), Error> {
        Self::validate(&polygons)?;
        let flags = match self.objects.get(id).and_then(|o| o.pieces.first()) {
            Some(&p) => self.pieces[p].flags,
            None if self.objects.contains_key(id) => PieceFlags::default(),
            None => return Err(Error::UnknownObject),
        };
        self.change(id, Some((polygons, flags)))
    }

    /// Moves an object by `d` grid steps: [`Self::move_object`] with each
    /// of its polygons [translated](ConvexPolygon::translated), the step an
    /// application takes frame after frame. Errors: no such object, or a
    /// polygon moved off the grid ([`Error::OffGrid`], nothing changed).
    pub fn translate_object(&mut self, id: ObjectId, d: [i64; 3]) -> Result<(), Error> {
        let pieces = self.object_pieces(id).ok_or(Error::UnknownObject)?;
        let moved = pieces
            .iter()
            .enumerate()
            .map(|(k, &piece)| {
                self.pieces[piece]
                    .polygon
                    .translated(d)
                    .map_err(|e| match e {
                        bsp_core::Error::ImplicitVertex => Error::ImplicitInput(k),
                        _ => Error::OffGrid(k),
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        self.move_object(id, moved)
    }

    /// How many changes the scene has seen: a build is one, and so is each
    /// addition, removal or move of an object, each
    /// [`illuminate`](Self::illuminate) call and each
    /// [`set_receiver_normal`](Self::set_receiver_normal). Kept before a
    /// change, it is what [`Self::receivers_changed_since`] takes after.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The receivers whose cells or vertex irradiance changed after
    /// revision `since` (see [`Self::revision`]), new ones included, in
    /// no set order: what an application reads again after a change,
    /// every other receiver keeping its cells, keys and values. (The
    /// receivers of a moved or removed object are gone, and its new
    /// pieces are [`Self::object_pieces`].) Before the first
    /// [`illuminate`](Self::illuminate) call every receiver a change
    /// reaches is listed, whether its cells changed or not; from then on
    /// only those whose cells changed. It walks every receiver (cheap: the
    /// 10k-polygon hall's 10k in a few microseconds).
    pub fn receivers_changed_since(&self, since: u64) -> impl Iterator<Item = PieceId> + '_ {
        self.changed_at
            .iter()
            .filter(move |&(_, &at)| at > since)
            .map(|(piece, _)| piece)
    }

    /// Whether an object was declared movable ([`Self::build_movable`]);
    /// `false` for a handle of no object.
    pub fn is_movable(&self, id: ObjectId) -> bool {
        self.objects.get(id).is_some_and(|o| o.movable)
    }

    /// The pieces of an object, in the order given.
    pub fn object_pieces(&self, id: ObjectId) -> Option<&[PieceId]> {
        self.objects.get(id).map(|o| o.pieces.as_slice())
    }

    /// The objects.
    pub fn objects(&self) -> impl Iterator<Item = ObjectId> + '_ {
        self.objects.keys()
    }

    /// A receiver's DM-tree.
    pub fn receiver(&self, piece: PieceId) -> Option<&ReceiverDm<PieceId>> {
        self.receivers.get(piece)
    }

    /// Every receiver, objects in insertion order.
    pub fn receivers(&self) -> impl Iterator<Item = (PieceId, &ReceiverDm<PieceId>)> + '_ {
        self.objects
            .values()
            .flat_map(|o| o.pieces.iter())
            .map(|&p| (p, &self.receivers[p]))
    }

    /// Checks every receiver: its tree and mesh
    /// ([`ReceiverDm::check_invariants`]), and every cell's occluder list
    /// against the occluders' volumes and internal discontinuities, exactly
    /// (a cell lists an occluder only if it lies in its penumbra, wholly in
    /// or out of its umbra as marked, crossed by none of its internal
    /// discontinuities; a cell that meets an occluder's penumbra lists it,
    /// unless another's umbra culled it there), and every unit as one of
    /// a piece in the scene, on a receiver its occluder's removal looks
    /// at (the overlap structure's). For tests and fuzz targets: it looks
    /// at every cell and unit.
    pub fn check_invariants(&self) -> Result<(), String> {
        let sources: Vec<AreaSource> = self.lights.iter().map(|l| l.source.clone()).collect();
        // The receivers each occluder's removal would look at.
        let mut overlap = self.overlap.clone();
        overlap.refresh(&self.pieces);
        let mut reach: KeyMap<PieceId, Vec<PieceId>> = KeyMap::default();
        for (piece, dm) in self.receivers() {
            for (u, (occluder, light)) in dm.units() {
                if !self.pieces.contains_key(occluder) {
                    return Err(format!(
                        "receiver {piece:?}: unit {u} ({occluder:?}, light {light}) is of a piece no longer in the scene"
                    ));
                }
                let near = reach
                    .entry(occluder)
                    .or_insert_with(|| overlap.receivers_near(occluder, &self.pieces));
                if near.binary_search(&piece).is_err() {
                    return Err(format!(
                        "receiver {piece:?}: unit {u} ({occluder:?}, light {light}) is where its occluder's removal would not look"
                    ));
                }
            }
            let units = dm.units().map(|(_, unit)| unit);
            let contact =
                ContactPlanes::new(&self.pieces[piece], &sources, units, |o| &self.pieces[o]);
            let planes =
                |k: PieceId, l: u8| contact.get(k, l, &self.pieces[k].volumes[usize::from(l)]);
            dm.check_invariants()
                .and_then(|()| dm.check_lists(planes))
                .map_err(|e| format!("receiver {piece:?}: {e}"))?;
        }
        Ok(())
    }

    /// How well the overlap structure localises: the occluder / receiver
    /// pairs it gives over every receiver, and how many of them pass the
    /// exact quick reject. A diagnostic: it looks at every pair it counts.
    pub fn overlap_figures(&mut self) -> OverlapFigures {
        self.overlap.refresh(&self.pieces);
        let mut figures = OverlapFigures::default();
        for r in self.receivers.keys() {
            let receiver = &self.pieces[r].polygon;
            for o in self.overlap.occluders_near(r, &self.pieces) {
                figures.candidates += 1;
                let shadows = self.pieces[o].volumes.iter().any(|v| {
                    v.volumes
                        .penumbra
                        .iter()
                        .any(|part| crate::tree::clip(receiver, part).is_some())
                });
                figures.shadowing += usize::from(shadows);
            }
        }
        figures
    }

    /// Per light, the DM-tree nodes its occluders cast over every
    /// receiver: on their penumbra volumes' planes or internal
    /// discontinuities (the first count), or on their umbra volumes'
    /// planes (the second; a plane of both counts there). Light planes,
    /// tiles and construction nodes are no occluder's, and not counted.
    pub fn light_node_counts(&self) -> Vec<(usize, usize)> {
        let mut counts = vec![(0, 0); self.lights.len()];
        for (_, dm) in self.receivers() {
            for (unit, line) in dm.unit_lines() {
                let Some((key, light)) = dm.unit(unit) else {
                    continue;
                };
                let planes = &self.pieces[key].volumes[usize::from(light)];
                let umbra = planes.volumes.umbra.iter().flatten();
                let count = &mut counts[usize::from(light)];
                if umbra.into_iter().any(|p| p.is_coincident(line)) {
                    count.1 += 1;
                } else {
                    count.0 += 1;
                }
            }
        }
        counts
    }

    /// The flags a piece was added with.
    pub fn piece_flags(&self, piece: PieceId) -> Option<PieceFlags> {
        self.pieces.get(piece).map(|p| p.flags)
    }

    /// The object a piece belongs to.
    pub fn piece_object(&self, piece: PieceId) -> Option<ObjectId> {
        self.pieces.get(piece).map(|p| p.object)
    }

    /// The polygon of a piece.
    pub fn piece_polygon(&self, piece: PieceId) -> Option<&ConvexPolygon> {
        self.pieces.get(piece).map(|p| &p.polygon)
    }

    fn validate(polygons: &[ConvexPolygon]) -> Result<(), Error> {
        for (k, p) in polygons.iter().enumerate() {
            if (0..p.len()).any(|i| p.vertex_grid_point(i).is_none()) {
                return Err(Error::ImplicitInput(k));
            }
        }
        Ok(())
    }
}
