//! Bergeron's general shadow volumes (1986): depth-counted shadow polygons
//! for open and closed models, non-planar polygons, an eye anywhere and
//! lights with a sphere of influence.
//!
//! For one light, [`BergeronVolumes::build`] turns every shadow-casting
//! [`Model`] into shadow polygons. A point is in shadow when it lies in the
//! shadow frustum of some model polygon (beyond it from the light, inside
//! the cone of rays through it); the *depth count* of a point is the number
//! of such frusta, and along any segment that crosses no model polygon it
//! changes only where the segment crosses the frusta's side walls and far
//! caps. Summed over a model, the side walls of two polygons that share an
//! edge cancel when both face the light the same way, and add up when one
//! faces it and the other does not: what is left are the **contour edges**,
//! each with Bergeron's increment `Nb_C` ([`ShadowPolygon::weight`]) of `±2`
//! for an edge shared by two polygons and `±1` for an open edge (an edge of
//! one polygon only). Closed and open models need no distinction.
//!
//! - **Non-planar polygons.** A non-planar model polygon comes as convex
//!   planar pieces (its triangulation) and its outline. If it is L-twisted
//!   ([`is_l_twisted`]: seen from the light, two of its edges cross) it gets
//!   a shadow volume and a depth count of its own, and a point is in its
//!   shadow when that count is positive: the in-shadow flag of the (light,
//!   polygon) pair.
//! - **The eye inside a shadow volume.** Counting along an eye ray needs
//!   the count at the eye. [`BergeronVolumes::eye_counts`] closes every
//!   frustum with its model polygon and, when the volumes are truncated, a
//!   projected capping copy of it, and counts the closed frusta around the
//!   eye. In Bergeron's three cases: outside every volume (Type 1) the
//!   count is 0; inside the volume of a closed model (Type 2) it grows by 2
//!   per model, a polygon facing the light and one facing away both lying
//!   between the eye and the light; inside the volume of an open model
//!   (Type 3) by the number of its sheets between the eye and the light,
//!   often 1 ([`BergeronVolumes::eye_cases`] tells them apart). The count
//!   then follows the eye ray: [`BergeronVolumes::in_shadow`].
//! - **Sphere of influence.** A model whose bounding box is wholly beyond a
//!   point light's range casts nothing. The others' shadow polygons end at
//!   Bergeron's projection `V + ((range - 1) / SD) (V - L)` of each contour
//!   vertex `V`, `SD` the distance from the light to the model's bounding
//!   box (to its nearest piece if the light is inside the box): every point
//!   in range lies before that end. The ratio is rounded up to an integer
//!   (and kept at least `range / SD`, which it is whenever `SD` is a grid
//!   unit or more) so that the far corners are exact, and the volumes are
//!   closed there by caps. Without a range, or when the ratio would exceed
//!   [`MAX_PROJECTION_RATIO`], a side polygon is unbounded: the contour edge
//!   and the two rays from the light through its ends
//!   ([`ShadowPolygon::closed`] is false).
//!
//! Coordinates are grid units. Every decision (which side of a shadow
//! polygon a point lies on, whether a segment crosses it, whether a
//! polygon is twisted) is an exact orientation of explicit points
//! ([`orient3d_f64`]); the eye and the visible points
//! given to the queries are `f64`, decided exactly as given.
//!
//! # Example
//!
//! ```
//! use bsp_core::{ConvexPolygon, GridPoint};
//! use svbsp::bergeron::{BergeronVolumes, EyeCase, Model, ModelPolygon};
//! use svbsp::Light;
//!
//! let g = |x, y, z| GridPoint { x, y, z };
//! // An open model: one square at y = 5 under a light at y = 10.
//! let square = [g(-2, 5, 2), g(2, 5, 2), g(2, 5, -2), g(-2, 5, -2)];
//! let model = Model {
//!     polygons: vec![ModelPolygon {
//!         boundary: square.to_vec(),
//!         pieces: vec![ConvexPolygon::from_grid_points(&square, 0).unwrap()],
//!     }],
//! };
//! let volumes = BergeronVolumes::build(&[model], &Light::point(g(0, 10, 0)), None).unwrap();
//! // Four open contour edges, each with an increment of 1.
//! assert_eq!(volumes.stats().open_edges, 4);
//! // The eye beside the square, outside the shadow; the floor under the
//! // square is in shadow, the floor farther out is lit.
//! let eye = [0.0, 5.0, 15.0];
//! let start = volumes.eye_counts(eye);
//! assert_eq!(start, vec![0]);
//! assert!(volumes.in_shadow(eye, &start, [1.0, 0.0, 1.0]));
//! assert!(!volumes.in_shadow(eye, &start, [6.0, 0.0, 1.0]));
//! // The eye under the square is inside its volume (Type 3): it starts at 1.
//! assert_eq!(volumes.eye_counts([0.0, 1.0, 0.0]), vec![1]);
//! assert_eq!(volumes.eye_cases([0.0, 1.0, 0.0]), vec![EyeCase::InOpenModel { depth: 1 }]);
//! ```

