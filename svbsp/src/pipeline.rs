//! Shadows of many point and directional lights, pipelined: the fragments
//! of one light's pass are the input of the next.

use crate::pass::light_pass;
use crate::{Error, Light};
use bsp_core::predicates::Side;
use bsp_core::{BuildOptions, ConvexPolygon};

/// At most this many lights: one bit each in a `u32` mask.
pub const MAX_LIGHTS: usize = 32;

/// What a piece does besides receiving light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PieceFlags {
    /// Whether it blocks light (whichever side faces the light).
    pub casts_shadows: bool,
    /// Whether its back side receives light too.
    pub two_sided: bool,
    /// Whether it belongs to a closed surface facing out (every edge shared
    /// by two faces, their fronts outside the volume they enclose) that no
    /// light lies in. The surface's faces towards the light then cast its
    /// whole shadow, so a one-sided face turned away needs no filtering at
    /// all. (Wound inwards, the faces towards the light are the ones turned
    /// away by their planes: such a surface must not set this.)
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
    /// Inner nodes of the SVBSP trees (one per cone) at the end of the
    /// pass.
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
    /// Cones the light's pass cut the scene into.
    pub cones: usize,
}

/// How [`compute_shadows_with`] works.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShadowOptions {
    /// How each cone's scene BSP is built.
    pub bsp: BuildOptions,
    /// A cone with more pieces than this is halved again (where a plane
    /// through the light separates them). Small cones make small trees
    /// and more, smaller tasks to run in parallel; each cut piece of a
    /// polygon is joined again when the pieces end up alike.
    pub cone_pieces: usize,
}

impl Default for ShadowOptions {
    fn default() -> Self {
        Self {
            bsp: BuildOptions::default(),
            cone_pieces: 256,
        }
    }
}

/// The result of [`compute_shadows`].
#[derive(Debug, Clone)]
pub struct ShadowOutput {
    /// Every fragment of every piece, in the order of the pieces (a piece's
    /// fragments together).
    pub fragments: Vec<Fragment>,
    /// One entry per light, in the order of the input.
    pub lights: Vec<LightStats>,
    /// Nodes of the scene BSPs (one per cone of each light).
    pub scene_nodes: usize,
    /// Seconds spent cutting cones and building their scene BSPs.
    pub bsp_seconds: f64,
    /// Seconds spent on the lights' SVBSP passes.
    pub shadow_seconds: f64,
}

/// Splits every piece into fragments lit or in shadow of each light, with
/// the default [`ShadowOptions`] and `options` for the scene BSPs.
pub fn compute_shadows(
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    lights: &[Light],
    options: &BuildOptions,
) -> Result<ShadowOutput, Error> {
    let options = ShadowOptions {
        bsp: *options,
        ..ShadowOptions::default()
    };
    compute_shadows_with(pieces, flags, lights, &options)
}

/// Splits every piece into fragments lit or in shadow of each light.
///
/// `pieces` are convex polygons with grid-point vertices (as
/// [`ConvexPolygon::from_grid_points`] makes them); the `source` of each
/// output fragment is the index of its piece. Lights run in order of
/// fewest facing pieces first (fragmenting least), each on the fragments of
/// the one before. For each light, the fragments that face away or lie
/// beyond its range are settled at once; the others are cut by planes
/// through the light into cones of at most
/// [`cone_pieces`](ShadowOptions::cone_pieces) pieces, which no light ray
/// crosses, and every cone is shadowed on its own, in parallel: its scene
/// BSP gives the front-to-back order from the light, its SVBSP tree the
/// lit and shadowed fragments. A fragment whose pieces all end up alike
/// stays whole. The result is the same whatever the number of threads
/// (run inside `rayon::ThreadPool::install` to choose it).
pub fn compute_shadows_with(
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    lights: &[Light],
    options: &ShadowOptions,
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
    if let Some(i) = (0..pieces.len())
        .find(|&i| (0..pieces[i].len()).any(|k| pieces[i].vertex_grid_point(k).is_none()))
    {
        return Err(Error::ImplicitInput(i));
    }
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

    let mut fragments: Vec<Fragment> = pieces
        .iter()
        .enumerate()
        .map(|(i, p)| Fragment {
            polygon: p.clone().with_source(i as u32),
            lit_mask: 0,
            umbra_mask: 0,
        })
        .collect();
    let (mut scene_nodes, mut bsp_seconds, mut shadow_seconds) = (0, 0.0, 0.0);
    for &i in &order {
        let pass = light_pass(
            fragments,
            pieces,
            flags,
            &lights[i],
            i,
            &options.bsp,
            options.cone_pieces,
        );
        fragments = pass.fragments;
        let s = &mut stats[i];
        s.tree_nodes = pass.stats.tree_nodes;
        s.planes_skipped = pass.stats.planes_skipped;
        s.whole_piece_volumes = pass.stats.whole_piece_volumes;
        s.cones = pass.stats.cones;
        scene_nodes += pass.scene_nodes;
        bsp_seconds += pass.bsp_seconds;
        shadow_seconds += pass.shadow_seconds;
    }
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
        shadow_seconds,
    })
}
