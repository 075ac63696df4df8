//! Winged-edge meshes: every invariant after random sequences of face
//! splits, edge splits, merges and vertex removals, with the area kept.

use crate::common::{convex_polygon, gp, plane};
use bsp_core::{
    ConvexPolygon, FaceKey, FaceSplit, ImplicitPoint, Plane, Side, VertexPosition, WingedMesh,
};
use proptest::prelude::*;

#[derive(Debug, Clone)]
enum Op {
    SplitFace(usize, Plane),
    SplitEdge(usize, Plane),
    Merge(usize),
    RemoveVertex(usize),
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        3 => (0_usize..64, plane(1500)).prop_map(|(i, p)| Op::SplitFace(i, p)),
        1 => (0_usize..64, plane(1500)).prop_map(|(i, p)| Op::SplitEdge(i, p)),
        2 => (0_usize..64).prop_map(Op::Merge),
        1 => (0_usize..64).prop_map(Op::RemoveVertex),
    ]
}

/// `face_sides` walks each edge of the face once, names the face across
/// each, and leaves each edge at the vertex the next one starts from.
fn check_face_sides(mesh: &WingedMesh) -> Result<(), TestCaseError> {
    for (f, _) in mesh.faces() {
        let sides: Vec<_> = mesh.face_sides(f).collect();
        // Every edge of the face once (counted from the edges' wings).
        let bounding = mesh
            .edges()
            .filter(|(_, e)| e.left == Some(f) || e.right == Some(f))
            .count();
        let mut keys: Vec<_> = sides.iter().map(|s| s.key).collect();
        keys.sort();
        keys.dedup();
        prop_assert_eq!((keys.len(), sides.len()), (bounding, bounding));
        for (i, side) in sides.iter().enumerate() {
            let e = mesh.edge(side.key).unwrap();
            prop_assert!(
                (e.left == Some(f) && side.across == e.right)
                    || (e.right == Some(f) && side.across == e.left)
            );
            let (start, end) = if e.left == Some(f) {
                (e.start, e.end)
            } else {
                (e.end, e.start)
            };
            prop_assert_eq!((side.start, side.end), (start, end));
            prop_assert_eq!(end, sides[(i + 1) % sides.len()].start);
        }
    }
    Ok(())
}

fn total_area(mesh: &WingedMesh) -> f64 {
    mesh.faces()
        .map(|(f, _)| mesh.face_polygon(f, 0).unwrap().area())
        .sum()
}

