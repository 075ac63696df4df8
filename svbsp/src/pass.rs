//! One light's pass over the fragments: the ones that take no part are
//! settled at once, the others are cut into the light's cones
//! ([`crate::cones`]), and each cone gets its own scene BSP and SVBSP tree
//! (Chin & Feiner 1989) and is shadowed on its own, in parallel. Pieces that
//! end up alike are joined again into the fragment they were cut from.

use crate::cones::{self, Common, Cones};
use crate::pipeline::{Fragment, LightStats, PieceFlags};
use crate::tree::{Filtered, Filtering, ShadowVolumeTree};
use crate::volume::shadow_volume;
use crate::{Light, LightSource};
use bsp_core::predicates::Side;
use bsp_core::{BuildOptions, ConvexPolygon, SceneBsp};
use rayon::prelude::*;
use smallvec::SmallVec;
use std::time::Instant;

/// What a piece sees of the pass's light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    Lit,
    Umbra,
}

/// Everything a cone needs to know of the scene.
struct Context<'a> {
    /// The input pieces (grid-point vertices), by piece index.
    pieces: &'a [ConvexPolygon],
    flags: &'a [PieceFlags],
    light: &'a Light,
    bsp: &'a BuildOptions,
}

/// The result of one light's pass.
pub(crate) struct PassOutput {
    pub(crate) fragments: Vec<Fragment>,
    pub(crate) stats: LightStats,
    pub(crate) scene_nodes: usize,
    pub(crate) bsp_seconds: f64,
    pub(crate) shadow_seconds: f64,
}

/// The fragments a cone's slot became.
enum SlotResult {
    /// All alike: the slot's piece, whole.
    Whole(Class, ConvexPolygon),
    /// Pieces of both classes.
    Pieces(Vec<(ConvexPolygon, Class)>),
}

/// A cone with its scene BSP.
struct ConeBsp {
    /// Per local index (the BSP polygons' `source` during the pass): the
    /// slot and the piece index.
    slots: Vec<(u32, u32)>,
    bsp: SceneBsp,
    /// The pieces the BSP cut, whole, by local index (in order).
    cut: Vec<(u32, ConvexPolygon)>,
}

/// Figures of one cone.
#[derive(Default)]
struct ConeStats {
    tree_nodes: usize,
    planes_skipped: usize,
    whole_piece_volumes: usize,
    scene_nodes: usize,
    /// Thread seconds building the scene BSP, and in all.
    bsp_seconds: f64,
    seconds: f64,
}

/// Shadows `fragments` by light `index` (bit `1 << index`), cutting cones
/// of at most `cone_pieces` pieces.
pub(crate) fn light_pass(
    fragments: Vec<Fragment>,
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    light: &Light,
    index: usize,
    bsp: &BuildOptions,
    cone_pieces: usize,
) -> PassOutput {
    let bit = 1_u32 << index;
    let started = Instant::now();
    // Settled without a tree, or active (then the polygon moves on). The
    // settled list takes the input's buffer.
    let mut masks = Vec::with_capacity(fragments.len());
    let mut active = Vec::new();
    let settled: Vec<Option<Fragment>> = fragments
        .into_iter()
        .map(|fragment| {
            masks.push((fragment.lit_mask, fragment.umbra_mask));
            let flags = &flags[fragment.polygon.source() as usize];
            let facing = light.source.side(fragment.polygon.support());
            let beyond = light.range.is_some()
                && light.wholly_beyond_range(&fragment.polygon.vertices_f64());
            let receives = facing == Side::Front || flags.two_sided;
            // Edge-on to the light, beyond its reach, or turned away and
            // casting nothing the rest of its closed surface does not:
            // umbra, untouched.
            if facing == Side::On
                || beyond
                || (!receives && (flags.closed_surface || !flags.casts_shadows))
            {
                Some(Fragment {
                    umbra_mask: fragment.umbra_mask | bit,
                    ..fragment
                })
            } else {
                active.push(fragment.polygon);
                None
            }
        })
        .collect();
    let mut cones = cones::partition(light.source, active, cone_pieces);
    let context = Context {
        pieces,
        flags,
        light,
        bsp,
    };
    let cone_count = cones.len();
    let partition_seconds = started.elapsed().as_secs_f64();
    // Each cone's scene BSP is built and used at once, on one thread:
    // the cone's pieces are still in cache.
    let started = Instant::now();
    let shade = |cone| {
        let begun = Instant::now();
        let cone = cone_bsp(cone, &context);
        let bsp_seconds = begun.elapsed().as_secs_f64();
        let (results, mut stats) = shade_cone(cone, &context);
        stats.bsp_seconds = bsp_seconds;
        stats.seconds = begun.elapsed().as_secs_f64();
        (results, stats)
    };
    let cone_list = cones.take_cones();
    // One cone, or one thread: on this thread, so that what it allocates
    // is freed where it was allocated (a pool thread's allocations freed
    // here cost the allocator more than the work).
    let shaded: Vec<(Vec<(u32, SlotResult)>, ConeStats)> =
        if cone_list.len() == 1 || rayon::current_num_threads() == 1 {
            cone_list.into_iter().map(shade).collect()
        } else {
            cone_list.into_par_iter().map(shade).collect()
        };
    let cones_seconds = started.elapsed().as_secs_f64();
    let mut stats = LightStats {
        cones: cone_count,
        ..LightStats::default()
    };
    let (mut scene_nodes, mut bsp_cpu, mut cpu) = (0, 0.0, 0.0);
    let mut results: Vec<Option<SlotResult>> = Vec::new();
    results.resize_with(cones.node_of.len(), || None);
    for (slots, cone) in shaded {
        stats.tree_nodes += cone.tree_nodes;
        stats.planes_skipped += cone.planes_skipped;
        stats.whole_piece_volumes += cone.whole_piece_volumes;
        scene_nodes += cone.scene_nodes;
        bsp_cpu += cone.bsp_seconds;
        cpu += cone.seconds;
        for (slot, result) in slots {
            results[slot as usize] = Some(result);
        }
    }
    // The cones' wall time, shared between the scene BSPs and the SVBSP
    // trees as their threads' times are.
    let bsp_share = if cpu > 0.0 { bsp_cpu / cpu } else { 0.0 };
    let started = Instant::now();
    let fragments = join(&mut cones, results, settled, &masks, bit);
    PassOutput {
        fragments,
        stats,
        scene_nodes,
        bsp_seconds: partition_seconds + bsp_share * cones_seconds,
        shadow_seconds: (1.0 - bsp_share) * cones_seconds + started.elapsed().as_secs_f64(),
    }
}

