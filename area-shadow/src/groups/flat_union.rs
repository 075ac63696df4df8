//! Coplanar pieces whose union is a polygon that is not convex (a concave
//! input polygon cut into convex pieces, an L of two quads): they hide all
//! of a light together from points where no one of them does, and that
//! region is polyhedral too.
//!
//! Let `U` be the union, in plane `P`, wholly in front of a light `L`. A
//! point `p` beyond `P` sees none of `L` exactly when `L_p`, the light
//! projected through `p` onto `P`, lies in `U`. With `H` the convex hull of
//! `U`, and its *pockets* `H \ U` cut into triangles `T_k` (their vertices
//! are `U`'s and `H`'s, grid points), `L_p` lies in `U` exactly when it
//! lies in `H` and meets no `T_k`'s interior: when `p` lies in `H`'s umbra
//! volume and outside every `T_k`'s penumbra volume. That is a convex
//! volume with convex volumes taken out: a union of convex parts, found by
//! taking a volume `B` (behind planes `b_1..b_m`) out of each part `A` as
//! the parts `A`, behind `b_1..b_{j-1}`, in front of `b_j` (`j = 1..m`),
//! the empty ones dropped. Every plane is one of the volumes', through
//! three grid points.

use super::{cross, difference};
use crate::AreaSource;
use crate::volumes::volume_planes;
use bsp_core::predicates::Side;
use bsp_core::{ConvexPolygon, GridPoint, Plane};
use std::cmp::Ordering;
use svbsp::{CellParts, ConvexPolyhedron};

/// The most vertices of a union's outline looked at (its simplicity is
/// checked pair by pair); bigger unions form no group.
const MAX_OUTLINE: usize = 256;

/// The most convex parts one union's umbra is cut into; a union whose
/// pockets would cut it into more keeps its pieces' umbrae only.
const MAX_PARTS: usize = 64;

/// Coplanar pieces, facing one way and edge-connected, covering once a
/// polygon that is not convex: a simple outline, with holes or not. (The
/// holes are pockets of the hull too.)
#[derive(Debug, Clone, PartialEq)]
pub struct FlatUnion {
    /// The pieces' indices, ascending.
    pub pieces: Vec<u32>,
    /// The polygon, counter-clockwise seen from the front of `support`.
    outline: Vec<GridPoint>,
    /// Its holes, each clockwise.
    holes: Vec<Vec<GridPoint>>,
    support: Plane,
    /// For a section through a closed surface (module `section`): what
    /// it casts under.
    section: Option<Section>,
}

/// What a section through a closed surface casts under: a light whose
/// plane's normal is nearest to its axis (the others see it nearly edge
/// on), with all of the surface in front. (A segment from a point of the
/// section, inside the surface, to the light must cross the surface only
/// when the light is outside; the light's plane then separates them.)
#[derive(Debug, Clone, PartialEq)]
struct Section {
    axis: usize,
    /// The surface's corners.
    surface: Vec<GridPoint>,
}

impl FlatUnion {
    /// The union of pieces `pieces` in plane `support` whose unmatched
    /// edges form the cycles `cycles`, if one of them runs
    /// counter-clockwise seen from the front (the outline) and the others
    /// clockwise (holes), no two edges meet but at a shared corner, and
    /// the region is not convex (a hole, or a concave outline).
    pub(super) fn new(
        pieces: Vec<u32>,
        cycles: Vec<Vec<GridPoint>>,
        support: Plane,
    ) -> Option<Self> {
        let union = Self::of_cycles(pieces, cycles, support, None)?;
        let n = union.outline.len();
        let convex = (0..n).all(|i| {
            let [a, b, c] = [i, (i + 1) % n, (i + 2) % n].map(|k| union.outline[k]);
            union.turn(a, b, c) != Ordering::Less
        });
        ((!convex || !union.holes.is_empty()) && union.is_simple()).then_some(union)
    }

    /// A section along `axis` through the closed surface of pieces
    /// `pieces` with corners `surface` (module `section`): the region of
    /// `cycles` (as for [`Self::new`], in plane `support`), convex or not,
    /// if simple.
    pub(super) fn section(
        pieces: Vec<u32>,
        cycles: Vec<Vec<GridPoint>>,
        support: Plane,
        axis: usize,
        surface: Vec<GridPoint>,
    ) -> Option<Self> {
        let section = Section { axis, surface };
        Self::of_cycles(pieces, cycles, support, Some(section)).filter(Self::is_simple)
    }

