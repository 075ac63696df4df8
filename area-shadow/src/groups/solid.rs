//! Closed surfaces that block light as a convex body, and that body's
//! umbra planes.
//!
//! A closed surface `S` (every directed edge matched by its reverse once)
//! blocks light at least as a convex body `B` does whenever `B` lies
//! within the intersection `K` of the half-spaces behind `S`'s faces:
//! from a point of `K` every face of `S` turns its back, so the point has a
//! winding number of at least one and any segment from it to a point
//! outside `S`'s hull (the light) crosses `S`. When every vertex of `S` is
//! in `K`, `S` is convex and `B` is its solid. Rounding to the grid often
//! leaves a convex surface a few units off: two triangles of a planar quad
//! meet at a slight valley, and the vertices beside it stand out of the
//! other triangle's plane. Those vertices are moved a few grid units
//! towards the surface's centre until they are in `K`; if the surface so
//! moved is convex, its solid lies in `K` (it is the hull of points of
//! `K`, which is convex) and stands for `B`: its umbra is part of `S`'s,
//! every plane still through three grid points. A body really concave
//! (a bumpy sphere) stands for the hull of grid points of `K` found along
//! 162 directions from a centre (module `kernel`), when `K` holds
//! one; a body with no kernel (a torus) for up to 8 convex cores, each
//! in the local kernel of a point inside it (module `cores`).

use super::closed::{ClosedFaces, signed_volume};
use super::cores::local_cores;
use super::edge_set;
use super::hull::convex_hull;
use super::kernel::{bounding_planes, kernel_points};
use crate::hash::HashSet;
use crate::{AreaSource, SourceSide};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, Plane};

/// The farthest a vertex is moved towards the centre, in grid units.
const MAX_NUDGE: f64 = 64.0;

/// The most corners of a hole closed by a fan of triangles
/// ([`Solid::capped`]).
const MAX_FAN_CORNERS: usize = 12;

/// The most ways to close a surface's holes tried ([`Solid::capped`]).
const MAX_CAP_CHOICES: usize = 64;

/// A closed convex surface: the body a group blocks light as.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Solid {
    vertices: Vec<GridPoint>,
    /// Each face's plane, the body behind it.
    faces: Vec<Plane>,
    /// Each edge once, with the two faces (indices into `faces`) it joins.
    edges: Vec<(GridPoint, GridPoint, u32, u32)>,
    /// Whether the body is the surface's own solid (not moved in).
    exact: bool,
    /// Whether the surface's pieces face into the body.
    faces_in: bool,
    /// Whether the surface was open, and faces over its hole were added to
    /// close it ([`Self::of_open_surface`]).
    capped: bool,
    /// Those faces' planes, facing out, when more than one (then the
    /// light must lie on one side of them all, see [`Self::umbra_parts`]).
    caps: Vec<Plane>,
    /// The planes of all the faces that closed an open surface, facing
    /// out (no occluder lies there).
    open: Vec<Plane>,
    /// Those faces' corners (convex polygons, in the order of `open`).
    cap_corners: Vec<Vec<GridPoint>>,
    /// The pieces (outline, support) of the surface it was made from,
    /// without the faces that closed it; empty for a hull.
    surface: Vec<(Vec<GridPoint>, Plane)>,
    /// The planes of the convex hull of the surface (closed by its caps),
    /// the hull behind each: a point in front of one is outside the
    /// surface. The faces themselves when the body is exact; the hull's
    /// when it was moved in, which leaves a layer of the surface's inside
    /// outside the body; for a core of the kernel, those of a box with
    /// its edges and corners cut around the surface (a convex set that
    /// holds it, of 26 planes at most).
    hull: Vec<Plane>,
    /// The corners of the core a shell is made about ([`Self::shell`])
    /// when it is not the body itself: a core of a local kernel makes its
    /// shell about the hull of fewer of its points (within the body), for
    /// proofs that test its faces at every step. Empty (or flat): the
    /// body's.
    shell_core: Vec<GridPoint>,
}