mod apex;
mod crossing;
mod twist;

use std::collections::BTreeMap;

use bsp_core::predicates::{Side, orient3d_f64};
use bsp_core::{ConvexPolygon, GridPoint};

pub use crossing::ShadowPolygon;
pub use twist::is_l_twisted;

use crate::{Error, Light};
use apex::{Apex, f};

/// Largest ratio by which a contour vertex is pushed away from the light:
/// far corners stay exact in `f64` (grid coordinates below `2^25` times
/// `2^26`).
pub const MAX_PROJECTION_RATIO: f64 = (1u64 << 26) as f64;

/// A shadow-casting model: an object of the scene, open or closed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Model {
    /// Its polygons.
    pub polygons: Vec<ModelPolygon>,
}

/// One polygon of a model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelPolygon {
    /// Its corners as given (grid points), planar or not; used to find
    /// L-twisted polygons.
    pub boundary: Vec<GridPoint>,
    /// Convex planar pieces that tile it (its triangulation if it is not
    /// planar), with grid-point vertices.
    pub pieces: Vec<ConvexPolygon>,
}

/// Figures of one light's volumes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct VolumeStats {
    /// Contour edges shared by two polygons (`Nb_C = ±2`, or more where
    /// more polygons meet).
    pub shared_edges: usize,
    /// Open contour edges (`Nb_C = ±1`).
    pub open_edges: usize,
    /// L-twisted polygons, each with its own volume and count.
    pub twisted_polygons: usize,
    /// Models wholly beyond the light's range, left out.
    pub models_beyond_range: usize,
    /// Far caps (volumes truncated by a range).
    pub caps: usize,
}

/// An edge of a model's pieces: the counter it adds to and its corners,
/// smaller first.
type EdgeKey = (u32, [i64; 3], [i64; 3]);

/// A model polygon's piece as the eye count needs it.
#[derive(Debug, Clone, PartialEq)]
struct Piece {
    vertices: Vec<[f64; 3]>,
    cap: Option<Vec<[f64; 3]>>,
    counter: u32,
    model: u32,
}

/// Where the eye is for one model: Bergeron's three cases.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EyeCase {
    /// Type 1: in none of the model's shadow volumes; it adds nothing to
    /// the starting count.
    Outside,
    /// Type 2: in the shadow volume of a closed model; it adds `depth` (2
    /// for a convex model, a polygon facing the light and one facing away
    /// lying between the eye and the light; more for a model folded on
    /// itself).
    InClosedModel {
        /// What the model adds to the starting count.
        depth: i32,
    },
    /// Type 3: in the shadow volume of an open model; it adds `depth`, the
    /// number of its sheets between the eye and the light.
    InOpenModel {
        /// What the model adds to the starting count.
        depth: i32,
    },
}

