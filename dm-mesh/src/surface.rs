//! Where an object's surface continues past a piece's edges and around its
//! vertices, so that EV and VE surfaces through an edge or vertex inside
//! the object's silhouette can be left out.
//!
//! Seen from a point `x`, the edge `ab` shared by two consistently
//! oriented faces `F` and `G` (`ab` in one, `ba` in the other) bounds the
//! union of their images only if `x` is in front of exactly one of them.
//! A point of the EV surface of light vertex `v` and edge `ab` lies beyond
//! the edge from `v`, so it is on the other side of each face's plane than
//! `v` is: if `v` is strictly on the same side of both planes, no such
//! point sees `ab` on the silhouette, and the light vertex crossing it
//! changes nothing. Likewise a VE surface of vertex `p` and light edge
//! `cd` is silent when the faces around `p` close up into a fan and both
//! `c` and `d` lie strictly on one and the same side of every one of them;
//! when only a stretch of `cd` from one end does, the surface is cast from
//! the rest of `cd` only.
//! Only exact matches of grid-point edges count; anything else (an open
//! border, a T-junction, a non-manifold edge) keeps its discontinuities.

use crate::hash::KeyMap;
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, ImplicitPoint, Plane};
use smallvec::SmallVec;

/// The surface around one piece of an object.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Surroundings {
    /// Per edge `i` (vertex `i` to `i + 1`): the support plane of the one
    /// piece holding the reversed edge.
    pub(crate) beyond_edge: Vec<Option<Plane>>,
    /// Per vertex: the support planes of the pieces around it (this one
    /// included), when they close up into one fan.
    pub(crate) around_vertex: Vec<Option<SmallVec<[Plane; 6]>>>,
}

impl Surroundings {
    /// Whether no point of light vertex `v`'s EV surface through edge `k`
    /// of the piece on `support` sees that edge on the silhouette: the
    /// piece beyond it has `v` strictly on the same side.
    pub(crate) fn edge_hidden(&self, support: &Plane, k: usize, v: GridPoint) -> bool {
        let Some(Some(beyond)) = self.beyond_edge.get(k) else {
            return false;
        };
        let side = side_of_point(support, v);
        side != Side::On && side_of_point(beyond, v) == side
    }

    /// Whether no point of the VE surface of vertex `k` and the light edge
    /// `cd` sees the vertex on the silhouette: every piece around it has
    /// `c` and `d` strictly on one and the same side.
    pub(crate) fn vertex_hidden(&self, k: usize, c: GridPoint, d: GridPoint) -> bool {
        let Some(Some(fan)) = self.around_vertex.get(k) else {
            return false;
        };
        let side = side_of_point(&fan[0], c);
        side != Side::On
            && fan
                .iter()
                .all(|plane| side_of_point(plane, c) == side && side_of_point(plane, d) == side)
    }

    /// Where, along the light edge `cd`, the stretches that hide vertex `k`
    /// from its ends stop: per end, the plane of the fan at which the
    /// stretch from that end leaves the side of every piece the end is on,
    /// oriented with the end in front. `None` for an end that sees the
    /// vertex, and for a stretch that reaches the other end's; `[None,
    /// None]` when the two stretches meet. `line` is two distinct planes
    /// through `cd`.
    ///
    /// A point of the VE surface lies on the line from a point `x` of `cd`
    /// through the vertex, beyond it, so only the part of the surface cast
    /// from the rest of `cd` is a discontinuity; the returned plane holds
    /// the vertex and the stretch's end, and bounds that part.
    pub(crate) fn hidden_stretch_ends(
        &self,
        k: usize,
        c: GridPoint,
        d: GridPoint,
        line: [&Plane; 2],
    ) -> [Option<Plane>; 2] {
        let Some(Some(fan)) = self.around_vertex.get(k) else {
            return [None, None];
        };
        let from_c = stretch_end(fan, c, d, line);
        let from_d = stretch_end(fan, d, c, line);
        if let (Some((at_c, _)), Some((_, meets_d))) = (&from_c, &from_d) {
            // Past the end of the stretch from `c`, strictly, or the
            // stretches touch and the surface left would be one line.
            if meets_d.side(at_c) != Side::Back {
                return [None, None];
            }
        }
        [
            from_c.map(|(plane, _)| plane),
            from_d.map(|(plane, _)| plane),
        ]
    }
}

