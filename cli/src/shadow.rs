//! The `umbra shadow` pipeline: scene in, classified and illuminated
//! fragments out.

use std::time::Instant;

use area_shadow::dark::{DARK_FRACTION, sees_none};
use area_shadow::{
    AreaSource, Class, ConformingMesh, LightFigures, SceneLight, ShadowGroups, conform_fragments,
    grid_fragments, subdivide_adaptive,
};
use bsp_core::{BuildOptions, ConvexPolygon};
use rayon::prelude::*;
use svbsp::{Fragment, LightSource};

use crate::closed_surface::{Surfaces, surfaces};
use crate::dark::Occluders;
use crate::decompose::{Pieces, SnappedLight};
use crate::error::{Error, Result};
use crate::illuminate::{IllumLight, Illuminated, Illuminator, illuminate};
use crate::mesh::{OutputFace, OutputMesh, irradiance_f32};
use crate::scene::{LightKind, Scene};
use crate::stats::{LightStats, Seconds, Stats};

/// What `umbra shadow` computes: the output mesh and the statistics.
#[derive(Debug, Clone)]
pub struct ShadowResult {
    /// Every fragment of every receiving polygon, with vertex irradiance.
    pub mesh: OutputMesh,
    /// The figures of FORMATS.md §3.
    pub stats: Stats,
    /// Direct irradiance at every vertex of [`Self::mesh`] from each light
    /// separately (0 where the fragment does not see all of the light), for
    /// coloured images: `lights` values per vertex, vertex after vertex.
    /// [`Self::vertex_light_irradiance`] reads one vertex's values.
    pub light_irradiance: Vec<f64>,
    /// Number of lights of the scene (values per vertex in
    /// [`Self::light_irradiance`]).
    pub lights: usize,
}

impl ShadowResult {
    /// The direct irradiance from each light (scene-file order) at vertex
    /// `vertex` of [`Self::mesh`].
    ///
    /// # Panics
    ///
    /// If `vertex` is not a vertex of the mesh.
    pub fn vertex_light_irradiance(&self, vertex: usize) -> &[f64] {
        &self.light_irradiance[vertex * self.lights..(vertex + 1) * self.lights]
    }
}

/// Faces with more corners than this (a large fragment beside many small
/// ones gathers their vertices) are halved: the PLY's vertex lists hold at
/// most 255, and shading is smoother on compact faces.
pub(crate) const MAX_FACE_CORNERS: usize = 64;

/// Options of the shadow pipeline beyond the scene file.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShadowOptions {
    /// Gridding: lit fragments are cut into cells of the scene's largest
    /// extent divided by this, penumbra fragments into cells half that
    /// size; umbra is left whole. `None`: no gridding.
    pub grid: Option<u32>,
    /// Adaptive subdivision: cells (or whole fragments) are halved across
    /// their longer side while the irradiance at their corners varies by
    /// more than this fraction of the largest. `None`: none.
    pub adaptive: Option<f64>,
}

/// Runs the shadow pipeline on a loaded scene with default options.
pub fn shadow_scene(scene: &Scene) -> Result<ShadowResult> {
    shadow_scene_with(scene, &ShadowOptions::default())
}