impl Solid {
    /// The convex body that the closed surface of `outlines` (with support
    /// planes `supports`, all facing out or all in) blocks light as: the
    /// surface itself when convex, else the surface with the vertices that
    /// stand out moved in (module docs); `None` when neither is convex.
    pub(super) fn of_surface(outlines: &[&[GridPoint]], supports: &[Plane]) -> Option<Self> {
        let closed = ClosedFaces::of(outlines, supports)?;
        Self::of_closed(&closed, outlines, supports)
    }

    /// As [`Self::of_surface`], and for a closed surface that is really
    /// concave the hull of grid points of its kernel (a bumpy sphere,
    /// module `kernel`), or with no kernel (a torus) several cores, each
    /// in the local kernel of a point inside (module `cores`). The
    /// surface is checked once for all.
    pub(super) fn of_closed_surface(outlines: &[&[GridPoint]], supports: &[Plane]) -> Vec<Self> {
        let Some(closed) = ClosedFaces::of(outlines, supports) else {
            return Vec::new();
        };
        match Self::of_closed(&closed, outlines, supports) {
            Some(solid) => vec![solid],
            None => Self::cores(&closed, outlines, supports),
        }
    }

    /// The planes of a closed surface that is no convex body (nor one the
    /// grid's rounding left a few units from convex), turned to face out:
    /// what its sections (module `section`) are checked against. `None`
    /// for any other surface.
    pub(super) fn concave_faces(
        outlines: &[&[GridPoint]],
        supports: &[Plane],
    ) -> Option<Vec<Plane>> {
        let closed = ClosedFaces::of(outlines, supports)?;
        if Self::of_closed(&closed, outlines, supports).is_some() {
            return None;
        }
        let faces_in = signed_volume(outlines) < 0.0;
        Some(closed.faces_turned(faces_in, supports).into_owned())
    }

    /// [`Self::of_surface`] of a surface already checked closed.
    fn of_closed(
        closed: &ClosedFaces,
        outlines: &[&[GridPoint]],
        supports: &[Plane],
    ) -> Option<Self> {
        let solid = if closed.out.contains(&true) {
            let hull = closed.hull()?;
            Self::moved_in(&closed.faces, &closed.vertices, &closed.out)
                .map(|solid| Self { hull, ..solid })
        } else {
            Self::with_faces(
                outlines,
                closed.faces.clone(),
                closed.vertices.clone(),
                true,
            )
        };
        solid.map(|solid| solid.made_of(outlines, supports, closed.faces_in))
    }

    /// Convex cores inside a closed surface that is no convex body: the
    /// hull of grid points of its kernel, if it has one, else of local
    /// kernels (module `cores`).
    fn cores(closed: &ClosedFaces, outlines: &[&[GridPoint]], supports: &[Plane]) -> Vec<Self> {
        // Far from convex, as many vertices may stand out of the faces'
        // planes one way as the other: the enclosed volume's sign tells
        // which way the pieces face.
        let faces_in = signed_volume(outlines) < 0.0;
        let faces = closed.faces_turned(faces_in, supports);
        let cores = match kernel_points(&faces, &closed.vertices) {
            Some(points) => Self::of_hull(&points, false).into_iter().collect(),
            None => local_cores(outlines, &faces),
        };
        let hull = bounding_planes(&closed.vertices);
        cores
            .into_iter()
            .map(|core| {
                Self {
                    hull: hull.clone(),
                    ..core
                }
                .made_of(outlines, supports, faces_in)
            })
            .collect()
    }

    /// The solid with its shell made about the hull of `corners` (points
    /// of the body) rather than the body ([`Self::shell`]).
    pub(super) fn with_shell_core(self, corners: Vec<GridPoint>) -> Self {
        Self {
            shell_core: corners,
            ..self
        }
    }

    /// The solid as made from the surface of `outlines` (with `supports`),
    /// whose pieces face in when `faces_in`.
    fn made_of(self, outlines: &[&[GridPoint]], supports: &[Plane], faces_in: bool) -> Self {
        let surface = outlines
            .iter()
            .zip(supports)
            .map(|(o, s)| (o.to_vec(), *s))
            .collect();
        Self {
            faces_in,
            surface,
            ..self
        }
    }