/// The fan plane, oriented with `from` in front, at which the segment from
/// `from` to `to` first leaves the side of the fan `from` is strictly on,
/// with the point where it does; `None` if `from` is not hidden or the
/// stretch reaches `to`.
fn stretch_end(
    fan: &[Plane],
    from: GridPoint,
    to: GridPoint,
    line: [&Plane; 2],
) -> Option<(Plane, ImplicitPoint)> {
    let side = side_of_point(&fan[0], from);
    if side == Side::On {
        return None;
    }
    let mut first: Option<(Plane, ImplicitPoint)> = None;
    for plane in fan {
        if side_of_point(plane, from) != side {
            return None;
        }
        let plane = if side == Side::Front {
            *plane
        } else {
            plane.flipped()
        };
        if side_of_point(&plane, to) == Side::Front {
            continue;
        }
        // The segment crosses `plane` (at `to` itself, perhaps): keep the
        // crossing nearest `from`.
        let meets = ImplicitPoint::new(*line[0], *line[1], plane).ok()?;
        if first
            .as_ref()
            .is_none_or(|(_, nearest)| nearest.side(&plane) == Side::Back)
        {
            first = Some((plane, meets));
        }
    }
    first.filter(|(plane, _)| side_of_point(plane, to) != Side::On)
}

/// The surroundings of each of an object's pieces, in their order.
pub(crate) fn surroundings(pieces: &[ConvexPolygon]) -> Vec<Surroundings> {
    let corners: Vec<Option<Vec<GridPoint>>> = pieces
        .iter()
        .map(|p| (0..p.len()).map(|k| p.vertex_grid_point(k)).collect())
        .collect();
    // Directed edge -> the (piece, edge) holding it; `None` once two do.
    let mut edges: KeyMap<(GridPoint, GridPoint), Option<(usize, usize)>> = KeyMap::default();
    for (i, points) in corners.iter().enumerate() {
        let Some(points) = points else { continue };
        for k in 0..points.len() {
            let edge = (points[k], points[(k + 1) % points.len()]);
            edges
                .entry(edge)
                .and_modify(|held| *held = None)
                .or_insert(Some((i, k)));
        }
    }
    // The (piece, edge) across edge `k` of piece `i`.
    let across = |i: usize, k: usize| -> Option<(usize, usize)> {
        let points = corners[i].as_ref()?;
        let (a, b) = (points[k], points[(k + 1) % points.len()]);
        edges.get(&(b, a)).copied().flatten()
    };
    corners
        .iter()
        .enumerate()
        .map(|(i, points)| {
            let n = points.as_ref().map_or(0, Vec::len);
            let beyond_edge = (0..n)
                .map(|k| across(i, k).map(|(j, _)| *pieces[j].support()))
                .collect();
            let around_vertex = (0..n).map(|k| fan(pieces, i, k, &across)).collect();
            Surroundings {
                beyond_edge,
                around_vertex,
            }
        })
        .collect()
}

