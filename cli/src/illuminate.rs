//! Direct illumination of the conforming mesh's vertices, each light by
//! its own rule: point and directional lights in closed form, area lights
//! by Lambert's contour integral over the whole light (lit) or its visible
//! part (penumbra), with the 1992 paper's vertex-sharing rules.

use std::collections::HashMap;

use smallvec::SmallVec;

use area_shadow::{Class, ConformingMesh, MeshPoint};
use bsp_core::{ConvexPolygon, Grid, Side};
use illum::rayon::prelude::*;
use illum::{FragmentClass, OccluderIndex, Sidedness, VertexPlan, VisiblePart, vertex_plan};
use svbsp::Fragment;

use crate::decompose::Pieces;

/// A light as `illum` evaluates it.
#[derive(Debug, Clone)]
pub enum IllumLight {
    /// A point light, in world units.
    Point(illum::PointLight),
    /// A directional light.
    Directional(illum::DirectionalLight),
    /// An area light, in grid units (irradiance from a polygon does not
    /// change with the scale).
    Area(illum::AreaLight),
}

/// Everything illumination needs about the scene.
pub struct Illuminator<'a> {
    /// The lights, in scene order.
    pub lights: &'a [IllumLight],
    /// The pieces (grid units); fragment sources index them.
    pub pieces: &'a [ConvexPolygon],
    /// Per piece, the unit normal light falls on (its input polygon's).
    pub normals: &'a [[f64; 3]],
    /// Per piece: whether it receives on both sides.
    pub two_sided: &'a [bool],
    /// The grid, for world coordinates.
    pub grid: &'a Grid,
    /// The shadow-casting pieces' outlines (grid units), to find the
    /// occluders between a point and an area light (empty when there is no
    /// area light).
    occluders: OccluderIndex,
    /// The piece of each outline.
    occluder_pieces: Vec<usize>,
}

impl<'a> Illuminator<'a> {
    /// Sets up illumination of `pieces` under `lights`; indexes the
    /// occluders when some light is an area light.
    pub fn new(lights: &'a [IllumLight], pieces: &'a Pieces) -> Self {
        let any_area = lights.iter().any(|l| matches!(l, IllumLight::Area(_)));
        let occluder_pieces: Vec<usize> = if any_area {
            (0..pieces.polygons.len())
                .filter(|&k| pieces.casts_shadows[k])
                .collect()
        } else {
            Vec::new()
        };
        let occluders = OccluderIndex::new(
            occluder_pieces
                .iter()
                .map(|&k| pieces.polygons[k].vertices_f64())
                .collect(),
        );
        Self {
            lights,
            pieces: &pieces.polygons,
            normals: &pieces.normals,
            two_sided: &pieces.two_sided,
            grid: &pieces.grid,
            occluders,
            occluder_pieces,
        }
    }

    fn sidedness(&self, piece: usize) -> Sidedness {
        if self.two_sided[piece] {
            Sidedness::TwoSided
        } else {
            Sidedness::OneSided
        }
    }

    /// Irradiance from light `i` at the point `at` (grid coordinates `p`)
    /// on piece `piece`, as `value` asks.
    fn value(&self, i: usize, value: Value, at: (&MeshPoint, [f64; 3]), piece: usize) -> f64 {
        let (exact, p) = at;
        let normal = self.normals[piece];
        let sidedness = self.sidedness(piece);
        match (&self.lights[i], value) {
            (_, Value::Zero) => 0.0,
            (IllumLight::Point(l), _) => {
                l.irradiance(self.grid.grid_to_world(p), normal, sidedness)
            }
            (IllumLight::Directional(l), _) => l.irradiance(normal, sidedness),
            (IllumLight::Area(l), Value::Whole) => l.irradiance(p, normal, sidedness),
            (IllumLight::Area(l), Value::Visible) => {
                let occluders = self.occluders(exact, p, l);
                let mut part = VisiblePart::new();
                part.compute(l, &occluders, p);
                part.irradiance(l, p, normal, sidedness)
            }
        }
    }

    /// Outlines of the shadow-casting polygons that may lie between the
    /// point `exact` (grid coordinates `p`) and `light`, except those whose
    /// plane holds the point (exactly): from there a polygon hides nothing
    /// of positive area (the receiver's own plane; a bent quad's other
    /// triangle, from their common edge), and in floating point the
    /// point's rounding error off the plane made the blocked region from a
    /// point on the polygon's edge the whole light.
    fn occluders(
        &self,
        exact: &MeshPoint,
        p: [f64; 3],
        light: &illum::AreaLight,
    ) -> Vec<&[[f64; 3]]> {
        let mut candidates = Vec::new();
        self.occluders.candidates_between(p, light, &mut candidates);
        candidates
            .into_iter()
            .map(|k| k as usize)
            .filter(|&k| exact.side(self.pieces[self.occluder_pieces[k]].support()) != Side::On)
            .map(|k| self.occluders.outlines()[k].as_slice())
            .collect()
    }

