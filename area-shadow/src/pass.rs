//! One area light's pass over the fragments: penumbra and umbra trees,
//! then classification.
//!
//! The 1992 paper filters polygons front-to-back from the light and grows
//! the trees as it goes, which is right only when the order is the same from
//! every point of the light (hence its splitting of the light). umbra
//! separates the two jobs instead:
//!
//! 1. **Volumes.** Every shadow-casting piece adds the penumbra and umbra
//!    volumes of its whole original polygon ([`crate::cast_volumes`]). A
//!    piece already inside the umbra tree adds only its umbra volume: every
//!    ray it stops was stopped before (each of its points is hidden from
//!    all of the light by one earlier occluder), so its penumbra changes
//!    nothing, but where it alone hides the whole light the earlier ones
//!    may do so only together, and that is umbra (one occluder hides it
//!    all). Pieces go nearest the light first so that this culling finds
//!    most of what the paper's order would; the order changes only the
//!    trees' size.
//! 2. **Classification.** Every fragment is filtered down the final trees:
//!    outside the penumbra tree it sees all of the light (lit); inside the
//!    umbra tree, none (umbra); otherwise part (penumbra). A point strictly
//!    inside an occluder's penumbra volume has part of the light hidden by
//!    it whichever order the pieces came in, so the classification does not
//!    depend on the order, and the light need not be split.
//!
//! A two-sided piece whose plane cuts the light receives each part of the
//! light on its own side, so it is lit where no other piece hides any of
//! the light; but it lies inside its own two penumbra volumes (one each
//! side of its plane), and inside those of any other piece in its plane
//! (a floor it lies on), which hide nothing from it either. Such volumes
//! go into a union of their own, and the piece is cut by each of them but
//! its own, with the points of its plane outside.
//!
//! The paper's umbra is the union of single occluders' umbrae. Pieces
//! that make up one convex body (module `groups`: a triangulated sphere, a
//! quad given as two triangles) hide the whole light together from the
//! body's umbra volume: these go into a tree of their own, and what is not
//! in umbra already is filtered down it too. A fragment lying in a plane of
//! a body's volume (a face in contact with the body) is taken for the
//! points just off it on the side it receives on, which is what it sees
//! light from: in contact, the body covers it. The pieces of a flat
//! polygon that is not convex add the convex parts of the umbra they make
//! together ([`crate::FlatUnion::umbra_parts`]) to that tree too, and so
//! do a body that holds the light in, all around it, and a body one face
//! short, outside it ([`ConvexGroup::umbra_parts`]). Where
//! separate bodies
//! together hide the whole light (a boundary of quadric EEE surfaces in
//! general), fragments stay penumbra and their vertices' visible part of
//! the light comes out empty.

use crate::groups::{
    ConvexGroup, FlatUnion, convex_groups, convex_unions, flat_joints, flat_unions, section_unions,
};
use crate::merge_pieces::merge_same_class;
use crate::tree::{Partition, VolumeTree};
use crate::volumes::cast_volumes_within;
use crate::{AreaSource, SourceSide};
use bsp_core::{ConvexPolygon, GRID_LIMIT, GridPoint, Plane, Split};
use rayon::prelude::*;
use std::collections::HashSet;
use svbsp::{ConvexPolyhedron, Fragment, PieceFlags};

/// Shadow-casting pieces per cell of the trees' skeleton
/// ([`VolumeTree::with_cells`]). On the 600- and 1665-box halls of the
/// benchmarks, 8 to 64 give trees half the size of no skeleton at all, and
/// about 5 % fewer fragments; 16 was a little faster than the rest.
pub const OCCLUDERS_PER_CELL: usize = 16;

/// Figures of one area light's pass (the 1992 paper's Figure 8 columns that
/// belong to classification).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AreaLightStats {
    /// Input pieces that some of the light reaches from the front.
    pub front_facing_polygons: usize,
    /// Edges of those pieces.
    pub front_facing_edges: usize,
    /// Inner nodes of the penumbra tree.
    pub penumbra_nodes: usize,
    /// Inner nodes of the umbra tree.
    pub umbra_nodes: usize,
    /// Pieces whose volumes went into the trees.
    pub occluders: usize,
    /// Shadow-casting pieces left out because they lay in umbra already.
    pub occluders_culled: usize,
    /// Convex bodies of several pieces whose umbra volume went in.
    pub occluder_groups: usize,
    /// Final fragments that see all of the light.
    pub lit: usize,
    /// Final fragments that see part of it.
    pub penumbra: usize,
    /// Final fragments that see none of it.
    pub umbra: usize,
}