/// The shadow volumes of a set of models under one light, ready to count
/// along eye rays. See the [module documentation](self).
#[derive(Debug, Clone, PartialEq)]
pub struct BergeronVolumes {
    apex: Apex,
    polygons: Vec<ShadowPolygon>,
    pieces: Vec<Piece>,
    /// Per model given to `build`: whether it is closed (false if left out).
    closed: Vec<bool>,
    counters: usize,
    stats: VolumeStats,
}

impl BergeronVolumes {
    /// The shadow volumes of `models` under `light` (grid units).
    ///
    /// `reach` is the distance from a point light up to
    /// which counts must be exact when the light has a range: at least the
    /// range (smaller values count as the range). A renderer passes the
    /// farthest point of any polygon that straddles the sphere, so that such
    /// a polygon is classified by visibility all over.
    ///
    /// # Errors
    ///
    /// [`Error::ImplicitInput`] if a piece has a vertex that is not a grid
    /// point (the index counts pieces over all models, in order).
    pub fn build(models: &[Model], light: &Light, reach: Option<f64>) -> Result<Self, Error> {
        let apex = Apex::of(&light.source);
        let mut out = Self {
            apex,
            polygons: Vec::new(),
            pieces: Vec::new(),
            closed: vec![false; models.len()],
            counters: 1,
            stats: VolumeStats::default(),
        };
        let mut piece_index = 0;
        for (index, model) in models.iter().enumerate() {
            // Grid-point corners of every polygon's pieces.
            let mut corners: Vec<Vec<Vec<[f64; 3]>>> = Vec::with_capacity(model.polygons.len());
            for polygon in &model.polygons {
                let mut of_polygon = Vec::with_capacity(polygon.pieces.len());
                for piece in &polygon.pieces {
                    let grid = piece
                        .grid_corners()
                        .ok_or(Error::ImplicitInput(piece_index))?;
                    piece_index += 1;
                    of_polygon.push(grid.into_iter().map(f).collect());
                }
                corners.push(of_polygon);
            }
            let Some(model_box) = bounding_box(corners.iter().flatten().flatten()) else {
                continue;
            };
            if let (Apex::Point(l), Some(range)) = (apex, light.range)
                && distance_to_box(l, model_box) >= range
            {
                out.stats.models_beyond_range += 1;
                continue;
            }
            // Which count each piece adds to: its own for an L-twisted
            // polygon.
            let mut pieces: Vec<(Vec<[f64; 3]>, u32)> = Vec::new();
            for (polygon, of_polygon) in model.polygons.iter().zip(corners) {
                let counter = if is_l_twisted(&polygon.boundary, &light.source) {
                    out.stats.twisted_polygons += 1;
                    out.counters += 1;
                    (out.counters - 1) as u32
                } else {
                    0
                };
                pieces.extend(of_polygon.into_iter().map(|v| (v, counter)));
            }
            out.closed[index] = is_closed(&pieces);
            out.add_model(&pieces, index as u32, model_box, light, reach);
        }
        Ok(out)
    }

