//! Winding numbers of a closed surface of convex grid polygons in a solid
//! BSP's empty cell, exactly: what labels a solid's cells when its
//! snapped surface folds or crosses itself (`umbra csg`).
//!
//! The count runs along a ray from a point of the cell's side on its last
//! plane, mostly parallel to a coordinate axis: the ray is a line through
//! two grid points, held by two planes through grid points, and each
//! point it meets a plane at is the kernel's implicit point of three
//! planes, so that every decision (is the start inside the cell, does a
//! face's crossing lie on the ray and inside the face) is an exact side
//! test. A ray that grazes a face's edge or meets a face at its start is
//! not counted: another start is tried. A cell too narrow on its plane for
//! an axis-parallel start there is counted along a steep line that
//! crosses the plane near its side's centroid, or asked at a grid point
//! inside it ([`area_shadow::winding_number`]).

use area_shadow::winding_number;
use bsp_core::predicates::side_of_point;
use bsp_core::{ConvexPolygon, GRID_LIMIT, GridPoint, ImplicitPoint, Plane, Side, Split};
use svbsp::ConvexPolyhedron;

/// A closed surface's faces, each with its grid-coordinate bounding box
/// (an axis-parallel ray meets only faces whose boxes hold its column),
/// to count crossings along rays.
pub(crate) struct Surface<'a> {
    faces: &'a [ConvexPolygon],
    /// Per face, its corners' least and greatest grid coordinates.
    boxes: Vec<([i32; 3], [i32; 3])>,
    /// Per face, its corners and its plane (for
    /// [`area_shadow::winding_number`] at grid points).
    outlines: Vec<Vec<GridPoint>>,
    planes: Vec<Plane>,
}

/// The mean of `points`.
fn centroid(points: &[[f64; 3]]) -> [f64; 3] {
    let n = points.len() as f64;
    std::array::from_fn(|k| points.iter().map(|p| p[k]).sum::<f64>() / n)
}

/// Grid coordinates (along axes `across`) of starts to try near `piece`:
/// its centroid's, points between the centroid and each corner (a long
/// thin piece holds grid points along its middle, seldom at its
/// centroid), and points past its corners (the cell's side may be wider
/// than a piece too thin to hold one), each once.
fn starts(piece: &ConvexPolygon, across: [usize; 2]) -> Vec<[i64; 2]> {
    let corners = piece.vertices_f64();
    let mean = centroid(&corners);
    let centre = across.map(|k| mean[k]);
    let mut out: Vec<[i64; 2]> = Vec::new();
    let mut push = |p: [f64; 2]| {
        let g = p.map(|x| x.round() as i64);
        if !out.contains(&g) {
            out.push(g);
        }
    };
    push(centre);
    for t in [0.5, 0.25, 0.75, 0.9, 1.5, 3.0] {
        for c in &corners {
            let corner = across.map(|k| c[k]);
            push([0, 1].map(|i| centre[i] + t * (corner[i] - centre[i])));
        }
    }
    out
}

impl<'a> Surface<'a> {
    /// The surface of `faces` (convex polygons with grid-point corners,
    /// counter-clockwise seen from outside).
    pub(crate) fn new(faces: &'a [ConvexPolygon]) -> Self {
        let boxes = faces
            .iter()
            .map(|f| {
                (0..f.len()).filter_map(|i| f.vertex_grid_point(i)).fold(
                    ([i32::MAX; 3], [i32::MIN; 3]),
                    |(lo, hi), g| {
                        let g = g.to_array();
                        (
                            std::array::from_fn(|k| lo[k].min(g[k])),
                            std::array::from_fn(|k| hi[k].max(g[k])),
                        )
                    },
                )
            })
            .collect();
        let outlines = faces
            .iter()
            .map(|f| {
                (0..f.len())
                    .filter_map(|i| f.vertex_grid_point(i))
                    .collect()
            })
            .collect();
        let planes = faces.iter().map(|f| *f.support()).collect();
        Self {
            faces,
            boxes,
            outlines,
            planes,
        }
    }