/// Runs the shadow pipeline on a loaded scene: classification for every
/// light, gridding, a conforming mesh, illumination.
pub fn shadow_scene_with(scene: &Scene, options: &ShadowOptions) -> Result<ShadowResult> {
    let started = Instant::now();
    let pieces = Pieces::from_scene(scene)?;
    let lights = scene_lights(scene, &pieces)?;
    let objects = piece_objects(scene, &pieces);
    let Surfaces {
        flags,
        facing_inside,
    } = surfaces(&pieces, &objects);
    let groups = ShadowGroups::of_objects(&pieces.polygons, &flags, &objects);
    let out = area_shadow::compute_shadows_with_groups(
        &pieces.polygons,
        &flags,
        &groups,
        &lights,
        &BuildOptions::default(),
    )
    .map_err(|e| Error::Field {
        path: scene.path.clone(),
        field: "light".into(),
        message: e.to_string(),
    })?;
    let illum_lights = illum_lights(scene, &pieces)?;
    let illuminator = Illuminator::new(&illum_lights, &pieces);

    let grid_started = Instant::now();
    let area_mask = lights
        .iter()
        .enumerate()
        .filter(|(_, l)| matches!(l, SceneLight::Area(_)))
        .fold(0_u32, |m, (i, _)| m | (1 << i));
    let mut fragments = out.fragments;
    settle_facing_inside(&mut fragments, &facing_inside, lights.len());
    let extent = scene_extent(&pieces.polygons);
    if let Some(n) = options.grid.filter(|&n| n > 0) {
        let cell = (extent / f64::from(n)).ceil().max(2.0) as i64;
        fragments = grid_fragments(fragments, lights.len(), area_mask, cell);
    }
    if let Some(tolerance) = options.adaptive {
        // Cells stop halving at 1/1024 of the scene: far below what an
        // image shows.
        fragments = subdivide_adaptive(
            fragments,
            lights.len(),
            area_mask,
            tolerance,
            extent / 1024.0,
            |f| illuminator.fragment_irradiance(f),
        );
    }
    let point_lights = lights.iter().enumerate().filter_map(|(i, l)| match l {
        SceneLight::Svbsp(l) => Some((i, l)),
        SceneLight::Area(_) => None,
    });
    settle_beyond_range(&mut fragments, point_lights);
    let dark_started = Instant::now();
    mark_joint_umbra(
        &mut fragments,
        &illuminator,
        &lights,
        &pieces,
        &Occluders::new(&pieces, &groups, &objects),
    );
    let dark_seconds = dark_started.elapsed().as_secs_f64();
    let (fragments, conforming) = conform_fragments(fragments, MAX_FACE_CORNERS);
    let grid = grid_started.elapsed().as_secs_f64() - dark_seconds;

    let illum_started = Instant::now();
    let (mesh, lit) = illuminated_mesh(&fragments, &conforming, &illuminator, &pieces);
    let (mesh, origin) = pieces.frames.place(mesh);
    let lights = illum_lights.len();
    let light_irradiance: Vec<f64> = origin
        .iter()
        .flat_map(|&v| &lit.per_light[v as usize * lights..(v as usize + 1) * lights])
        .copied()
        .collect();
    let illum = illum_started.elapsed().as_secs_f64();

    let class_count = |i: usize, class: Class| -> u64 {
        fragments
            .iter()
            .filter(|f| Class::of(f, i as u32) == class)
            .count() as u64
    };
    let stats = Stats {
        input_polygons: pieces.input_polygons as u64,
        dropped_polygons: pieces.dropped.clone(),
        output_fragments: mesh.faces.len() as u64,
        seconds: Seconds {
            bsp: out.bsp_seconds,
            shadow: out.shadow_seconds + dark_seconds,
            grid,
            illum,
            total: started.elapsed().as_secs_f64(),
        },
        lights: out
            .lights
            .iter()
            .enumerate()
            .map(|(i, figures)| {
                let [lit_vertices, penumbra_vertices, umbra_vertices] = lit.vertex_classes[i];
                let mut s = LightStats {
                    lit: class_count(i, Class::Lit),
                    penumbra: class_count(i, Class::Penumbra),
                    umbra: class_count(i, Class::Umbra),
                    lit_vertices: Some(lit_vertices),
                    penumbra_vertices: Some(penumbra_vertices),
                    umbra_vertices: Some(umbra_vertices),
                    ..LightStats::default()
                };
                match figures {
                    LightFigures::Svbsp(f) => {
                        s.front_facing_polygons = f.front_facing_polygons as u64;
                        s.front_facing_edges = f.front_facing_edges as u64;
                        s.tree_nodes = Some(f.tree_nodes as u64);
                        s.cones = Some(f.cones as u64);
                    }
                    LightFigures::Area(f) => {
                        s.front_facing_polygons = f.front_facing_polygons as u64;
                        s.front_facing_edges = f.front_facing_edges as u64;
                        s.penumbra_nodes = Some(f.penumbra_nodes as u64);
                        s.umbra_nodes = Some(f.umbra_nodes as u64);
                    }
                }
                s
            })
            .collect(),
    };
    Ok(ShadowResult {
        mesh,
        stats,
        light_irradiance,
        lights: illum_lights.len(),
    })
}

