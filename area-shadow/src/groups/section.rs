//! Flat sections through closed surfaces that are no convex body: a
//! region of a plane that lies inside the surface hides from a point what
//! the solid does through it, so its umbra (a flat union's, exact and
//! bounded by planes, module `flat_union`) is part of the surface's.
//!
//! Where cores (modules `kernel`, `cores`) must stay convex inside a
//! bent body, a section follows it: the plane through the middle of a
//! torus's ring meets it in an annulus that hides the light from nearly
//! all the floor the ring hides it from under a light above it, where
//! the torus's cores are short chunks of its tube with gaps between.
//!
//! Per axis, the section is made in floating point and then checked
//! exactly:
//!
//! 1. the grid planes `x_axis = c` through no vertex whose sections,
//!    among [`LEVELS`] levels across the surface's extent, are widest
//!    ([`PER_AXIS`] of them: a torus's floor umbra grows by an eighth from
//!    one to three, by a seventieth more with five);
//! 2. each face crossing it gives a segment, with the inside of the
//!    surface on its left seen from the plane's front (decided by the
//!    face's outline turning about its outward normal, exactly), chained
//!    into loops through the edges they end on;
//! 3. each loop is cut to at most [`MAX_LOOP_CORNERS`] corners and moved
//!    inside, each edge by its inset and by how far the corners it cut
//!    off stand inside it, then rounded to grid points;
//! 4. the region is kept when every corner lies inside the surface
//!    (winding number at least 1, module `winding`), no edge of it meets
//!    a face, and no point where an edge of the surface crosses the plane
//!    lies in it or on its boundary: the region is then connected and
//!    meets no face, so it lies inside the surface. Otherwise a larger
//!    inset is tried.
//!
//! A section's union casts only under lights whose plane's normal is
//! nearest to its axis, with all of the surface in front
//! ([`FlatUnion::umbra_parts`]): the others see it nearly edge on, and
//! another axis's section serves them; and a segment from a point of the
//! section to the light crosses the surface only when the light is
//! outside it, as the light's plane then makes sure.

use super::flat_union::FlatUnion;
use super::winding::winding_number;
use crate::hash::HashMap;
use bsp_core::predicates::{Side, orient3d_f64, side_of_point};
use bsp_core::{GridPoint, Plane};

/// Levels tried across the surface's extent along an axis.
const LEVELS: i64 = 7;

/// Sections per axis, the widest levels first.
const PER_AXIS: usize = 3;

/// The most corners a loop keeps: a union's umbra is cut into about as
/// many parts as its hole has corners, and at most 64 are made.
const MAX_LOOP_CORNERS: usize = 24;

/// Insets tried, in grid units: rounding moves a corner by up to 0.71,
/// less than a quarter of the least.
const INSETS: [f64; 3] = [4.0, 32.0, 256.0];