    /// The winding number in a cell bounded by `path` (planes root first,
    /// each with the side the cell lies on; the cell lies against the
    /// last, where `pieces` lie in it): 1 inside a solid the surface
    /// bounds, 0 outside. Counted along a ray into the cell from a point
    /// of the last plane inside the other planes, near the pieces; `None`
    /// if no start tried ([`starts`]) gives a ray clear of every face's
    /// edges.
    pub(crate) fn winding_in(
        &self,
        path: &[(Plane, Side)],
        pieces: &[ConvexPolygon],
    ) -> Option<i64> {
        let (&(plane, side), bounds) = path.split_last()?;
        let axis = plane.dominant_axis();
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        // The ray runs along the axis into the cell.
        let up = (plane.normal()[axis] > 0) == (side == Side::Front);
        // Starts near the pieces, then in the cell's side on the plane
        // (wider than the pieces where they are slivers), found only if
        // the pieces give none.
        let try_starts = |piece: &ConvexPolygon| {
            starts(piece, [u, v]).into_iter().find_map(|[cu, cv]| {
                let ray = Ray::along_axis(axis, [u, v], [cu, cv], up)?;
                let start = ImplicitPoint::new(plane, ray.planes[0], ray.planes[1]).ok()?;
                if bounds.iter().any(|(p, s)| start.side(p) != *s) {
                    return None;
                }
                self.count(&ray, &plane, side)
            })
        };
        if let Some(count) = pieces.iter().find_map(try_starts) {
            return Some(count);
        }
        let section = section(&plane, bounds);
        if let Some(count) = section.as_ref().and_then(try_starts) {
            return Some(count);
        }
        // A side on the plane narrower than a grid step: lines through
        // grid points that cross the plane a small fraction of a step
        // from the side's centroid.
        if let Some(count) = section
            .as_ref()
            .and_then(|section| self.fine_count(&plane, side, bounds, section))
        {
            return Some(count);
        }
        // A cell whose side on the plane holds no start (a wedge that
        // widens away from it): grid points inside the cell, around its
        // corners' centroid.
        let outward: Vec<Plane> = path
            .iter()
            .map(|(p, s)| if *s == Side::Back { *p } else { p.flipped() })
            .collect();
        let cell = ConvexPolyhedron::from_planes(&outward)?;
        let corners: Vec<[f64; 3]> = cell
            .facets()
            .iter()
            .flat_map(|f| f.vertices_f64())
            .collect();
        let centre = centroid(&corners);
        let outlines: Vec<&[GridPoint]> = self.outlines.iter().map(Vec::as_slice).collect();
        let mut tried: Vec<GridPoint> = Vec::new();
        for t in [0.0, 0.5, 0.25, 0.75] {
            for corner in &corners {
                let at = |k: usize| (centre[k] + t * (corner[k] - centre[k])).round() as i64;
                let Ok(g) = GridPoint::new(at(0), at(1), at(2)) else {
                    continue;
                };
                if tried.contains(&g) {
                    continue;
                }
                tried.push(g);
                if path.iter().any(|(p, s)| side_of_point(p, g) != *s) {
                    continue;
                }
                if let Some(w) = winding_number(g, &outlines, &self.planes) {
                    return Some(w);
                }
            }
        }
        None
    }

    /// The count along a steep line into the cell from its side
    /// `section` on `plane` (the cell on `side`, within `bounds`): from a
    /// grid point two or three steps off the plane through one `2^k`
    /// times as far, aimed at the section's centroid, the line crosses the
    /// plane within about `2^-k` of a step from it.
    fn fine_count(
        &self,
        plane: &Plane,
        side: Side,
        bounds: &[(Plane, Side)],
        section: &ConvexPolygon,
    ) -> Option<i64> {
        let corners = section.vertices_f64();
        let centre = centroid(&corners);
        let normal = plane.unit_normal_f64();
        let facing: [i128; 3] = plane.normal().map(i128::from);
        for off in [2.0, -2.0, 3.0, -3.0] {
            let from: [i64; 3] =
                std::array::from_fn(|k| (centre[k] + off * normal[k]).round() as i64);
            for scale in [1_i64 << 8, 1 << 12, 1 << 16] {
                let aim: [i64; 3] = std::array::from_fn(|k| {
                    (scale as f64 * (centre[k] - from[k] as f64)).round() as i64
                });
                let into: i128 = (0..3).map(|k| facing[k] * i128::from(aim[k])).sum();
                if into == 0 {
                    continue;
                }
                // Into the cell: along the aim if it heads to the cell's
                // side of the plane.
                let direction = if (into > 0) == (side == Side::Front) {
                    aim
                } else {
                    aim.map(|c| -c)
                };
                let Some(ray) = Ray::through(from, direction) else {
                    continue;
                };
                let Ok(start) = ImplicitPoint::new(*plane, ray.planes[0], ray.planes[1]) else {
                    continue;
                };
                if bounds.iter().any(|(p, s)| start.side(p) != *s) {
                    continue;
                }
                if let Some(count) = self.count(&ray, plane, side) {
                    return Some(count);
                }
            }
        }
        None
    }