    /// The body of a surface closed but for one face: its unmatched edges
    /// close into one cycle, a planar convex polygon, that capped with it
    /// the surface is convex (or nearly, [`Self::of_surface`]). The open
    /// surface blocks light as that body does from every point outside
    /// it: a segment through the body crosses its boundary twice, and at
    /// most once in the hole's plane. From inside (through the hole) it
    /// does not, so the umbra is given in parts outside the body
    /// ([`super::ConvexGroup::umbra_parts`]).
    ///
    /// A hole of four corners not in one plane (a quad the grid bent,
    /// given as two triangles) is closed by the two triangles of its other
    /// diagonal: a thin tetrahedron. Two faces over the hole can both be
    /// crossed by one segment, but not when the light lies on one side of
    /// both: then a segment from the light leaves or enters the body by a
    /// face of the surface (the light behind both, it leaves by a face the
    /// light is in front of; in front of both, a point in the umbra lies
    /// behind both, and the segment enters by a face the point is in front
    /// of).
    pub(super) fn of_open_surface(outlines: &[&[GridPoint]], supports: &[Plane]) -> Option<Self> {
        let hole = super::boundary_cycle(outlines)?;
        Self::capped(outlines, supports, &[hole], false)
    }

    /// The surface of `outlines` (with `supports`) closed over each of
    /// its `holes` (boundary cycles) as [`Self::of_open_surface`] closes
    /// one: each hole by itself if a planar convex polygon, a bent one of
    /// four corners by the triangles of either diagonal (the first choice
    /// that makes the surface convex, or nearly). With `fans`, a hole of
    /// more corners that is no planar convex polygon (bent by the grid,
    /// or with a corner in line with its neighbours) may be closed by the
    /// fan of triangles from any of its corners.
    pub(super) fn capped(
        outlines: &[&[GridPoint]],
        supports: &[Plane],
        holes: &[Vec<GridPoint>],
        fans: bool,
    ) -> Option<Self> {
        // Each hole's ways to be closed.
        let options: Vec<Vec<Vec<Vec<GridPoint>>>> = holes
            .iter()
            .map(|hole| {
                let mut hole = hole.clone();
                hole.reverse();
                if ConvexPolygon::from_grid_points(&hole, 0).is_ok() {
                    return vec![vec![hole]];
                }
                let n = hole.len();
                let bent = n == 4
                    && Plane::through(hole[0], hole[1], hole[2])
                        .is_some_and(|plane| side_of_point(&plane, hole[3]) != Side::On);
                // Four corners bent: either diagonal (a fan from either end).
                let apexes = if bent {
                    2
                } else if fans && n <= MAX_FAN_CORNERS {
                    n
                } else {
                    0
                };
                (0..apexes)
                    .map(|apex| {
                        (1..n - 1)
                            .map(|k| {
                                vec![hole[apex], hole[(apex + k) % n], hole[(apex + k + 1) % n]]
                            })
                            .collect()
                    })
                    .collect()
            })
            .collect();
        let choices = options
            .iter()
            .map(Vec::len)
            .try_fold(1_usize, |all, n| all.checked_mul(n))
            .filter(|&all| all <= MAX_CAP_CHOICES)?;
        (0..choices).find_map(|mut choice| {
            let mut cap: Vec<Vec<GridPoint>> = Vec::new();
            for ways in &options {
                cap.extend(ways[choice % ways.len()].iter().cloned());
                choice /= ways.len();
            }
            Self::closed_by(outlines, supports, cap)
        })
    }

    /// The surface of `outlines` closed by the polygons `cap`, if it is
    /// convex or nearly so.
    fn closed_by(
        outlines: &[&[GridPoint]],
        supports: &[Plane],
        cap: Vec<Vec<GridPoint>>,
    ) -> Option<Self> {
        let polygons: Vec<ConvexPolygon> = cap
            .iter()
            .map(|outline| ConvexPolygon::from_grid_points(outline, 0).ok())
            .collect::<Option<_>>()?;
        let mut closed: Vec<&[GridPoint]> = outlines.to_vec();
        closed.extend(cap.iter().map(Vec::as_slice));
        let mut planes = supports.to_vec();
        planes.extend(polygons.iter().map(|p| *p.support()));
        let solid = Self::of_surface(&closed, &planes)?;
        let open: Vec<Plane> = polygons
            .iter()
            .map(|p| solid.outward(p.support()))
            .collect();
        let caps = if open.len() > 1 {
            open.clone()
        } else {
            Vec::new()
        };
        Some(Self {
            capped: true,
            caps,
            open,
            cap_corners: cap,
            surface: outlines
                .iter()
                .zip(supports)
                .map(|(o, s)| (o.to_vec(), *s))
                .collect(),
            ..solid
        })
    }

