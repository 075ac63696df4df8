//! Making the output mesh of a [`DmRun`]: one face per DM cell, the cells
//! in a joint umbra proven dark on the way.

use std::time::Instant;

use area_shadow::{AreaSource, ShadowGroups};
use bsp_core::{ConvexPolygon, FaceKey, VertexKey};
use dm_mesh::{Cell, CellClass, ObjectId, PieceId, ReceiverDm, Region};
use rayon::prelude::*;
use slotmap::SecondaryMap;
use svbsp::{Fragment, PieceFlags};

use super::{DmRun, DmStats};
use crate::dark::{Occluders, proven_dark_past};
use crate::dm_lights::cut_by_other_lights;
use crate::error::Result;
use crate::mesh::{OutputFace, OutputMesh, irradiance_f32};
use crate::stats::LightStats;

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

impl DmRun {
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
}
