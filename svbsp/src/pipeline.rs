//! Shadows of many point and directional lights, pipelined: the fragments
//! of one light's pass are the input of the next.

use crate::tree::{Filtering, ShadowVolumeTree};
use crate::volume::shadow_volume;
use crate::{Error, Light};
use bsp_core::predicates::Side;
use bsp_core::{BuildOptions, ConvexPolygon, SceneBsp};
use smallvec::{SmallVec, smallvec};
use std::time::Instant;

/// The fragments of one scene-BSP polygon (most stay whole).
type FragmentList = SmallVec<[Fragment; 1]>;

/// At most this many lights: one bit each in a `u32` mask.
pub const MAX_LIGHTS: usize = 32;

/// What a piece does besides receiving light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PieceFlags {
    /// Whether it blocks light (whichever side faces the light).
    pub casts_shadows: bool,
    /// Whether its back side receives light too.
    pub two_sided: bool,
    /// Whether it belongs to a closed surface (every edge shared by two
    /// faces). The surface's faces towards the light then cast its whole
    /// shadow, so a one-sided face turned away needs no filtering at all.
    pub closed_surface: bool,
}

impl Default for PieceFlags {
    fn default() -> Self {
        Self {
            casts_shadows: true,
            two_sided: false,
            closed_surface: false,
        }
    }
}

/// A piece of an input polygon with what it sees of each light.
#[derive(Debug, Clone, PartialEq)]
pub struct Fragment {
    /// The fragment; its `source` is the index of the piece it came from.
    pub polygon: ConvexPolygon,
    /// Bit `i`: the fragment sees all of light `i`.
    pub lit_mask: u32,
    /// Bit `i`: the fragment sees none of light `i`.
    pub umbra_mask: u32,
}

/// Figures of one light's pass (the columns of Chin & Feiner 1989, Table 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LightStats {
    /// Input pieces whose front faces the light.
    pub front_facing_polygons: usize,
    /// Edges of those pieces.
    pub front_facing_edges: usize,
    /// Inner nodes of the SVBSP tree at the end of the pass.
    pub tree_nodes: usize,
    /// Final fragments that see all of the light.
    pub lit: usize,
    /// Final fragments that see none of it.
    pub umbra: usize,
    /// Shadow planes left out because they already bound the leaf they
    /// would go in (edges made by SVBSP splits, edges shared by lit faces):
    /// the tree would be this many nodes larger without the check.
    pub planes_skipped: usize,
    /// Volumes cast with the whole original piece (a fragment edge that no
    /// exact shadow plane could be built for).
    pub whole_piece_volumes: usize,
}

/// The result of [`compute_shadows`].
#[derive(Debug, Clone)]
pub struct ShadowOutput {
    /// Every fragment of every piece, grouped by scene-BSP polygon.
    pub fragments: Vec<Fragment>,
    /// One entry per light, in the order of the input.
    pub lights: Vec<LightStats>,
    /// Nodes of the scene BSP.
    pub scene_nodes: usize,
    /// Seconds spent building the scene BSP.
    pub bsp_seconds: f64,
    /// Seconds spent on the lights' SVBSP passes.
    pub shadow_seconds: f64,
}