    fn add_model(
        &mut self,
        pieces: &[(Vec<[f64; 3]>, u32)],
        model: u32,
        model_box: [[f64; 3]; 2],
        light: &Light,
        reach: Option<f64>,
    ) {
        let apex = self.apex;
        // Nb_C of every edge, canonically directed (smaller corner first):
        // crossing the plane through the light and the edge from the back
        // of orient3d(L, a, b, .) to its front adds the weight.
        let mut edges: BTreeMap<EdgeKey, i32> = BTreeMap::new();
        let key = |v: [f64; 3]| v.map(|c| c as i64);
        let mut casting = Vec::new();
        for (v, counter) in pieces {
            let light_side = orient3d_f64(v[0], v[1], v[2], apex.beside(v[0]));
            if light_side == Side::On {
                continue; // edge-on to the light: an empty frustum
            }
            let inside = orient3d_f64(apex.beside(v[0]), v[0], v[1], v[2]);
            let inside_front = inside == Side::Front;
            for i in 0..v.len() {
                let (a, b) = (key(v[i]), key(v[(i + 1) % v.len()]));
                let (lo, hi, reversed) = if a < b { (a, b, false) } else { (b, a, true) };
                *edges.entry((*counter, lo, hi)).or_insert(0) +=
                    if inside_front != reversed { 1 } else { -1 };
            }
            casting.push((v, *counter));
        }
        let contour: Vec<(EdgeKey, i32)> = edges.into_iter().filter(|&(_, w)| w != 0).collect();

        // With a range, the volumes end at Bergeron's projection of every
        // vertex, ratio 1 + (R - 1) / SD (never less than R / SD, which
        // reaches R from the nearest point), rounded up to an integer so
        // that far corners are exact; a ratio beyond MAX_PROJECTION_RATIO
        // leaves the volumes unbounded. Without a range they are unbounded.
        let to_f = |k: [i64; 3]| k.map(|c| c as f64);
        let ratio = match (apex, light.range) {
            (Apex::Point(l), Some(range)) => {
                // Bergeron's SD: the distance from the light to the model's
                // bounding box or, from inside the box, to its nearest
                // casting piece (none holds the light: those were skipped).
                let sd = if distance_to_box(l, model_box) > 0.0 {
                    distance_to_box(l, model_box)
                } else {
                    casting
                        .iter()
                        .map(|(v, _)| crate::light::distance_to_polygon(l, v))
                        .fold(f64::INFINITY, f64::min)
                };
                // SD comes from f64 distances: a relative slack far above
                // their rounding keeps the ratio on the long side. (Sizing
                // only; an infinite or NaN ratio leaves the volumes
                // unbounded.)
                let r = reach.map_or(range, |x| x.max(range)) * (1.0 + 1e-9);
                let m = (1.0 + (r - 1.0) / sd).max(r / sd).ceil().max(2.0);
                (m <= MAX_PROJECTION_RATIO).then_some(m)
            }
            _ => None,
        };

        for ((counter, a, b), w) in contour {
            let (a, b) = (to_f(a), to_f(b));
            if w.abs() == 1 {
                self.stats.open_edges += 1;
            } else {
                self.stats.shared_edges += 1;
            }
            // [a', a, b, b'] turns the other way from (L, a, b) around the
            // plane: orient3d(a', a, b, x) = -(m - 1) orient3d(L, a, b, x)
            // with a' = L + m (a - L) (and likewise for a direction), so the
            // increment changes sign.
            let (vertices, closed) = match ratio {
                Some(m) => (vec![apex.far(a, m), a, b, apex.far(b, m)], true),
                None => (vec![apex.far(a, 2.0), a, b, apex.far(b, 2.0)], false),
            };
            self.polygons.push(ShadowPolygon {
                vertices,
                closed,
                weight: -w,
                counter,
            });
        }
        for (v, counter) in casting {
            let cap = ratio.map(|m| v.iter().map(|&p| apex.far(p, m)).collect::<Vec<_>>());
            if let Some(c) = &cap {
                // Crossing a cap away from the light leaves the frustum.
                let light_side = orient3d_f64(c[0], c[1], c[2], apex.beside(c[0]));
                self.polygons.push(ShadowPolygon {
                    vertices: c.clone(),
                    closed: true,
                    weight: if light_side == Side::Back { -1 } else { 1 },
                    counter,
                });
                self.stats.caps += 1;
            }
            self.pieces.push(Piece {
                vertices: v.clone(),
                cap,
                counter,
                model,
            });
        }
    }

    /// The shadow polygons: contour edges' side polygons and, with a range,
    /// far caps.
    pub fn shadow_polygons(&self) -> &[ShadowPolygon] {
        &self.polygons
    }

