//! `umbra dm` and `umbra update`: discontinuity meshes (dm-mesh) of a
//! scene's receivers under its area lights, written as PLY (one face per
//! DM cell), and objects moved step by step with incremental updates timed
//! against full rebuilds.

use std::time::Instant;

use area_shadow::{AreaSource, ShadowGroups};
use bsp_core::{ConvexPolygon, FaceKey, VertexKey};
use dm_mesh::{
    Cell, CellClass, DmLight, DmOptions, DmScene, IllumStats, ObjectId, PieceId, ReceiverDm, Region,
};
use rayon::prelude::*;
use serde::Serialize;
use slotmap::SecondaryMap;
use svbsp::{Fragment, PieceFlags};

use crate::atomic::Outputs;
use crate::closed_surface::{Surfaces, surfaces};
use crate::dark::{Occluders, proven_dark_past};
use crate::decompose::{Motion, Pieces, SnappedLight};
use crate::dm_lights::{LightMap, cut_by_other_lights};
use crate::error::{Error, Result};
use crate::mesh::{OutputFace, OutputMesh, irradiance_f32};
use crate::scene::Scene;
use crate::shadow::piece_objects;
use crate::stats::{LightStats, Seconds, Stats};

/// Figures of the DM-trees (beside FORMATS.md §3's fields).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct DmFigures {
    /// Receivers (convex pieces), one DM-tree each.
    pub receivers: u64,
    /// Inner nodes of all DM-trees.
    pub tree_nodes: u64,
    /// Cells (leaves) of all DM-trees.
    pub cells: u64,
    /// Distinct cell vertices (per receiver).
    pub vertices: u64,
    /// Vertex-light pairs whose visible part of the light was computed.
    pub visibility_vertices: u64,
    /// Light/occluder comparisons those computations made.
    pub comparisons: u64,
    /// Comparisons per vertex (the paper: 1.3 to 2.1).
    pub comparisons_per_vertex: f64,
    /// Comparisons per vertex that needed a visibility computation.
    pub comparisons_per_visibility_vertex: f64,
    /// Seconds building the trees (casting and merging shadows).
    pub build_seconds: f64,
    /// Seconds illuminating vertices.
    pub illum_seconds: f64,
    /// Seconds turning the cells into output faces, proving the cells in a
    /// joint umbra dark on the way (counted in `seconds.total`).
    pub output_seconds: f64,
}

/// Per-step figures of `umbra update`.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct UpdateFigures {
    /// The object moved.
    pub object: String,
    /// Its share of the scene's input polygons.
    pub object_fraction: f64,
    /// Seconds of each incremental step (delete, add, re-illuminate).
    pub update_seconds: Vec<f64>,
    /// Seconds of a full rebuild (build and illuminate) after each step.
    pub rebuild_seconds: Vec<f64>,
    /// Vertices re-evaluated by each step.
    pub reilluminated_vertices: Vec<u64>,
    /// Receivers whose cells or vertex irradiance each step changed (the
    /// moved object's new polygons among them): what an application
    /// drawing the cells reads again ([`DmScene::receivers_changed_since`]).
    pub changed_receivers: Vec<u64>,
}

/// What `umbra dm` / `umbra update` write with `--stats`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DmStats {
    /// The fields of FORMATS.md §3 (`shadow` holds the DM build, `bsp` and
    /// `grid` are zero).
    #[serde(flatten)]
    pub stats: Stats,
    /// DM-tree figures.
    pub dm: DmFigures,
    /// `umbra update` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub update: Option<UpdateFigures>,
}

impl DmStats {
    /// Writes the JSON to `path`, atomically.
    pub fn save(&self, path: &std::path::Path) -> Result<()> {
        let mut outputs = Outputs::default();
        self.stage(&mut outputs, path)?;
        outputs.commit()
    }

    /// [`Self::save`] as one of a run's [`Outputs`], written when they are.
    pub fn stage(&self, outputs: &mut Outputs, path: &std::path::Path) -> Result<()> {
        // Serialising plain numbers and structs cannot fail.
        let json = serde_json::to_string_pretty(self).unwrap_or_default();
        crate::stats::stage_json(outputs, path, &json)
    }
}

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