    /// The union of `cycles` sorted into its outline and holes, if one
    /// runs counter-clockwise and the others clockwise.
    fn of_cycles(
        pieces: Vec<u32>,
        cycles: Vec<Vec<GridPoint>>,
        support: Plane,
        section: Option<Section>,
    ) -> Option<Self> {
        let corners: usize = cycles.iter().map(Vec::len).sum();
        if corners > MAX_OUTLINE || cycles.iter().any(|c| c.len() < 3) {
            return None;
        }
        let mut union = Self {
            pieces,
            outline: Vec::new(),
            holes: Vec::new(),
            support,
            section,
        };
        for cycle in cycles {
            match union.winding(&cycle) {
                Ordering::Greater if union.outline.is_empty() => union.outline = cycle,
                Ordering::Less => union.holes.push(cycle),
                _ => return None,
            }
        }
        (!union.outline.is_empty()).then_some(union)
    }

    /// The outline and the holes.
    #[cfg(test)]
    pub(super) fn cycles(&self) -> impl Iterator<Item = &[GridPoint]> {
        std::iter::once(self.outline.as_slice()).chain(self.holes.iter().map(Vec::as_slice))
    }

    /// A section's axis (module `section`), `None` for a union of
    /// coplanar pieces.
    #[cfg(test)]
    pub(super) fn axis(&self) -> Option<usize> {
        self.section.as_ref().map(|s| s.axis)
    }

    /// The sign of a cycle's area seen from the front: `Greater` when it
    /// runs counter-clockwise, exactly.
    fn winding(&self, cycle: &[GridPoint]) -> Ordering {
        let n = self.support.normal().map(i128::from);
        // Each term below 2^103, at most MAX_OUTLINE of them.
        let twice_area: i128 = (1..cycle.len().saturating_sub(1))
            .map(|i| {
                let c = cross(
                    difference(cycle[0], cycle[i]),
                    difference(cycle[0], cycle[i + 1]),
                );
                c[0] * n[0] + c[1] * n[1] + c[2] * n[2]
            })
            .sum();
        twice_area.cmp(&0)
    }

    /// The convex parts of the union's umbra under `light`, each a list of
    /// planes with the part behind all of them: the points from which the
    /// pieces together hide all of the light. Empty when the union does not
    /// lie strictly in front of the light, or would need too many parts,
    /// and for a section through a closed surface ([`crate::section_unions`])
    /// but under a light whose plane's normal is nearest to its axis, with
    /// all of the surface in front.
    pub fn umbra_parts(&self, light: &AreaSource) -> Vec<Vec<Plane>> {
        if let Some(section) = &self.section {
            let facing = light.support().dominant_axis() == section.axis;
            if !facing
                || section
                    .surface
                    .iter()
                    .any(|&p| light.side_of_point(p) != Side::Front)
            {
                return Vec::new();
            }
        }
        if self
            .outline
            .iter()
            .any(|&p| light.side_of_point(p) != Side::Front)
        {
            return Vec::new();
        }
        let Some(hull) = self.hull() else {
            return Vec::new();
        };
        let Some(umbra) = volume_planes(&hull, light).umbra else {
            return Vec::new();
        };
        let Some(pockets) = self.pockets() else {
            return Vec::new();
        };
        let Some(first) = ConvexPolyhedron::from_planes(&umbra) else {
            return Vec::new();
        };
        // The parts are carried as polyhedra, cut one plane at a time:
        // rebuilding each candidate from its planes cost the furnished room
        // twice its shadow time.
        let mut parts = vec![first];
        for pocket in pockets {
            for taken in volume_planes(&pocket, light).penumbra {
                parts = parts
                    .into_iter()
                    .flat_map(|part| without(part, &taken))
                    .collect();
                if parts.len() > MAX_PARTS {
                    return Vec::new();
                }
            }
        }
        let frame: Vec<Plane> = ConvexPolyhedron::bounding_box()
            .facets()
            .iter()
            .map(|f| *f.support())
            .collect();
        parts
            .iter()
            .map(|part| {
                let mut planes: Vec<Plane> = Vec::new();
                for facet in part.facets() {
                    let plane = facet.support();
                    if !frame.contains(plane) && !planes.contains(plane) {
                        planes.push(*plane);
                    }
                }
                planes
            })
            .collect()
    }

    /// How `c` turns from the line `ab`, seen from the front of the plane:
    /// `Greater` to the left (counter-clockwise), exactly.
    fn turn(&self, a: GridPoint, b: GridPoint, c: GridPoint) -> Ordering {
        let cross = cross(difference(a, b), difference(a, c));
        let n = self.support.normal().map(i128::from);
        // |cross| < 2^51 and |n| < 2^51: the sum is below 2^104.
        (cross[0] * n[0] + cross[1] * n[1] + cross[2] * n[2]).cmp(&0)
    }