/// The class of a fragment for one light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Class {
    /// Sees all of the light.
    Lit,
    /// Sees part of it.
    Penumbra,
    /// Sees none of it.
    Umbra,
}

impl Class {
    /// The class of a fragment for the light of mask bit `bit`.
    pub fn of(fragment: &Fragment, bit: u32) -> Class {
        let mask = 1_u32 << bit;
        if fragment.lit_mask & mask != 0 {
            Class::Lit
        } else if fragment.umbra_mask & mask != 0 {
            Class::Umbra
        } else {
            Class::Penumbra
        }
    }

    fn apply(self, fragment: &mut Fragment, bit: u32) {
        let mask = 1_u32 << bit;
        fragment.lit_mask &= !mask;
        fragment.umbra_mask &= !mask;
        match self {
            Class::Lit => fragment.lit_mask |= mask,
            Class::Umbra => fragment.umbra_mask |= mask,
            Class::Penumbra => {}
        }
    }
}

/// The convex bodies and the flat unions that are no convex polygon that
/// several shadow-casting pieces form (module `groups`), found once for
/// every light.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ShadowGroups {
    /// Convex bodies (and flat convex polygons) of several pieces.
    pub bodies: Vec<ConvexGroup>,
    /// Flat unions of pieces that are no convex polygon.
    pub flat_unions: Vec<FlatUnion>,
    /// Convex bodies that bodies of [`Self::bodies`] touching face to face
    /// make together, whatever their objects ([`convex_unions`]), and flat
    /// convex polygons that coplanar pieces of several objects cover
    /// ([`flat_joints`]; their flat unions that are no convex polygon are
    /// among [`Self::flat_unions`]): they add their umbrae.
    pub joint_bodies: Vec<ConvexGroup>,
}

impl ShadowGroups {
    /// The bodies of edge-connected shadow-casting pieces, whatever object
    /// each came from.
    ///
    /// # Panics
    ///
    /// If `flags` is shorter than `pieces`.
    pub fn connected(pieces: &[ConvexPolygon], flags: &[PieceFlags]) -> Self {
        let objects: Vec<u32> = vec![0; pieces.len()];
        Self::of_objects(pieces, flags, &objects)
    }

    /// The bodies of edge-connected shadow-casting pieces of one object
    /// (`objects[k]` is piece `k`'s).
    ///
    /// # Panics
    ///
    /// If `flags` or `objects` is shorter than `pieces`.
    pub fn of_objects(pieces: &[ConvexPolygon], flags: &[PieceFlags], objects: &[u32]) -> Self {
        let casting: Vec<Option<u32>> = (0..pieces.len())
            .map(|k| flags[k].casts_shadows.then_some(objects[k]))
            .collect();
        let bodies = convex_groups(pieces, &casting);
        let mut joint_bodies: Vec<ConvexGroup> = convex_unions(&bodies.iter().collect::<Vec<_>>())
            .into_iter()
            .map(|(_, union)| union)
            .collect();
        let (flat_groups, joint_unions) = flat_joints(pieces, &casting);
        joint_bodies.extend(flat_groups);
        let mut unions = flat_unions(pieces, &casting);
        unions.extend(joint_unions);
        unions.extend(section_unions(pieces, &casting));
        Self {
            bodies,
            flat_unions: unions,
            joint_bodies,
        }
    }
}

/// The trees of one area light, built from the pieces' volumes.
#[derive(Debug, Clone, Default)]
pub struct AreaTrees {
    /// Where some of the light is hidden.
    pub penumbra: VolumeTree,
    /// Where all of it is hidden (by one piece).
    pub umbra: VolumeTree,
    /// Where all of it is hidden by one convex body of several pieces.
    pub bodies: VolumeTree,
    /// Pieces whose volumes went in.
    pub occluders: usize,
    /// Pieces left out because they lay in umbra already.
    pub culled: usize,
    /// Convex bodies of several pieces whose umbra volume went in
    /// ([`Self::bodies`]).
    pub groups: usize,
    /// Penumbra volumes of two-sided pieces whose plane cuts the light,
    /// with the piece's index; kept out of [`Self::penumbra`]. Such a piece
    /// receives on both sides, so it sees all of the light where nothing
    /// else hides any, but it lies inside the union of its own two volumes
    /// (one each side of its plane, glued along it). The same holds for
    /// every other piece in its plane (a one-sided floor under a two-sided
    /// sheet that covers it): their volumes are kept here too.
    pub straddling: Vec<(u32, ConvexPolyhedron)>,
    /// The same volumes as one union, for every other receiver.
    pub straddling_union: VolumeTree,
}

