//! The penumbra and umbra volumes of one occluder under one area light
//! (Chin & Feiner 1992, after Nishita & Nakamae).
//!
//! For a convex occluder `O` and a convex light `L` with `L` on one side of
//! `O`'s plane, the **penumbra volume** is where some point of `L` is hidden
//! by `O`: the union of the shadow volumes of `O` from every light point,
//! which is convex. The **umbra volume** is where all of `L` is hidden: the
//! intersection of the shadow volumes from `L`'s vertices. Both lie behind
//! `O`'s plane (away from the light) and are bounded by planes through an
//! edge of `O` and a vertex of `L` (light-source vertex planes) or a vertex
//! of `O` and an edge of `L` (light-source edge planes). Oriented with `O`
//! behind them, a candidate plane bounds the penumbra volume when every
//! light vertex is on or in front of it (it separates `O` from `L`), and
//! the umbra volume when every light vertex is on or behind it.
//!
//! Two cases the papers leave to splitting are handled without rounding:
//!
//! - `O` straddles the light's plane: only its part in front receives or
//!   blocks light (rays leave the light forwards). Its new edge lies in the
//!   light's plane, so the planes it would give are the light's plane
//!   itself, added to the volume; every other plane goes through an
//!   original edge or vertex of `O`.
//! - `L` straddles `O`'s plane: each part of the light casts its own
//!   penumbra volume, on its own side of `O`; the light's new edge lies in
//!   `O`'s plane and gives that plane, the cap. There is no umbra volume
//!   then: no point is hidden from light on both sides of `O`'s plane.
//!
//! - A light vertex lies in `O`'s plane: the shadow from that vertex is
//!   flat, so the umbra is empty (as a volume) and only the penumbra volume
//!   is cast.
//!
//! So every plane is a plane through three grid points, in the kernel's
//! bounded family, and every side decision is exact.

use crate::AreaSource;
use bsp_core::predicates::Side;
use bsp_core::{ConvexPolygon, GridPoint, Plane, Split};
use smallvec::SmallVec;
use svbsp::ConvexPolyhedron;

/// The volumes one occluder casts from one area light.
#[derive(Debug, Clone, Default)]
pub struct CastVolumes {
    /// Penumbra volumes: one, or two when the light straddles the
    /// occluder's plane (one per side).
    pub penumbra: SmallVec<[ConvexPolyhedron; 2]>,
    /// The umbra volume, when there is one.
    pub umbra: Option<ConvexPolyhedron>,
}

/// The bounding planes of the volumes, each oriented with its volume behind
/// it (what [`ConvexPolyhedron::from_planes`] takes).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VolumePlanes {
    /// Planes of each penumbra volume.
    pub penumbra: SmallVec<[Vec<Plane>; 2]>,
    /// Planes of the umbra volume, if any.
    pub umbra: Option<Vec<Plane>>,
}

/// The volumes that `occluder` (a convex polygon with grid-point vertices)
/// casts from `light`; empty when it lies in or behind the light's plane, or
/// in a plane through the light.
pub fn cast_volumes(occluder: &ConvexPolygon, light: &AreaSource) -> CastVolumes {
    cast_volumes_within(occluder, light, &ConvexPolyhedron::bounding_box())
}

/// [`cast_volumes`] cut down to `region`: where no receiver lies, a
/// volume's only effect would be to split the trees for nothing.
pub fn cast_volumes_within(
    occluder: &ConvexPolygon,
    light: &AreaSource,
    region: &ConvexPolyhedron,
) -> CastVolumes {
    let planes = volume_planes(occluder, light);
    let cut = |planes: &[Plane]| region.clone().cut_by(planes);
    CastVolumes {
        penumbra: planes.penumbra.iter().filter_map(|p| cut(p)).collect(),
        umbra: planes.umbra.as_deref().and_then(cut),
    }
}

