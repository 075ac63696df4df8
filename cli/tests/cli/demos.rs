//! The built-in scenes load, validate and have the expected shape.

use umbra::{DEMOS, LightKind, Pieces, Scene, tetra_triangles, write_demo};

use crate::folder;

#[test]
fn every_demo_loads_and_cuts_into_pieces() {
    for name in DEMOS {
        let dir = folder(&[]);
        let path = write_demo(name, dir.path()).unwrap();
        assert_eq!(path, dir.path().join(format!("{name}.toml")));
        let scene = Scene::load(&path).unwrap();
        let pieces = Pieces::from_scene(&scene).unwrap();
        assert!(pieces.dropped.is_empty(), "{name}: {:?}", pieces.dropped);
        assert!(scene.camera.is_some() && !scene.lights.is_empty());
        assert_eq!(pieces.lights.len(), scene.lights.len());
    }
}

#[test]
fn tetra_has_256_triangles_and_the_ground_faces_the_light() {
    assert_eq!(tetra_triangles(4).len(), 256);
    assert_eq!(tetra_triangles(5).len(), 1024);
    let dir = folder(&[]);
    let scene = Scene::load(write_demo("tetra", dir.path()).unwrap()).unwrap();
    assert_eq!(scene.objects[0].polygons.len(), 256);
    let ground = &scene.objects[1].polygons[0].vertices;
    let f = |p: [f64; 3]| p[0] + p[1] - p[2] - 1.0;
    assert!(ground.iter().all(|&p| f(p).abs() < 1e-12));
    let LightKind::Point { position } = scene.lights[0].kind else {
        panic!("tetra has a point light");
    };
    // The light is on the tetrahedra's side of the ground...
    assert!(f(position) < 0.0 && f([0.0; 3]) < 0.0);
    // ... and the ground's counter-clockwise normal points to it.
    let (a, b, c) = (ground[0], ground[1], ground[2]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let to_light = [position[0] - a[0], position[1] - a[1], position[2] - a[2]];
    assert!(n[0] * to_light[0] + n[1] * to_light[1] + n[2] * to_light[2] > 0.0);
}

#[test]
fn window_room_faces_inward_and_its_window_wall_is_concave() {
    let dir = folder(&[]);
    let scene = Scene::load(write_demo("window", dir.path()).unwrap()).unwrap();
    let pieces = Pieces::from_scene(&scene).unwrap();
    // Room: 5 quads; window wall: 2 concave faces; two boxes of 6 faces.
    assert_eq!(pieces.input_polygons, 5 + 2 + 12);
    let centre = pieces.grid.world_to_grid([0.0, 2.0, 0.0]);
    for input in 0..7 {
        for p in pieces.pieces_of(input) {
            // Every surface of the room faces its centre.
            let n = p.support().unit_normal_f64();
            let v = p.vertices_f64()[0];
            let d: f64 = (0..3).map(|k| n[k] * (centre[k] - v[k])).sum();
            assert!(d > 0.0, "input {input} faces outward");
        }
    }
    // Each C-shaped wall has two reflex corners: at least three convex
    // parts, and at most 2 * 2 + 1 after Hertel-Mehlhorn merging.
    for wall in [5, 6] {
        let parts = pieces.pieces_of(wall).count();
        assert!((3..=5).contains(&parts), "{parts}");
    }
    let scale2 = pieces.grid.scale().powi(2);
    let wall: f64 = (5..7)
        .flat_map(|i| pieces.pieces_of(i))
        .map(|p| p.area() / scale2)
        .sum();
    assert!((wall - (40.0 - 3.0)).abs() < 1e-9, "{wall}");
}

#[test]
fn room_has_the_plate_6_polygon_count_under_two_quad_lights() {
    for (name, lights) in [("room", 2), ("room1", 1)] {
        let dir = folder(&[]);
        let scene = Scene::load(write_demo(name, dir.path()).unwrap()).unwrap();
        assert_eq!(scene.polygon_count(), 151, "{name}");
        assert_eq!(scene.lights.len(), lights);
        assert!(
            scene
                .lights
                .iter()
                .all(|l| matches!(l.kind, LightKind::Area { .. }))
        );
    }
}

#[test]
fn dm_demos_have_their_sizes_and_run_with_umbra_dm() {
    let dir = folder(&[]);
    let office = Scene::load(write_demo("office", dir.path()).unwrap()).unwrap();
    let polygons = office.input_polygons().count();
    assert!((100..=200).contains(&polygons), "{polygons}");
    assert!(matches!(office.lights[0].kind, LightKind::Area { .. }));
    let cubes = Scene::load(write_demo("cubes", dir.path()).unwrap()).unwrap();
    let names: Vec<&str> = cubes.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names.iter().filter(|n| n.starts_with("cube_")).count(), 15);
    // Each cube: six quads with dyadic corners (the grid holds them
    // exactly), each exactly planar, so the cube is an exactly convex body.
    for (o, polygon) in cubes.input_polygons() {
        if !cubes.objects[o].name.starts_with("cube_") {
            continue;
        }
        let exact: Vec<[i128; 3]> = polygon
            .vertices
            .iter()
            .map(|v| {
                v.map(|c| {
                    let scaled = c * 2048.0;
                    assert_eq!(scaled.fract(), 0.0, "{c} is no multiple of 1/2048");
                    scaled as i128
                })
            })
            .collect();
        assert_eq!(exact.len(), 4);
        let d = |k: usize| std::array::from_fn::<i128, 3, _>(|a| exact[k][a] - exact[0][a]);
        let (u, v, w) = (d(1), d(2), d(3));
        let volume = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0]);
        assert_eq!(volume, 0, "a face of {} bends", cubes.objects[o].name);
    }
    // The same text every time (a fixed seed).
    let again = folder(&[]);
    let a = std::fs::read_to_string(write_demo("cubes", again.path()).unwrap()).unwrap();
    let b = std::fs::read_to_string(dir.path().join("cubes.toml")).unwrap();
    assert_eq!(a, b);
    let run = crate::umbra(dir.path(), &["demo", "office", "-o", "o"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("cells"), "{}", run.stdout);
    let json = std::fs::read_to_string(dir.path().join("o/office.json")).unwrap();
    assert!(json.contains("\"dm\""), "{json}");
}