fn nth_face(mesh: &WingedMesh, i: usize) -> FaceKey {
    let keys: Vec<FaceKey> = mesh.faces().map(|(k, _)| k).collect();
    keys[i % keys.len()]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn random_operations_keep_every_invariant(polygon in convex_polygon(4000), ops in prop::collection::vec(op(), 1..30)) {
        let mut mesh: WingedMesh = WingedMesh::from_polygon(&polygon, (), ());
        mesh.check_invariants().map_err(TestCaseError::fail)?;
            mesh.check_plane_holds([]).map_err(TestCaseError::fail)?;
        let area = polygon.area();
        for op in ops {
            match op {
                Op::SplitFace(i, p) => {
                    let f = nth_face(&mesh, i);
                    let before = mesh.counts().2;
                    match mesh.split_face(f, &p) {
                        FaceSplit::Split { back, front, edge } => {
                            prop_assert_eq!(mesh.counts().2, before + 1);
                            let b = mesh.face_polygon(back, 0).unwrap();
                            let fr = mesh.face_polygon(front, 0).unwrap();
                            for i in 0..b.len() {
                                prop_assert_ne!(b.vertex_side(i, &p), Side::Front);
                            }
                            for i in 0..fr.len() {
                                prop_assert_ne!(fr.vertex_side(i, &p), Side::Back);
                            }
                            prop_assert!(mesh.edge(edge).unwrap().line.is_coincident(&p));
                        }
                        FaceSplit::NotSplit(side) => {
                            prop_assert_ne!(side, Side::On);
                            prop_assert_eq!(mesh.counts().2, before);
                        }
                    }
                }
                Op::SplitEdge(i, p) => {
                    let edges: Vec<_> = mesh.edges().map(|(k, e)| (k, e.line, e.left.or(e.right).unwrap())).collect();
                    let (e, line, face) = edges[i % edges.len()];
                    let support = *mesh.face_support(face).unwrap();
                    if let Ok(point) = ImplicitPoint::new(support, line, p) {
                        // Inside the edge or not, the mesh decides exactly.
                        let (v, e) = match mesh.split_edge(e, VertexPosition::Implicit(point)) {
                            Ok(split) => split,
                            Err(_) => continue,
                        };
                        prop_assert!(mesh.vertex(v).unwrap().position.same_point(&VertexPosition::Implicit(point)));
                        prop_assert!(mesh.edge(e).is_some());
                    }
                }
                Op::Merge(i) => {
                    let edges: Vec<_> = mesh.edges().map(|(k, _)| k).collect();
                    let e = edges[i % edges.len()];
                    let faces = mesh.counts().2;
                    if mesh.merge_faces(e).is_ok() {
                        prop_assert_eq!(mesh.counts().2, faces - 1);
                    }
                }
                Op::RemoveVertex(i) => {
                    let vertices: Vec<_> = mesh.faces().flat_map(|(f, _)| mesh.face_vertices(f)).collect();
                    let v = vertices[i % vertices.len()];
                    mesh.remove_vertex_if_collinear(v);
                }
            }
            mesh.check_invariants().map_err(TestCaseError::fail)?;
            mesh.check_plane_holds([]).map_err(TestCaseError::fail)?;
            check_face_sides(&mesh)?;
            let now = total_area(&mesh);
            prop_assert!((now - area).abs() <= 1e-9 * area, "area {now} vs {area}");
        }
    }

    #[test]
    fn merging_undoes_a_split(polygon in convex_polygon(4000), p in plane(1500)) {
        let mut mesh: WingedMesh<u8, u8> = WingedMesh::from_polygon(&polygon, 7, 1);
        let original = mesh.counts();
        let planes = mesh.plane_count();
        let face = mesh.faces().next().unwrap().0;
        if let FaceSplit::Split { back, front, edge } = mesh.split_face(face, &p) {
            prop_assert_eq!(mesh.face(front).unwrap().data, 7);
            let (start, end) = { let e = mesh.edge(edge).unwrap(); (e.start, e.end) };
            prop_assert_eq!(mesh.merge_faces(edge).unwrap(), front);
            prop_assert!(mesh.face(back).is_none());
            // The cut's ends are straight vertices now, unless they were
            // vertices of the polygon.
            mesh.remove_vertex_if_collinear(start);
            mesh.remove_vertex_if_collinear(end);
            mesh.check_invariants().map_err(TestCaseError::fail)?;
            mesh.check_plane_holds([]).map_err(TestCaseError::fail)?;
            prop_assert_eq!(mesh.counts(), original);
            // The cut's planes went with its vertices.
            prop_assert_eq!(mesh.plane_count(), planes);
            let f = mesh.faces().next().unwrap().0;
            let rebuilt = mesh.face_polygon(f, 0).unwrap();
            prop_assert!((rebuilt.area() - polygon.area()).abs() <= 1e-9 * polygon.area());
        }
    }
}

