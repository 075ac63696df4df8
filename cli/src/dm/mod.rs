//! `umbra dm` and `umbra update`: discontinuity meshes (dm-mesh) of a
//! scene's receivers under its area lights, written as PLY (one face per
//! DM cell), and objects moved step by step with incremental updates timed
//! against full rebuilds.

mod figures;
mod output;
mod update;

use std::time::Instant;

use area_shadow::AreaSource;
use bsp_core::ConvexPolygon;
use dm_mesh::{DmLight, DmOptions, DmScene, IllumStats, ObjectId};
use svbsp::PieceFlags;

use crate::closed_surface::{Surfaces, surfaces};
use crate::decompose::{Motion, Pieces, SnappedLight};
use crate::dm_lights::LightMap;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::shadow::piece_objects;
use crate::stats::Stats;

pub use figures::{DmFigures, DmStats};
pub use update::UpdateFigures;

/// DM-trees built from scratch, with the figures of their build.
struct FreshDm {
    dm: DmScene,
    ids: Vec<ObjectId>,
    illum: IllumStats,
    build_seconds: f64,
    illum_seconds: f64,
}

impl FreshDm {
    /// Builds and illuminates `objects` under `lights` (those at the
    /// indices `movable` declared movable), timing both; light falls on
    /// object `o`'s polygon `i` along `normals[o][i]`.
    fn build(
        lights: Vec<DmLight>,
        objects: Vec<(Vec<ConvexPolygon>, PieceFlags)>,
        movable: &[usize],
        normals: &[Vec<[f64; 3]>],
        options: DmOptions,
    ) -> Result<Self> {
        let build_started = Instant::now();
        let (mut dm, ids) = DmScene::build_movable(lights, objects, movable, options)
            .map_err(|e| Error::Dm(e.to_string()))?;
        for (&id, normals) in ids.iter().zip(normals) {
            let pieces = dm.object_pieces(id).unwrap_or_default().to_vec();
            for (piece, &normal) in pieces.into_iter().zip(normals) {
                dm.set_receiver_normal(piece, normal)
                    .map_err(|e| Error::Dm(e.to_string()))?;
            }
        }
        let build_seconds = build_started.elapsed().as_secs_f64();
        let illum_started = Instant::now();
        let illum = dm.illuminate();
        Ok(Self {
            dm,
            ids,
            illum,
            build_seconds,
            illum_seconds: illum_started.elapsed().as_secs_f64(),
        })
    }
}

/// A scene's DM-trees, built.
pub struct DmRun {
    /// The scene on the grid.
    pub pieces: Pieces,
    /// The discontinuity meshes.
    pub dm: DmScene,
    /// Per scene object: its handle and its pieces' indices.
    pub objects: Vec<(ObjectId, Vec<usize>)>,
    /// Figures of the build.
    pub stats: DmStats,
    /// Where the DM (area) lights stand among the scene's, and the point
    /// and directional lights cut into the cells at output.
    pub(crate) light_map: LightMap,
    /// Per piece, whether it faces the inside of a closed surface wound
    /// inwards: in umbra for every light ([`crate::closed_surface`]).
    pub(crate) facing_inside: Vec<bool>,
}

/// The DM lights: the scene's area lights, in order (the others are cut
/// into the cells at output, `dm_lights`).
fn area_lights(scene: &Scene, pieces: &Pieces) -> Result<Vec<DmLight>> {
    let mut out = Vec::new();
    for (i, (light, snapped)) in scene.lights.iter().zip(&pieces.lights).enumerate() {
        let field = |message: String| Error::Field {
            path: scene.path.clone(),
            field: format!("light[{i}]"),
            message,
        };
        let SnappedLight::Area(polygon) = snapped else {
            continue;
        };
        let source = AreaSource::new(polygon.clone()).map_err(|e| field(e.to_string()))?;
        out.push(DmLight::new(source, light.intensity).map_err(|e| field(e.to_string()))?);
    }
    Ok(out)
}

/// The pieces of each scene object (piece `k` of object `objects[k]`),
/// with the object's flags: closed surfaces in it when any piece is part
/// of one (the DM finds which are).
fn grouped(scene: &Scene, objects: &[u32], flags: &[PieceFlags]) -> Vec<(Vec<usize>, PieceFlags)> {
    let mut out: Vec<(Vec<usize>, PieceFlags)> = scene
        .objects
        .iter()
        .map(|o| {
            let f = PieceFlags {
                casts_shadows: o.casts_shadows,
                two_sided: o.two_sided,
                closed_surface: false,
            };
            (Vec::new(), f)
        })
        .collect();
    for (k, &o) in objects.iter().enumerate() {
        let (pieces, object_flags) = &mut out[o as usize];
        let closed = !pieces.is_empty() && object_flags.closed_surface;
        pieces.push(k);
        *object_flags = PieceFlags {
            closed_surface: closed || flags[k].closed_surface,
            ..flags[k]
        };
    }
    out
}