/// The output mesh of conforming fragments (world units), each vertex's
/// irradiance from all the lights together, and their illumination (its
/// faces moved into the mesh).
pub(crate) fn illuminated_mesh(
    fragments: &[Fragment],
    conforming: &ConformingMesh,
    illuminator: &Illuminator<'_>,
    pieces: &Pieces,
) -> (OutputMesh, Illuminated) {
    let mut lit = illuminate(illuminator, fragments, conforming);
    let mut mesh = OutputMesh::default();
    let lights = illuminator.lights.len();
    for (v, p) in lit.coords.iter().enumerate() {
        let e: f64 = lit.per_light[v * lights..(v + 1) * lights].iter().sum();
        mesh.vertices
            .push((pieces.grid.grid_to_world(*p), irradiance_f32(e)));
    }
    for (fragment, face) in fragments.iter().zip(std::mem::take(&mut lit.faces)) {
        mesh.faces.push(OutputFace {
            vertices: face,
            source: pieces.input_of[fragment.polygon.source() as usize],
            lit_mask: fragment.lit_mask,
            umbra_mask: fragment.umbra_mask,
        });
    }
    (mesh, lit)
}

/// The largest side of the pieces' bounding box, in grid units.
fn scene_extent(pieces: &[ConvexPolygon]) -> f64 {
    let (lo, hi) = pieces.iter().flat_map(|p| p.vertices_f64()).fold(
        ([f64::MAX; 3], [f64::MIN; 3]),
        |(lo, hi), v| {
            (
                [0, 1, 2].map(|i| lo[i].min(v[i])),
                [0, 1, 2].map(|i| hi[i].max(v[i])),
            )
        },
    );
    (0..3).map(|i| hi[i] - lo[i]).fold(0.0, f64::max)
}

/// The scene's lights for the shadow passes.
fn scene_lights(scene: &Scene, pieces: &Pieces) -> Result<Vec<SceneLight>> {
    let mut lights = Vec::with_capacity(pieces.lights.len());
    for (i, (light, snapped)) in scene.lights.iter().zip(&pieces.lights).enumerate() {
        let range = light.falloff.map(|f| f.range * pieces.grid.scale());
        lights.push(match snapped {
            SnappedLight::Point(p) => SceneLight::Svbsp(svbsp::Light {
                source: LightSource::Point(*p),
                range,
            }),
            SnappedLight::Directional(d) => SceneLight::Svbsp(svbsp::Light {
                source: LightSource::Directional(*d),
                range,
            }),
            SnappedLight::Area(polygon) => {
                SceneLight::Area(AreaSource::new(polygon.clone()).map_err(|e| Error::Field {
                    path: scene.path.clone(),
                    field: format!("light[{i}].vertices"),
                    message: e.to_string(),
                })?)
            }
        });
    }
    Ok(lights)
}

/// Marks umbra, for each point light with a range, every fragment wholly
/// beyond it (it takes no part for that light). The shadow pass settles
/// whole polygons so; the fragments it and gridding cut from a polygon
/// that straddles the range may lie beyond it too.
pub(crate) fn settle_beyond_range<'a>(
    fragments: &mut [Fragment],
    lights: impl IntoIterator<Item = (usize, &'a svbsp::Light)>,
) {
    for (i, light) in lights {
        if light.range.is_none() {
            continue;
        }
        let bit = 1 << i;
        for fragment in fragments.iter_mut() {
            if fragment.umbra_mask & bit == 0
                && light.wholly_beyond_range(&fragment.polygon.vertices_f64())
            {
                fragment.lit_mask &= !bit;
                fragment.umbra_mask |= bit;
            }
        }
    }
}