#[test]
fn walks_around_faces_and_vertices() {
    let square =
        ConvexPolygon::from_grid_points(&[gp(0, 0, 0), gp(8, 0, 0), gp(8, 8, 0), gp(0, 8, 0)], 0)
            .unwrap();
    let mut mesh: WingedMesh<char, ()> = WingedMesh::from_polygon(&square, 'a', ());
    let f = mesh.faces().next().unwrap().0;
    assert_eq!(mesh.face_vertices(f).len(), 4);
    // Cut along x = 4, then along y = 4 in the back half.
    let x4 = Plane::with_normal_through([1, 0, 0], gp(4, 0, 0)).unwrap();
    let FaceSplit::Split { back, front, .. } = mesh.split_face(f, &x4) else {
        panic!("x = 4 cuts")
    };
    assert_eq!(mesh.face_outline(back).len(), 4);
    assert_eq!(mesh.face_outline(front).len(), 4);
    let y4 = Plane::with_normal_through([0, 1, 0], gp(0, 4, 0)).unwrap();
    let FaceSplit::Split { edge: y_edge, .. } = mesh.split_face(back, &y4) else {
        panic!("y = 4 cuts")
    };
    mesh.check_invariants().unwrap();
    assert_eq!(mesh.counts(), (8, 10, 3));
    // The vertex (4, 4) now has three edges and three faces.
    let centre = mesh
        .faces()
        .flat_map(|(f, _)| mesh.face_vertices(f))
        .find(|&v| mesh.vertex(v).unwrap().position.to_f64() == [4.0, 4.0, 0.0])
        .unwrap();
    assert_eq!(mesh.vertex_edges(centre).len(), 3);
    let faces = mesh.vertex_faces(centre);
    assert_eq!(faces.len(), 3);
    assert_eq!(mesh.faces_around(centre).collect::<Vec<_>>(), faces);
    assert_eq!(mesh.vertices().count(), mesh.counts().0);
    assert!(faces.iter().all(Option::is_some));
    // A plane through a vertex and along an edge touches without cutting.
    assert_eq!(
        mesh.split_face(front, &x4),
        FaceSplit::NotSplit(Side::Front)
    );
    // The outside: a corner of the square has two edges, faces None and one.
    let corner = mesh
        .faces()
        .flat_map(|(f, _)| mesh.face_vertices(f))
        .find(|&v| mesh.vertex(v).unwrap().position.to_f64() == [8.0, 8.0, 0.0])
        .unwrap();
    let around = mesh.vertex_faces(corner);
    assert_eq!(around.len(), 2);
    assert!(around.contains(&None));
    // Merging across the boundary is refused.
    let boundary = mesh.edges().find(|(_, e)| e.right.is_none()).unwrap().0;
    assert!(mesh.merge_faces(boundary).is_err());
    // Undo the y = 4 cut, then x = 4: the chain of two collinear edges along
    // x = 4 (split at (4, 4)) is joined before the merge.
    mesh.merge_faces(y_edge).unwrap();
    mesh.check_invariants().unwrap();
    let x_edge = mesh
        .edges()
        .find(|(_, e)| e.left.is_some() && e.right.is_some())
        .unwrap()
        .0;
    mesh.merge_faces(x_edge).unwrap();
    mesh.check_invariants().unwrap();
    let f = mesh.faces().next().unwrap().0;
    assert_eq!(mesh.face_polygon(f, 0).unwrap().area(), 64.0);
    // Straight vertices left on the outline can be removed.
    for v in mesh.face_vertices(f) {
        mesh.remove_vertex_if_collinear(v);
    }
    mesh.check_invariants().unwrap();
    assert_eq!(mesh.counts(), (4, 4, 1));
}