/// Builds a cone's scene BSP over its pieces.
fn cone_bsp(cone: Vec<(u32, ConvexPolygon)>, context: &Context) -> ConeBsp {
    let mut slots = Vec::with_capacity(cone.len());
    let polygons: Vec<ConvexPolygon> = cone
        .into_iter()
        .enumerate()
        .map(|(j, (slot, piece))| {
            slots.push((slot, piece.source()));
            piece.with_source(j as u32)
        })
        .collect();
    let (bsp, cut) = SceneBsp::build_keeping_cut(polygons, context.bsp);
    ConeBsp { slots, bsp, cut }
}

/// Shadows one cone: its pieces front-to-back from the light down its own
/// SVBSP tree. Returns each slot's fragments.
fn shade_cone(cone: ConeBsp, context: &Context) -> (Vec<(u32, SlotResult)>, ConeStats) {
    let ConeBsp { slots, bsp, cut } = cone;
    let light = context.light.source;
    let scene_nodes = bsp.nodes().len();
    let visit: Vec<u32> = bsp
        .front_to_back(light.viewpoint())
        .map(|(k, _)| k)
        .collect();
    let mut polygons: Vec<Option<ConvexPolygon>> =
        bsp.into_polygons().into_iter().map(Some).collect();
    // About five nodes per piece (Tetra1024: 2625 for 515): grown by
    // copying otherwise.
    let mut tree = ShadowVolumeTree::with_capacity(light, 5 * visit.len());
    let mut stats = ConeStats::default();
    // Per local index: its pieces so far, and whether all are alike.
    let mut parts: Vec<SmallVec<[(ConvexPolygon, Class); 1]>> =
        (0..slots.len()).map(|_| SmallVec::new()).collect();
    let mut alike: Vec<bool> = vec![true; slots.len()];
    let mut scratch = Filtered::default();
    for k in visit {
        let polygon = polygons[k as usize].take().expect("visited once");
        let j = polygon.source() as usize;
        let piece = slots[j].1;
        let polygon = polygon.with_source(piece);
        let list = &mut parts[j];
        match shade_polygon(&mut tree, polygon, context, &mut stats, &mut scratch, list) {
            Some(class) => alike[j] &= list[0].1 == class,
            None => alike[j] = false,
        }
    }
    stats.tree_nodes = tree.nodes().len();
    stats.scene_nodes = scene_nodes;
    let mut cut = cut.into_iter().peekable();
    let results = slots
        .iter()
        .zip(parts)
        .zip(alike)
        .enumerate()
        .map(|(j, (((slot, piece), mut list), alike))| {
            let whole = cut.next_if(|(k, _)| *k as usize == j).map(|(_, p)| p);
            let result = if alike {
                let class = list[0].1;
                let whole = match whole {
                    Some(whole) => whole.with_source(*piece),
                    None => list.pop().expect("an uncut piece is one polygon").0,
                };
                SlotResult::Whole(class, whole)
            } else {
                SlotResult::Pieces(list.into_vec())
            };
            (*slot, result)
        })
        .collect();
    (results, stats)
}

