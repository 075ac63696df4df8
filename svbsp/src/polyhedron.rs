//! Convex polyhedra as lists of facets, and their exact splitting by a plane.
//!
//! This is the geometry under the set operations of Thibault & Naylor
//! (1987) and Naylor, Amanatides & Thibault (1990): the cell of a BSP node
//! is a convex polyhedron, and the *sub-hyperplane* of a node is its plane
//! restricted to its cell, a convex polygon. Cells of unbounded regions are
//! closed by the **bounding box** `|x|, |y|, |z| <= GRID_LIMIT` (`2^24`): it
//! holds every grid point, so results restricted to it are exact for every
//! point the kernel can name.
//!
//! Every decision goes through the exact predicates of [`bsp_core`]; no
//! coordinate is rounded.

use bsp_core::predicates::Side;
use bsp_core::{ConvexPolygon, GRID_LIMIT, GridPoint, Plane, Split};
use smallvec::SmallVec;

/// The `source` of facets that the set operations made (sections of cells,
/// faces of the bounding box): they are not part of any input boundary.
pub const SECTION_SOURCE: u32 = u32::MAX;

/// A bounded convex polyhedron: the intersection of the half-spaces behind
/// its facets' support planes (facets face outwards).
///
/// Facets are strictly convex polygons with exact (grid or implicit)
/// vertices. Several facets may share a support plane (a face given as
/// triangles, say).
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexPolyhedron {
    facets: Vec<ConvexPolygon>,
}

/// The result of [`ConvexPolyhedron::split`].
#[derive(Debug, Clone, PartialEq)]
pub enum CellSplit {
    /// The polyhedron lies behind the plane (touching it at most along its
    /// boundary).
    Back,
    /// The polyhedron lies in front of the plane.
    Front,
    /// The plane cuts the polyhedron's interior.
    Both {
        /// The part behind the plane.
        back: ConvexPolyhedron,
        /// The part in front of the plane.
        front: ConvexPolyhedron,
        /// The plane restricted to the polyhedron (its sub-hyperplane), with
        /// the plane's orientation: `back` lies behind it.
        section: ConvexPolygon,
    },
}

impl ConvexPolyhedron {
    /// The polyhedron bounded by `facets`, faces of a closed convex
    /// polyhedron with outward normals. Not checked: the caller vouches that
    /// they close up and that the solid is convex.
    pub fn from_faces(facets: Vec<ConvexPolygon>) -> Self {
        Self { facets }
    }

    /// The bounding box `[-2^24, 2^24]^3`, its facets marked
    /// [`SECTION_SOURCE`].
    pub fn bounding_box() -> Self {
        let l = GRID_LIMIT;
        let corner = |c: i32| GridPoint { x: c, y: c, z: c };
        Self::axis_box(corner(-l), corner(l)).expect("the bounding box has volume")
    }

    /// The axis-aligned box from `lo` to `hi` (grid points), its facets
    /// marked [`SECTION_SOURCE`]; `None` unless `lo < hi` in every
    /// coordinate.
    pub fn axis_box(lo: GridPoint, hi: GridPoint) -> Option<Self> {
        if lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z {
            return None;
        }
        let p = |x: i32, y: i32, z: i32| GridPoint { x, y, z };
        let (a, b) = (lo, hi);
        let quads = [
            [
                p(a.x, a.y, a.z),
                p(a.x, b.y, a.z),
                p(b.x, b.y, a.z),
                p(b.x, a.y, a.z),
            ],
            [
                p(a.x, a.y, b.z),
                p(b.x, a.y, b.z),
                p(b.x, b.y, b.z),
                p(a.x, b.y, b.z),
            ],
            [
                p(a.x, a.y, a.z),
                p(b.x, a.y, a.z),
                p(b.x, a.y, b.z),
                p(a.x, a.y, b.z),
            ],
            [
                p(a.x, b.y, a.z),
                p(a.x, b.y, b.z),
                p(b.x, b.y, b.z),
                p(b.x, b.y, a.z),
            ],
            [
                p(a.x, a.y, a.z),
                p(a.x, a.y, b.z),
                p(a.x, b.y, b.z),
                p(a.x, b.y, a.z),
            ],
            [
                p(b.x, a.y, a.z),
                p(b.x, b.y, a.z),
                p(b.x, b.y, b.z),
                p(b.x, a.y, b.z),
            ],
        ];
        let facets = quads
            .iter()
            .map(|q| ConvexPolygon::from_grid_points(q, SECTION_SOURCE).ok())
            .collect::<Option<Vec<_>>>()?;
        Some(Self { facets })
    }