#[test]
fn straight_vertex_between_edges_of_two_planes_through_one_line() {
    // Two planes of a scene can cut the face's plane in one line: here
    // x = 4 and x + z = 4 both cut z = 0 along x = 4. A vertex where an
    // edge of each meets is straight, and merging across that line must
    // join them (dm-mesh's local deletion found it).
    let square =
        ConvexPolygon::from_grid_points(&[gp(0, 0, 0), gp(8, 0, 0), gp(8, 8, 0), gp(0, 8, 0)], 0)
            .unwrap();
    let mut mesh: WingedMesh = WingedMesh::from_polygon(&square, (), ());
    let f = mesh.faces().next().unwrap().0;
    let y4 = Plane::with_normal_through([0, 1, 0], gp(0, 4, 0)).unwrap();
    let FaceSplit::Split {
        back: low,
        front: high,
        ..
    } = mesh.split_face(f, &y4)
    else {
        panic!("y = 4 cuts")
    };
    let x4 = Plane::with_normal_through([1, 0, 0], gp(4, 0, 0)).unwrap();
    let tilted = Plane::with_normal_through([1, 0, 1], gp(4, 0, 0)).unwrap();
    assert!(!x4.is_coincident(&tilted));
    let FaceSplit::Split { .. } = mesh.split_face(low, &x4) else {
        panic!("x = 4 cuts the lower half")
    };
    let FaceSplit::Split { .. } = mesh.split_face(high, &tilted) else {
        panic!("x + z = 4 cuts the upper half")
    };
    mesh.check_invariants().unwrap();
    // Undo the y = 4 cut on both sides of x = 4.
    loop {
        let Some(e) = mesh
            .edges()
            .find(|(_, e)| e.left.is_some() && e.right.is_some() && e.line.is_coincident(&y4))
            .map(|(k, _)| k)
        else {
            break;
        };
        mesh.merge_faces(e).unwrap();
        mesh.check_invariants().unwrap();
    }
    let centre = mesh
        .faces()
        .flat_map(|(f, _)| mesh.face_vertices(f))
        .find(|&v| mesh.vertex(v).unwrap().position.to_f64() == [4.0, 4.0, 0.0])
        .unwrap();
    assert!(mesh.remove_vertex_if_collinear(centre));
    mesh.check_invariants().unwrap();
    let inner = mesh
        .edges()
        .find(|(_, e)| e.left.is_some() && e.right.is_some())
        .unwrap()
        .0;
    let f = mesh.merge_faces(inner).unwrap();
    for v in mesh.face_vertices(f) {
        mesh.remove_vertex_if_collinear(v);
    }
    mesh.check_invariants().unwrap();
    assert_eq!(mesh.counts(), (4, 4, 1));
    assert_eq!(mesh.face_polygon(f, 0).unwrap().area(), 64.0);
}

fn cube_faces(s: i64) -> Vec<ConvexPolygon> {
    let c = |x: bool, y: bool, z: bool| {
        gp(
            if x { s } else { 0 },
            if y { s } else { 0 },
            if z { s } else { 0 },
        )
    };
    let (f, t) = (false, true);
    [
        [c(f, f, f), c(f, t, f), c(t, t, f), c(t, f, f)],
        [c(f, f, t), c(t, f, t), c(t, t, t), c(f, t, t)],
        [c(f, f, f), c(t, f, f), c(t, f, t), c(f, f, t)],
        [c(f, t, f), c(f, t, t), c(t, t, t), c(t, t, f)],
        [c(f, f, f), c(f, f, t), c(f, t, t), c(f, t, f)],
        [c(t, f, f), c(t, t, f), c(t, t, t), c(t, f, t)],
    ]
    .iter()
    .map(|q| ConvexPolygon::from_grid_points(q, 0).unwrap())
    .collect()
}