    /// Whether no two edges of the outline and the holes meet but at the
    /// corner two neighbours share.
    fn is_simple(&self) -> bool {
        let cycles: Vec<&Vec<GridPoint>> =
            std::iter::once(&self.outline).chain(&self.holes).collect();
        let edges: Vec<(usize, usize, (GridPoint, GridPoint))> = cycles
            .iter()
            .enumerate()
            .flat_map(|(c, cycle)| {
                let n = cycle.len();
                (0..n).map(move |i| (c, i, (cycle[i], cycle[(i + 1) % n])))
            })
            .collect();
        edges.iter().enumerate().all(|(k, &(c, i, e))| {
            edges[k + 1..].iter().all(|&(d, j, f)| {
                let n = cycles[c].len();
                let adjacent = c == d && (j == i + 1 || (i == 0 && j == n - 1));
                !self.segments_meet(e, f, adjacent)
            })
        })
    }

    /// Whether the closed segments meet; for `adjacent` ones (sharing an
    /// end), whether they meet anywhere else.
    fn segments_meet(
        &self,
        (a, b): (GridPoint, GridPoint),
        (c, d): (GridPoint, GridPoint),
        adjacent: bool,
    ) -> bool {
        let (c_side, d_side) = (self.turn(a, b, c), self.turn(a, b, d));
        let (a_side, b_side) = (self.turn(c, d, a), self.turn(c, d, b));
        if c_side == Ordering::Equal && d_side == Ordering::Equal {
            // Collinear: they overlap beyond a shared end when one's end
            // lies strictly inside the other.
            let inside =
                |p: GridPoint, (s, t): (GridPoint, GridPoint)| p != s && p != t && within(p, s, t);
            return inside(c, (a, b))
                || inside(d, (a, b))
                || inside(a, (c, d))
                || inside(b, (c, d))
                || (!adjacent && (within(c, a, b) || within(d, a, b)));
        }
        if adjacent {
            // Not collinear, one shared end: they meet only there.
            return false;
        }
        c_side != d_side
            && a_side != b_side
            && (c_side != Ordering::Equal || within(c, a, b))
            && (d_side != Ordering::Equal || within(d, a, b))
            && (a_side != Ordering::Equal || within(a, c, d))
            && (b_side != Ordering::Equal || within(b, c, d))
    }

    /// The convex hull, as a polygon in the union's plane facing its way
    /// (Melkman's algorithm on the simple outline).
    fn hull(&self) -> Option<ConvexPolygon> {
        let left = |a, b, c| self.turn(a, b, c) == Ordering::Greater;
        let points = &self.outline;
        let mut deque: std::collections::VecDeque<GridPoint> = std::collections::VecDeque::new();
        // Start from three points that turn.
        let start = (0..points.len()).find(|&i| {
            let n = points.len();
            self.turn(points[i], points[(i + 1) % n], points[(i + 2) % n]) != Ordering::Equal
        })?;
        let n = points.len();
        let (a, b, c) = (
            points[start],
            points[(start + 1) % n],
            points[(start + 2) % n],
        );
        if left(a, b, c) {
            deque.extend([c, a, b, c]);
        } else {
            deque.extend([c, b, a, c]);
        }
        for k in 3..n {
            let p = points[(start + k) % n];
            let len = deque.len();
            if left(deque[len - 2], deque[len - 1], p) && left(p, deque[0], deque[1]) {
                continue;
            }
            while deque.len() > 2 {
                let len = deque.len();
                if left(deque[len - 2], deque[len - 1], p) {
                    break;
                }
                deque.pop_back();
            }
            deque.push_back(p);
            while deque.len() > 2 {
                if left(p, deque[0], deque[1]) {
                    break;
                }
                deque.pop_front();
            }
            deque.push_front(p);
        }
        deque.pop_back();
        let hull: Vec<GridPoint> = deque.into_iter().collect();
        let polygon = ConvexPolygon::from_grid_points(&hull, 0).ok()?;
        (polygon.support() == &self.support).then_some(polygon)
    }

