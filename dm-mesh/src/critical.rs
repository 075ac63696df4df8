//! The internal discontinuities of one occluder's penumbra: EV and VE
//! critical surfaces where the visible part of the light changes
//! qualitatively.
//!
//! Inside the penumbra of a convex occluder `O` under a convex light `L`,
//! the visible part of `L` changes its combinatorial shape where, seen from
//! the receiving point,
//!
//! - a light vertex `v` crosses an occluder edge `ab` (EV): the point lies
//!   in the plane through `v`, `a`, `b`, inside the wedge of rays from `v`
//!   through the segment `ab`;
//! - an occluder vertex `p` crosses a light edge `cd` (VE): the point lies
//!   in the plane through `p`, `c`, `d`, inside the wedge of lines from the
//!   segment `cd` through `p`, beyond `p`.
//!
//! The planes that bound the penumbra or umbra volumes are of the same
//! family; the others are the internal ones. Each comes with two planes
//! through its wedge's bounding lines (each through three grid points),
//! oriented with the wedge behind, so a cell is cut only where the wedge
//! crosses it. Only a polygon wholly in front of the light, with the
//! light wholly on one side of it, gets internal discontinuities here (a
//! convex body casting one unit gets those of all its polygons the light
//! reaches, [`body_internal_planes`]), and none through an edge or vertex
//! its object's surface hides on both sides ([`crate::surface`]). A VE
//! wedge is cast only from the part of the light edge that can see its
//! vertex on the silhouette: where the stretch of
//! the edge that sees it hidden ends, the plane of the face it leaves holds
//! the vertex and bounds the wedge in place of the plane through the
//! edge's end.

use crate::cell::Sides;
use crate::surface::Surroundings;
use area_shadow::{AreaSource, VolumePlanes};
use bsp_core::predicates::{self, Pencil, Side};
use bsp_core::{ConvexPolygon, GridPoint, Plane};

/// What one occluder merges into a receiver under one light: its volume
/// planes and its internal discontinuities. Made by [`UnitPlanes::new`]
/// (the planes are not to change after).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct UnitPlanes {
    /// Penumbra and umbra volume planes.
    pub(crate) volumes: VolumePlanes,
    /// Internal EV / VE planes with their wedges.
    pub(crate) internal: Vec<Critical>,
    /// The receiver's sides from which the umbra hides the light (`BOTH`
    /// but where a two-sided receiver lies against a body:
    /// [`crate::scene`]'s contact planes).
    pub(crate) umbra_sides: Sides,
    /// The normal of every plane above, internal, penumbra and umbra in
    /// that order, converted to `f64` (exactly: components below 2^51),
    /// side by side: [`Self::has_plane_on`] scans them all where a node
    /// of a DM-tree may go, and most are told apart by the normal alone.
    normals: Vec<[f64; 3]>,
}

impl UnitPlanes {
    pub(crate) fn new(volumes: VolumePlanes, internal: Vec<Critical>) -> Self {
        let normals = internal
            .iter()
            .map(|c| &c.plane)
            .chain(volumes.penumbra.iter().flatten())
            .chain(volumes.umbra.iter().flatten())
            .map(|p| p.normal().map(|c| c as f64))
            .collect();
        Self {
            volumes,
            internal,
            normals,
            umbra_sides: Sides::BOTH,
        }
    }

    /// These planes with their umbra hiding the light from `sides` only.
    pub(crate) fn hiding_from(mut self, sides: Sides) -> Self {
        self.umbra_sides = sides;
        self
    }

    /// Whether one of the unit's discontinuity planes is `line` (either
    /// orientation) or, given `trace` (where `line` meets the receiver),
    /// holds that trace; the penumbra planes looked at only with
    /// `penumbra`, the umbra planes only with `umbra`.
    pub(crate) fn has_plane_on(
        &self,
        line: &Plane,
        trace: Option<&Pencil>,
        penumbra: bool,
        umbra: bool,
    ) -> bool {
        let line_normal = line.normal().map(|c| c as f64);
        // A plane coincident with `line` holds its trace too; without a
        // trace, only a normal equal or opposite to `line`'s is possible.
        let on = |normal: &[f64; 3], plane: &Plane| match trace {
            Some(t) => t.may_hold(*normal) && (plane.is_coincident(line) || t.holds(plane)),
            None => {
                (*normal == line_normal || *normal == line_normal.map(|c| -c))
                    && plane.is_coincident(line)
            }
        };
        let (internal, rest) = self.normals.split_at(self.internal.len());
        if internal
            .iter()
            .zip(&self.internal)
            .any(|(n, c)| on(n, &c.plane))
        {
            return true;
        }
        let penumbra_planes = self.volumes.penumbra.iter().flatten();
        let (penumbra_normals, umbra_normals) = rest.split_at(penumbra_planes.clone().count());
        let mut penumbra_on = penumbra_normals.iter().zip(penumbra_planes);
        let mut umbra_on = umbra_normals
            .iter()
            .zip(self.volumes.umbra.iter().flatten());
        debug_assert!(
            penumbra || !penumbra_on.clone().any(|(n, p)| on(n, p)),
            "a single penumbra part's plane between cells that both list its unit"
        );
        debug_assert!(
            umbra || !umbra_on.clone().any(|(n, p)| on(n, p)),
            "an umbra plane between cells in that umbra"
        );
        (penumbra && penumbra_on.any(|(n, p)| on(n, p)))
            || (umbra && umbra_on.any(|(n, p)| on(n, p)))
    }
}