#[test]
fn the_meshes_demo_finds_most_of_the_joint_umbra_under_both_meshes() {
    use crate::closed_mesh::{floor_umbra, true_floor_umbra};
    let dir = folder(&[]);
    let run = crate::umbra(dir.path(), &["demo", "meshes", "-o", "m"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let m = dir.path().join("m");
    let scene = Scene::load(m.join("meshes.toml")).unwrap();
    assert_eq!(scene.polygon_count(), 1 + 1024 + 320);
    let LightKind::Area { vertices } = &scene.lights[0].kind else {
        panic!("meshes has an area light");
    };
    // Points over the light (a square 0.8 wide, 5 high): its corners, edge
    // middles and centre.
    let (lo, hi) = (vertices[0], vertices[2]);
    let light: Vec<[f64; 3]> = (0..9)
        .map(|k| {
            let (s, t) = (f64::from(k % 3) / 2.0, f64::from(k / 3) / 2.0);
            [
                lo[0] + s * (hi[0] - lo[0]),
                lo[1],
                lo[2] + t * (hi[2] - lo[2]),
            ]
        })
        .collect();
    // `floor_umbra` runs `umbra shadow scene.toml` and checks every umbra
    // floor face by the ray oracle.
    std::fs::copy(m.join("meshes.toml"), m.join("scene.toml")).unwrap();
    let floor = floor_umbra(&m, "shadow", &light);
    let triangles = |name: &str| -> Vec<[[f64; 3]; 3]> {
        let object = scene.objects.iter().find(|o| o.name == name).unwrap();
        object
            .polygons
            .iter()
            .map(|p| [p.vertices[0], p.vertices[1], p.vertices[2]])
            .collect()
    };
    let (torus, blob) = (triangles("torus"), triangles("blob"));
    assert_eq!((torus.len(), blob.len()), (1024, 320));
    // The torus's shadow lies at x < 0.5, the blob's at x > 0.5.
    let truth = true_floor_umbra(&torus, &light, [-5.0, 0.5], [-4.0, 3.5])
        + true_floor_umbra(&blob, &light, [0.5, 5.0], [-2.5, 3.5]);
    // 13.9 in truth; `umbra shadow` finds 13.1 (`umbra dm` 13.4).
    assert!(
        floor.umbra_area > 0.85 * truth,
        "floor umbra {} of {truth}",
        floor.umbra_area
    );
    // Under the torus's tube and the blob's middle, seen from the light's.
    assert!(floor.umbra_at([-3.75, -0.42]) && floor.umbra_at([2.64, 0.56]));
}