    /// Irradiance at each vertex of `polygon` (a part of piece
    /// `polygon.source()`) from area light `i` past the occluders, and
    /// what all of the light would give there, computed as iterated.
    pub fn corner_irradiance(
        &self,
        i: usize,
        polygon: &ConvexPolygon,
    ) -> impl Iterator<Item = (f64, f64)> {
        let piece = polygon.source() as usize;
        polygon
            .vertices_f64()
            .into_iter()
            .enumerate()
            .map(move |(k, p)| {
                let exact = MeshPoint::vertex(polygon, k);
                (
                    self.value(i, Value::Visible, (&exact, p), piece),
                    self.value(i, Value::Whole, (&exact, p), piece),
                )
            })
    }

    /// Irradiance at every vertex of `fragment` from each light by its
    /// class (no sharing: for adaptive subdivision), summed over lights.
    pub fn fragment_irradiance(&self, fragment: &Fragment) -> Vec<f64> {
        let piece = fragment.polygon.source() as usize;
        let polygon = &fragment.polygon;
        polygon
            .vertices_f64()
            .into_iter()
            .enumerate()
            .map(|(k, p)| {
                let exact = MeshPoint::vertex(polygon, k);
                (0..self.lights.len())
                    .map(|i| {
                        let value = match Class::of(fragment, i as u32) {
                            Class::Lit => Value::Whole,
                            Class::Penumbra => Value::Visible,
                            Class::Umbra => Value::Zero,
                        };
                        self.value(i, value, (&exact, p), piece)
                    })
                    .sum()
            })
            .collect()
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Value {
    Whole,
    Visible,
    Zero,
}

/// The illuminated mesh: output vertices (grid units) with per-light
/// irradiance, faces as indices into them.
pub struct Illuminated {
    /// Grid coordinates of each output vertex.
    pub coords: Vec<[f64; 3]>,
    /// Per output vertex, one value per light (vertex `v`'s values are
    /// `per_light[v * lights..(v + 1) * lights]`).
    pub per_light: Vec<f64>,
    /// Per fragment, its output vertex indices.
    pub faces: Vec<Vec<u32>>,
    /// Per light: mesh points evaluated whole (lit), from their visible
    /// part (penumbra), and given zero (umbra); a point shared by lit and
    /// umbra fragments counts as lit and umbra.
    pub vertex_classes: Vec<[u64; 3]>,
}

/// Illuminates the conforming mesh of `fragments`: each distinct point of
/// each receiving plane once per light, with the sharing rules deciding
/// what is evaluated; a vertex shared by lit and umbra fragments keeps a
/// value for each side.
///
/// The bookkeeping is in flat arrays (corners and fragments around a group
/// as offsets into one list) so that the serial part stays small beside
/// the parallel evaluation.
pub fn illuminate(
    illuminator: &Illuminator<'_>,
    fragments: &[Fragment],
    mesh: &ConformingMesh,
) -> Illuminated {
    let lights = illuminator.lights.len();
    // Groups: a point on one receiving plane (its normal and sidedness
    // decide its irradiance), with the fragments around it.
    // Per point, the groups on it: (plane id, group); nearly always one.
    let mut groups_at: Vec<SmallVec<[(usize, usize); 1]>> =
        vec![SmallVec::new(); mesh.points.len()];
    let mut plane_key: HashMap<([i64; 3], i128, bool), usize> = HashMap::new();
    let mut plane_of_piece: Vec<Option<usize>> = vec![None; illuminator.pieces.len()];
    let mut groups: Vec<(u32, usize)> = Vec::new();
    // Fragment f's corners' groups: corners[corner_start[f]..corner_start[f + 1]].
    let mut corner_start: Vec<usize> = Vec::with_capacity(fragments.len() + 1);
    let mut corners: Vec<usize> = Vec::with_capacity(4 * fragments.len());
    for (f, face) in fragments.iter().zip(&mesh.faces) {
        let piece = f.polygon.source() as usize;
        let plane = *plane_of_piece[piece].get_or_insert_with(|| {
            let support = f.polygon.support();
            let planes = plane_key.len();
            *plane_key
                .entry((
                    support.normal(),
                    support.offset(),
                    illuminator.two_sided[piece],
                ))
                .or_insert(planes)
        });
        corner_start.push(corners.len());
        for &point in face {
            let at = &mut groups_at[point as usize];
            let g = match at.iter().find(|(p, _)| *p == plane) {
                Some(&(_, g)) => g,
                None => {
                    let g = groups.len();
                    groups.push((point, piece));
                    at.push((plane, g));
                    g
                }
            };
            corners.push(g);
        }
    }
    corner_start.push(corners.len());
    let corners_of = |f: usize| &corners[corner_start[f]..corner_start[f + 1]];
    // Fragments around each group: around[around_start[g]..around_start[g + 1]].
    let mut around_start = vec![0_usize; groups.len() + 1];
    for &g in &corners {
        around_start[g + 1] += 1;
    }
    for g in 0..groups.len() {
        around_start[g + 1] += around_start[g];
    }
    let mut around = vec![0_usize; corners.len()];
    let mut filled = around_start.clone();
    for f in 0..fragments.len() {
        for &g in corners_of(f) {
            around[filled[g]] = f;
            filled[g] += 1;
        }
    }
    // Plans and values, in parallel (each group's depend only on its own
    // inputs, so results do not depend on the thread count). A fragment
    // listed twice around a group (a repeated corner) changes no plan.
    let (plans, values): (Vec<VertexPlan>, Vec<f64>) = (0..groups.len())
        .into_par_iter()
        .with_min_len(64)
        .flat_map_iter(|g| {
            let fs = &around[around_start[g]..around_start[g + 1]];
            let (point, piece) = groups[g];
            let at = (&mesh.points[point as usize], mesh.coords[point as usize]);
            (0..lights).map(move |i| {
                let plan = vertex_plan(
                    fs.iter()
                        .map(|&f| to_illum(Class::of(&fragments[f], i as u32))),
                )
                .expect("a group has a fragment");
                let value = match plan {
                    VertexPlan::Zero => 0.0,
                    VertexPlan::VisiblePart => illuminator.value(i, Value::Visible, at, piece),
                    VertexPlan::Unoccluded | VertexPlan::Split => {
                        illuminator.value(i, Value::Whole, at, piece)
                    }
                };
                (plan, value)
            })
        })
        .unzip();
    let mut vertex_classes = vec![[0_u64; 3]; lights];
    for (k, plan) in plans.iter().enumerate() {
        let i = k % lights.max(1);
        match plan {
            VertexPlan::Unoccluded => vertex_classes[i][0] += 1,
            VertexPlan::VisiblePart => vertex_classes[i][1] += 1,
            VertexPlan::Zero => vertex_classes[i][2] += 1,
            VertexPlan::Split => {
                vertex_classes[i][0] += 1;
                vertex_classes[i][2] += 1;
            }
        }
    }
    // Output vertices: one per group and per set of lights that a Split
    // plan zeroes for the fragment at hand.
    let mut out = Illuminated {
        coords: Vec::with_capacity(groups.len()),
        per_light: Vec::with_capacity(groups.len() * lights),
        faces: Vec::with_capacity(fragments.len()),
        vertex_classes,
    };
    // Per group, its output vertices by the lights a Split plan zeroes.
    let mut vertex_of: Vec<SmallVec<[(u32, u32); 1]>> = vec![SmallVec::new(); groups.len()];
    for (f, fragment) in fragments.iter().enumerate() {
        let mut face = Vec::with_capacity(corners_of(f).len());
        for &g in corners_of(f) {
            let zeroed = (0..lights)
                .filter(|&i| {
                    plans[g * lights + i] == VertexPlan::Split
                        && Class::of(fragment, i as u32) == Class::Umbra
                })
                .fold(0_u32, |m, i| m | (1 << i));
            let next = out.coords.len() as u32;
            let v = match vertex_of[g].iter().find(|(z, _)| *z == zeroed) {
                Some(&(_, v)) => v,
                None => {
                    vertex_of[g].push((zeroed, next));
                    next
                }
            };
            if v == next {
                out.coords.push(mesh.coords[groups[g].0 as usize]);
                out.per_light.extend((0..lights).map(|i| {
                    if zeroed & (1 << i) != 0 {
                        0.0
                    } else {
                        values[g * lights + i]
                    }
                }));
            }
            face.push(v);
        }
        out.faces.push(face);
    }
    out
}

fn to_illum(class: Class) -> FragmentClass {
    match class {
        Class::Lit => FragmentClass::Lit,
        Class::Penumbra => FragmentClass::Penumbra,
        Class::Umbra => FragmentClass::Umbra,
    }
}
