//! Scenes to pieces: transforms, source numbering, concave and non-planar
//! faces, degenerate faces.

use umbra::{Pieces, Scene};

use crate::folder;

fn newell_area(v: &[[f64; 3]]) -> f64 {
    let mut a = [0.0; 3];
    for i in 0..v.len() {
        let (p, q) = (v[i], v[(i + 1) % v.len()]);
        a[0] += p[1] * q[2] - p[2] * q[1];
        a[1] += p[2] * q[0] - p[0] * q[2];
        a[2] += p[0] * q[1] - p[1] * q[0];
    }
    0.5 * (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

#[test]
fn transforms_match_hand_computed_values() {
    let dir = folder(&[
        (
            "scene.toml",
            r#"
[[object]]
name = "a"
mesh = "tri.obj"
scale = [2.0, 3.0, 4.0]
rotate_deg = [90.0, 90.0, 0.0]
translate = [10.0, 20.0, 30.0]

[[object]]
name = "b"
mesh = "tri.obj"
scale = 0.5
rotate_deg = [0.0, 0.0, -90.0]
"#,
        ),
        ("tri.obj", "v 0 0 0\nv 1 1 1\nv 1 0 0\nf 1 2 3\n"),
    ]);
    let scene = Scene::load(dir.path().join("scene.toml")).unwrap();
    let a = &scene.objects[0].polygons[0].vertices;
    // (1,1,1): scale (2,3,4); Rx 90: (2,-4,3); Ry 90: (3,-4,-2); + t.
    assert!(close(a[1], [13.0, 16.0, 28.0], 1e-12), "{a:?}");
    // (1,0,0): (2,0,0); Rx: same; Ry 90: (0,0,-2); + t.
    assert!(close(a[2], [10.0, 20.0, 28.0], 1e-12), "{a:?}");
    let b = &scene.objects[1].polygons[0].vertices;
    // (1,1,1) * 0.5, then Rz -90: (x, y) -> (y, -x).
    assert!(close(b[1], [0.5, -0.5, 0.5], 1e-12), "{b:?}");
    assert_eq!(
        scene.objects[0].mesh.as_deref(),
        Some(dir.path().join("tri.obj").as_path())
    );
}

#[test]
fn sources_number_objects_then_faces_across_groups() {
    let dir = folder(&[
        (
            "scene.toml",
            r#"
[[object]]
name = "first"
polygons = [
    [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
    [[2, 0, 0], [3, 0, 0], [2, 1, 0]],
]

[[object]]
name = "grouped"
mesh = "g.obj"
casts_shadows = false
two_sided = true

[[object]]
name = "last"
polygons = [[[0, 0, 5], [1, 0, 5], [0, 1, 5]]]
"#,
        ),
        (
            "g.obj",
            "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\no x\nf 1 2 3\ng y\nf 1 3 4\nf -4 -3 -2 -1\no z\nf 4//1 3//1 2//1\n",
        ),
    ]);
    let scene = Scene::load(dir.path().join("scene.toml")).unwrap();
    assert_eq!(scene.polygon_count(), 7);
    let groups: Vec<_> = scene.objects[1]
        .polygons
        .iter()
        .map(|p| p.group.clone())
        .collect();
    assert_eq!(
        groups,
        [
            Some("x".into()),
            Some("y".into()),
            Some("y".into()),
            Some("z".into())
        ]
    );
    let pieces = Pieces::from_scene(&scene).unwrap();
    assert_eq!(pieces.input_polygons, 7);
    assert!(pieces.dropped.is_empty());
    assert_eq!(pieces.input_of, [0, 1, 2, 3, 4, 5, 6]);
    for (k, p) in pieces.polygons.iter().enumerate() {
        assert_eq!(p.source() as usize, k);
        // Each piece sits where its input polygon is.
        let (_, input) = scene
            .input_polygons()
            .nth(pieces.input_of[k] as usize)
            .unwrap();
        let world: Vec<[f64; 3]> = p
            .vertices_f64()
            .into_iter()
            .map(|v| pieces.grid.grid_to_world(v))
            .collect();
        let tol = 2.0 * pieces.grid.cell_size();
        for v in &world {
            assert!(input.vertices.iter().any(|w| close(*v, *w, tol)), "{v:?}");
        }
    }
    assert_eq!(
        pieces.casts_shadows,
        [true, true, false, false, false, false, true]
    );
    assert_eq!(
        pieces.two_sided,
        [false, false, true, true, true, true, false]
    );
    assert!(pieces.max_snap_distance <= pieces.grid.cell_size());
}

#[test]
fn concave_and_non_planar_faces_become_pieces_that_name_them() {
    let dir = folder(&[
        ("scene.toml", "[[object]]\nname = \"m\"\nmesh = \"m.obj\"\n"),
        (
            "m.obj",
            "# a triangle, a concave star in a tilted plane, a twisted quad, a zero-area face\n\
             v 0 0 0\nv 1 0 0\nv 0 1 0\n\
             v 0 0 2\nv 4 0 2.5\nv 4 4 3\nv 2 1.5 2.4375\nv 0 4 2.5\n\
             v 0 0 -1\nv 2 0 -1\nv 2 2 0\nv 0 2 -1\n\
             v 5 5 5\nv 6 6 6\nv 7 7 7\n\
             f 1 2 3\nf 4 5 6 7 8\nf 9 10 11 12\nf 13 14 15\n",
        ),
    ]);
    let scene = Scene::load(dir.path().join("scene.toml")).unwrap();
    let pieces = Pieces::from_scene(&scene).unwrap();
    assert_eq!(pieces.input_polygons, 4);
    assert_eq!(pieces.dropped, [3]);
    let scale2 = pieces.grid.scale() * pieces.grid.scale();

    // The concave dart in the plane z = 2 + x/8 + y/8 tiles exactly.
    let star: Vec<_> = pieces.pieces_of(1).collect();
    assert!(star.len() >= 2, "{}", star.len());
    let total: f64 = star.iter().map(|p| p.area() / scale2).sum();
    let want = newell_area(&scene.objects[0].polygons[1].vertices);
    assert!((total - want).abs() <= 1e-6 * want, "{total} vs {want}");

    // The twisted quad becomes two triangles that together keep its corners.
    let twisted: Vec<_> = pieces.pieces_of(2).collect();
    assert_eq!(twisted.len(), 2);
    assert!(twisted.iter().all(|p| p.len() == 3));

    // Every piece names its face, and pieces are numbered in order.
    for (k, p) in pieces.polygons.iter().enumerate() {
        assert_eq!(p.source() as usize, k);
        assert!(p.check_invariants().is_ok());
    }
    let mut sorted = pieces.input_of.clone();
    sorted.sort();
    assert_eq!(sorted, pieces.input_of);
}