/// An internal critical plane and its wedge.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Critical {
    /// The plane of the EV or VE surface.
    pub(crate) plane: Plane,
    /// Two planes through the wedge's bounding lines, the wedge behind
    /// (as a convex polygon lies behind its edge planes).
    pub(crate) wedge: [Plane; 2],
}

/// A plane through the line `xy` other than `critical`, oriented with `z`
/// (a grid point off that line, in `critical`) behind it; flipped when
/// `away`.
fn bound(
    x: GridPoint,
    y: GridPoint,
    z: GridPoint,
    away: bool,
    critical: &Plane,
    others: &[GridPoint],
) -> Option<Plane> {
    let plane = others.iter().find_map(|&t| {
        if predicates::side_of_point(critical, t) == Side::On {
            return None;
        }
        Plane::through(x, y, t)
    })?;
    let side = predicates::side_of_point(&plane, z);
    let toward = match side {
        Side::Back => plane,
        Side::Front => plane.flipped(),
        Side::On => return None,
    };
    Some(if away { toward.flipped() } else { toward })
}

/// The internal EV and VE discontinuities of `occluder` under `light`,
/// given its volume planes (none without an umbra volume or when the
/// occluder reaches the light's plane) and the surface of its object
/// around it.
pub(crate) fn internal_planes(
    occluder: &ConvexPolygon,
    light: &AreaSource,
    volumes: &VolumePlanes,
    around: &Surroundings,
) -> Vec<Critical> {
    let mut out = Vec::new();
    if volumes.umbra.is_some() {
        critical_planes(occluder, light, volumes, around, None, &mut out);
    }
    out
}

/// The internal EV and VE discontinuities of a convex body (wholly in
/// front of the light) that casts one unit in place of its polygons,
/// given the body's volume planes; `members` are its polygons with some of
/// the light in front, each with its surroundings. These are the EV
/// surfaces through a light vertex and an edge the vertex sees on the
/// body's silhouette, and the VE surfaces through a vertex and a light
/// edge from where the vertex is on the silhouette, that do not bound the
/// body's volumes: found member by member as for a polygon (its
/// surroundings leave out what the body hides on both sides), but from
/// every member, whether or not the light is all on one side of it. The
/// wedges are bounded by planes through the body's vertices, the same
/// from every member, so that an edge or vertex two members share gives
/// one surface.
pub(crate) fn body_internal_planes(
    members: &[(&ConvexPolygon, &Surroundings)],
    light: &AreaSource,
    volumes: &VolumePlanes,
) -> Vec<Critical> {
    let mut others: Vec<GridPoint> = light.vertices().collect();
    let mut vertices: Vec<GridPoint> = members
        .iter()
        .flat_map(|(m, _)| (0..m.len()).filter_map(|k| m.vertex_grid_point(k)))
        .collect();
    vertices.sort_unstable();
    vertices.dedup();
    others.extend(vertices);
    let mut out = Vec::new();
    for (member, around) in members {
        critical_planes(member, light, volumes, around, Some(&others), &mut out);
    }
    out
}