/// Filters one polygon (source: its piece) down the cone's tree and adds
/// the volumes of its lit pieces if its piece casts shadows. Appends to
/// `list` what the polygon became: itself, with its class (returned), or
/// its lit and shadowed pieces (`None`). `scratch` holds the pieces
/// meanwhile.
fn shade_polygon(
    tree: &mut ShadowVolumeTree,
    polygon: ConvexPolygon,
    context: &Context,
    stats: &mut ConeStats,
    scratch: &mut Filtered,
    list: &mut SmallVec<[(ConvexPolygon, Class); 1]>,
) -> Option<Class> {
    let light: LightSource = context.light.source;
    let piece = polygon.source() as usize;
    let flags = &context.flags[piece];
    let receives = light.side(polygon.support()) == Side::Front || flags.two_sided;
    let casts = flags.casts_shadows;
    let lit = if receives { Class::Lit } else { Class::Umbra };
    let mut cast = |tree: &mut ShadowVolumeTree, polygon: &ConvexPolygon, slot| {
        if let Some(volume) = shadow_volume(polygon, &context.pieces[piece], light) {
            stats.whole_piece_volumes += usize::from(volume.whole_piece);
            let (_, skipped) = tree.insert_volume(slot, &volume.shadow_planes, volume.cap);
            stats.planes_skipped += skipped;
        }
    };
    let class = match tree.filter_ref(&polygon, scratch) {
        Filtering::Lit(slot) => {
            if casts {
                cast(tree, &polygon, slot);
            }
            lit
        }
        Filtering::Shadowed => Class::Umbra,
        Filtering::Pieces => {
            if casts {
                for (piece, slot) in &scratch.lit {
                    cast(tree, piece, *slot);
                }
            }
            // The tree may cut a polygon into pieces that all end up on one
            // side (planes of neighbouring volumes cross it): then it stays
            // whole, and only its lit pieces' volumes went in.
            if !receives || scratch.lit.is_empty() {
                Class::Umbra
            } else if scratch.shadowed.is_empty() {
                Class::Lit
            } else {
                list.extend(scratch.lit.drain(..).map(|(p, _)| (p, Class::Lit)));
                list.extend(scratch.shadowed.drain(..).map(|p| (p, Class::Umbra)));
                return None;
            }
        }
    };
    list.push((polygon, class));
    Some(class)
}

/// Puts the pass's fragments together in input order: settled ones as
/// they are, active ones from their cones' results, joined back up the cut
/// forest wherever all pieces of a fragment are alike.
fn join(
    cones: &mut Cones,
    mut results: Vec<Option<SlotResult>>,
    settled: Vec<Option<Fragment>>,
    masks: &[(u32, u32)],
    bit: u32,
) -> Vec<Fragment> {
    // The slot of each forest leaf, to find a leaf's result.
    let mut slot_of = vec![u32::MAX; cones.forest.len()];
    for (slot, &node) in cones.node_of.iter().enumerate() {
        slot_of[node as usize] = slot as u32;
    }
    let common = cones
        .forest
        .common(|node| match &results[slot_of[node as usize] as usize] {
            Some(SlotResult::Whole(class, _)) => Common::All(*class),
            _ => Common::Mixed,
        });
    // At most one fragment per settled one and per piece a slot became:
    // the exact size, so that a million fragments are not copied into a
    // buffer twice as large.
    let most = settled.iter().filter(|f| f.is_some()).count()
        + results
            .iter()
            .map(|r| match r {
                Some(SlotResult::Pieces(pieces)) => pieces.len(),
                _ => 1,
            })
            .sum::<usize>();
    let mut out = Vec::with_capacity(most);
    // Active fragments are the forest's roots, in order.
    let mut root = 0_u32;
    let mut stack = Vec::new();
    for (fragment, &(lit_mask, umbra_mask)) in settled.into_iter().zip(masks) {
        if let Some(fragment) = fragment {
            out.push(fragment);
            continue;
        }
        let make = |polygon, class| match class {
            Class::Lit => Fragment {
                polygon,
                lit_mask: lit_mask | bit,
                umbra_mask,
            },
            Class::Umbra => Fragment {
                polygon,
                lit_mask,
                umbra_mask: umbra_mask | bit,
            },
        };
        stack.push(root);
        root += 1;
        while let Some(node) = stack.pop() {
            let children = cones.forest.children(node);
            match (common[node as usize], children) {
                (Common::All(class), Some(_)) => {
                    let whole = cones.forest.take_uncut(node).expect("a cut node's polygon");
                    out.push(make(whole, class));
                }
                (Common::Mixed, Some([back, front])) => {
                    // Back popped first, as the cut made them.
                    stack.push(front);
                    stack.push(back);
                }
                (_, None) => match results[slot_of[node as usize] as usize]
                    .take()
                    .expect("every slot was shaded once")
                {
                    SlotResult::Whole(class, polygon) => out.push(make(polygon, class)),
                    SlotResult::Pieces(pieces) => {
                        out.extend(pieces.into_iter().map(|(p, c)| make(p, c)));
                    }
                },
            }
        }
    }
    out
}