    /// Whether the body's umbra is the open surface's from outside (see
    /// [`Self::of_open_surface`]): with one face over the hole always,
    /// with more when `light` lies on one side of them all.
    pub(super) fn caps_let_through(&self, light: &AreaSource) -> bool {
        let sides: Vec<SourceSide> = self.caps.iter().map(|c| light.side_of(c)).collect();
        !sides.iter().all(|s| *s == SourceSide::Back)
            && !sides.iter().all(|s| *s == SourceSide::Front)
    }

    /// The body as a blocker for joint-umbra proofs
    /// ([`crate::dark::Body`]), its boundary covered by `surface` but for
    /// the faces that closed it: only a surface's own solid (not moved in,
    /// which blocks less than the surface but not only through it).
    pub(super) fn blocking_body(&self, surface: &[&ConvexPolygon]) -> Option<crate::dark::Body> {
        if !self.exact {
            return None;
        }
        crate::dark::Body::new(self.faces.clone(), self.open.clone(), surface)
    }

    /// The shell of a surface closed over its hole, or of a closed one
    /// the body only stands for ([`crate::dark::Body::shell`]): the body
    /// (its own solid, one moved in, or a core of the kernel: each lies
    /// behind every face plane of the closed surface; or a core of a
    /// local kernel, inside the surface), or the hull of some of its
    /// points, as the core, with the surface's hull and caps (none for a
    /// closed surface). `None` when the body is a closed surface's own
    /// solid (it blocks as itself, [`Self::blocking_body`]).
    pub(super) fn shell(&self) -> Option<crate::dark::Body> {
        if self.exact && !self.capped {
            return None;
        }
        // The body's hull when the shell's corners span no volume.
        let hull = convex_hull(&self.shell_core).or_else(|| convex_hull(&self.vertices))?;
        let core: Vec<ConvexPolygon> = hull
            .iter()
            .map(|(triangle, _)| ConvexPolygon::from_grid_points(triangle, 0).ok())
            .collect::<Option<_>>()?;
        let core: Vec<&ConvexPolygon> = core.iter().collect();
        let mut corners: Vec<GridPoint> = self
            .surface
            .iter()
            .flat_map(|(outline, _)| outline.iter().copied())
            .collect();
        corners.sort_unstable();
        corners.dedup();
        let caps: Vec<(Vec<GridPoint>, Plane)> = self
            .cap_corners
            .iter()
            .cloned()
            .zip(self.open.iter().copied())
            .collect();
        let faces: Vec<(Vec<GridPoint>, Plane)> = self
            .surface
            .iter()
            .map(|(outline, support)| (outline.clone(), self.outward(support)))
            .chain(caps.iter().cloned())
            .collect();
        // The body's centre, if strictly behind every face's plane.
        let n = self.vertices.len() as f64;
        let centre: [f64; 3] =
            std::array::from_fn(|a| self.vertices.iter().map(|p| p.to_f64()[a]).sum::<f64>() / n);
        let inner = GridPoint::new(
            centre[0].round() as i64,
            centre[1].round() as i64,
            centre[2].round() as i64,
        )
        .ok()
        .filter(|&c| {
            faces
                .iter()
                .all(|(_, plane)| side_of_point(plane, c) == Side::Back)
        });
        crate::dark::Body::shell(
            &core,
            crate::dark::ShellSurface {
                faces,
                caps,
                corners,
                hull: self.hull.clone(),
                inner,
            },
        )
    }

    /// Whether the body closes an open surface ([`Self::of_open_surface`]).
    pub(super) fn is_capped(&self) -> bool {
        self.capped
    }

    /// Each face's plane, the body behind it.
    pub(super) fn faces(&self) -> &[Plane] {
        &self.faces
    }