impl AreaTrees {
    /// Builds the trees from `pieces` (grid-point vertices; `flags[k]` for
    /// piece `k`), with the convex bodies that edge-connected shadow-casting
    /// pieces form, whichever objects they came from
    /// ([`ShadowGroups::connected`]).
    ///
    /// # Panics
    ///
    /// If `flags` is shorter than `pieces`.
    pub fn build(pieces: &[ConvexPolygon], flags: &[PieceFlags], light: &AreaSource) -> Self {
        let groups = ShadowGroups::connected(pieces, flags);
        Self::build_with_groups(pieces, flags, &groups, light)
    }

    /// [`Self::build`] with the convex bodies given: each adds its umbra
    /// volume to [`Self::bodies`].
    ///
    /// # Panics
    ///
    /// If `flags` is shorter than `pieces`.
    pub fn build_with_groups(
        pieces: &[ConvexPolygon],
        flags: &[PieceFlags],
        groups: &ShadowGroups,
        light: &AreaSource,
    ) -> Self {
        let mut trees = AreaTrees::default();
        let centre = light.centroid();
        let mut order: Vec<(f64, usize)> = pieces
            .iter()
            .enumerate()
            .filter(|(k, piece)| {
                // A closed surface's faces turned away from all of the light
                // hide nothing its faces towards the light do not.
                flags[*k].casts_shadows
                    && !(flags[*k].closed_surface
                        && matches!(
                            light.side_of(piece.support()),
                            SourceSide::Back | SourceSide::In
                        ))
            })
            .map(|(k, piece)| (distance2(piece.centroid(), centre), k))
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        // The planes of two-sided pieces the light straddles, both ways
        // round: a piece in one of them hides nothing from such a receiver,
        // though the receiver lies inside the piece's two volumes (see
        // `straddling`).
        let two_sided_straddled: HashSet<Plane> = pieces
            .iter()
            .zip(flags)
            .filter(|(piece, f)| f.two_sided && light.side_of(piece.support()) == SourceSide::Both)
            .flat_map(|(piece, _)| [*piece.support(), piece.support().flipped()])
            .collect();
        let (lo, hi) = grid_box(pieces);
        let region = receiver_region(lo, hi);
        let cells = order.len() / OCCLUDERS_PER_CELL;
        trees.penumbra = VolumeTree::with_cells(lo, hi, cells);
        trees.umbra = VolumeTree::with_cells(lo, hi, cells);
        let skeleton = trees.penumbra.len();
        for (_, k) in order {
            let piece = &pieces[k];
            let in_umbra = trees.umbra.len() > skeleton && trees.umbra.contains(piece);
            let volumes = cast_volumes_within(piece, light, &region);
            if in_umbra {
                // Every ray it stops was stopped before, so its penumbra
                // adds nothing; but where it alone hides all of the light
                // (its umbra), the earlier occluders may do so only
                // together: that stays umbra, one occluder hiding it all.
                trees.culled += 1;
                if let Some(volume) = volumes.umbra {
                    trees.umbra.insert(volume);
                }
                continue;
            }
            if volumes.penumbra.is_empty() {
                continue;
            }
            trees.occluders += 1;
            let straddling = light.side_of(piece.support()) == SourceSide::Both
                && (flags[k].two_sided || two_sided_straddled.contains(piece.support()));
            for volume in volumes.penumbra {
                if straddling {
                    trees.straddling_union.insert(volume.clone());
                    trees.straddling.push((k as u32, volume));
                } else {
                    trees.penumbra.insert(volume);
                }
            }
            if let Some(volume) = volumes.umbra {
                trees.umbra.insert(volume);
            }
        }
        for group in groups.bodies.iter().chain(&groups.joint_bodies) {
            let volume = group
                .umbra_planes(light)
                .and_then(|planes| region.clone().cut_by(&planes));
            if let Some(volume) = volume {
                trees.groups += 1;
                trees.bodies.insert(volume);
            }
        }
        let held_in = groups
            .bodies
            .iter()
            .chain(&groups.joint_bodies)
            .map(|body| body.umbra_parts(light));
        let unions = groups
            .flat_unions
            .iter()
            .map(|union| union.umbra_parts(light));
        for parts in held_in.chain(unions) {
            let volumes: Vec<_> = parts
                .iter()
                .filter_map(|planes| region.clone().cut_by(planes))
                .collect();
            trees.groups += usize::from(!volumes.is_empty());
            for volume in volumes {
                trees.bodies.insert(volume);
            }
        }
        trees
    }

