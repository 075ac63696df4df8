//! `umbra update`: a [`DmRun`]'s object moved step by step, each step
//! timed against a full rebuild.

use std::time::Instant;

use bsp_core::ConvexPolygon;
use serde::Serialize;
use svbsp::PieceFlags;

use super::{DmRun, FreshDm, normals_of};
use crate::error::{Error, Result};
use crate::scene::Scene;

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
    /// drawing the cells reads again
    /// ([`DmScene::receivers_changed_since`](dm_mesh::DmScene::receivers_changed_since)).
    pub changed_receivers: Vec<u64>,
}

impl DmRun {
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
}