    /// The signed crossings of the faces by `ray`, which starts in `plane`
    /// and runs to its `side`; `None` if the ray grazes a face (meets its
    /// edge, runs in its plane, or meets it at the start). Faces in
    /// `plane` are not met past the start.
    fn count(&self, ray: &Ray, plane: &Plane, side: Side) -> Option<i64> {
        let mut winding = 0;
        for (face, (lo, hi)) in self.faces.iter().zip(&self.boxes) {
            if let Some(([u, v], [cu, cv])) = ray.column {
                // An axis-parallel ray meets only faces whose boxes hold
                // its column.
                if i64::from(lo[u]) > cu
                    || i64::from(hi[u]) < cu
                    || i64::from(lo[v]) > cv
                    || i64::from(hi[v]) < cv
                {
                    continue;
                }
            }
            let support = face.support();
            if support.is_coincident(plane) || support.is_opposite(plane) {
                continue;
            }
            let normal = support.normal();
            let along: i128 = (0..3)
                .map(|k| i128::from(normal[k]) * i128::from(ray.direction[k]))
                .sum();
            if along == 0 {
                // Parallel to the face's plane: it misses the face unless
                // it lies in that plane (then it may run along the face).
                if ray
                    .points
                    .iter()
                    .all(|&p| side_of_point(support, p) == Side::On)
                {
                    return None;
                }
                continue;
            }
            let Ok(hit) = ImplicitPoint::new(*support, ray.planes[0], ray.planes[1]) else {
                return None;
            };
            match hit.side(plane) {
                Side::On => return None,
                s if s != side => continue,
                _ => {}
            }
            let mut inside = true;
            for edge in face.edges() {
                match hit.side(edge) {
                    Side::Back => {}
                    Side::On => return None,
                    Side::Front => {
                        inside = false;
                        break;
                    }
                }
            }
            if inside {
                // Leaving through a face's front (outward) counts one out
                // of the solid.
                winding += if along > 0 { 1 } else { -1 };
            }
        }
        Some(winding)
    }
}

/// The part of `plane` inside the grid's box and on the given side of
/// each of `bounds`; `None` if it is empty.
fn section(plane: &Plane, bounds: &[(Plane, Side)]) -> Option<ConvexPolygon> {
    let axis = plane.dominant_axis();
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let limit = i64::from(GRID_LIMIT);
    let wall = |k: usize, sign: i64| {
        let mut normal = [0_i64; 3];
        normal[k] = sign;
        let mut point = [0_i64; 3];
        point[k] = sign * limit;
        Plane::with_normal_through(normal, GridPoint::new(point[0], point[1], point[2]).ok()?)
    };
    // Counter-clockwise around the axis: v low, u high, v high, u low.
    let mut walls = [wall(v, -1)?, wall(u, 1)?, wall(v, 1)?, wall(u, -1)?];
    if plane.normal()[axis] < 0 {
        walls.reverse();
    }
    let mut part = ConvexPolygon::from_planes(*plane, &walls, 0).ok()?;
    for (bound, side) in bounds {
        part = match (part.split(bound), side) {
            (Split::Back, Side::Back) | (Split::Front, Side::Front) => part,
            (Split::Both(back, _), Side::Back) => back,
            (Split::Both(_, front), Side::Front) => front,
            _ => return None,
        };
    }
    Some(part)
}

/// A directed line through two grid points, as the two planes that hold
/// it (each crossing is the implicit point of a face's plane and these).
struct Ray {
    planes: [Plane; 2],
    /// Two of its grid points, `points[1] - points[0] = direction`.
    points: [GridPoint; 2],
    direction: [i64; 3],
    /// Of a ray parallel to an axis: the other two axes and its
    /// coordinates on them (a face's box must hold them to be met).
    column: Option<([usize; 2], [i64; 2])>,
}

impl Ray {
    /// The ray parallel to `axis` through `at` on the axes `across`, up or
    /// down the axis.
    fn along_axis(axis: usize, across: [usize; 2], at: [i64; 2], up: bool) -> Option<Self> {
        let mut from = [0_i64; 3];
        from[across[0]] = at[0];
        from[across[1]] = at[1];
        let mut direction = [0_i64; 3];
        direction[axis] = if up { 1 } else { -1 };
        let mut ray = Self::through(from, direction)?;
        ray.column = Some((across, at));
        Some(ray)
    }

