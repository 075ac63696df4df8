//! Which objects are closed surfaces bounding their inside, so that their
//! faces turned away from a light may skip the shadow pass, and which
//! faces face the inside of a closed surface wound inwards.
//!
//! From a light outside such a surface, a segment that reaches one of its
//! faces turned away from the light has crossed a face turned towards it
//! first: the faces towards the light cast the whole shadow. That needs
//! more than every edge being shared: the faces must face *out*. A closed
//! box wound inwards has its faces towards the light turned away by their
//! planes, and skipping those would light its inside.
//!
//! The faces of such a box face its inside: from a point just in front of
//! one, every segment to a light outside leaves the box through another of
//! its faces. They see none of any light; the shadow passes would find that
//! only where single occluders or convex bodies prove it (a box the grid
//! bends is no exact body), so the pipelines mark them in umbra outright.
//! (Both rules take each closed part to bound its inside once, as a solid's
//! surface does.)

use std::collections::HashMap;

use bsp_core::{ConvexPolygon, GridPoint};
use svbsp::PieceFlags;

use crate::decompose::{Pieces, SnappedLight};
use crate::scene::Scene;
use area_shadow::AreaSource;

/// What each piece's object is as a surface.
pub(crate) struct Surfaces {
    /// Per piece: casts, two-sided, and whether its object is a closed
    /// surface facing out: every piece's corners on the grid, every
    /// directed edge between them matched by its reverse exactly once, each
    /// connected part enclosing a positive volume, and every light clear
    /// of it.
    pub flags: Vec<PieceFlags>,
    /// Per piece: one-sided and casting shadows, of such an object but for
    /// its part enclosing a negative volume (wound inwards): its front
    /// faces the part's inside, which no light outside reaches (the part's
    /// other faces block it).
    pub facing_inside: Vec<bool>,
}

/// The pieces' objects as surfaces (see [`Surfaces`]); `objects[k]` is
/// piece `k`'s object ([`piece_objects`](crate::shadow::piece_objects)).
pub(crate) fn surfaces(scene: &Scene, pieces: &Pieces, objects: &[u32]) -> Surfaces {
    let object_of = |k: usize| objects[k] as usize;
    // Objects that are no closed surface, or that some light shines into.
    let mut open = vec![false; scene.objects.len()];
    // Each directed edge with the piece it bounds, `None` once two do.
    let mut edges: HashMap<(usize, GridPoint, GridPoint), Option<usize>> = HashMap::new();
    for (k, piece) in pieces.polygons.iter().enumerate() {
        match grid_corners(piece) {
            Some(corners) => {
                for (a, b) in cyclic_pairs(&corners) {
                    edges
                        .entry((object_of(k), a, b))
                        .and_modify(|owner| *owner = None)
                        .or_insert(Some(k));
                }
            }
            None => open[object_of(k)] = true,
        }
    }
    let mut parts = Parts::new(pieces.polygons.len());
    for (&(object, a, b), &owner) in &edges {
        match (owner, edges.get(&(object, b, a))) {
            (Some(k), Some(&Some(j))) => parts.join(k, j),
            _ => open[object] = true,
        }
    }
    // A closed surface a light may shine into (the light on it or inside
    // it) is taken as open: there its faces turned away from the light
    // hide what its faces towards the light do not.
    let mut points: Vec<Vec<GridPoint>> = vec![Vec::new(); scene.objects.len()];
    for (k, piece) in pieces.polygons.iter().enumerate() {
        points[object_of(k)].extend((0..piece.len()).filter_map(|i| piece.vertex_grid_point(i)));
    }
    for (object, points) in points.iter().enumerate() {
        if !pieces
            .lights
            .iter()
            .all(|light| light_clear_of(light, points))
        {
            open[object] = true;
        }
    }
    // Six times the volume each connected part encloses (exact: grid
    // coordinates below 2^31, so each term is below 2^95).
    let mut volumes: HashMap<usize, i128> = HashMap::new();
    for (k, piece) in pieces.polygons.iter().enumerate() {
        if open[object_of(k)] {
            continue;
        }
        if let Some(corners) = grid_corners(piece) {
            *volumes.entry(parts.root(k)).or_insert(0) += six_volume_under(&corners);
        }
    }
    let volume_of: Vec<Option<i128>> = (0..pieces.polygons.len())
        .map(|k| volumes.get(&parts.root(k)).copied())
        .collect();
    // Faces out: every part of the object encloses a positive volume.
    let mut faces_out: Vec<bool> = open.iter().map(|&o| !o).collect();
    for (k, volume) in volume_of.iter().enumerate() {
        if volume.is_some_and(|v| v <= 0) {
            faces_out[object_of(k)] = false;
        }
    }
    Surfaces {
        flags: (0..pieces.polygons.len())
            .map(|k| PieceFlags {
                casts_shadows: pieces.casts_shadows[k],
                two_sided: pieces.two_sided[k],
                closed_surface: faces_out[object_of(k)],
            })
            .collect(),
        facing_inside: (0..pieces.polygons.len())
            .map(|k| {
                pieces.casts_shadows[k]
                    && !pieces.two_sided[k]
                    && volume_of[k].is_some_and(|v| v < 0)
            })
            .collect(),
    }
}