    /// Number of depth counts: 1 (the models') plus one per L-twisted
    /// polygon.
    pub fn counters(&self) -> usize {
        self.counters
    }

    /// Figures of these volumes.
    pub fn stats(&self) -> VolumeStats {
        self.stats
    }

    /// The depth counts at `eye` (one per counter): for every model polygon
    /// piece, whether the eye lies strictly inside its frustum closed by the
    /// piece and its cap.
    pub fn eye_counts(&self, eye: [f64; 3]) -> Vec<i32> {
        let mut counts = vec![0; self.counters];
        for piece in &self.pieces {
            if crossing::in_frustum(&self.apex, &piece.vertices, piece.cap.as_deref(), eye) {
                counts[piece.counter as usize] += 1;
            }
        }
        counts
    }

    /// Bergeron's case (Type 1, 2 or 3) of `eye` for every model given to
    /// [`Self::build`], in order; a model left out (beyond the range) is
    /// [`EyeCase::Outside`]. The depths add up to the sum of
    /// [`Self::eye_counts`].
    pub fn eye_cases(&self, eye: [f64; 3]) -> Vec<EyeCase> {
        let mut depth = vec![0; self.closed.len()];
        for piece in &self.pieces {
            if crossing::in_frustum(&self.apex, &piece.vertices, piece.cap.as_deref(), eye) {
                depth[piece.model as usize] += 1;
            }
        }
        depth
            .iter()
            .zip(&self.closed)
            .map(|(&depth, &closed)| match (depth, closed) {
                (0, _) => EyeCase::Outside,
                (depth, true) => EyeCase::InClosedModel { depth },
                (depth, false) => EyeCase::InOpenModel { depth },
            })
            .collect()
    }

    /// Whether `p`, seen from `eye` with depth counts `eye_counts`
    /// ([`Self::eye_counts`]), is in shadow: some count is positive once
    /// every shadow polygon the segment crosses has added its increment.
    /// The segment must cross no model polygon (`p` is what the eye sees).
    pub fn in_shadow(&self, eye: [f64; 3], eye_counts: &[i32], p: [f64; 3]) -> bool {
        let mut counts = eye_counts.to_vec();
        for polygon in &self.polygons {
            counts[polygon.counter as usize] += polygon.crossing(eye, p);
        }
        is_shadowed(&counts)
    }
}

/// Whether pieces (corners as exact grid coordinates) close a surface:
/// every edge between two corners is used exactly once in each direction.
fn is_closed(pieces: &[(Vec<[f64; 3]>, u32)]) -> bool {
    let key = |v: [f64; 3]| v.map(|c| c as i64);
    let mut directed: BTreeMap<([i64; 3], [i64; 3]), u32> = BTreeMap::new();
    for (v, _) in pieces {
        for i in 0..v.len() {
            *directed
                .entry((key(v[i]), key(v[(i + 1) % v.len()])))
                .or_insert(0) += 1;
        }
    }
    directed
        .iter()
        .all(|(&(a, b), &n)| n == 1 && directed.get(&(b, a)) == Some(&1))
}

/// Whether depth counts mean shadow: the models' count or an L-twisted
/// polygon's own count is positive.
pub fn is_shadowed(counts: &[i32]) -> bool {
    counts.iter().any(|&c| c > 0)
}

fn bounding_box<'a>(points: impl Iterator<Item = &'a [f64; 3]>) -> Option<[[f64; 3]; 2]> {
    let mut b: Option<[[f64; 3]; 2]> = None;
    for p in points {
        let [lo, hi] = b.get_or_insert([*p, *p]);
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    b
}

/// Distance from `p` to a box (0 inside).
fn distance_to_box(p: [f64; 3], b: [[f64; 3]; 2]) -> f64 {
    (0..3)
        .map(|i| (b[0][i] - p[i]).max(p[i] - b[1][i]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests;