    /// The ray from grid point `from` along the integer `direction`.
    fn through(from: [i64; 3], direction: [i64; 3]) -> Option<Self> {
        let point = |p: [i64; 3]| GridPoint::new(p[0], p[1], p[2]).ok();
        let a = point(from)?;
        let b = point(std::array::from_fn(|k| from[k] + direction[k]))?;
        // Two planes through the line, each holding a unit step off it
        // along an axis the direction leans least on.
        let mut axes = [0, 1, 2];
        axes.sort_by_key(|&k| direction[k].unsigned_abs());
        let plane = |k: usize| {
            let mut off = from;
            off[k] += 1;
            Plane::through(a, b, point(off)?)
        };
        Some(Self {
            planes: [plane(axes[0])?, plane(axes[1])?],
            points: [a, b],
            direction,
            column: None,
        })
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    fn g(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint::new(x, y, z).expect("a grid point")
    }

    /// A box `[lo, hi]` as six quads, counter-clockwise seen from outside.
    pub(crate) fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Vec<ConvexPolygon> {
        let (lo, hi) = (g(lo[0], lo[1], lo[2]), g(hi[0], hi[1], hi[2]));
        let solid = svbsp::ConvexPolyhedron::axis_box(lo, hi).expect("a box with volume");
        solid.facets().to_vec()
    }

    /// The winding number just off `face` on its `side` (a cell bounded by
    /// its plane alone).
    fn off(surface: &Surface<'_>, face: &ConvexPolygon, side: Side) -> Option<i64> {
        surface.winding_in(&[(*face.support(), side)], std::slice::from_ref(face))
    }

    /// Just behind a box's faces the winding number is 1, just in front 0;
    /// with a second box inside the first (both wound out), 2 between the
    /// inner box's faces and 1 outside them; a face turned inside out
    /// counts the other way.
    #[test]
    fn boxes_wind_once_inside_and_nested_twice() {
        let outer = cuboid([-40, -40, -40], [40, 40, 40]);
        let surface = Surface::new(&outer);
        for face in &outer {
            assert_eq!(off(&surface, face, Side::Back), Some(1));
            assert_eq!(off(&surface, face, Side::Front), Some(0));
        }
        let mut nested = outer.clone();
        nested.extend(cuboid([-10, -10, -10], [10, 10, 10]));
        let surface = Surface::new(&nested);
        for face in &nested[6..] {
            assert_eq!(off(&surface, face, Side::Back), Some(2));
            assert_eq!(off(&surface, face, Side::Front), Some(1));
        }
        let mut turned = outer.clone();
        turned.extend(
            cuboid([-10, -10, -10], [10, 10, 10])
                .iter()
                .map(|f| f.flipped()),
        );
        let surface = Surface::new(&turned);
        for face in &turned[6..] {
            assert_eq!(off(&surface, face, Side::Front), Some(0));
            assert_eq!(off(&surface, face, Side::Back), Some(1));
        }
    }

    /// Starts lie in the cell: one a grid step wide on the plane is
    /// counted along a steep line (no axis-parallel start fits), one
    /// wider from a start past its piece; a cell outside the box and one
    /// inside it are told apart.
    #[test]
    fn a_start_must_lie_in_the_cell() {
        let outer = cuboid([-40, -40, -40], [40, 40, 40]);
        let surface = Surface::new(&outer);
        let sliver =
            ConvexPolygon::from_grid_points(&[g(-30, 0, 5), g(30, 0, 5), g(30, 1, 5)], 0).unwrap();
        let plane = *sliver.support();
        let slab = |y: i64| Plane::with_normal_through([0, 1, 0], g(0, y, 0)).unwrap();
        let pieces = std::slice::from_ref(&sliver);
        // The cell z > 5, 0 < y < 1: no grid point inside it.
        let narrow = [
            (slab(0), Side::Front),
            (slab(1), Side::Back),
            (plane, Side::Front),
        ];
        assert_eq!(surface.winding_in(&narrow, pieces), Some(1));
        let wide = [
            (slab(-5), Side::Front),
            (slab(5), Side::Back),
            (plane, Side::Front),
        ];
        assert_eq!(surface.winding_in(&wide, pieces), Some(1));
        // Past the box's side x = 40: outside.
        let beyond = Plane::with_normal_through([1, 0, 0], g(41, 0, 0)).unwrap();
        let outside = [
            (beyond, Side::Front),
            (slab(0), Side::Front),
            (slab(1), Side::Back),
            (plane, Side::Front),
        ];
        let far =
            ConvexPolygon::from_grid_points(&[g(50, 0, 5), g(90, 0, 5), g(90, 1, 5)], 0).unwrap();
        assert_eq!(
            surface.winding_in(&outside, std::slice::from_ref(&far)),
            Some(0)
        );
    }
}