/// The planes of [`cast_volumes`]'s volumes.
pub fn volume_planes(occluder: &ConvexPolygon, light: &AreaSource) -> VolumePlanes {
    let mut out = VolumePlanes::default();
    let light_support = *light.support();
    // The part of the occluder that light reaches.
    let (front, clipped) = match occluder.split(&light_support) {
        Split::Front => (occluder.clone(), false),
        Split::Both(_, front) => (front, true),
        Split::Back | Split::Coplanar(_) => return out,
    };
    let support = *occluder.support();
    // A light vertex in the occluder's plane sees past it (the shadow from
    // that vertex is flat): nothing is hidden from all of the light.
    let touches =
        (0..light.polygon().len()).any(|k| light.polygon().vertex_side(k, &support) == Side::On);
    let parts: SmallVec<[(ConvexPolygon, Plane, bool); 2]> = match light.polygon().split(&support) {
        // Light in front of the occluder: volumes behind its plane.
        Split::Front => [(light.polygon().clone(), support, !touches)]
            .into_iter()
            .collect(),
        Split::Back => [(light.polygon().clone(), support.flipped(), !touches)]
            .into_iter()
            .collect(),
        Split::Both(back, front_part) => [
            (front_part, support, false),
            (back, support.flipped(), false),
        ]
        .into_iter()
        .collect(),
        Split::Coplanar(_) => return out,
    };
    for (light_part, cap, whole_light) in parts {
        let mut penumbra = vec![cap];
        let mut umbra = vec![cap];
        if clipped {
            // The volume stays in front of the light's plane.
            penumbra.push(light_support.flipped());
            umbra.push(light_support.flipped());
        }
        for plane in candidate_planes(&front, occluder, &light_part, light.polygon()) {
            let Some((plane, kind)) = orient(plane, &front, &light_part) else {
                continue;
            };
            let list = match kind {
                Kind::Penumbra => &mut penumbra,
                Kind::Umbra => &mut umbra,
            };
            if !list.contains(&plane) {
                list.push(plane);
            }
        }
        out.penumbra.push(penumbra);
        if whole_light {
            out.umbra = Some(umbra);
        }
    }
    out
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Penumbra,
    Umbra,
}

/// Orients `plane` with the occluder part behind it and says which volume
/// it bounds; `None` when it is not tangent to both (the occluder or the
/// light on both sides, or all of either in the plane).
fn orient(plane: Plane, occluder: &ConvexPolygon, light: &ConvexPolygon) -> Option<(Plane, Kind)> {
    let (back, front) = sides(occluder, &plane);
    let plane = match (back, front) {
        (true, true) | (false, false) => return None,
        (true, false) => plane,
        (false, true) => plane.flipped(),
    };
    match sides(light, &plane) {
        (false, true) => Some((plane, Kind::Penumbra)),
        (true, false) => Some((plane, Kind::Umbra)),
        _ => None,
    }
}

/// Whether `polygon` has vertices strictly behind, and strictly in front
/// of, `plane`.
fn sides(polygon: &ConvexPolygon, plane: &Plane) -> (bool, bool) {
    let (mut back, mut front) = (false, false);
    for k in 0..polygon.len() {
        match polygon.vertex_side(k, plane) {
            Side::Back => back = true,
            Side::Front => front = true,
            Side::On => {}
        }
    }
    (back, front)
}

/// Planes through an edge of one polygon and a grid vertex of the other,
/// both ways. An edge of a clipped part is extended to the original edge it
/// lies on (same edge plane), whose end points are grid points; an edge
/// made by the clip has none and is skipped (its planes are the clipping
/// plane, which the caller adds).
fn candidate_planes(
    occluder: &ConvexPolygon,
    occluder_original: &ConvexPolygon,
    light: &ConvexPolygon,
    light_original: &ConvexPolygon,
) -> impl Iterator<Item = Plane> {
    let occluder_edges = grid_edges(occluder, occluder_original);
    let light_edges = grid_edges(light, light_original);
    let occluder_points = grid_vertices(occluder);
    let light_points = grid_vertices(light);
    let mut planes = Vec::with_capacity(
        occluder_edges.len() * light_points.len() + light_edges.len() * occluder_points.len(),
    );
    for &(a, b) in &occluder_edges {
        for &v in &light_points {
            planes.extend(Plane::through(a, b, v));
        }
    }
    for &(c, d) in &light_edges {
        for &p in &occluder_points {
            planes.extend(Plane::through(p, c, d));
        }
    }
    planes.into_iter()
}

fn grid_vertices(polygon: &ConvexPolygon) -> SmallVec<[GridPoint; 8]> {
    (0..polygon.len())
        .filter_map(|k| polygon.vertex_grid_point(k))
        .collect()
}

fn grid_edges(
    part: &ConvexPolygon,
    original: &ConvexPolygon,
) -> SmallVec<[(GridPoint, GridPoint); 8]> {
    let n = original.len();
    part.edges()
        .filter_map(|edge| {
            let j = original.edges().position(|e| e == edge)?;
            Some((
                original.vertex_grid_point(j)?,
                original.vertex_grid_point((j + 1) % n)?,
            ))
        })
        .collect()
}