/// The most cells a region proven dark at once may gather (see
/// [`DmRun::proven_dark`]). The 10k hall's floor has 68k cells to prove:
/// in 30k regions, 13k of them of several cells, most proven at once;
/// `umbra dm`'s output took 4.1 s cell by cell, 3.6 s with regions of up
/// to 4 cells, 3.5 s with 16 and 3.4 s with 256 or more (2 cores). A
/// bound keeps a region whose proof fails from being a big one.
const PROOF_REGION_CELLS: usize = 256;

/// What the joint-umbra proofs of the output's cells need (`cli::dark`).
struct DarkContext<'a> {
    areas: &'a [&'a AreaSource],
    occluders: &'a Occluders<'a>,
    /// The index into [`DmRun::objects`] of each object.
    object_of: &'a SecondaryMap<ObjectId, u32>,
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
        .ok_or_else(|| {
            field(
                "object",
                format!("no object is named `{object}` (from --move)"),
            )
        })?;
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

    /// The output mesh and the statistics, their cell counts per class
    /// those of the mesh (joint umbrae proven as it is made turn penumbra
    /// cells umbra, see [`Self::mesh`]).
    pub fn output(&self) -> Result<(OutputMesh, DmStats)> {
        let started = Instant::now();
        let (mesh, figures) = self.mesh_with_figures()?;
        let mut stats = self.stats.clone();
        for (i, s) in figures {
            stats.stats.lights[i] = s;
        }
        stats.dm.output_seconds = started.elapsed().as_secs_f64();
        stats.stats.seconds.total += stats.dm.output_seconds;
        for (i, light) in stats.stats.lights.iter_mut().enumerate() {
            let bit = 1 << i;
            light.lit = mesh.faces.iter().filter(|f| f.lit_mask & bit != 0).count() as u64;
            light.umbra = mesh
                .faces
                .iter()
                .filter(|f| f.umbra_mask & bit != 0)
                .count() as u64;
            light.penumbra = mesh.faces.len() as u64 - light.lit - light.umbra;
        }
        stats.stats.output_fragments = mesh.faces.len() as u64;
        Ok((mesh, stats))
    }

    /// The cells as an output mesh (world units; one face per cell), the
    /// receivers in scene order. A cell that the DM-tree leaves in
    /// penumbra, but whose corners all see none of a light, is umbra for it
    /// when proven to see none of it past the occluders it lists
    /// (`cli::dark`: a joint umbra of several occluders, which no
    /// one volume bounds).
    ///
    /// Point and directional lights cut the cells along their shadows
    /// (`dm_lights`); errors only as their passes may.
    pub fn mesh(&self) -> Result<OutputMesh> {
        Ok(self.mesh_with_figures()?.0)
    }

    /// [`Self::mesh`], with the figures of the point and directional
    /// lights' passes (scene index, statistics).
    fn mesh_with_figures(&self) -> Result<(OutputMesh, Vec<(usize, LightStats)>)> {
        let receivers: Vec<(usize, PieceId)> = self
            .objects
            .iter()
            .filter_map(|(id, ks)| {
                let handles = self.dm.object_pieces(*id)?;
                Some(ks.iter().copied().zip(handles.iter().copied()))
            })
            .flatten()
            .collect();
        let mut objects = vec![0_u32; self.pieces.polygons.len()];
        for (o, (_, ks)) in self.objects.iter().enumerate() {
            for &k in ks {
                objects[k] = o as u32;
            }
        }
        let flags: Vec<PieceFlags> = (0..objects.len())
            .map(|k| PieceFlags {
                casts_shadows: self.pieces.casts_shadows[k],
                two_sided: self.pieces.two_sided[k],
                closed_surface: false,
            })
            .collect();
        let groups = ShadowGroups::of_objects(&self.pieces.polygons, &flags, &objects);
        let occluders = Occluders::new(&self.pieces, &groups, &objects);
        let mut object_of: SecondaryMap<ObjectId, u32> = SecondaryMap::new();
        for (o, (id, _)) in self.objects.iter().enumerate() {
            object_of.insert(*id, o as u32);
        }
        let areas: Vec<&AreaSource> = self.dm.lights().iter().map(|l| l.source()).collect();
        let context = DarkContext {
            areas: &areas,
            occluders: &occluders,
            object_of: &object_of,
        };
        // Each receiver's part on its own (in parallel: millions of cells
        // on a big scene), then joined in order.
        let parts: Vec<OutputMesh> = receivers
            .par_iter()
            .with_max_len(1)
            .map(|&(k, piece)| self.receiver_mesh(k, piece, &context))
            .collect();
        if !self.light_map.others.is_empty() {
            let cells = receivers
                .iter()
                .zip(&parts)
                .flat_map(|(&(k, piece), part)| self.cell_fragments(k, piece, part))
                .collect();
            let (mesh, figures) =
                cut_by_other_lights(cells, &self.pieces, &flags, &groups, &self.light_map)?;
            return Ok((self.pieces.frames.place(mesh).0, figures));
        }
        let mut mesh = OutputMesh {
            vertices: Vec::with_capacity(parts.iter().map(|p| p.vertices.len()).sum()),
            faces: Vec::with_capacity(parts.iter().map(|p| p.faces.len()).sum()),
        };
        for part in parts {
            let offset = mesh.vertices.len() as u32;
            mesh.vertices.extend(part.vertices);
            mesh.faces.extend(part.faces.into_iter().map(|mut face| {
                face.vertices.iter_mut().for_each(|v| *v += offset);
                face
            }));
        }
        Ok((self.pieces.frames.place(mesh).0, Vec::new()))
    }

    /// The cells of one receiver (`piece`, of scene piece `k`) as exact
    /// polygons (source `k`) with the masks of its output faces `part`
    /// ([`Self::receiver_mesh`], one face per cell in the same order).
    fn cell_fragments(&self, k: usize, piece: PieceId, part: &OutputMesh) -> Vec<Fragment> {
        let Some(receiver) = self.dm.receiver(piece) else {
            return Vec::new();
        };
        receiver
            .cells()
            .zip(&part.faces)
            .filter_map(|((face, _), out)| {
                Some(Fragment {
                    polygon: receiver.mesh().face_polygon(face, k as u32).ok()?,
                    lit_mask: out.lit_mask,
                    umbra_mask: out.umbra_mask,
                })
            })
            .collect()
    }

    /// The cells of one receiver (`piece`, of scene piece `k`), its
    /// vertices numbered from 0 as first met.
    fn receiver_mesh(&self, k: usize, piece: PieceId, dark: &DarkContext<'_>) -> OutputMesh {
        let mut mesh = OutputMesh::default();
        let Some(receiver) = self.dm.receiver(piece) else {
            return mesh;
        };
        let lights = self.dm.lights().len();
        let two_sided = self.pieces.two_sided[k];
        // Facing the inside of a closed surface wound inwards: no light.
        let inside = self.facing_inside.get(k).copied().unwrap_or(false);
        let mut index: SecondaryMap<VertexKey, u32> = SecondaryMap::new();
        // Cells to prove dark: their output faces, and the lights.
        let mut candidates: SecondaryMap<FaceKey, (usize, u32)> = SecondaryMap::new();
        for (face, cell) in receiver.cells() {
            let corners = receiver.mesh().face_vertices(face);
            let mut vertices = Vec::with_capacity(corners.len());
            // The lights every corner gets nothing from.
            let mut dark_corners = u32::MAX;
            for v in corners {
                dark_corners &= self.dm.vertex_dark_lights(piece, v).unwrap_or(0);
                let slot = match index.get(v) {
                    Some(&slot) => slot,
                    None => {
                        let slot = mesh.vertices.len() as u32;
                        let p = receiver.mesh().vertex(v).map(|x| x.position.to_f64());
                        let e = if inside {
                            0.0
                        } else {
                            self.dm.vertex_irradiance(piece, v).unwrap_or(0.0)
                        };
                        let p = self.pieces.grid.grid_to_world(p.unwrap_or([0.0; 3]));
                        mesh.vertices.push((p, irradiance_f32(e)));
                        index.insert(v, slot);
                        slot
                    }
                };
                vertices.push(slot);
            }
            let (mut lit_mask, mut umbra_mask, mut penumbra_mask) = (0, 0, 0);
            for i in 0..lights {
                match receiver.class(cell, i) {
                    CellClass::Lit => lit_mask |= 1 << i,
                    CellClass::Umbra => umbra_mask |= 1 << i,
                    CellClass::Penumbra => penumbra_mask |= 1 << i,
                }
            }
            if inside {
                (lit_mask, umbra_mask, penumbra_mask) =
                    (0, lit_mask | umbra_mask | penumbra_mask, 0);
            }
            // Cells in a joint umbra: penumbra for the volumes, every corner
            // dark, and proven to see none of the light (below).
            if penumbra_mask & dark_corners != 0 {
                candidates.insert(face, (mesh.faces.len(), penumbra_mask & dark_corners));
            }
            mesh.faces.push(OutputFace {
                vertices,
                source: self.pieces.input_of[k],
                lit_mask: self.light_map.scene_bits(lit_mask),
                umbra_mask: self.light_map.scene_bits(umbra_mask),
            });
        }
        let proven = self.proven_dark(receiver, two_sided, &candidates, dark);
        for (f, lights) in proven {
            mesh.faces[f].umbra_mask |= self.light_map.scene_bits(lights);
        }
        mesh
    }

    /// The output faces (with the lights) of the `candidates` (cells left
    /// in penumbra whose corners all see none of a light: cell, its output
    /// face and those lights) proven to see none of those lights past the
    /// occluders they list. The proofs go by the regions the DM-tree
    /// gathers them into ([`dm_mesh::ReceiverDm::kept_regions`]): a joint
    /// umbra that discontinuities cut into many cells is proven at once
    /// where it can be, and cell by cell where it cannot. The regions in
    /// parallel: one receiver (a floor) may hold most of the cells.
    fn proven_dark(
        &self,
        receiver: &ReceiverDm<PieceId>,
        two_sided: bool,
        candidates: &SecondaryMap<FaceKey, (usize, u32)>,
        dark: &DarkContext<'_>,
    ) -> Vec<(usize, u32)> {
        let all = candidates.values().fold(0, |m, &(_, l)| m | l);
        let regions: Vec<(u32, Region)> = (0..u32::BITS)
            .map(|i| 1_u32 << i)
            .filter(|bit| all & bit != 0)
            .flat_map(|bit| {
                let keep =
                    |f: FaceKey, _: &Cell| candidates.get(f).is_some_and(|(_, l)| l & bit != 0);
                receiver
                    .kept_regions(keep, PROOF_REGION_CELLS)
                    .into_iter()
                    .map(move |region| (bit, region))
            })
            .collect();
        // The objects whose occluders the cells list.
        let objects_of = |faces: &[FaceKey]| -> Vec<u32> {
            let mut objects: Vec<u32> = faces
                .iter()
                .filter_map(|&f| receiver.mesh().face(f))
                .flat_map(|face| face.data.entries())
                .filter_map(|e| receiver.unit_source(e.unit))
                .filter_map(|(occluder, _)| self.dm.piece_object(occluder))
                .filter_map(|id| dark.object_of.get(id).copied())
                .collect();
            objects.sort_unstable();
            objects.dedup();
            objects
        };
        let proves = |region: &ConvexPolygon, bit: u32, faces: &[FaceKey]| {
            let objects = objects_of(faces);
            proven_dark_past(region, two_sided, bit, dark.areas, dark.occluders, &objects) != 0
        };
        regions
            .par_iter()
            .with_max_len(1)
            .flat_map_iter(|(bit, (region, faces))| {
                let dark_faces: Vec<FaceKey> = if proves(region, *bit, faces) {
                    faces.clone()
                } else if faces.len() == 1 {
                    Vec::new()
                } else {
                    faces
                        .iter()
                        .copied()
                        .filter(|&f| {
                            receiver
                                .mesh()
                                .face_polygon(f, 0)
                                .is_ok_and(|cell| proves(&cell, *bit, &[f]))
                        })
                        .collect()
                };
                dark_faces
                    .into_iter()
                    .filter_map(|f| candidates.get(f).map(|&(out, _)| (out, *bit)))
                    .collect::<Vec<_>>()
            })
            .collect()
    }

    fn figures(&self, build: f64, illum_seconds: f64, illum: &IllumStats, total: f64) -> DmStats {
        let lights = self.dm.lights();
        let mut light_stats: Vec<LightStats> = self
            .dm
            .light_node_counts()
            .into_iter()
            .map(|(penumbra, umbra)| LightStats {
                penumbra_nodes: Some(penumbra as u64),
                umbra_nodes: Some(umbra as u64),
                ..LightStats::default()
            })
            .collect();
        let (mut nodes, mut cells, mut receivers) = (0, 0, 0);
        for (_, dm) in self.dm.receivers() {
            receivers += 1;
            nodes += dm.node_count() as u64;
            cells += dm.cell_count() as u64;
            for (i, s) in light_stats.iter_mut().enumerate() {
                if lights[i].source().reaches_front_of(dm.polygon().support()) {
                    s.front_facing_polygons += 1;
                    s.front_facing_edges += dm.polygon().len() as u64;
                }
                for (_, cell) in dm.cells() {
                    match dm.class(cell, i) {
                        CellClass::Lit => s.lit += 1,
                        CellClass::Penumbra => s.penumbra += 1,
                        CellClass::Umbra => s.umbra += 1,
                    }
                }
            }
        }
        // In the scene's order (the point and directional lights' figures
        // come with the output).
        let mut in_scene = vec![LightStats::default(); self.light_map.len()];
        for (s, &i) in light_stats.into_iter().zip(&self.light_map.area) {
            in_scene[i] = s;
        }
        let light_stats = in_scene;
        let per = |n: usize| {
            if n == 0 {
                0.0
            } else {
                illum.comparisons as f64 / n as f64
            }
        };
        DmStats {
            stats: Stats {
                input_polygons: self.pieces.input_polygons as u64,
                dropped_polygons: self.pieces.dropped.clone(),
                output_fragments: cells,
                seconds: Seconds {
                    bsp: 0.0,
                    shadow: build,
                    grid: 0.0,
                    illum: illum_seconds,
                    total,
                },
                lights: light_stats,
            },
            dm: DmFigures {
                receivers,
                tree_nodes: nodes,
                cells,
                vertices: illum.vertices as u64,
                visibility_vertices: illum.visibility as u64,
                comparisons: illum.comparisons as u64,
                comparisons_per_vertex: per(illum.vertices),
                comparisons_per_visibility_vertex: per(illum.visibility),
                build_seconds: build,
                illum_seconds,
                output_seconds: 0.0,
            },
            update: None,
        }
    }

    /// Moves scene object `name` by `by` (world units) `steps` times, step
    /// `s` to `s * by` from its place rounded to whole grid cells, updating
    /// incrementally, then
    /// times a full rebuild of each step's state for comparison.
    /// `on_step(k, update, rebuild)` is called for each step once its
    /// rebuild is timed.
    ///
    /// The steps run one after another, as frames of an application would,
    /// and the rebuilds after all of them: a rebuild between two steps
    /// leaves gigabytes freed on the worker threads' heaps, which the
    /// allocator settles during the next step's allocations (on the 10k
    /// hall that made a box's move 70-130 ms instead of 17-23 ms).
    pub fn move_steps(
        &mut self,
        scene: &Scene,
        name: &str,
        by: [f64; 3],
        steps: u32,
        mut on_step: impl FnMut(u32, f64, f64),
    ) -> Result<UpdateFigures> {
        let field = |message: String| Error::Field {
            path: scene.path.clone(),
            field: "--move".into(),
            message,
        };
        let index = scene
            .objects
            .iter()
            .position(|o| o.name == name)
            .ok_or_else(|| field(format!("no object is named `{name}`")))?;
        let grid = self.pieces.grid;
        let (id, ks) = self.objects[index].clone();
        let original: Vec<ConvexPolygon> = ks
            .iter()
            .map(|&k| self.pieces.polygons[k].clone())
            .collect();
        let mut figures = UpdateFigures {
            object: name.to_string(),
            object_fraction: ks.len() as f64 / self.pieces.polygons.len().max(1) as f64,
            ..UpdateFigures::default()
        };
        let mut states = Vec::with_capacity(steps as usize);
        for s in 1..=steps {
            // The whole way so far, rounded once: after `s` steps the
            // object is where a scene file `s * by` away puts it, not `s`
            // rounded steps away.
            let offset = by.map(|x| grid.length_to_units(x * f64::from(s)).round() as i64);
            let moved = original
                .iter()
                .map(|p| p.translated(offset))
                .collect::<std::result::Result<Vec<_>, _>>()
                .map_err(|_| field(format!("step {s} moves `{name}` off the scene's grid")))?;
            let since = self.dm.revision();
            let started = Instant::now();
            self.dm
                .move_object(id, moved.clone())
                .map_err(|e| field(e.to_string()))?;
            let illum = self.dm.illuminate();
            figures.update_seconds.push(started.elapsed().as_secs_f64());
            figures.reilluminated_vertices.push(illum.evaluated as u64);
            let changed = self.dm.receivers_changed_since(since).count();
            figures.changed_receivers.push(changed as u64);
            states.push(moved);
        }
        // The input polygons went `steps * by`, their pieces as rounded.
        let way = by.map(|x| x * f64::from(steps));
        let offset = way.map(|x| grid.length_to_units(x).round() as i64);
        let mut sources: Vec<u32> = ks.iter().map(|&k| self.pieces.input_of[k]).collect();
        sources.dedup();
        for source in sources {
            self.pieces.frames.translate(source, offset, way);
        }
        for (s, moved) in (1..=steps).zip(states) {
            for (&k, p) in ks.iter().zip(moved) {
                self.pieces.polygons[k] = p;
            }
            let rebuild = self.rebuild_seconds()?;
            on_step(s, figures.update_seconds[s as usize - 1], rebuild);
            figures.rebuild_seconds.push(rebuild);
        }
        Ok(figures)
    }

    /// Seconds a from-scratch build and illumination of the current state
    /// takes.
    fn rebuild_seconds(&self) -> Result<f64> {
        let started = Instant::now();
        drop(self.fresh_dm()?);
        Ok(started.elapsed().as_secs_f64())
    }

    /// A from-scratch build and illumination of the current state (the
    /// objects where the updates left them), with the same objects, pieces
    /// and options: what the incremental updates must agree with.
    pub fn rebuilt(&self) -> Result<DmRun> {
        let started = Instant::now();
        let fresh = self.fresh_dm()?;
        let groups = self.objects.iter().map(|(_, ks)| ks.clone()).collect();
        Ok(DmRun::assemble(
            self.pieces.clone(),
            fresh,
            groups,
            self.light_map.clone(),
            self.facing_inside.clone(),
            started,
        ))
    }

    /// The DM-trees of the current state built and illuminated from
    /// scratch.
    fn fresh_dm(&self) -> Result<FreshDm> {
        let objects: Vec<(Vec<ConvexPolygon>, PieceFlags)> = self
            .objects
            .iter()
            .map(|(id, ks)| {
                let flags = self
                    .dm
                    .object_pieces(*id)
                    .and_then(|ps| ps.first())
                    .and_then(|p| self.dm.piece_flags(*p))
                    .unwrap_or_default();
                (
                    ks.iter()
                        .map(|&k| self.pieces.polygons[k].clone())
                        .collect(),
                    flags,
                )
            })
            .collect();
        let normals = normals_of(&self.pieces, self.objects.iter().map(|(_, ks)| ks));
        let movable: Vec<usize> = (self.objects.iter().enumerate())
            .filter(|(_, (id, _))| self.dm.is_movable(*id))
            .map(|(k, _)| k)
            .collect();
        FreshDm::build(
            self.dm.lights().to_vec(),
            objects,
            &movable,
            &normals,
            self.dm.options(),
        )
    }

    /// Recomputes the figures after updates (timings of the build kept).
    pub fn refresh_figures(&mut self) {
        let s = self.stats.dm.clone();
        let illum = IllumStats {
            vertices: s.vertices as usize,
            evaluated: s.vertices as usize,
            visibility: s.visibility_vertices as usize,
            comparisons: s.comparisons as usize,
            ..IllumStats::default()
        };
        let update = self.stats.update.take();
        self.stats = self.figures(
            s.build_seconds,
            s.illum_seconds,
            &illum,
            self.stats.stats.seconds.total,
        );
        self.stats.update = update;
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