/// Builds and illuminates the DM-trees of a loaded scene (internal EV / VE
/// discontinuities included).
pub fn dm_scene(scene: &Scene) -> Result<DmRun> {
    dm_scene_with(scene, DmOptions::default())
}

/// Builds and illuminates the DM-trees of a loaded scene.
pub fn dm_scene_with(scene: &Scene, options: DmOptions) -> Result<DmRun> {
    dm_scene_for(scene, options, None)
}

/// [`dm_scene_with`] for a scene whose object named `object` will move by
/// `by` (world units) `steps` times, one step after another: the grid
/// holds the object's whole way and one step's lengths
/// ([`Pieces::from_scene_moving`]), and the object is declared movable
/// ([`DmScene::build_movable`]: even its first move deletes only its own
/// nodes). Errors: those of a build, no object of that name, and a way
/// beyond finite numbers.
pub fn dm_scene_moving(
    scene: &Scene,
    options: DmOptions,
    object: &str,
    by: [f64; 3],
    steps: u32,
) -> Result<DmRun> {
    let field = |field: &str, message: String| Error::Field {
        path: scene.path.clone(),
        field: field.into(),
        message,
    };
    let index = scene
        .objects
        .iter()
        .position(|o| o.name == object)
        .ok_or_else(|| field("--move", format!("no object is named `{object}`")))?;
    let motion = Motion {
        object: index,
        by,
        steps,
    };
    if motion.way().iter().any(|x| !x.is_finite()) {
        return Err(field(
            "--by",
            format!("{steps} steps of {by:?} go beyond finite numbers"),
        ));
    }
    dm_scene_for(scene, options, Some(motion))
}

/// Builds and illuminates the DM-trees of a loaded scene, the grid sized
/// for `motion` (if any), whose object is declared movable.
fn dm_scene_for(scene: &Scene, options: DmOptions, motion: Option<Motion>) -> Result<DmRun> {
    let started = Instant::now();
    let pieces = Pieces::from_scene_moving(scene, motion).map_err(|e| match motion {
        // The scene snaps on a grid of its own: the way stretched the
        // grid so far that the scene lost what it needs.
        Some(m) if Pieces::from_scene(scene).is_ok() => Error::Field {
            path: scene.path.clone(),
            field: "--by".into(),
            message: format!(
                "{} steps of {:?} stretch the scene's grid too far: {}",
                m.steps,
                m.by,
                match &e {
                    Error::Field { field, message, .. } => format!("{field}: {message}"),
                    Error::Grid { source, .. } => source.to_string(),
                    other => other.to_string(),
                }
            ),
        },
        _ => e,
    })?;
    let lights = area_lights(scene, &pieces)?;
    let light_map = LightMap::of(scene, &pieces)?;
    let objects = piece_objects(scene, &pieces);
    let Surfaces {
        flags,
        facing_inside,
    } = surfaces(&pieces, &objects);
    let groups = grouped(scene, &objects, &flags);
    let objects: Vec<(Vec<ConvexPolygon>, PieceFlags)> = groups
        .iter()
        .map(|(ks, f)| (ks.iter().map(|&k| pieces.polygons[k].clone()).collect(), *f))
        .collect();
    let normals = normals_of(&pieces, groups.iter().map(|(ks, _)| ks));
    let movable: Vec<usize> = motion.map(|m| m.object).into_iter().collect();
    let fresh = FreshDm::build(lights, objects, &movable, &normals, options)?;
    let groups = groups.into_iter().map(|g| g.0).collect();
    Ok(DmRun::assemble(
        pieces,
        fresh,
        groups,
        light_map,
        facing_inside,
        started,
    ))
}

impl DmRun {
    /// The run of `fresh` (built from `pieces`, object `k` of the pieces
    /// `groups[k]`; `facing_inside` by piece), its figures timed from
    /// `started`.
    fn assemble(
        pieces: Pieces,
        fresh: FreshDm,
        groups: Vec<Vec<usize>>,
        light_map: LightMap,
        facing_inside: Vec<bool>,
        started: Instant,
    ) -> Self {
        let mut run = DmRun {
            light_map,
            facing_inside,
            pieces,
            dm: fresh.dm,
            objects: fresh.ids.into_iter().zip(groups).collect(),
            stats: DmStats {
                stats: Stats::default(),
                dm: DmFigures::default(),
                update: None,
            },
        };
        run.stats = run.figures(
            fresh.build_seconds,
            fresh.illum_seconds,
            &fresh.illum,
            started.elapsed().as_secs_f64(),
        );
        run
    }
}

/// Per object (its pieces' indices), the normals light falls on.
fn normals_of<'a>(
    pieces: &Pieces,
    objects: impl Iterator<Item = &'a Vec<usize>>,
) -> Vec<Vec<[f64; 3]>> {
    objects
        .map(|ks| ks.iter().map(|&k| pieces.normals[k]).collect())
        .collect()
}
