//! Every light of a scene in one run: point and directional lights through
//! `svbsp`'s SVBSP trees, area lights through their penumbra and umbra
//! trees, each fragment carrying its bits in `lit_mask` / `umbra_mask`.

use crate::pass::{AreaLightStats, AreaTrees, ShadowGroups, classify_fragments};
use crate::{AreaSource, Error};
use bsp_core::{BuildOptions, ConvexPolygon};
use rayon::prelude::*;
use std::time::Instant;
use svbsp::{Fragment, PieceFlags};

/// A light of any kind.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneLight {
    /// A point or directional light (SVBSP trees).
    Svbsp(svbsp::Light),
    /// A convex area light (penumbra and umbra trees).
    Area(AreaSource),
}

impl SceneLight {
    /// The area lights among `lights`, each with its index (its mask bit).
    pub fn areas(lights: &[SceneLight]) -> Vec<(usize, &AreaSource)> {
        lights
            .iter()
            .enumerate()
            .filter_map(|(i, l)| match l {
                SceneLight::Area(source) => Some((i, source)),
                SceneLight::Svbsp(_) => None,
            })
            .collect()
    }
}

/// Figures of one light's pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightFigures {
    /// A point or directional light.
    Svbsp(svbsp::LightStats),
    /// An area light.
    Area(AreaLightStats),
}

/// The result of [`compute_shadows`].
#[derive(Debug, Clone)]
pub struct Shadows {
    /// Every fragment; `polygon.source()` is its piece's index.
    pub fragments: Vec<Fragment>,
    /// One entry per light, in the order of the input.
    pub lights: Vec<LightFigures>,
    /// Nodes of the scene BSP (0 when only area lights ran: they need none).
    pub scene_nodes: usize,
    /// Seconds spent building the scene BSP.
    pub bsp_seconds: f64,
    /// Seconds spent on the lights' passes.
    pub shadow_seconds: f64,
}

/// Splits every piece into fragments lit, in penumbra or in umbra of each
/// light; bit `i` of the masks is `lights[i]`.
///
/// Point and directional lights run first, together
/// ([`svbsp::compute_shadows`]: each in its cones of the scene); each area
/// light then refines their fragments. Shadow-casting pieces that form one
/// convex body (edge-connected, whatever their objects) also cast its
/// umbra ([`ShadowGroups::connected`]).
pub fn compute_shadows(
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    lights: &[SceneLight],
    options: &BuildOptions,
) -> Result<Shadows, Error> {
    let groups = if lights.iter().any(|l| matches!(l, SceneLight::Area(_))) {
        if flags.len() != pieces.len() {
            return Err(Error::FlagsLength {
                pieces: pieces.len(),
                flags: flags.len(),
            });
        }
        ShadowGroups::connected(pieces, flags)
    } else {
        ShadowGroups::default()
    };
    compute_shadows_with_groups(pieces, flags, &groups, lights, options)
}

/// [`compute_shadows`] with the convex bodies given (say, found within
/// objects by [`ShadowGroups::of_objects`]); their piece indices refer to
/// `pieces`.
pub fn compute_shadows_with_groups(
    pieces: &[ConvexPolygon],
    flags: &[PieceFlags],
    groups: &ShadowGroups,
    lights: &[SceneLight],
    options: &BuildOptions,
) -> Result<Shadows, Error> {
    if lights.len() > svbsp::MAX_LIGHTS {
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

    let (point_bits, point_lights): (Vec<u32>, Vec<svbsp::Light>) = lights
        .iter()
        .enumerate()
        .filter_map(|(i, l)| match l {
            SceneLight::Svbsp(light) => Some((i as u32, *light)),
            SceneLight::Area(_) => None,
        })
        .unzip();
    let mut figures: Vec<Option<LightFigures>> = vec![None; lights.len()];
    let (mut fragments, scene_nodes, bsp_seconds, mut shadow_seconds) = if point_lights.is_empty() {
        let fragments = originals
            .iter()
            .map(|p| Fragment {
                polygon: p.clone(),
                lit_mask: 0,
                umbra_mask: 0,
            })
            .collect();
        (fragments, 0, 0.0, 0.0)
    } else {
        let out = svbsp::compute_shadows(&originals, flags, &point_lights, options)?;
        for (j, stats) in out.lights.iter().enumerate() {
            figures[point_bits[j] as usize] = Some(LightFigures::Svbsp(*stats));
        }
        let fragments = out
            .fragments
            .into_iter()
            .map(|f| Fragment {
                lit_mask: remap(f.lit_mask, &point_bits),
                umbra_mask: remap(f.umbra_mask, &point_bits),
                polygon: f.polygon,
            })
            .collect();
        (
            fragments,
            out.scene_nodes,
            out.bsp_seconds,
            out.shadow_seconds,
        )
    };

    let started = Instant::now();
    // Each area light's trees depend only on the pieces: build them side by
    // side, then let each light refine the fragments in turn.
    let area_lights = SceneLight::areas(lights);
    let trees: Vec<AreaTrees> = area_lights
        .par_iter()
        .map(|(_, source)| AreaTrees::build_with_groups(&originals, flags, groups, source))
        .collect();
    for ((i, source), trees) in area_lights.into_iter().zip(&trees) {
        let (next, stats) =
            classify_fragments(trees, fragments, &originals, flags, source, i as u32);
        fragments = next;
        figures[i] = Some(LightFigures::Area(stats));
    }
    shadow_seconds += started.elapsed().as_secs_f64();
    Ok(Shadows {
        fragments,
        lights: figures
            .into_iter()
            .map(|f| f.expect("every light ran"))
            .collect(),
        scene_nodes,
        bsp_seconds,
        shadow_seconds,
    })
}

/// Moves bit `j` of `mask` to bit `bits[j]`.
fn remap(mask: u32, bits: &[u32]) -> u32 {
    bits.iter()
        .enumerate()
        .filter(|(j, _)| mask & (1 << j) != 0)
        .fold(0, |acc, (_, &b)| acc | (1 << b))
}