/// The piece's corners, counter-clockwise seen from its front, when all
/// are grid points.
fn grid_corners(piece: &ConvexPolygon) -> Option<Vec<GridPoint>> {
    (0..piece.len())
        .map(|i| piece.vertex_grid_point(i))
        .collect()
}

fn cyclic_pairs(corners: &[GridPoint]) -> impl Iterator<Item = (GridPoint, GridPoint)> + '_ {
    corners
        .iter()
        .copied()
        .zip(corners.iter().copied().cycle().skip(1))
}

/// Six times the signed volume of the cone from the origin over the
/// polygon `corners` (positive when the polygon faces away from the
/// origin); summed over a closed surface, six times the volume it
/// encloses, positive when it faces out.
fn six_volume_under(corners: &[GridPoint]) -> i128 {
    let v = |p: &GridPoint| [i128::from(p.x), i128::from(p.y), i128::from(p.z)];
    let a = v(&corners[0]);
    corners[1..]
        .windows(2)
        .map(|w| {
            let (b, c) = (v(&w[0]), v(&w[1]));
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum()
}

/// Connected parts of a surface: pieces joined across shared edges
/// (union-find with path halving).
struct Parts {
    parent: Vec<usize>,
}

impl Parts {
    fn new(count: usize) -> Self {
        Self {
            parent: (0..count).collect(),
        }
    }

    fn root(&mut self, mut k: usize) -> usize {
        while self.parent[k] != k {
            self.parent[k] = self.parent[self.parent[k]];
            k = self.parent[k];
        }
        k
    }

    fn join(&mut self, a: usize, b: usize) {
        let (a, b) = (self.root(a), self.root(b));
        // The smaller index becomes the root: the same parts whatever the
        // order the edges come in.
        let (low, high) = (a.min(b), a.max(b));
        self.parent[high] = low;
    }
}

/// Whether `light` lies clear of every solid whose surface has its
/// vertices among `points` (see [`AreaSource::clear_of`]): a point light
/// outside their bounding box; a directional light always (it comes from
/// infinity).
fn light_clear_of(light: &SnappedLight, points: &[GridPoint]) -> bool {
    match light {
        SnappedLight::Point(p) => {
            let outside = |c: fn(&GridPoint) -> i32| {
                points.iter().all(|q| c(q) < c(p)) || points.iter().all(|q| c(q) > c(p))
            };
            outside(|g| g.x) || outside(|g| g.y) || outside(|g| g.z)
        }
        SnappedLight::Directional(_) => true,
        SnappedLight::Area(polygon) => {
            AreaSource::new(polygon.clone()).is_ok_and(|light| light.clear_of(points))
        }
    }
}