/// Marks umbra, for every light, each fragment of a piece facing the inside
/// of a closed surface wound inwards (`facing_inside`, by piece): it sees
/// none of any light ([`crate::closed_surface`]).
pub(crate) fn settle_facing_inside(
    fragments: &mut [Fragment],
    facing_inside: &[bool],
    lights: usize,
) {
    let all = if lights >= 32 {
        u32::MAX
    } else {
        (1 << lights) - 1
    };
    for fragment in fragments {
        if facing_inside[fragment.polygon.source() as usize] {
            fragment.lit_mask = 0;
            fragment.umbra_mask = all;
        }
    }
}

/// Marks umbra, for an area light, each penumbra fragment that sees none
/// of it: every corner dark (in floating point, [`DARK_FRACTION`]) and the
/// whole fragment proven dark past the blockers between it and the light
/// ([`area_shadow::dark::sees_none`]). These are the joint umbrae of
/// occluders that hide the light only together; a joint umbra ends along a
/// curve, which fragments follow as finely as `--grid` or `--adaptive` cut
/// them. Fragments are worked on in parallel, each on its own.
fn mark_joint_umbra(
    fragments: &mut [Fragment],
    illuminator: &Illuminator<'_>,
    lights: &[SceneLight],
    pieces: &Pieces,
    occluders: &Occluders<'_>,
) {
    let areas = SceneLight::areas(lights);
    fragments.par_iter_mut().for_each(|fragment| {
        for &(i, light) in &areas {
            // (The corners go first, each stopping at the first lit one:
            // most penumbra fragments have one.)
            if Class::of(fragment, i as u32) != Class::Penumbra
                || !illuminator
                    .corner_irradiance(i, &fragment.polygon)
                    .all(|(seen, whole)| seen <= DARK_FRACTION * whole)
            {
                continue;
            }
            let (polygons, bodies) = occluders.near(&fragment.polygon, light);
            let two_sided = pieces.two_sided[fragment.polygon.source() as usize];
            if sees_none(&fragment.polygon, two_sided, light, &polygons, &bodies) {
                fragment.umbra_mask |= 1 << i;
            }
        }
    });
}

/// Per piece, the index of its object in the scene file.
pub(crate) fn piece_objects(scene: &Scene, pieces: &Pieces) -> Vec<u32> {
    let object_of_input: Vec<u32> = scene
        .input_polygons()
        .map(|(object, _)| object as u32)
        .collect();
    pieces
        .input_of
        .iter()
        .map(|&input| object_of_input[input as usize])
        .collect()
}

/// The scene's lights for `illum`, at their snapped positions so that
/// illumination and classification agree. Intensities and falloffs were
/// validated when the scene was loaded.
pub(crate) fn illum_lights(scene: &Scene, pieces: &Pieces) -> Result<Vec<IllumLight>> {
    let mut out = Vec::with_capacity(scene.lights.len());
    for (i, (light, snapped)) in scene.lights.iter().zip(&pieces.lights).enumerate() {
        let field = |message: String| Error::Field {
            path: scene.path.clone(),
            field: format!("light[{i}]"),
            message,
        };
        let made = match (&light.kind, snapped) {
            (LightKind::Point { .. }, SnappedLight::Point(g)) => {
                let mut point = illum::PointLight::new(pieces.grid.to_world(*g), light.intensity)
                    .map_err(|e| field(e.to_string()))?;
                if let Some(f) = light.falloff {
                    let falloff = f.to_illum().map_err(|e| field(e.to_string()))?;
                    point = point.with_falloff(falloff);
                }
                IllumLight::Point(point)
            }
            (LightKind::Directional { direction }, _) => IllumLight::Directional(
                illum::DirectionalLight::new(*direction, light.intensity)
                    .map_err(|e| field(e.to_string()))?,
            ),
            (LightKind::Area { .. }, SnappedLight::Area(polygon)) => IllumLight::Area(
                illum::AreaLight::new(&polygon.vertices_f64(), light.intensity)
                    .map_err(|e| field(e.to_string()))?,
            ),
            _ => return Err(field("the light's kind changed when snapped".into())),
        };
        out.push(made);
    }
    Ok(out)
}