    /// The body's corners (and, for a surface's own solid, the surface's
    /// vertices).
    pub(super) fn vertices(&self) -> &[GridPoint] {
        &self.vertices
    }

    /// The pieces (outline, support) of the surface the body was made
    /// from, without faces that closed it; empty for a hull.
    pub(super) fn surface(&self) -> &[(Vec<GridPoint>, Plane)] {
        &self.surface
    }

    /// Whether the body is the closed surface's own solid: neither moved
    /// in nor closed over a hole.
    pub(super) fn is_closed_and_exact(&self) -> bool {
        self.exact && !self.capped
    }

    /// The planes of the surface's convex hull, facing out (see the
    /// field).
    pub(super) fn hull(&self) -> &[Plane] {
        &self.hull
    }

    /// A piece's support plane turned to face out of the body.
    pub(super) fn outward(&self, support: &Plane) -> Plane {
        if self.faces_in {
            support.flipped()
        } else {
            *support
        }
    }

    /// The hull of the surface's vertices, those marked `out` (in front of
    /// some face) moved towards its centre until they are behind every
    /// face: a convex body within them all.
    fn moved_in(faces: &[Plane], vertices: &[GridPoint], out: &[bool]) -> Option<Self> {
        let n = vertices.len() as f64;
        let centre: [f64; 3] =
            std::array::from_fn(|a| vertices.iter().map(|p| p.to_f64()[a]).sum::<f64>() / n);
        let inside = |p: GridPoint| faces.iter().all(|f| side_of_point(f, p) != Side::Front);
        let mut points = Vec::with_capacity(vertices.len());
        for (&p, &stands_out) in vertices.iter().zip(out) {
            if !stands_out {
                points.push(p);
                continue;
            }
            let from = p.to_f64();
            let d: [f64; 3] = std::array::from_fn(|a| centre[a] - from[a]);
            let length = d.iter().map(|c| c * c).sum::<f64>().sqrt();
            let mut step = 1.0;
            loop {
                if step > MAX_NUDGE || step >= length {
                    return None;
                }
                let q = GridPoint::new(
                    (from[0] + d[0] / length * step).round() as i64,
                    (from[1] + d[1] / length * step).round() as i64,
                    (from[2] + d[2] / length * step).round() as i64,
                )
                .ok()?;
                if inside(q) {
                    points.push(q);
                    break;
                }
                step *= 2.0;
            }
        }
        Self::of_hull(&points, false)
    }

    /// The convex hull of `points` as a solid (`exact`: the body itself,
    /// not one moved in); `None` when they span no volume.
    pub(super) fn of_hull(points: &[GridPoint], exact: bool) -> Option<Self> {
        let hull = convex_hull(points)?;
        let triangles: Vec<&[GridPoint]> = hull.iter().map(|(t, _)| &t[..]).collect();
        let planes: Vec<Plane> = hull.iter().map(|(_, plane)| *plane).collect();
        let mut corners: Vec<GridPoint> = hull.iter().flat_map(|(t, _)| *t).collect();
        corners.sort_unstable();
        corners.dedup();
        Self::with_faces(&triangles, planes, corners, exact)
    }

    /// The solid of a closed convex surface, its faces' planes given;
    /// `exact`: the surface's own (not moved in).
    fn with_faces(
        outlines: &[&[GridPoint]],
        faces: Vec<Plane>,
        vertices: Vec<GridPoint>,
        exact: bool,
    ) -> Option<Self> {
        let edges = edge_set(outlines)?;
        let mut solid_edges = Vec::with_capacity(edges.len() / 2);
        for (&(a, b), &f) in &edges {
            let &g = edges.get(&(b, a))?;
            if a < b {
                solid_edges.push((a, b, f, g));
            }
        }
        solid_edges.sort_unstable();
        Some(Self {
            vertices,
            hull: distinct_planes(faces.clone()),
            faces,
            edges: solid_edges,
            exact,
            faces_in: false,
            capped: false,
            caps: Vec::new(),
            open: Vec::new(),
            cap_corners: Vec::new(),
            surface: Vec::new(),
            shell_core: Vec::new(),
        })
    }