/// The sections (module docs) of the closed surface of convex `outlines`
/// (grid points, counter-clockwise seen from the front of their own
/// planes) whose planes `faces` face out, as flat unions of pieces
/// `pieces`: per axis at most [`PER_AXIS`] levels, a union per loop
/// holding no other.
pub(super) fn sections(
    outlines: &[&[GridPoint]],
    faces: &[Plane],
    pieces: &[u32],
) -> Vec<FlatUnion> {
    let surface = Surface::new(outlines, faces);
    (0..3)
        .flat_map(|axis| {
            let levels = surface.widest_levels(axis);
            levels
                .into_iter()
                .flat_map(|level| surface.section(axis, level, pieces))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// A closed surface, faces facing out.
struct Surface<'a> {
    outlines: &'a [&'a [GridPoint]],
    faces: &'a [Plane],
    /// Per face: whether its outline turns counter-clockwise about its
    /// outward normal (the surface's pieces face out, not in).
    counter_clockwise: Vec<bool>,
    /// Per face, its box (grid units).
    boxes: Vec<([f64; 3], [f64; 3])>,
    /// The surface's corners, ascending.
    corners: Vec<GridPoint>,
}

/// A point where an edge of the surface crosses a section's plane: the
/// edge (its ends in ascending order) and the point's in-plane
/// coordinates.
#[derive(Debug, Clone, Copy)]
struct Crossing {
    edge: (GridPoint, GridPoint),
    at: [f64; 2],
}

/// A loop of points in a section's plane (in-plane coordinates).
type Loop = Vec<[f64; 2]>;

/// The in-plane coordinates of an axis's planes: `(u, v, axis)` is
/// right-handed, so counter-clockwise in `(u, v)` is so seen from `+axis`.
fn plane_axes(axis: usize) -> [usize; 2] {
    [(axis + 1) % 3, (axis + 2) % 3]
}

impl<'a> Surface<'a> {
    fn new(outlines: &'a [&'a [GridPoint]], faces: &'a [Plane]) -> Self {
        let counter_clockwise = outlines
            .iter()
            .zip(faces)
            .map(|(outline, face)| turns_counter_clockwise(outline, face))
            .collect();
        let boxes = outlines
            .iter()
            .map(|outline| {
                let mut lo = [f64::INFINITY; 3];
                let mut hi = [f64::NEG_INFINITY; 3];
                for p in outline.iter() {
                    let p = p.to_f64();
                    for k in 0..3 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                (lo, hi)
            })
            .collect();
        let mut corners: Vec<GridPoint> = outlines.iter().flat_map(|o| o.iter().copied()).collect();
        corners.sort_unstable();
        corners.dedup();
        Self {
            outlines,
            faces,
            counter_clockwise,
            boxes,
            corners,
        }
    }

    /// The section along `axis` (module docs), as flat unions.
    fn section(&self, axis: usize, level: i64, pieces: &[u32]) -> Vec<FlatUnion> {
        let Some(loops) = self.loops(axis, level) else {
            return Vec::new();
        };
        let crossings: Vec<Crossing> = loops.iter().flatten().copied().collect();
        let support = section_plane(axis, level);
        // Outer loops (counter-clockwise) with the holes (clockwise) in
        // them: a union each.
        let points = |l: &Vec<Crossing>| l.iter().map(|c| c.at).collect::<Vec<_>>();
        let (outer, holes): (Vec<Loop>, Vec<Loop>) =
            loops.iter().map(points).partition(|l| area(l) > 0.0);
        let mut unions = Vec::new();
        for o in &outer {
            let inside: Vec<&Loop> = holes.iter().filter(|h| contains(o, h[0])).collect();
            let region: Vec<&Loop> = std::iter::once(o).chain(inside).collect();
            let union = INSETS.iter().find_map(|&inset| {
                let cycles: Vec<Vec<GridPoint>> = region
                    .iter()
                    .map(|l| inset_loop(l, inset, axis, level))
                    .collect::<Option<_>>()?;
                if !self.holds(&cycles, axis, level, &crossings) {
                    return None;
                }
                FlatUnion::section(
                    pieces.to_vec(),
                    cycles,
                    *support.as_ref()?,
                    axis,
                    self.corners.clone(),
                )
            });
            unions.extend(union);
        }
        unions
    }

    /// The level (a grid coordinate along `axis` in no vertex's plane)
    /// among [`LEVELS`] across the surface whose section is widest.
    fn widest_levels(&self, axis: usize) -> Vec<i64> {
        let coordinate = |p: &GridPoint| i64::from(p.to_array()[axis]);
        let mut taken: Vec<i64> = self.corners.iter().map(coordinate).collect();
        taken.sort_unstable();
        taken.dedup();
        let (Some(&lo), Some(&hi)) = (taken.first(), taken.last()) else {
            return Vec::new();
        };
        if hi - lo < 4 {
            return Vec::new();
        }
        let mut widths: Vec<(f64, i64)> = (1..=LEVELS)
            .filter_map(|k| {
                let mut level = lo + (hi - lo) * k / (LEVELS + 1);
                while taken.binary_search(&level).is_ok() {
                    level += 1;
                }
                let loops = self.loops(axis, level)?;
                let width: f64 = loops
                    .iter()
                    .map(|l| area(&l.iter().map(|c| c.at).collect::<Vec<_>>()))
                    .sum();
                (level < hi && width > 0.0).then_some((width, level))
            })
            .collect();
        widths.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        widths.dedup_by_key(|w| w.1);
        widths
            .into_iter()
            .take(PER_AXIS)
            .map(|(_, level)| level)
            .collect()
    }

    /// The section's loops at `level` (a plane through no vertex), each
    /// with the inside of the surface on its left; `None` when the
    /// segments do not chain into loops (not reached for a closed
    /// surface).
    fn loops(&self, axis: usize, level: i64) -> Option<Vec<Vec<Crossing>>> {
        // Each crossing face's segment, from its start to its end.
        let mut next: HashMap<(GridPoint, GridPoint), Crossing> = HashMap::default();
        for (f, outline) in self.outlines.iter().enumerate() {
            let (lo, hi) = self.boxes[f];
            let l = level as f64;
            if lo[axis] > l || hi[axis] < l {
                continue;
            }
            let n = outline.len();
            let height = |p: GridPoint| i64::from(p.to_array()[axis]) - level;
            let (mut up, mut down) = (None, None);
            for i in 0..n {
                let (a, b) = (outline[i], outline[(i + 1) % n]);
                match (height(a) < 0, height(b) < 0) {
                    (true, false) => up = Some(crossing(a, b, axis, level)),
                    (false, true) => down = Some(crossing(a, b, axis, level)),
                    _ => {}
                }
            }
            let (Some(up), Some(down)) = (up, down) else {
                continue;
            };
            // Walked counter-clockwise about the outward normal, the
            // segment runs from the edge going down to the one going up
            // (module docs).
            let (start, end) = if self.counter_clockwise[f] {
                (down, up)
            } else {
                (up, down)
            };
            if next.insert(start.edge, end).is_some() {
                return None;
            }
        }
        let mut loops = Vec::new();
        while let Some(&first) = next.keys().min() {
            let mut cycle = Vec::new();
            let mut at = first;
            loop {
                let end = next.remove(&at)?;
                cycle.push(end);
                at = end.edge;
                if at == first {
                    break;
                }
            }
            loops.push(cycle);
        }
        Some(loops)
    }

    /// Whether the region of `cycles` (grid points in the plane
    /// `x_axis = level`) lies inside the surface, exactly (module docs):
    /// its corners inside, its edges meeting no face, and none of the
    /// surface's `crossings` of the plane in it or on its boundary.
    fn holds(
        &self,
        cycles: &[Vec<GridPoint>],
        axis: usize,
        level: i64,
        crossings: &[Crossing],
    ) -> bool {
        let corners_inside = cycles
            .iter()
            .flatten()
            .all(|&p| winding_number(p, self.outlines, self.faces).is_some_and(|w| w >= 1));
        if !corners_inside {
            return false;
        }
        let edges_clear = cycles.iter().all(|cycle| {
            let n = cycle.len();
            (0..n).all(|i| !self.meets_face(cycle[i], cycle[(i + 1) % n]))
        });
        edges_clear
            && crossings
                .iter()
                .all(|c| !in_or_on(cycles, c.edge, axis, level))
    }

    /// Whether the segment `pq` meets a face (closed: touching counts).
    fn meets_face(&self, p: GridPoint, q: GridPoint) -> bool {
        let (a, b) = (p.to_f64(), q.to_f64());
        self.outlines.iter().enumerate().any(|(f, outline)| {
            let (lo, hi) = self.boxes[f];
            if (0..3).any(|k| a[k].max(b[k]) < lo[k] || a[k].min(b[k]) > hi[k]) {
                return false;
            }
            let face = &self.faces[f];
            let (sp, sq) = (side_of_point(face, p), side_of_point(face, q));
            if sp == sq && sp != Side::On {
                return false;
            }
            if sp == Side::On && sq == Side::On {
                // In the face's plane: taken to meet it.
                return true;
            }
            // The line crosses the plane at one point, inside the closed
            // outline when it turns no way against any edge.
            let n = outline.len();
            let turns: Vec<Side> = (0..n)
                .map(|i| orient3d_f64(a, b, outline[i].to_f64(), outline[(i + 1) % n].to_f64()))
                .collect();
            let positive = turns.contains(&Side::Front);
            let negative = turns.contains(&Side::Back);
            !(positive && negative)
        })
    }
}

/// Whether `outline` turns counter-clockwise about `face`'s normal: the
/// sign of its area along it, exactly.
fn turns_counter_clockwise(outline: &[GridPoint], face: &Plane) -> bool {
    let n = face.normal().map(i128::from);
    let d = |p: GridPoint, q: GridPoint| -> [i128; 3] {
        std::array::from_fn(|k| i128::from(q.to_array()[k]) - i128::from(p.to_array()[k]))
    };
    let twice_area: i128 = (1..outline.len().saturating_sub(1))
        .map(|i| {
            let (u, v) = (d(outline[0], outline[i]), d(outline[0], outline[i + 1]));
            let c = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            c[0] * n[0] + c[1] * n[1] + c[2] * n[2]
        })
        .sum();
    twice_area > 0
}

/// Where edge `ab` (its ends on either side) crosses the plane
/// `x_axis = level`, computed from its ends in ascending order so that
/// both faces on the edge find the same point.
fn crossing(a: GridPoint, b: GridPoint, axis: usize, level: i64) -> Crossing {
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    let (pa, pb) = (a.to_f64(), b.to_f64());
    let t = (level as f64 - pa[axis]) / (pb[axis] - pa[axis]);
    let [u, v] = plane_axes(axis);
    Crossing {
        edge: (a, b),
        at: [pa[u] + t * (pb[u] - pa[u]), pa[v] + t * (pb[v] - pa[v])],
    }
}

/// The plane `x_axis = level`, facing `+axis`.
fn section_plane(axis: usize, level: i64) -> Option<Plane> {
    let mut normal = [0; 3];
    normal[axis] = 1;
    let mut at = [0; 3];
    at[axis] = level;
    Plane::with_normal_through(normal, GridPoint::new(at[0], at[1], at[2]).ok()?)
}

/// The signed area of a loop (counter-clockwise positive).
fn area(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    0.5 * (0..n)
        .map(|i| {
            let (p, q) = (points[i], points[(i + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum::<f64>()
}

/// Whether `p` lies inside the loop (floating point, crossing count).
fn contains(points: &[[f64; 2]], p: [f64; 2]) -> bool {
    let n = points.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if x > p[0] {
                inside = !inside;
            }
        }
    }
    inside
}

/// A loop (inside on its left) cut to at most [`MAX_LOOP_CORNERS`]
/// corners and moved inside (module docs), as grid points in the plane
/// `x_axis = level`; `None` if it degenerates.
fn inset_loop(points: &[[f64; 2]], inset: f64, axis: usize, level: i64) -> Option<Vec<GridPoint>> {
    // Corners closer than a grid unit to the last kept one go.
    let mut kept: Vec<usize> = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        if kept.last().is_none_or(|&k| distance(points[k], *p) >= 1.0) {
            kept.push(i);
        }
    }
    while kept.len() > 1 && distance(points[kept[0]], points[*kept.last()?]) < 1.0 {
        kept.pop();
    }
    // Every `step`-th corner, the others cut off.
    let step = kept.len().div_ceil(MAX_LOOP_CORNERS);
    let corners: Vec<usize> = kept.iter().copied().step_by(step.max(1)).collect();
    let m = corners.len();
    if m < 3 {
        return None;
    }
    // Each kept edge's line, moved inside by the inset and by how far the
    // corners it cuts off stand inside it (left): where the loop bends
    // away from the inside, the line cuts across the outside.
    let lines: Vec<([f64; 2], [f64; 2], f64)> = (0..m)
        .map(|j| {
            let (from, to) = (corners[j], corners[(j + 1) % m]);
            let (a, b) = (points[from], points[to]);
            let length = distance(a, b);
            let left = [-(b[1] - a[1]) / length, (b[0] - a[0]) / length];
            let mut cut = 0.0_f64;
            let mut k = (from + 1) % points.len();
            while k != to {
                let p = points[k];
                cut = cut.max((p[0] - a[0]) * left[0] + (p[1] - a[1]) * left[1]);
                k = (k + 1) % points.len();
            }
            let shift = inset + cut;
            (
                [a[0] + shift * left[0], a[1] + shift * left[1]],
                [b[0] - a[0], b[1] - a[1]],
                shift,
            )
        })
        .collect();
    let [u, v] = plane_axes(axis);
    let mut moved: Vec<[f64; 2]> = Vec::with_capacity(m);
    for j in 0..m {
        // The corner between the line before and the line after.
        let (p, d, before) = lines[(j + m - 1) % m];
        let (q, e, after) = lines[j];
        let det = d[0] * e[1] - d[1] * e[0];
        let corner = if det.abs() <= 1e-12 * (d[0].hypot(d[1]) * e[0].hypot(e[1])) {
            q
        } else {
            let t = ((q[0] - p[0]) * e[1] - (q[1] - p[1]) * e[0]) / det;
            [p[0] + t * d[0], p[1] + t * d[1]]
        };
        // A sharp corner's lines meet far off: cut it back.
        let original = points[corners[j]];
        let reach = distance(original, corner);
        let limit = 8.0 * (before.max(after) + 1.0);
        let corner = if reach > limit {
            let s = limit / reach;
            [
                original[0] + s * (corner[0] - original[0]),
                original[1] + s * (corner[1] - original[1]),
            ]
        } else {
            corner
        };
        if !corner.iter().all(|x| x.is_finite()) {
            return None;
        }
        moved.push(corner);
    }
    // Corners nearly in line with their neighbours go: rounded to grid
    // points, they would turn either way, and each dent makes a pocket,
    // which cuts the umbra into more parts. A dent of less than half the
    // inset left out moves the boundary out by less than the inset moved
    // it in; the exact check has the last word.
    let mut j = 0;
    let mut since = 0;
    while moved.len() > 3 && since < moved.len() {
        let n = moved.len();
        let (a, b, c) = (moved[(j + n - 1) % n], moved[j], moved[(j + 1) % n]);
        let base = distance(a, c);
        let off = ((c[0] - a[0]) * (b[1] - a[1]) - (c[1] - a[1]) * (b[0] - a[0])).abs() / base;
        if base == 0.0 || off < inset / 2.0 {
            moved.remove(j);
            since = 0;
            j %= moved.len();
        } else {
            since += 1;
            j = (j + 1) % n;
        }
    }
    let mut out: Vec<GridPoint> = Vec::with_capacity(moved.len());
    for corner in moved {
        let mut at = [0_i64; 3];
        at[axis] = level;
        at[u] = corner[0].round() as i64;
        at[v] = corner[1].round() as i64;
        let g = GridPoint::new(at[0], at[1], at[2]).ok()?;
        if out.last() != Some(&g) {
            out.push(g);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    (out.len() >= 3).then_some(out)
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Whether the point where edge `edge` (ends in ascending order, on
/// either side of the plane `x_axis = level`) crosses the plane lies in
/// the region of `cycles` (outline and holes, grid points in the plane)
/// or on its boundary, exactly: the point is `a + t (b - a)` with `t =
/// (level - a_axis) / (b_axis - a_axis)`, scaled by the denominator to
/// integers.
fn in_or_on(
    cycles: &[Vec<GridPoint>],
    edge: (GridPoint, GridPoint),
    axis: usize,
    level: i64,
) -> bool {
    let [u, v] = plane_axes(axis);
    let (a, b) = (edge.0.to_i64(), edge.1.to_i64());
    let mut denominator = i128::from(b[axis] - a[axis]);
    let mut numerator = i128::from(level - a[axis]);
    if denominator < 0 {
        denominator = -denominator;
        numerator = -numerator;
    }
    // The point times the denominator (below 2^74 in magnitude).
    let scaled = |k: usize| i128::from(a[k]) * denominator + numerator * i128::from(b[k] - a[k]);
    let x = [scaled(u), scaled(v)];
    let at = |p: GridPoint| {
        let p = p.to_i64();
        [
            i128::from(p[u]) * denominator,
            i128::from(p[v]) * denominator,
        ]
    };
    let mut inside = false;
    for cycle in cycles {
        let n = cycle.len();
        for i in 0..n {
            let (p, q) = (at(cycle[i]), at(cycle[(i + 1) % n]));
            // Products of scaled differences (below 2^75 each) fit i128
            // once divided by the denominator: the cross product of the
            // unscaled edge (below 2^26) with the scaled offset.
            let (eu, ev) = (
                i128::from(cycle[(i + 1) % n].to_i64()[u] - cycle[i].to_i64()[u]),
                i128::from(cycle[(i + 1) % n].to_i64()[v] - cycle[i].to_i64()[v]),
            );
            let turn = eu * (x[1] - p[1]) - ev * (x[0] - p[0]);
            let between = |k: usize| p[k].min(q[k]) <= x[k] && x[k] <= p[k].max(q[k]);
            if turn == 0 && between(0) && between(1) {
                return true;
            }
            // Crossing count along +u, half-open in v.
            if (p[1] > x[1]) != (q[1] > x[1]) {
                // The edge crosses the line v = x_v to the right of x
                // when x lies on the side of the edge it turns from.
                let right = if q[1] > p[1] { turn > 0 } else { turn < 0 };
                if right {
                    inside = !inside;
                }
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_shapes::{cuboid, solid_angle_winding, torus};

    /// Every section of tori of several proportions, wound either way,
    /// lies inside the torus by a sum of solid angles (an oracle apart
    /// from the winding numbers the check uses) at points spread over
    /// it; the widest in the ring's plane is an annulus covering most of
    /// the ring's section.
    #[test]
    fn a_toruss_sections_lie_inside_it() {
        for (big, small, rings, segments) in [
            (4000.0, 1500.0, 12, 8),
            (6000.0, 900.0, 24, 6),
            (3000.0, 2000.0, 16, 12),
            (40_000.0, 15_000.0, 48, 24),
        ] {
            let (triangles, planes) = torus(big, small, rings, segments);
            for inward in [false, true] {
                let turned: Vec<[GridPoint; 3]> = triangles
                    .iter()
                    .map(|&[a, b, c]| if inward { [c, b, a] } else { [a, b, c] })
                    .collect();
                let outlines: Vec<&[GridPoint]> = turned.iter().map(|t| &t[..]).collect();
                let pieces: Vec<u32> = (0..outlines.len() as u32).collect();
                let unions = sections(&outlines, &planes, &pieces);
                let ring: Vec<&FlatUnion> = unions.iter().filter(|u| u.axis() == Some(1)).collect();
                assert!(
                    (1..=PER_AXIS).contains(&ring.len()),
                    "torus {big} {small}: {} sections",
                    ring.len()
                );
                // The widest first.
                let cycles: Vec<&[GridPoint]> = ring[0].cycles().collect();
                assert_eq!(cycles.len(), 2, "an outline and a hole");
                let area_of = |c: &[GridPoint]| {
                    area(
                        &c.iter()
                            .map(|p| [f64::from(p.z), f64::from(p.x)])
                            .collect::<Vec<_>>(),
                    )
                };
                // The section of the ring through the tube's middle: an
                // annulus of area 4 pi big small, less what the polygons
                // cut off.
                let annulus: f64 = cycles.iter().map(|c| area_of(c)).sum();
                let whole = 4.0 * std::f64::consts::PI * big * small;
                assert!(annulus > 0.7 * whole, "annulus {annulus} of {whole}");
                for union in &unions {
                    check_inside(union, &turned);
                }
            }
        }
    }

    /// Points spread over a union's region are inside the surface.
    fn check_inside(union: &FlatUnion, triangles: &[[GridPoint; 3]]) {
        let axis = union.axis().expect("a section");
        let [u, v] = plane_axes(axis);
        let cycles: Vec<Vec<[f64; 2]>> = union
            .cycles()
            .map(|c| c.iter().map(|p| [p.to_f64()[u], p.to_f64()[v]]).collect())
            .collect();
        let level = union.cycles().next().expect("an outline")[0].to_f64()[axis];
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in cycles.iter().flatten() {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let mut tried = 0;
        for i in 0..40 {
            for j in 0..40 {
                let q = [
                    lo[0] + (hi[0] - lo[0]) * (f64::from(i) + 0.5) / 40.0,
                    lo[1] + (hi[1] - lo[1]) * (f64::from(j) + 0.5) / 40.0,
                ];
                let crossings = cycles.iter().filter(|c| contains(c, q)).count();
                if crossings % 2 == 0 {
                    continue;
                }
                let mut p = [0.0; 3];
                (p[axis], p[u], p[v]) = (level, q[0], q[1]);
                let w = solid_angle_winding(p, triangles).abs();
                assert!((w - 1.0).abs() < 1e-6, "{p:?} in a section wound {w}");
                tried += 1;
            }
        }
        assert!(tried > 100, "{tried} points in the section");
    }

    /// A section casts under a light above the torus facing its axis; not
    /// under one whose plane cuts the torus (in its hole: a section's
    /// point sees it without crossing the surface), nor one facing
    /// another axis.
    #[test]
    fn a_section_casts_under_a_light_clear_of_the_surface() {
        let (triangles, planes) = torus(4000.0, 1500.0, 12, 8);
        let outlines: Vec<&[GridPoint]> = triangles.iter().map(|t| &t[..]).collect();
        let pieces: Vec<u32> = (0..outlines.len() as u32).collect();
        let unions = sections(&outlines, &planes, &pieces);
        let g = |x: i64, y: i64, z: i64| GridPoint::new(x, y, z).expect("a grid point");
        let square = |y: i64| {
            let corners = [
                g(-500, y, -500),
                g(500, y, -500),
                g(500, y, 500),
                g(-500, y, 500),
            ];
            crate::AreaSource::from_grid_points(&corners).expect("a light")
        };
        let casting = |light: &crate::AreaSource| {
            unions
                .iter()
                .filter(|u| !u.umbra_parts(light).is_empty())
                .count()
        };
        let above = square(9000);
        assert!(casting(&above) >= 1);
        assert_eq!(casting(&square(300)), 0);
        // Facing -x, beside the torus.
        let wall = [
            g(9000, -500, -500),
            g(9000, -500, 500),
            g(9000, 500, 500),
            g(9000, 500, -500),
        ];
        let side = crate::AreaSource::from_grid_points(&wall).expect("a light");
        for (light, axis) in [(&above, 1), (&side, 0)] {
            assert!(
                unions
                    .iter()
                    .filter(|u| !u.umbra_parts(light).is_empty())
                    .all(|u| u.axis() == Some(axis))
            );
        }
    }

    /// A convex body has no section: its own umbra is exact.
    #[test]
    fn a_box_has_no_section() {
        let faces = cuboid([0, 0, 0], [100, 200, 300]);
        assert!(crate::section_unions(&faces, &[Some(0); 6]).is_empty());
    }
}
