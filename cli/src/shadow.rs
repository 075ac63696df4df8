//! The `umbra shadow` pipeline: scene in, classified and illuminated
//! fragments out.

use std::collections::HashMap;
use std::time::Instant;

use bsp_core::{BuildOptions, ConvexPolygon, GridPoint};
use svbsp::{LightSource, PieceFlags, compute_shadows};

use crate::decompose::{Pieces, SnappedLight};
use crate::error::{Error, Result};
use crate::mesh::{OutputFace, OutputMesh};
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

/// Runs the shadow pipeline on a loaded scene.
///
/// Point and directional lights are supported; area lights are reported as
/// not supported yet (their penumbra trees are still to come).
pub fn shadow_scene(scene: &Scene) -> Result<ShadowResult> {
    let started = Instant::now();
    let pieces = Pieces::from_scene(scene)?;
    let lights = svbsp_lights(scene, &pieces)?;
    let flags = piece_flags(scene, &pieces);
    let out = compute_shadows(&pieces.polygons, &flags, &lights, &BuildOptions::default())
        .map_err(|e| Error::Field {
            path: scene.path.clone(),
            field: "light".into(),
            message: e.to_string(),
        })?;

    let illum_started = Instant::now();
    let illum_lights = illum_lights(scene, &pieces)?;
    let mut mesh = OutputMesh::default();
    let mut light_irradiance = Vec::new();
    for fragment in &out.fragments {
        let piece = &pieces.polygons[fragment.polygon.source() as usize];
        let two_sided = flags[fragment.polygon.source() as usize].two_sided;
        let normal = piece.support().unit_normal_f64();
        let first = mesh.vertices.len() as u32;
        for v in fragment.polygon.vertices_f64() {
            let p = pieces.grid.grid_to_world(v);
            let first_value = light_irradiance.len();
            light_irradiance.extend(per_light_irradiance(
                &illum_lights,
                p,
                normal,
                two_sided,
                fragment.lit_mask,
            ));
            // The sum over the lit lights, in light order, as the PLY has
            // always had it.
            let e: f64 = light_irradiance[first_value..]
                .iter()
                .enumerate()
                .filter(|(i, _)| fragment.lit_mask & (1 << i) != 0)
                .map(|(_, e)| e)
                .sum();
            mesh.vertices.push((p, e as f32));
        }
        mesh.faces.push(OutputFace {
            vertices: (first..mesh.vertices.len() as u32).collect(),
            source: pieces.input_of[fragment.polygon.source() as usize],
            lit_mask: fragment.lit_mask,
            umbra_mask: fragment.umbra_mask,
        });
    }
    let illum = illum_started.elapsed().as_secs_f64();

    let stats = Stats {
        input_polygons: pieces.input_polygons as u64,
        output_fragments: mesh.faces.len() as u64,
        seconds: Seconds {
            bsp: out.bsp_seconds,
            shadow: out.shadow_seconds,
            grid: 0.0,
            illum,
            total: started.elapsed().as_secs_f64(),
        },
        lights: out
            .lights
            .iter()
            .map(|s| LightStats {
                front_facing_polygons: s.front_facing_polygons as u64,
                front_facing_edges: s.front_facing_edges as u64,
                tree_nodes: Some(s.tree_nodes as u64),
                penumbra_nodes: None,
                umbra_nodes: None,
                lit: s.lit as u64,
                penumbra: 0,
                umbra: s.umbra as u64,
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

/// The scene's lights for `svbsp`; area lights are not supported yet.
fn svbsp_lights(scene: &Scene, pieces: &Pieces) -> Result<Vec<svbsp::Light>> {
    let mut lights = Vec::with_capacity(pieces.lights.len());
    for (i, (light, snapped)) in scene.lights.iter().zip(&pieces.lights).enumerate() {
        let source = match snapped {
            SnappedLight::Point(p) => LightSource::Point(*p),
            SnappedLight::Directional(d) => LightSource::Directional(*d),
            SnappedLight::Area(_) => {
                return Err(Error::Field {
                    path: scene.path.clone(),
                    field: format!("light[{i}].type"),
                    message: "area lights are not supported by `umbra shadow` yet (penumbra and umbra trees are still to come)".into(),
                });
            }
        };
        let range = light.falloff.map(|f| f.range * pieces.grid.scale());
        lights.push(svbsp::Light { source, range });
    }
    Ok(lights)
}

/// Per piece: casts, two-sided, and whether its object is a closed surface
/// (every directed edge between grid points matched by its reverse exactly
/// once), which lets faces turned away from a light skip the shadow pass.
fn piece_flags(scene: &Scene, pieces: &Pieces) -> Vec<PieceFlags> {
    let object_of_input: Vec<usize> = scene.input_polygons().map(|(object, _)| object).collect();
    let object_of = |k: usize| object_of_input[pieces.input_of[k] as usize];
    let mut edges: HashMap<(usize, GridPoint, GridPoint), u32> = HashMap::new();
    for (k, piece) in pieces.polygons.iter().enumerate() {
        for (a, b) in grid_edges(piece) {
            *edges.entry((object_of(k), a, b)).or_insert(0) += 1;
        }
    }
    let mut open = vec![false; scene.objects.len()];
    for (&(object, a, b), &count) in &edges {
        if count != 1 || edges.get(&(object, b, a)) != Some(&1) {
            open[object] = true;
        }
    }
    (0..pieces.polygons.len())
        .map(|k| PieceFlags {
            casts_shadows: pieces.casts_shadows[k],
            two_sided: pieces.two_sided[k],
            closed_surface: !open[object_of(k)],
        })
        .collect()
}

fn grid_edges(piece: &ConvexPolygon) -> impl Iterator<Item = (GridPoint, GridPoint)> + '_ {
    let n = piece.len();
    (0..n).filter_map(move |i| {
        Some((
            piece.vertex_grid_point(i)?,
            piece.vertex_grid_point((i + 1) % n)?,
        ))
    })
}

/// A light as `illum` evaluates it (area lights are not supported yet).
enum IllumLight {
    Point(illum::PointLight),
    Directional(illum::DirectionalLight),
}

/// The scene's lights for `illum`, at their snapped positions so that
/// illumination and classification agree. Intensities and falloffs were
/// validated when the scene was loaded.
fn illum_lights(scene: &Scene, pieces: &Pieces) -> Result<Vec<IllumLight>> {
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
                    let falloff = illum::Falloff::new(f.start, f.range, f.exponent)
                        .map_err(|e| field(e.to_string()))?;
                    point = point.with_falloff(falloff);
                }
                IllumLight::Point(point)
            }
            (LightKind::Directional { direction }, _) => IllumLight::Directional(
                illum::DirectionalLight::new(*direction, light.intensity)
                    .map_err(|e| field(e.to_string()))?,
            ),
            _ => {
                return Err(field(
                    "area lights are not supported by `umbra shadow` yet".into(),
                ));
            }
        };
        out.push(made);
    }
    Ok(out)
}

/// Direct irradiance at world point `p` with unit normal `normal` from each
/// light in turn: its value if its bit is set in `lit_mask`, else 0 (ambient
/// excluded).
fn per_light_irradiance(
    lights: &[IllumLight],
    p: [f64; 3],
    normal: [f64; 3],
    two_sided: bool,
    lit_mask: u32,
) -> impl Iterator<Item = f64> + '_ {
    let sidedness = if two_sided {
        illum::Sidedness::TwoSided
    } else {
        illum::Sidedness::OneSided
    };
    lights.iter().enumerate().map(move |(i, light)| {
        if lit_mask & (1 << i) == 0 {
            return 0.0;
        }
        match light {
            IllumLight::Point(l) => l.irradiance(p, normal, sidedness),
            IllumLight::Directional(l) => l.irradiance(normal, sidedness),
        }
    })
}