    /// The pockets between the hull and the outline, and the holes, each
    /// whole if convex, else cut into triangles, facing the union's way;
    /// `None` if one cannot be cut (not reached for simple cycles).
    fn pockets(&self) -> Option<Vec<ConvexPolygon>> {
        let hull = self.hull()?;
        // Outline vertices on the hull's boundary (its corners, and points
        // of its edges) split the pockets: between two of them the outline
        // leaves the hull and comes back.
        let corners: Vec<GridPoint> = (0..hull.len())
            .filter_map(|k| hull.vertex_grid_point(k))
            .collect();
        let h = corners.len();
        let on_hull: Vec<bool> = self
            .outline
            .iter()
            .map(|&p| {
                (0..h).any(|k| {
                    let (s, t) = (corners[k], corners[(k + 1) % h]);
                    self.turn(s, t, p) == Ordering::Equal && within(p, s, t)
                })
            })
            .collect();
        let corners: Vec<usize> = (0..self.outline.len()).filter(|&i| on_hull[i]).collect();
        let n = self.outline.len();
        let mut triangles = Vec::new();
        for (k, &from) in corners.iter().enumerate() {
            let to = corners[(k + 1) % corners.len()];
            let steps = (to + n - from) % n;
            if steps <= 1 {
                continue;
            }
            // The outline from one hull corner to the next, then back
            // along the hull edge: the pocket, clockwise; reversed, it is
            // counter-clockwise.
            let mut pocket: Vec<GridPoint> =
                (0..=steps).map(|s| self.outline[(from + s) % n]).collect();
            pocket.reverse();
            triangles.extend(self.convex_parts(pocket)?);
        }
        // Each hole, clockwise, is a pocket reversed.
        for hole in &self.holes {
            let mut pocket = hole.clone();
            pocket.reverse();
            triangles.extend(self.convex_parts(pocket)?);
        }
        Some(triangles)
    }

    /// A simple counter-clockwise polygon itself when it is convex (its
    /// straight corners dropped: one penumbra volume to take out of the
    /// umbra rather than one per triangle, and fewer parts), else cut
    /// into triangles ([`Self::ear_clip`]).
    fn convex_parts(&self, polygon: Vec<GridPoint>) -> Option<Vec<ConvexPolygon>> {
        let n = polygon.len();
        let turns: Vec<Ordering> = (0..n)
            .map(|i| self.turn(polygon[(i + n - 1) % n], polygon[i], polygon[(i + 1) % n]))
            .collect();
        if turns.contains(&Ordering::Less) {
            return self.ear_clip(polygon);
        }
        let corners: Vec<GridPoint> = polygon
            .iter()
            .zip(&turns)
            .filter(|(_, turn)| **turn == Ordering::Greater)
            .map(|(p, _)| *p)
            .collect();
        match ConvexPolygon::from_grid_points(&corners, 0) {
            Ok(convex) if convex.support() == &self.support => Some(vec![convex]),
            _ => self.ear_clip(polygon),
        }
    }

    /// A simple counter-clockwise polygon cut into triangles by ear
    /// clipping, exactly; straight vertices are dropped without a
    /// triangle.
    fn ear_clip(&self, mut polygon: Vec<GridPoint>) -> Option<Vec<ConvexPolygon>> {
        let mut out = Vec::new();
        while polygon.len() >= 3 {
            let n = polygon.len();
            let ear = (0..n).find_map(|i| {
                let (a, b, c) = (polygon[(i + n - 1) % n], polygon[i], polygon[(i + 1) % n]);
                match self.turn(a, b, c) {
                    Ordering::Equal => Some((i, None)),
                    Ordering::Less => None,
                    Ordering::Greater => {
                        let blocked = polygon.iter().any(|&p| {
                            p != a
                                && p != b
                                && p != c
                                && self.turn(a, b, p) != Ordering::Less
                                && self.turn(b, c, p) != Ordering::Less
                                && self.turn(c, a, p) != Ordering::Less
                        });
                        (!blocked).then_some((i, Some([a, b, c])))
                    }
                }
            })?;
            let (i, triangle) = ear;
            if let Some(t) = triangle {
                out.push(ConvexPolygon::from_grid_points(&t, 0).ok()?);
            }
            polygon.remove(i);
        }
        Some(out)
    }
}

/// Whether grid point `p`, on the line `st`, lies on the closed segment.
fn within(p: GridPoint, s: GridPoint, t: GridPoint) -> bool {
    let between = |p: i32, s: i32, t: i32| s.min(t) <= p && p <= s.max(t);
    between(p.x, s.x, t.x) && between(p.y, s.y, t.y) && between(p.z, s.z, t.z)
}

/// The convex parts of `part` outside the convex volume behind `taken`:
/// `part` itself when they share no interior.
fn without(part: ConvexPolyhedron, taken: &[Plane]) -> Vec<ConvexPolyhedron> {
    let mut out = Vec::new();
    let mut rest = part.clone();
    for plane in taken {
        match rest.into_split(plane) {
            CellParts::Back(back) => rest = back,
            // What is left lies outside the volume: so does all of `part`.
            CellParts::Front(_) => return vec![part],
            CellParts::Both { back, front, .. } => {
                out.push(front);
                rest = back;
            }
        }
    }
    out
}