/// Appends to `out` the EV and VE surfaces of `occluder` (if all of its
/// vertices are strictly in front of the light) that are neither planes
/// of the `known` volumes, nor the occluder's plane, nor already in `out`.
/// Wedges are bounded by planes through the light's vertices and `others`
/// (by default the occluder's vertices).
fn critical_planes(
    occluder: &ConvexPolygon,
    light: &AreaSource,
    known: &VolumePlanes,
    around: &Surroundings,
    others: Option<&[GridPoint]>,
    out: &mut Vec<Critical>,
) {
    let o: Vec<GridPoint> = (0..occluder.len())
        .filter_map(|k| occluder.vertex_grid_point(k))
        .collect();
    let l: Vec<GridPoint> = light.vertices().collect();
    if o.len() != occluder.len()
        || o.iter()
            .any(|&p| predicates::side_of_point(light.support(), p) != Side::Front)
    {
        return;
    }
    let own: Vec<GridPoint>;
    let others = match others {
        Some(others) => others,
        None => {
            own = l.iter().chain(&o).copied().collect();
            &own
        }
    };
    let known = |plane: &Plane| {
        plane.is_coincident(occluder.support())
            || known
                .penumbra
                .iter()
                .flatten()
                .chain(known.umbra.iter().flatten())
                .any(|q| q.is_coincident(plane))
    };
    // A plane already known (a volume's, or found before for this
    // occluder) is skipped before its wedge is made. Surfaces of other
    // members of a body (earlier in `out`) with the same plane may hold
    // other wedges (two triangles of a face along one line): only the same
    // wedge is left out.
    let start = out.len();
    let mut push = |plane: Option<Plane>, wedge: &dyn Fn(&Plane) -> Option<[Plane; 2]>| {
        let Some(plane) = plane else { return };
        if known(&plane) || out[start..].iter().any(|d| d.plane.is_coincident(&plane)) {
            return;
        }
        if let Some(wedge) = wedge(&plane) {
            // (From the two members along an edge, the plane comes
            // oriented either way, the wedge's planes in either order.)
            let same = |d: &Critical| {
                d.plane.is_coincident(&plane)
                    && (d.wedge == wedge || d.wedge == [wedge[1], wedge[0]])
            };
            if !out[..start].iter().any(same) {
                out.push(Critical { plane, wedge });
            }
        }
    };
    // EV: light vertex v, occluder edge ab; the wedge is the sector at v
    // holding ab.
    for &v in &l {
        for i in 0..o.len() {
            if around.edge_hidden(occluder.support(), i, v) {
                continue;
            }
            let (a, b) = (o[i], o[(i + 1) % o.len()]);
            push(Plane::through(v, a, b), &|plane| {
                Some([
                    bound(v, a, b, false, plane, others)?,
                    bound(v, b, a, false, plane, others)?,
                ])
            });
        }
    }
    // VE: occluder vertex p, light edge cd; the wedge is the sector at p
    // opposite cd.
    for (k, &p) in o.iter().enumerate() {
        for i in 0..l.len() {
            let (c, d) = (l[i], l[(i + 1) % l.len()]);
            if around.vertex_hidden(k, c, d) {
                continue;
            }
            // Cast from a stretch of `cd` that sees `p` hidden, the
            // surface changes nothing: the fan plane where the stretch
            // ends bounds the wedge there.
            push(Plane::through(p, c, d), &|plane| {
                let [at_c, at_d] = around.hidden_stretch_ends(k, c, d, [light.support(), plane]);
                Some([
                    match at_c {
                        Some(end) => end.flipped(),
                        None => bound(p, c, d, true, plane, others)?,
                    },
                    match at_d {
                        Some(end) => end.flipped(),
                        None => bound(p, d, c, true, plane, others)?,
                    },
                ])
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use area_shadow::volume_planes;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    #[test]
    fn a_turned_triangle_has_internal_discontinuities() {
        let light =
            AreaSource::from_grid_points(&[g(-2, 10, -2), g(2, 10, -2), g(2, 10, 2), g(-2, 10, 2)])
                .unwrap();
        let occluder =
            ConvexPolygon::from_grid_points(&[g(-3, 5, -1), g(3, 5, -2), g(0, 5, 4)], 0).unwrap();
        let volumes = volume_planes(&occluder, &light);
        let internal = internal_planes(&occluder, &light, &volumes, &Surroundings::default());
        assert!(!internal.is_empty());
        for c in &internal {
            assert!(!c.wedge[0].is_coincident(&c.plane) && !c.wedge[1].is_coincident(&c.plane));
        }
    }

    #[test]
    fn parallel_squares_have_none() {
        // Every EV plane of a square under a parallel, aligned square light
        // holds a light edge parallel to the occluder edge: it bounds a
        // volume already.
        let light =
            AreaSource::from_grid_points(&[g(-1, 10, -1), g(1, 10, -1), g(1, 10, 1), g(-1, 10, 1)])
                .unwrap();
        let occluder = ConvexPolygon::from_grid_points(
            &[g(-4, 5, 4), g(4, 5, 4), g(4, 5, -4), g(-4, 5, -4)],
            0,
        )
        .unwrap();
        let volumes = volume_planes(&occluder, &light);
        assert!(internal_planes(&occluder, &light, &volumes, &Surroundings::default()).is_empty());
    }
}