/// The support planes of the pieces around vertex `k` of piece `i`,
/// turning across the edge leaving the vertex until the walk is back at
/// `i`; `None` if it runs into a border or does not close.
fn fan(
    pieces: &[ConvexPolygon],
    i: usize,
    k: usize,
    across: &impl Fn(usize, usize) -> Option<(usize, usize)>,
) -> Option<SmallVec<[Plane; 6]>> {
    let mut planes: SmallVec<[Plane; 6]> = SmallVec::new();
    let (mut piece, mut vertex) = (i, k);
    for _ in 0..=pieces.len() {
        planes.push(*pieces[piece].support());
        // Edge `vertex` leaves the vertex; the piece across holds it
        // reversed, entering the vertex, so its next edge leaves it again.
        let (next, entering) = across(piece, vertex)?;
        let after = (entering + 1) % pieces[next].len();
        if next == i {
            return (after == k).then_some(planes);
        }
        (piece, vertex) = (next, after);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    /// The six faces of the box `[lo, hi]`, wound outward.
    fn cuboid(lo: [i32; 3], hi: [i32; 3]) -> Vec<ConvexPolygon> {
        let [x0, y0, z0] = lo;
        let [x1, y1, z1] = hi;
        let faces = [
            [g(x0, y0, z0), g(x0, y1, z0), g(x1, y1, z0), g(x1, y0, z0)],
            [g(x0, y0, z1), g(x1, y0, z1), g(x1, y1, z1), g(x0, y1, z1)],
            [g(x0, y0, z0), g(x1, y0, z0), g(x1, y0, z1), g(x0, y0, z1)],
            [g(x0, y1, z0), g(x0, y1, z1), g(x1, y1, z1), g(x1, y1, z0)],
            [g(x0, y0, z0), g(x0, y0, z1), g(x0, y1, z1), g(x0, y1, z0)],
            [g(x1, y0, z0), g(x1, y1, z0), g(x1, y1, z1), g(x1, y0, z1)],
        ];
        faces
            .iter()
            .map(|f| ConvexPolygon::from_grid_points(f, 0).unwrap())
            .collect()
    }

    fn cube() -> Vec<ConvexPolygon> {
        cuboid([0; 3], [2; 3])
    }

    /// The four faces of a tetrahedron, wound outward (`None` if flat).
    fn tetrahedron(p: [GridPoint; 4]) -> Option<Vec<ConvexPolygon>> {
        [[0, 1, 2, 3], [0, 3, 1, 2], [1, 3, 2, 0], [0, 2, 3, 1]]
            .iter()
            .map(|&[a, b, c, opposite]| {
                let face = ConvexPolygon::from_grid_points(&[p[a], p[b], p[c]], 0).ok()?;
                match side_of_point(face.support(), p[opposite]) {
                    Side::Back => Some(face),
                    Side::Front => ConvexPolygon::from_grid_points(&[p[a], p[c], p[b]], 0).ok(),
                    Side::On => None,
                }
            })
            .collect()
    }

    fn f64s(p: GridPoint) -> [f64; 3] {
        p.to_i64().map(|c| c as f64)
    }

    /// Whether the segment `pq` meets the convex solid behind the support
    /// planes of `faces` (Cyrus-Beck clipping, in `f64`: the test keeps its
    /// segments far from grazing the solid, relative to rounding).
    fn meets_solid(p: [f64; 3], q: [f64; 3], faces: &[ConvexPolygon]) -> bool {
        let (mut enter, mut leave) = (0.0_f64, 1.0_f64);
        for face in faces {
            let [a, b, c, d] = face.support().approx();
            let value = |x: [f64; 3]| a * x[0] + b * x[1] + c * x[2] + d;
            let (vp, vq) = (value(p), value(q));
            if vp > 0.0 && vq > 0.0 {
                return false;
            }
            if vp > 0.0 {
                enter = enter.max(vp / (vp - vq));
            } else if vq > 0.0 {
                leave = leave.min(vp / (vp - vq));
            }
        }
        enter <= leave
    }

    /// Whether the light point `light` is hidden from both points a small
    /// step either side of `plane` (through three grid points, `light`
    /// in it), at the mirror image of `light` in the point `at`. The step
    /// stays far short of the planes in `clear` (the faces at `at`, which
    /// must not swap sides) and of a sliver's thickness, yet far above the
    /// rounding of the clipping.
    fn hidden_either_side(
        light: [f64; 3],
        at: [f64; 3],
        plane: [GridPoint; 3],
        clear: &[Plane],
        solid: &[ConvexPolygon],
    ) -> bool {
        let [o, a, b] = plane.map(f64s);
        let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
        let (u, w) = (sub(a, o), sub(b, o));
        let n = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let length = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        let mirror: [f64; 3] = std::array::from_fn(|i| 2.0 * at[i] - light[i]);
        let margin = clear.iter().fold(length(sub(at, light)), |m, plane| {
            let [a, b, c, d] = plane.approx();
            let value = a * mirror[0] + b * mirror[1] + c * mirror[2] + d;
            m.min(value.abs() / length([a, b, c]))
        });
        let step = 1e-7 * margin / length(n);
        [1.0, -1.0].iter().all(|s| {
            let x: [f64; 3] = std::array::from_fn(|i| mirror[i] + s * step * n[i]);
            meets_solid(light, x, solid)
        })
    }

    fn grid_point() -> impl Strategy<Value = GridPoint> {
        prop::array::uniform3(-40_i32..40).prop_map(|[x, y, z]| g(x, y, z))
    }

    fn convex_solid() -> impl Strategy<Value = Vec<ConvexPolygon>> {
        prop_oneof![
            (
                prop::array::uniform3(-20_i32..0),
                prop::array::uniform3(1_i32..20)
            )
                .prop_map(|(lo, hi)| cuboid(lo, hi)),
            prop::array::uniform4(prop::array::uniform3(-20_i32..20))
                .prop_filter_map("flat", |p| tetrahedron(p.map(|[x, y, z]| g(x, y, z)))),
        ]
    }

    proptest! {
        /// On a convex solid, an EV surface is left out exactly when the
        /// light vertex is hidden on both sides of it, just past the edge;
        /// a VE surface only when the light edge's midpoint is.
        #[test]
        fn left_out_surfaces_change_nothing_in_sight(
            solid in convex_solid(),
            lights in prop::collection::vec(grid_point(), 2..5),
        ) {
            for (i, around) in surroundings(&solid).iter().enumerate() {
                let face = &solid[i];
                let n = face.len();
                let corner = |k: usize| face.vertex_grid_point(k % n).unwrap();
                for k in 0..n {
                    let (a, b) = (corner(k), corner(k + 1));
                    let beyond = around.beyond_edge[k].unwrap();
                    for &v in &lights {
                        let on = [face.support(), &beyond]
                            .iter()
                            .any(|plane| side_of_point(plane, v) == Side::On);
                        if on || Plane::through(v, a, b).is_none() {
                            continue;
                        }
                        let (fa, fb) = (f64s(a), f64s(b));
                        let at = std::array::from_fn(|c| (2.0 * fa[c] + fb[c]) / 3.0);
                        prop_assert_eq!(
                            around.edge_hidden(face.support(), k, v),
                            hidden_either_side(f64s(v), at, [v, a, b], &[*face.support(), beyond], &solid)
                        );
                    }
                    for (c, d) in lights.iter().zip(lights.iter().skip(1)) {
                        let p = corner(k);
                        if !around.vertex_hidden(k, *c, *d) || Plane::through(p, *c, *d).is_none() {
                            continue;
                        }
                        let (fc, fd) = (f64s(*c), f64s(*d));
                        let r: [f64; 3] = std::array::from_fn(|x| (fc[x] + fd[x]) / 2.0);
                        let fan = around.around_vertex[k].as_ref().unwrap();
                        prop_assert!(hidden_either_side(r, f64s(p), [p, *c, *d], fan, &solid));
                    }
                    for (c, d) in lights.iter().zip(lights.iter().skip(1)) {
                        let p = corner(k);
                        let (Some(critical), Some(light_plane)) = (
                            Plane::through(p, *c, *d),
                            lights.iter().find_map(|&t| {
                                (side_of_point(&Plane::through(p, *c, *d)?, t) != Side::On)
                                    .then(|| Plane::through(*c, *d, t))
                                    .flatten()
                            }),
                        ) else {
                            continue;
                        };
                        let ends = around.hidden_stretch_ends(k, *c, *d, [&light_plane, &critical]);
                        let fan = around.around_vertex[k].as_ref();
                        for (end, (from, to)) in ends.iter().zip([(c, d), (d, c)]) {
                            let Some(end) = end else { continue };
                            // The light points of the stretch up to its end
                            // see the vertex hidden.
                            let [a, b, cc, dd] = end.approx();
                            let value = |x: [f64; 3]| a * x[0] + b * x[1] + cc * x[2] + dd;
                            let (ff, ft) = (f64s(*from), f64s(*to));
                            let (vf, vt) = (value(ff), value(ft));
                            prop_assert!(vf > 0.0 && vt < 0.0);
                            let stop = vf / (vf - vt);
                            for share in [0.5, 0.999] {
                                let t = stop * share;
                                let x: [f64; 3] = std::array::from_fn(|i| ff[i] + t * (ft[i] - ff[i]));
                                prop_assert!(hidden_either_side(x, f64s(p), [p, *c, *d], fan.unwrap(), &solid));
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_box_under_a_light_hides_the_edges_between_faces_facing_it() {
        // Seen from above one corner, the top and the two sides facing the
        // light meet at three edges inside the silhouette.
        let pieces = cube();
        let v = g(5, 7, 6);
        let hidden: usize = surroundings(&pieces)
            .iter()
            .zip(&pieces)
            .map(|(s, f)| {
                (0..f.len())
                    .filter(|&k| s.edge_hidden(f.support(), k, v))
                    .count()
            })
            .sum();
        // Three edges between faces facing v, three between faces turned
        // away, each counted from both of its faces.
        assert_eq!(hidden, 12);
    }

    #[test]
    fn a_ve_wedge_is_cast_only_from_where_the_light_edge_sees_its_vertex() {
        use crate::critical::internal_planes;
        use area_shadow::{AreaSource, volume_planes};
        // The corner (2, 2, 2) of the box is hidden from the light edge's
        // end (3, 10, 3), above the three faces at it, up to z = 2 (a fifth
        // of the way; x = 2 comes later).
        let pieces = cube();
        let light =
            AreaSource::from_grid_points(&[g(3, 10, 3), g(-1, 10, -2), g(2, 10, -4), g(5, 10, 0)])
                .unwrap();
        let (c, d) = (g(3, 10, 3), g(-1, 10, -2));
        let top = 3;
        let around = &surroundings(&pieces)[top];
        let occluder = &pieces[top];
        let k = (0..occluder.len())
            .find(|&k| occluder.vertex_grid_point(k) == Some(g(2, 2, 2)))
            .unwrap();
        let p = g(2, 2, 2);
        let volumes = volume_planes(occluder, &light);
        let internal = internal_planes(occluder, &light, &volumes, around);
        let critical = Plane::through(p, c, d).unwrap();
        let ve = internal
            .iter()
            .find(|i| i.plane.is_coincident(&critical))
            .expect("the VE surface of the corner and the edge");
        let fan = around.around_vertex[k].as_ref().unwrap();
        let [pc, cd, dd] = [f64s(p), f64s(c), f64s(d)];
        let mut seen = [0, 0];
        for step in 1..40 {
            // Light points x along cd, off the crossings (1 / 5 and 1 / 4).
            let t = (f64::from(step) - 0.5) / 40.0;
            let x: [f64; 3] = std::array::from_fn(|i| cd[i] + t * (dd[i] - cd[i]));
            let r: [f64; 3] = std::array::from_fn(|i| 2.0 * pc[i] - x[i]);
            let value = |plane: &Plane, at: [f64; 3]| {
                let [a, b, c, d] = plane.approx();
                a * at[0] + b * at[1] + c * at[2] + d
            };
            let in_wedge = ve.wedge.iter().all(|w| value(w, r) < 0.0);
            let first = value(&fan[0], x) > 0.0;
            let shows = fan.iter().any(|plane| (value(plane, x) > 0.0) != first);
            assert_eq!(in_wedge, shows, "t = {t}");
            seen[usize::from(shows)] += 1;
        }
        assert!(seen[0] > 0 && seen[1] > 0, "{seen:?}");
    }

    #[test]
    fn every_edge_and_vertex_of_a_closed_box_is_surrounded() {
        let pieces = cube();
        for (i, s) in surroundings(&pieces).iter().enumerate() {
            for (k, beyond) in s.beyond_edge.iter().enumerate() {
                let beyond = beyond.expect("a closed box has a face across every edge");
                // The face across is another, not coplanar one.
                assert!(!beyond.is_coincident(pieces[i].support()), "{i} {k}");
            }
            for fan in &s.around_vertex {
                let fan = fan.as_ref().expect("three faces close around a corner");
                assert_eq!(fan.len(), 3);
                assert!(fan[0].is_coincident(pieces[i].support()));
            }
        }
    }

    #[test]
    fn an_open_box_has_borders() {
        let mut pieces = cube();
        pieces.pop();
        let s = surroundings(&pieces);
        // The face opposite the missing one touches it at no edge.
        assert!(s[4].beyond_edge.iter().all(Option::is_some));
        assert!(s[4].around_vertex.iter().all(Option::is_some));
        // Every other face has one border edge and two border vertices.
        for s in &s[..4] {
            assert_eq!(s.beyond_edge.iter().filter(|b| b.is_none()).count(), 1);
            assert_eq!(s.around_vertex.iter().filter(|f| f.is_none()).count(), 2);
        }
    }
}