    /// The planes of the body's penumbra volume under `light` (see
    /// [`super::ConvexGroup::penumbra_planes`]): every plane that separates
    /// the body from the light is a plane through a face of one with the
    /// other on or in front, or through an edge of one and a vertex of the
    /// other; the volume is strictly on the body's side of all of them.
    pub(super) fn penumbra_planes(&self, light: &AreaSource) -> Option<Vec<Plane>> {
        let support = light.support();
        if !self.exact
            || self.capped
            || self
                .vertices
                .iter()
                .any(|&p| side_of_point(support, p) != Side::Front)
        {
            return None;
        }
        let lights: Vec<GridPoint> = light.vertices().collect();
        // The body behind `plane`, the light on or in front.
        let separates = |plane: &Plane| {
            lights
                .iter()
                .all(|&w| side_of_point(plane, w) != Side::Back)
        };
        let mut planes: Vec<Plane> = vec![support.flipped()];
        let mut seen: HashSet<Plane> = planes.iter().copied().collect();
        for face in &self.faces {
            if separates(face) && seen.insert(*face) {
                planes.push(*face);
            }
        }
        let light_edges = (0..lights.len()).map(|i| (lights[i], lights[(i + 1) % lights.len()]));
        let through_edges = self
            .edges
            .iter()
            .flat_map(|&(a, b, _, _)| lights.iter().map(move |&v| Plane::through(a, b, v)));
        let through_vertices = self.vertices.iter().flat_map(|&p| {
            light_edges
                .clone()
                .map(move |(c, d)| Plane::through(c, d, p))
        });
        for plane in through_edges.chain(through_vertices).flatten() {
            let Some(plane) = self.tangent(plane) else {
                continue;
            };
            if separates(&plane) && seen.insert(plane) {
                planes.push(plane);
            }
        }
        Some(planes)
    }

    /// The umbra of a body that encloses `light` (see
    /// [`super::ConvexGroup::enclosing_umbra`]).
    pub(super) fn enclosing_umbra(&self, light: &AreaSource) -> Vec<Vec<Plane>> {
        let support = light.support();
        let inside = light.vertices().all(|v| {
            self.faces
                .iter()
                .all(|f| side_of_point(f, v) != Side::Front)
        });
        // A body moved in is not the surface that holds the light in, and a
        // light in a face's plane facing out shines out of the body.
        if !self.exact || self.capped || !inside || self.faces.contains(support) {
            return Vec::new();
        }
        self.faces
            .iter()
            .filter(|f| **f != support.flipped())
            .map(|f| vec![f.flipped()])
            .collect()
    }

    /// The planes of the body's umbra volume under `light` (see
    /// [`super::ConvexGroup::umbra_planes`]).
    pub(super) fn umbra_planes(&self, light: &AreaSource) -> Option<Vec<Plane>> {
        let support = light.support();
        // A body that stands for a surface blocks as it does only from
        // outside the surface's hull: the light strictly behind it all.
        let stands_for = if self.exact {
            &[][..]
        } else {
            &self.surface[..]
        };
        let surface = stands_for.iter().flat_map(|(outline, _)| outline);
        if self
            .vertices
            .iter()
            .chain(surface)
            .any(|&p| side_of_point(support, p) != Side::Front)
        {
            return None;
        }
        let lights: Vec<GridPoint> = light.vertices().collect();
        // sides[f * n + k]: light vertex k against face f.
        let n = lights.len();
        let sides: Vec<Side> = self
            .faces
            .iter()
            .flat_map(|f| lights.iter().map(move |&v| side_of_point(f, v)))
            .collect();
        let mut planes: Vec<Plane> = Vec::new();
        let mut seen: HashSet<Plane> = HashSet::default();
        // The faces some light vertex sees: the ray from it enters there.
        for (f, face) in self.faces.iter().enumerate() {
            if sides[f * n..(f + 1) * n].contains(&Side::Front) && seen.insert(*face) {
                planes.push(*face);
            }
        }
        // The cones' sides: planes through a light vertex and an edge where
        // the vertex's view of the body turns (one face seen, the other
        // not, or either edge-on), tangent to the body, all of the light on
        // or behind.
        for (k, &v) in lights.iter().enumerate() {
            for &(a, b, f, g) in &self.edges {
                let (sf, sg) = (sides[f as usize * n + k], sides[g as usize * n + k]);
                let turns =
                    (sf == Side::Front) != (sg == Side::Front) || sf == Side::On || sg == Side::On;
                if !turns {
                    continue;
                }
                let Some(plane) = Plane::through(a, b, v) else {
                    continue;
                };
                let Some(plane) = self.tangent(plane) else {
                    continue;
                };
                let light_behind = lights
                    .iter()
                    .all(|&w| side_of_point(&plane, w) != Side::Front);
                if light_behind && seen.insert(plane) {
                    planes.push(plane);
                }
            }
        }
        Some(planes)
    }