/// Splits every piece into fragments lit or in shadow of each light.
///
/// `pieces` are convex polygons with grid-point vertices (as
/// [`ConvexPolygon::from_grid_points`] makes them); the `source` of each
/// output fragment is the index of its piece. The scene BSP is built once;
/// lights run in order of fewest facing pieces first (fragmenting least),
/// each with its SVBSP tree, front-to-back from the light.
pub fn compute_shadows(
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    lights: &[Light],
    options: &BuildOptions,
) -> Result<ShadowOutput, Error> {
    if lights.len() > MAX_LIGHTS {
        return Err(Error::TooManyLights(lights.len()));
    }
    if flags.len() != pieces.len() {
        return Err(Error::FlagsLength {
            pieces: pieces.len(),
            flags: flags.len(),
        });
    }
    let originals: Vec<ConvexPolygon> = pieces
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if (0..p.len()).all(|k| p.vertex_grid_point(k).is_some()) {
                Ok(p.clone().with_source(i as u32))
            } else {
                Err(Error::ImplicitInput(i))
            }
        })
        .collect::<Result<_, _>>()?;
    let started = Instant::now();
    let bsp = SceneBsp::build(originals, options);
    let bsp_seconds = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let mut stats = vec![LightStats::default(); lights.len()];
    for (i, light) in lights.iter().enumerate() {
        for piece in pieces {
            if light.source.side(piece.support()) == Side::Front {
                stats[i].front_facing_polygons += 1;
                stats[i].front_facing_edges += piece.len();
            }
        }
    }
    let mut order: Vec<usize> = (0..lights.len()).collect();
    order.sort_by_key(|&i| stats[i].front_facing_polygons);
    // Every light's visiting order first, so that the scene BSP's polygons
    // can then be moved, not copied, into the fragment lists.
    let visits: Vec<Vec<u32>> = order
        .iter()
        .map(|&i| {
            bsp.front_to_back(lights[i].source.viewpoint())
                .map(|(k, _)| k)
                .collect()
        })
        .collect();
    let scene_nodes = bsp.nodes().len();
    let mut fragments: Vec<FragmentList> = bsp
        .into_polygons()
        .into_iter()
        .map(|polygon| {
            smallvec![Fragment {
                polygon,
                lit_mask: 0,
                umbra_mask: 0,
            }]
        })
        .collect();

    for (&i, visit) in order.iter().zip(visits) {
        let light = &lights[i];
        let bit = 1_u32 << i;
        let mut tree = ShadowVolumeTree::new(light.source);
        for k in visit {
            let list = std::mem::take(&mut fragments[k as usize]);
            let mut next = FragmentList::with_capacity(list.len());
            for fragment in list {
                let piece = fragment.polygon.source() as usize;
                let facing = light.source.side(fragment.polygon.support());
                let beyond = light.range.is_some()
                    && light.wholly_beyond_range(&fragment.polygon.vertices_f64());
                let lit_masks = (fragment.lit_mask | bit, fragment.umbra_mask);
                let umbra_masks = (fragment.lit_mask, fragment.umbra_mask | bit);
                let make = |polygon, (lit_mask, umbra_mask): (u32, u32)| Fragment {
                    polygon,
                    lit_mask,
                    umbra_mask,
                };
                if facing == Side::On || beyond {
                    // Edge-on to the light or beyond its reach: it neither
                    // receives nor casts.
                    next.push(make(fragment.polygon, umbra_masks));
                    continue;
                }
                let receives = facing == Side::Front || flags[piece].two_sided;
                if !receives && (flags[piece].closed_surface || !flags[piece].casts_shadows) {
                    // Turned away and casting nothing the rest of its
                    // closed surface does not: umbra, untouched.
                    next.push(make(fragment.polygon, umbra_masks));
                    continue;
                }
                let casts = flags[piece].casts_shadows;
                let mut cast = |tree: &mut ShadowVolumeTree, polygon: &ConvexPolygon, slot| {
                    if let Some(volume) = shadow_volume(polygon, &pieces[piece], light.source) {
                        stats[i].whole_piece_volumes += usize::from(volume.whole_piece);
                        let (_, skipped) =
                            tree.insert_volume(slot, &volume.shadow_planes, volume.cap);
                        stats[i].planes_skipped += skipped;
                    }
                };
                match tree.filter_ref(&fragment.polygon) {
                    Filtering::Lit(slot) => {
                        if casts {
                            cast(&mut tree, &fragment.polygon, slot);
                        }
                        let masks = if receives { lit_masks } else { umbra_masks };
                        next.push(make(fragment.polygon, masks));
                    }
                    Filtering::Shadowed => next.push(make(fragment.polygon, umbra_masks)),
                    Filtering::Pieces(filtered) => {
                        if casts {
                            for (polygon, slot) in &filtered.lit {
                                cast(&mut tree, polygon, *slot);
                            }
                        }
                        // The tree may cut a fragment into pieces that all
                        // end up on one side (planes of neighbouring volumes
                        // cross it): then it stays whole, and only its lit
                        // pieces' volumes go in.
                        if !receives || filtered.lit.is_empty() {
                            // It receives none of this light (turned away,
                            // or all in shadow): whole, in umbra.
                            next.push(make(fragment.polygon, umbra_masks));
                        } else if filtered.shadowed.is_empty() {
                            next.push(make(fragment.polygon, lit_masks));
                        } else {
                            for (polygon, _) in filtered.lit {
                                next.push(make(polygon, lit_masks));
                            }
                            for polygon in filtered.shadowed {
                                next.push(make(polygon, umbra_masks));
                            }
                        }
                    }
                }
            }
            fragments[k as usize] = next;
        }
        stats[i].tree_nodes = tree.nodes().len();
    }

    let mut all = Vec::with_capacity(fragments.iter().map(|l| l.len()).sum());
    for list in fragments {
        all.extend(list);
    }
    let fragments = all;
    for (i, s) in stats.iter_mut().enumerate() {
        s.lit = fragments
            .iter()
            .filter(|f| f.lit_mask & (1 << i) != 0)
            .count();
        s.umbra = fragments
            .iter()
            .filter(|f| f.umbra_mask & (1 << i) != 0)
            .count();
    }
    Ok(ShadowOutput {
        fragments,
        lights: stats,
        scene_nodes,
        bsp_seconds,
        shadow_seconds: started.elapsed().as_secs_f64(),
    })
}