    /// The intersection of the half-spaces behind `planes` (each oriented
    /// outwards), closed by the bounding box; `None` if it has no interior.
    ///
    /// Facets cut from plane `k` get source `k`; what the box closes gets
    /// [`SECTION_SOURCE`].
    pub fn from_planes(planes: &[Plane]) -> Option<Self> {
        Self::bounding_box().cut_by(planes)
    }

    /// The part of this polyhedron behind every plane of `planes` (each
    /// oriented outwards); `None` if it has no interior. Facets cut from
    /// plane `k` get source `k`.
    pub fn cut_by(self, planes: &[Plane]) -> Option<Self> {
        let mut cell = self;
        for (k, plane) in planes.iter().enumerate() {
            match cell.split(plane) {
                CellSplit::Back => {}
                CellSplit::Front => return None,
                CellSplit::Both { mut back, .. } => {
                    let section = back.facets.last_mut().expect("a section was added");
                    *section = section.clone().with_source(k as u32);
                    cell = back;
                }
            }
        }
        Some(cell)
    }

    /// The facets, outward.
    pub fn facets(&self) -> &[ConvexPolygon] {
        &self.facets
    }

    /// Distinct support planes of the facets that are not
    /// [`SECTION_SOURCE`], in facet order: the input planes that still bound
    /// this (piece of a) polyhedron.
    pub fn input_planes(&self) -> Vec<Plane> {
        let mut planes: Vec<Plane> = Vec::new();
        for f in &self.facets {
            if f.source() != SECTION_SOURCE && !planes.contains(f.support()) {
                planes.push(*f.support());
            }
        }
        planes
    }