#[test]
fn glued_polygons_share_vertices_and_edges() {
    // A 2 x 2 grid of squares in z = 0: a disk.
    let square = |x: i64, y: i64| {
        ConvexPolygon::from_grid_points(
            &[
                gp(x, y, 0),
                gp(x + 4, y, 0),
                gp(x + 4, y + 4, 0),
                gp(x, y + 4, 0),
            ],
            0,
        )
        .unwrap()
    };
    let grid = [square(0, 0), square(4, 0), square(0, 4), square(4, 4)];
    let mesh: WingedMesh = WingedMesh::from_polygons(&grid, (), ()).unwrap();
    mesh.check_invariants().unwrap();
    assert_eq!(mesh.counts(), (9, 12, 4));
    // The cube: a closed surface, every edge between two faces.
    let cube: WingedMesh = WingedMesh::from_polygons(&cube_faces(6), (), ()).unwrap();
    cube.check_invariants().unwrap();
    assert_eq!(cube.counts(), (8, 12, 6));
    assert!(
        cube.edges()
            .all(|(_, e)| e.left.is_some() && e.right.is_some())
    );
    // Faces in one plane share their support plane; the cube's six differ.
    let planes = |m: &WingedMesh| -> std::collections::HashSet<bsp_core::Plane> {
        m.faces()
            .map(|(f, _)| *m.face_support(f).unwrap())
            .collect()
    };
    assert_eq!(planes(&mesh).len(), 1);
    assert_eq!(planes(&cube).len(), 6);
    // (Faces are made in the polygons' order.)
    for ((f, _), polygon) in cube.faces().zip(cube_faces(6)) {
        assert_eq!(cube.face_support(f), Some(polygon.support()));
    }
    // The same square twice is an inconsistent surface.
    assert!(WingedMesh::<(), ()>::from_polygons(&[square(0, 0), square(0, 0)], (), ()).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    #[test]
    fn a_closed_cube_survives_random_cuts_and_merges(cuts in prop::collection::vec((0_usize..64, plane(12)), 1..12), merges in prop::collection::vec(0_usize..64, 0..8)) {
        let faces = cube_faces(6);
        let mut mesh: WingedMesh = WingedMesh::from_polygons(&faces, (), ()).unwrap();
        let area: f64 = faces.iter().map(ConvexPolygon::area).sum();
        for (i, p) in cuts {
            let f = nth_face(&mesh, i);
            mesh.split_face(f, &p);
            mesh.check_invariants().map_err(TestCaseError::fail)?;
            mesh.check_plane_holds([]).map_err(TestCaseError::fail)?;
        }
        for i in merges {
            let edges: Vec<_> = mesh.edges().map(|(k, _)| k).collect();
            let _ = mesh.merge_faces(edges[i % edges.len()]);
            mesh.check_invariants().map_err(TestCaseError::fail)?;
            mesh.check_plane_holds([]).map_err(TestCaseError::fail)?;
        }
        let now = total_area(&mesh);
        prop_assert!((now - area).abs() <= 1e-9 * area);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// A face replaced by a mesh of its polygon split on its own (its
    /// neighbours split meanwhile, so the outlines have different
    /// vertices): the result is one valid mesh with the grafted faces.
    #[test]
    fn grafted_faces_sew_into_their_neighbours(
        polygon in convex_polygon(1500),
        before in prop::collection::vec((0_usize..64, plane(1500)), 0..6),
        inside in prop::collection::vec((0_usize..64, plane(1500)), 0..10),
        after in prop::collection::vec((0_usize..64, plane(1500)), 0..8),
        pick in 0_usize..64,
    ) {
        let mut mesh: WingedMesh<u32, ()> = WingedMesh::from_polygon(&polygon, 0, ());
        for (i, p) in &before {
            let f = nth_face_of(&mesh, *i);
            mesh.split_face(f, p);
        }
        let f = nth_face_of(&mesh, pick);
        let mut sub: WingedMesh<u32, ()> =
            WingedMesh::from_polygon(&mesh.face_polygon(f, 0).unwrap(), 1, ());
        for (i, p) in &inside {
            let g = nth_face_of(&sub, *i);
            sub.split_face(g, p);
        }
        for (i, p) in &after {
            let g = nth_face_of(&mesh, *i);
            if g != f {
                mesh.split_face(g, p);
            }
        }
        sub.check_invariants().unwrap();
        let areas: Vec<(FaceKey, f64)> = sub
            .faces()
            .map(|(g, _)| (g, sub.face_polygon(g, 0).unwrap().area()))
            .collect();
        let faces = mesh.counts().2;
        let map = mesh.graft(f, sub).unwrap();
        mesh.check_invariants().unwrap();
        prop_assert_eq!(mesh.counts().2, faces - 1 + areas.len());
        for (g, area) in areas {
            let got = mesh.face_polygon(map[g], 0).unwrap().area();
            prop_assert!((got - area).abs() <= 1e-9 * polygon.area());
            prop_assert_eq!(mesh.face(map[g]).unwrap().data, 1);
        }
        let total: f64 = mesh
            .faces()
            .map(|(g, _)| mesh.face_polygon(g, 0).unwrap().area())
            .sum();
        prop_assert!((total - polygon.area()).abs() <= 1e-9 * polygon.area());
    }
}

fn nth_face_of<F: Clone>(mesh: &WingedMesh<F, ()>, i: usize) -> FaceKey {
    let keys: Vec<FaceKey> = mesh.faces().map(|(k, _)| k).collect();
    keys[i % keys.len()]
}