    /// `plane` oriented with the body behind it, if it has the body on one
    /// side.
    fn tangent(&self, plane: Plane) -> Option<Plane> {
        let (mut back, mut front) = (false, false);
        for &p in &self.vertices {
            match side_of_point(&plane, p) {
                Side::Back => back = true,
                Side::Front => front = true,
                Side::On => {}
            }
            if back && front {
                return None;
            }
        }
        match (back, front) {
            (true, false) => Some(plane),
            (false, true) => Some(plane.flipped()),
            _ => None,
        }
    }
}

/// The planes with repeats (coincident planes) dropped, in order.
pub(super) fn distinct_planes(planes: Vec<Plane>) -> Vec<Plane> {
    let mut out: Vec<Plane> = Vec::with_capacity(planes.len());
    for plane in planes {
        if !out.iter().any(|p| p.is_coincident(&plane)) {
            out.push(plane);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A UV sphere's quads cut into triangles, rounded: nearly convex.
    fn rounded_sphere() -> Vec<Vec<GridPoint>> {
        let at = |i: u32, j: u32| {
            let (t, f) = (
                std::f64::consts::PI * f64::from(i) / 6.0,
                std::f64::consts::PI * f64::from(j % 10) / 5.0,
            );
            GridPoint::new(
                (1000.0 * t.sin() * f.cos()).round() as i64,
                (1000.0 * t.cos()).round() as i64,
                (1000.0 * t.sin() * f.sin()).round() as i64,
            )
            .unwrap()
        };
        let mut out = Vec::new();
        for i in 0..6 {
            for j in 0..10 {
                let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
                for t in [vec![a, b, c], vec![a, c, d]] {
                    if Plane::through(t[0], t[1], t[2]).is_some() {
                        out.push(t);
                    }
                }
            }
        }
        out
    }

    #[test]
    fn a_nearly_convex_surface_stands_for_a_body_inside_it() {
        let outlines = rounded_sphere();
        let slices: Vec<&[GridPoint]> = outlines.iter().map(Vec::as_slice).collect();
        let supports: Vec<Plane> = outlines
            .iter()
            .map(|t| Plane::through(t[0], t[1], t[2]).unwrap())
            .collect();
        let mut vertices: Vec<GridPoint> = outlines.iter().flatten().copied().collect();
        vertices.sort_unstable();
        vertices.dedup();
        // Rounding left some vertex in front of some face.
        assert!(
            supports
                .iter()
                .any(|f| vertices.iter().any(|&p| side_of_point(f, p) == Side::Front))
        );
        let solid = Solid::of_surface(&slices, &supports).unwrap();
        // The body is convex and behind every face of the surface.
        for f in solid.faces.iter().chain(&supports) {
            assert!(
                solid
                    .vertices
                    .iter()
                    .all(|&p| side_of_point(f, p) != Side::Front)
            );
        }
        // Nearly all vertices are the hull's (moved in or not).
        assert!(
            solid.vertices.len() * 10 >= vertices.len() * 9,
            "{} of {}",
            solid.vertices.len(),
            vertices.len()
        );
        // The body moved in has its umbra inside the surface's, but its
        // penumbra would miss some of the surface's: none is given.
        let g = |x, y, z| GridPoint::new(x, y, z).unwrap();
        let light = AreaSource::from_grid_points(&[
            g(-500, 3000, -500),
            g(500, 3000, -500),
            g(500, 3000, 500),
            g(-500, 3000, 500),
        ])
        .unwrap();
        assert!(solid.umbra_planes(&light).is_some());
        assert!(solid.penumbra_planes(&light).is_none());
    }
}