    /// Volume in cubic grid units (divergence theorem, `f64`).
    pub fn volume(&self) -> f64 {
        let origin = self.facets.first().map_or([0.0; 3], |f| f.vertex_f64(0));
        let mut six = 0.0;
        for f in &self.facets {
            let v: Vec<[f64; 3]> = f
                .vertices_f64()
                .iter()
                .map(|p| [p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]])
                .collect();
            for i in 1..v.len() - 1 {
                six += triple(v[0], v[i], v[i + 1]);
            }
        }
        six / 6.0
    }

    /// Splits the polyhedron by `plane`, exactly.
    ///
    /// The section is the plane's polygon within the box's reach (see
    /// [`plane_parallelogram`]) clipped by the planes of the facets that
    /// touch the plane; facets strictly on one side cannot bound it.
    pub fn split(&self, plane: &Plane) -> CellSplit {
        match self.facet_sides(plane) {
            Err(Side::Front) => CellSplit::Front,
            Err(_) => CellSplit::Back,
            Ok((sides, touching)) => {
                let section = self.section(plane, &touching);
                let (back, front) =
                    cut(self.facets.iter().cloned(), plane, &sides, section.clone());
                CellSplit::Both {
                    back,
                    front,
                    section,
                }
            }
        }
    }

    /// [`split`](Self::split), consuming the polyhedron: facets move into
    /// the parts instead of being copied, and a polyhedron on one side comes
    /// back whole.
    pub fn into_split(self, plane: &Plane) -> CellParts {
        match self.facet_sides(plane) {
            Err(Side::Front) => CellParts::Front(self),
            Err(_) => CellParts::Back(self),
            Ok((sides, touching)) => {
                let section = self.section(plane, &touching);
                let (back, front) = cut(self.facets.into_iter(), plane, &sides, section.clone());
                CellParts::Both {
                    back,
                    front,
                    section,
                }
            }
        }
    }

    /// Per facet, whether it has vertices strictly behind and strictly in
    /// front of `plane`, and which facets touch or cross it; or `Err(side)`
    /// if the whole polyhedron lies on one side (`Back` or `Front`).
    fn facet_sides(&self, plane: &Plane) -> Result<FacetSides, Side> {
        let n = self.facets.len();
        let mut sides: SmallVec<[(bool, bool); 24]> = SmallVec::with_capacity(n);
        let mut touching: SmallVec<[usize; 16]> = SmallVec::new();
        let (mut any_back, mut any_front) = (false, false);
        for (k, f) in self.facets.iter().enumerate() {
            // A facet in the plane: the whole polyhedron is on one side.
            if f.support() == plane {
                return Err(Side::Back);
            }
            if f.support().is_opposite(plane) {
                return Err(Side::Front);
            }
            let (mut back, mut front, mut on) = (false, false, false);
            for i in 0..f.len() {
                match f.vertex_side(i, plane) {
                    Side::Back => back = true,
                    Side::Front => front = true,
                    Side::On => on = true,
                }
            }
            any_back |= back;
            any_front |= front;
            if on || (back && front) {
                touching.push(k);
            }
            sides.push((back, front));
        }
        if !any_front {
            return Err(Side::Back);
        }
        if !any_back {
            return Err(Side::Front);
        }
        Ok((sides, touching))
    }

    /// The section by a plane through the interior (vertices strictly on
    /// both sides, so it has area), clipped by the touching facets' planes.
    fn section(&self, plane: &Plane, touching: &[usize]) -> ConvexPolygon {
        let mut section = plane_parallelogram(plane);
        for &k in touching {
            match section.split(self.facets[k].support()) {
                Split::Back | Split::Coplanar(_) => {}
                Split::Both(back, _) => section = back,
                Split::Front => unreachable!("a plane through a cell's interior meets its facets"),
            }
        }
        section.with_source(SECTION_SOURCE)
    }
}

/// Per-facet sides and the touching facets, from `facet_sides`.
type FacetSides = (SmallVec<[(bool, bool); 24]>, SmallVec<[usize; 16]>);

/// The two parts of a polyhedron cut by `plane` through its interior.
fn cut(
    facets: impl Iterator<Item = ConvexPolygon>,
    plane: &Plane,
    sides: &[(bool, bool)],
    section: ConvexPolygon,
) -> (ConvexPolyhedron, ConvexPolyhedron) {
    let n = sides.len();
    let mut back = Vec::with_capacity(n + 1);
    let mut front = Vec::with_capacity(n + 1);
    for (f, &(b, fr)) in facets.zip(sides) {
        match (b, fr) {
            (true, true) => match f.split(plane) {
                Split::Both(bp, fp) => {
                    back.push(bp);
                    front.push(fp);
                }
                _ => unreachable!("a facet with vertices on both sides is cut"),
            },
            (true, false) => back.push(f),
            _ => front.push(f),
        }
    }
    front.push(section.flipped());
    back.push(section);
    (
        ConvexPolyhedron { facets: back },
        ConvexPolyhedron { facets: front },
    )
}

/// The result of [`ConvexPolyhedron::into_split`].
#[derive(Debug, Clone, PartialEq)]
pub enum CellParts {
    /// The polyhedron, wholly behind the plane.
    Back(ConvexPolyhedron),
    /// The polyhedron, wholly in front of the plane.
    Front(ConvexPolyhedron),
    /// The plane cuts the polyhedron's interior.
    Both {
        /// The part behind the plane.
        back: ConvexPolyhedron,
        /// The part in front of the plane.
        front: ConvexPolyhedron,
        /// The plane restricted to the polyhedron, with the plane's
        /// orientation.
        section: ConvexPolygon,
    },
}

