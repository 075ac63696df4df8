//! Tests of scene loading and validation.

use super::*;

fn load(text: &str) -> Result<Scene> {
    Scene::from_toml_str(text, "s.toml")
}

const TRI: &str = "[[object]]\nname = \"t\"\npolygons = [[[0,0,0],[1,0,0],[0,1,0]]]\n";

#[test]
fn defaults_and_transforms() {
    let scene = load(&format!(
        "{TRI}scale = [2, 1, 1]\nrotate_deg = [0, 0, 90]\ntranslate = [1, 1, 1]\n"
    ))
    .unwrap();
    let o = &scene.objects[0];
    assert!(o.casts_shadows && !o.two_sided);
    let v = &o.polygons[0].vertices;
    // (1,0,0) -> (2,0,0) -> Rz90 (0,2,0) -> (1,3,1).
    assert!((v[1][0] - 1.0).abs() < 1e-12 && (v[1][1] - 3.0).abs() < 1e-12);
    assert_eq!(scene.ambient, 0.0);
    assert!(scene.lights.is_empty() && scene.camera.is_none());
}

#[test]
fn mirroring_keeps_the_front() {
    let scene = load(&format!("{TRI}scale = [-1, 1, 1]\n")).unwrap();
    let v = &scene.objects[0].polygons[0].vertices;
    assert_eq!(v, &vec![[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]);
}

#[test]
fn toml_errors_have_line_and_column() {
    let e = load(&format!("{TRI}colour = 1\n")).unwrap_err().to_string();
    assert!(e.starts_with("s.toml:4:1: unknown field `colour`"), "{e}");
    let e = load("ambient = \n").unwrap_err().to_string();
    assert!(e.starts_with("s.toml:1:"), "{e}");
}

#[test]
fn area_lights_drop_vertices_in_line_and_allow_rounded_digits() {
    let area = |v: &str| -> Vec<[f64; 3]> {
        let scene = load(&format!(
            "{TRI}[[light]]\ntype = \"area\"\nvertices = {v}\n"
        ))
        .unwrap();
        let LightKind::Area { vertices } = &scene.lights[0].kind else {
            panic!("an area light")
        };
        vertices.clone()
    };
    // A square with a vertex mid-edge is the square.
    assert_eq!(
        area("[[-0.3,3,-0.3],[0,3,-0.3],[0.3,3,-0.3],[0.3,3,0.3],[-0.3,3,0.3]]"),
        [
            [-0.3, 3.0, -0.3],
            [0.3, 3.0, -0.3],
            [0.3, 3.0, 0.3],
            [-0.3, 3.0, 0.3]
        ]
    );
    // A tilted pentagon written with nine significant digits: its
    // vertices lie up to 2e-9 off one plane, and it is taken whole.
    let pentagon = "[[0.331859078,2.93521907,0.694760983],[0.00707110885,2.99002162,0.605084061],\
                    [-0.0653802043,3.08958008,-0.129351962],[0.486330607,3.03143682,-0.262917521],\
                    [0.770614682,2.95642145,0.0368352651]]";
    assert_eq!(area(pentagon).len(), 5);
}

#[test]
fn semantic_errors_name_the_field() {
    let cases = [
        (format!("{TRI}{TRI}"), "object[1].name: `t` is already"),
        (
            format!("{TRI}scale = nan\n"),
            "object[0].scale: NaN is not a finite",
        ),
        (
            format!("{TRI}[[light]]\ntype = \"area\"\nvertices = [[0,0,0],[1,0,0],[2,0,0]]\n"),
            "light[0].vertices: the polygon encloses no area",
        ),
        (
            format!(
                "{TRI}[[light]]\ntype = \"area\"\nvertices = [[0,0,0],[2,0,0],[1,0,-0.2],[1,0,-2]]\n"
            ),
            "light[0].vertices: not convex at vertex 2 (reflex)",
        ),
        (
            format!(
                "{TRI}[[light]]\ntype = \"area\"\nvertices = [[0,0,0],[1,0,0],[1,1,-1],[0,0,-1]]\n"
            ),
            "not planar",
        ),
        (
            format!("{TRI}[[light]]\ntype = \"directional\"\ndirection = [0,0,0]\n"),
            "light[0].direction: must not be zero",
        ),
        (
            format!(
                "{TRI}[[light]]\ntype = \"point\"\nposition = [0,0,0]\nrange = 2\nfalloff_start = 3\n"
            ),
            "light[0].range: must be greater",
        ),
        (
            format!("{TRI}[[light]]\ntype = \"point\"\n"),
            "light[0].position: a point light needs",
        ),
        (
            format!(
                "{TRI}[[light]]\ntype = \"directional\"\ndirection = [0,-1,0]\nposition = [0,0,0]\n"
            ),
            "light[0].position: not a field of a directional light",
        ),
        (
            "[[object]]\nname = \"a\"\n".to_string(),
            "object[0]: needs `mesh`",
        ),
        ("ambient = 0.1\n".to_string(), "the scene has no polygons"),
    ];
    for (text, expected) in cases {
        let e = load(&text).unwrap_err().to_string();
        assert!(e.contains(expected), "{e} / {expected}");
    }
}

#[test]
fn at_most_32_lights() {
    let light = "[[light]]\ntype = \"point\"\nposition = [0,5,0]\n";
    assert!(load(&format!("{TRI}{}", light.repeat(32))).is_ok());
    let e = load(&format!("{TRI}{}", light.repeat(33)))
        .unwrap_err()
        .to_string();
    assert!(e.contains("light: 33 lights; at most 32"), "{e}");
}

#[test]
fn falloff_factor() {
    let f = Falloff {
        start: 1.0,
        range: 3.0,
        exponent: 2.0,
    }
    .to_illum()
    .unwrap();
    assert_eq!(f.factor(0.5), 1.0);
    assert!((f.factor(2.0) - 0.25).abs() < 1e-15);
    assert_eq!(f.factor(3.5), 0.0);
}