    /// Classifies `polygon` (in the plane of a piece with flags `flags`):
    /// its pieces with their classes. A polygon whose pieces all have one
    /// class comes back whole.
    pub fn classify(
        &self,
        polygon: ConvexPolygon,
        flags: PieceFlags,
        light: &AreaSource,
    ) -> Vec<(ConvexPolygon, Class)> {
        let side = light.side_of(polygon.support());
        let reach = match side {
            SourceSide::In => Reach::None,
            SourceSide::Front => Reach::All,
            SourceSide::Back | SourceSide::Both if flags.two_sided => Reach::All,
            SourceSide::Back => Reach::None,
            SourceSide::Both => Reach::Part,
        };
        if reach == Reach::None {
            return vec![(polygon, Class::Umbra)];
        }
        let mut out: Vec<(ConvexPolygon, Class)> = Vec::new();
        // Behind the light's plane nothing arrives.
        let lit_part = match polygon.split(light.support()) {
            Split::Front => polygon.clone(),
            Split::Both(back, front) => {
                out.push((back, Class::Umbra));
                front
            }
            Split::Back | Split::Coplanar(_) => return vec![(polygon, Class::Umbra)],
        };
        let unblocked = if reach == Reach::All {
            Class::Lit
        } else {
            Class::Penumbra
        };
        // The side the polygon receives on, for the bodies' volumes (none
        // when light arrives on both: then a piece in a volume's plane is
        // inside only in the union's interior).
        let facing = match light.side_of(polygon.support()) {
            SourceSide::Back => Some(polygon.support().flipped()),
            SourceSide::Both if flags.two_sided => None,
            _ => Some(*polygon.support()),
        };
        let own = polygon.source();
        let mut hidden = self.penumbra.partition(lit_part);
        if !self.straddling.is_empty() {
            let mut open = Vec::new();
            for piece in hidden.outside {
                let cut = if flags.two_sided && side == SourceSide::Both {
                    self.outside_straddling_but(piece, own)
                } else {
                    self.straddling_union.partition(piece)
                };
                open.extend(cut.outside);
                hidden.inside.extend(cut.inside);
            }
            hidden.outside = open;
        }
        out.extend(hidden.outside.into_iter().map(|p| (p, unblocked)));
        for piece in hidden.inside {
            let dark = self.umbra.partition(piece);
            out.extend(dark.outside.into_iter().map(|p| (p, Class::Penumbra)));
            out.extend(dark.inside.into_iter().map(|p| (p, Class::Umbra)));
        }
        if !self.bodies.is_empty() {
            let mut bodies_cut = Vec::with_capacity(out.len());
            for (piece, class) in out {
                if class == Class::Umbra {
                    bodies_cut.push((piece, class));
                    continue;
                }
                let dark = match &facing {
                    Some(facing) => self.bodies.partition_facing(piece, facing),
                    None => self.bodies.partition(piece),
                };
                bodies_cut.extend(dark.outside.into_iter().map(|p| (p, class)));
                bodies_cut.extend(dark.inside.into_iter().map(|p| (p, Class::Umbra)));
            }
            out = bodies_cut;
        }
        if out.iter().all(|(_, c)| *c == out[0].1) {
            let class = out[0].1;
            return vec![(polygon, class)];
        }
        merge_same_class(out)
    }
}

impl AreaTrees {
    /// `polygon` cut by the [`Self::straddling`] volumes of every piece but
    /// `own`: the parts inside one of them and the parts outside all.
    fn outside_straddling_but(&self, polygon: ConvexPolygon, own: u32) -> Partition {
        let mut cut = Partition::default();
        let mut open = vec![polygon];
        for (_, volume) in self.straddling.iter().filter(|(k, _)| *k != own) {
            let mut next = Vec::with_capacity(open.len());
            for piece in open {
                let (outside, inside) = clip_to_volume(piece, volume);
                next.extend(outside);
                cut.inside.extend(inside);
            }
            open = next;
        }
        cut.outside = open;
        cut
    }
}

/// The parts of `polygon` outside the convex `volume`, and the part inside
/// it (a part on its boundary counts as outside, as in [`VolumeTree`]).
fn clip_to_volume(
    polygon: ConvexPolygon,
    volume: &ConvexPolyhedron,
) -> (Vec<ConvexPolygon>, Option<ConvexPolygon>) {
    let mut outside = Vec::new();
    let mut rest = polygon;
    for facet in volume.facets() {
        match rest.split(facet.support()) {
            Split::Back => {}
            Split::Front | Split::Coplanar(_) => {
                outside.push(rest);
                return (outside, None);
            }
            Split::Both(back, front) => {
                outside.push(front);
                rest = back;
            }
        }
    }
    (outside, Some(rest))
}