/// The part of `plane` over the box's square in the two axes other than
/// the normal's dominant one: a parallelogram containing the plane's part in
/// the bounding box (it may reach outside the box along the dominant axis).
pub fn plane_parallelogram(plane: &Plane) -> ConvexPolygon {
    let k = plane.dominant_axis();
    let (u, w) = ((k + 1) % 3, (k + 2) % 3);
    let axis_plane = |axis: usize, sign: i64| {
        let mut normal = [0_i64; 3];
        normal[axis] = sign;
        let mut p = [0_i32; 3];
        p[axis] = if sign > 0 { GRID_LIMIT } else { -GRID_LIMIT };
        Plane::with_normal_through(
            normal,
            GridPoint {
                x: p[0],
                y: p[1],
                z: p[2],
            },
        )
        .expect("a unit normal")
    };
    // (u, w, k) is a cyclic permutation of (x, y, z): seen from +k, the
    // sides u = +L, w = +L, u = -L, w = -L run counter-clockwise.
    let mut edges = [
        axis_plane(u, 1),
        axis_plane(w, 1),
        axis_plane(u, -1),
        axis_plane(w, -1),
    ];
    if plane.normal()[k] < 0 {
        edges.reverse();
    }
    ConvexPolygon::from_planes(*plane, &edges, SECTION_SOURCE)
        .expect("a plane's dominant axis is transverse to the box's sides")
}

/// The part of `plane` inside the bounding box, `None` if it only touches
/// the box's boundary.
pub fn plane_in_box(plane: &Plane) -> Option<ConvexPolygon> {
    let k = plane.dominant_axis();
    let mut polygon = plane_parallelogram(plane);
    for sign in [1_i64, -1] {
        let mut normal = [0_i64; 3];
        normal[k] = sign;
        let mut p = [0_i32; 3];
        p[k] = if sign > 0 { GRID_LIMIT } else { -GRID_LIMIT };
        let cap = Plane::with_normal_through(
            normal,
            GridPoint {
                x: p[0],
                y: p[1],
                z: p[2],
            },
        )
        .expect("a unit normal");
        match polygon.split(&cap) {
            Split::Back => {}
            Split::Both(back, _) => polygon = back,
            Split::Front => return None,
            Split::Coplanar(_) => {}
        }
    }
    Some(polygon)
}

fn triple(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1])
        + a[1] * (b[2] * c[0] - b[0] * c[2])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gp(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    #[test]
    fn box_volume_and_split() {
        let cell = ConvexPolyhedron::bounding_box();
        let l = f64::from(GRID_LIMIT);
        assert!((cell.volume() - 8.0 * l * l * l).abs() <= 1e-9 * l * l * l);
        let plane = Plane::through(gp(0, 0, 0), gp(1, 0, 0), gp(0, 1, 1)).unwrap();
        let CellSplit::Both {
            back,
            front,
            section,
        } = cell.split(&plane)
        else {
            panic!("the plane cuts the box");
        };
        section.check_invariants().unwrap();
        let total = back.volume() + front.volume();
        assert!((total - cell.volume()).abs() <= 1e-9 * cell.volume());
        for f in back.facets().iter().chain(front.facets()) {
            f.check_invariants().unwrap();
        }
        // The diagonal plane y = z cuts a rectangle of width 2L and length
        // 2L sqrt(2).
        let area = section.area() / plane.unit_normal_f64()[2].abs().max(1e-300);
        assert!(area > 0.0);
    }

    #[test]
    fn half_spaces_make_a_cube() {
        let planes: Vec<Plane> = (0..3)
            .flat_map(|axis| {
                [1_i64, -1].map(|s| {
                    let mut n = [0; 3];
                    n[axis] = s;
                    let mut p = [0; 3];
                    p[axis] = if s > 0 { 10 } else { -6 };
                    Plane::with_normal_through(n, gp(p[0], p[1], p[2])).unwrap()
                })
            })
            .collect();
        let cube = ConvexPolyhedron::from_planes(&planes).unwrap();
        assert!((cube.volume() - 16.0_f64.powi(3)).abs() < 1e-6);
        assert_eq!(cube.input_planes().len(), 6);
        let inverted = [
            planes[0],
            planes[1].flipped().flipped(),
            planes[0].flipped(),
        ];
        assert!(ConvexPolyhedron::from_planes(&inverted).is_none());
    }
}