/// The box `lo..hi` one grid unit larger on each side, so that every
/// receiver lies strictly inside it. Volumes are cut down to it: past it
/// there is nothing to shadow, and in a closed room the parts of the
/// volumes behind the floor and walls would otherwise cross each other and
/// split the trees for nothing.
fn receiver_region(lo: [i32; 3], hi: [i32; 3]) -> ConvexPolyhedron {
    let corner = |c: [i32; 3]| GridPoint {
        x: c[0],
        y: c[1],
        z: c[2],
    };
    let widen = |c: i32, by: i32| c.saturating_add(by).clamp(-GRID_LIMIT, GRID_LIMIT);
    ConvexPolyhedron::axis_box(
        corner(lo.map(|c| widen(c, -1))),
        corner(hi.map(|c| widen(c, 1))),
    )
    .unwrap_or_else(ConvexPolyhedron::bounding_box)
}

/// The box of the pieces' grid-point vertices.
fn grid_box(pieces: &[ConvexPolygon]) -> ([i32; 3], [i32; 3]) {
    let (mut lo, mut hi) = ([i32::MAX; 3], [i32::MIN; 3]);
    for piece in pieces {
        for p in (0..piece.len()).filter_map(|k| piece.vertex_grid_point(k)) {
            for (i, c) in [p.x, p.y, p.z].into_iter().enumerate() {
                lo[i] = lo[i].min(c);
                hi[i] = hi[i].max(c);
            }
        }
    }
    (lo, hi)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Reach {
    None,
    Part,
    All,
}

fn distance2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}

/// Runs one area light's pass: builds its trees from `pieces` and
/// classifies every fragment (whose `source` is its piece's index) for mask
/// bit `bit`, in place of what the fragment said about that bit.
///
/// # Panics
///
/// If `flags` is shorter than `pieces`, a fragment names a piece out of
/// range, or `bit >= 32`.
pub fn shadow_area_light(
    fragments: Vec<Fragment>,
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    light: &AreaSource,
    bit: u32,
) -> (Vec<Fragment>, AreaLightStats) {
    let trees = AreaTrees::build(pieces, flags, light);
    classify_fragments(&trees, fragments, pieces, flags, light, bit)
}

/// The classification half of [`shadow_area_light`], with trees built
/// beforehand (the trees of several lights can be built side by side).
/// Fragments are classified in parallel; the output keeps their order, so
/// it does not depend on the number of threads.
///
/// # Panics
///
/// As [`shadow_area_light`].
pub fn classify_fragments(
    trees: &AreaTrees,
    fragments: Vec<Fragment>,
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    light: &AreaSource,
    bit: u32,
) -> (Vec<Fragment>, AreaLightStats) {
    let mut stats = AreaLightStats {
        penumbra_nodes: trees.penumbra.len(),
        umbra_nodes: trees.umbra.len() + trees.bodies.len(),
        occluders: trees.occluders,
        occluders_culled: trees.culled,
        occluder_groups: trees.groups,
        ..AreaLightStats::default()
    };
    for piece in pieces {
        if light.reaches_front_of(piece.support()) {
            stats.front_facing_polygons += 1;
            stats.front_facing_edges += piece.len();
        }
    }
    let classified: Vec<Vec<(Fragment, Class)>> = fragments
        .into_par_iter()
        .with_min_len(16)
        .map(|fragment| {
            let piece = fragment.polygon.source() as usize;
            let (lit_mask, umbra_mask) = (fragment.lit_mask, fragment.umbra_mask);
            trees
                .classify(fragment.polygon, flags[piece], light)
                .into_iter()
                .map(|(polygon, class)| {
                    let mut made = Fragment {
                        polygon,
                        lit_mask,
                        umbra_mask,
                    };
                    class.apply(&mut made, bit);
                    (made, class)
                })
                .collect()
        })
        .collect();
    let mut out = Vec::with_capacity(classified.iter().map(Vec::len).sum());
    for (made, class) in classified.into_iter().flatten() {
        match class {
            Class::Lit => stats.lit += 1,
            Class::Penumbra => stats.penumbra += 1,
            Class::Umbra => stats.umbra += 1,
        }
        out.push(made);
    }
    (out, stats)
}
