//! The `meshes` demo: dense closed meshes over a floor under a small
//! square light, a torus of 1,024 triangles and a bumpy sphere of 320
//! ([`crate::shapes`]). No triangle alone casts an umbra that reaches the
//! floor; what is dark there is the joint umbra of many, which `umbra
//! shadow` finds by the umbrae of convex cores and flat sections inside
//! the meshes, and `umbra dm` by those and cells proven dark.

use crate::demo::{DemoFiles, obj_text};
use crate::shapes::{Triangle, bumpy_sphere, torus};

/// The torus's ring and tube radii and its quads around each.
const TORUS: ([f64; 3], (f64, f64), (u32, u32)) = ([-1.5, 1.4, -0.3], (1.2, 0.45), (32, 16));

/// The bumpy sphere's centre, radius, bumps and subdivisions.
const BLOB: ([f64; 3], f64, f64, u32) = ([1.9, 1.3, 0.4], 0.9, 0.06, 2);

/// The demo's files.
pub(crate) fn meshes_files() -> DemoFiles {
    let as_polygons = |triangles: Vec<Triangle>| -> Vec<Vec<[f64; 3]>> {
        triangles.iter().map(|t| t.to_vec()).collect()
    };
    let (centre, radii, quads) = TORUS;
    let ring = obj_text(
        "torus of 32 x 16 quads cut into triangles, wound outward",
        &[("torus", as_polygons(torus(centre, radii, quads)))],
    );
    let (centre, radius, bump, subdivisions) = BLOB;
    let blob = obj_text(
        "icosahedron split twice, corners 6 % in and out, wound outward",
        &[(
            "blob",
            as_polygons(bumpy_sphere(centre, radius, bump, subdivisions)),
        )],
    );
    DemoFiles {
        name: "meshes".into(),
        scene: SCENE.into(),
        meshes: vec![
            ("meshes/torus.obj".into(), ring),
            ("meshes/blob.obj".into(), blob),
        ],
        grid: None,
    }
}

const SCENE: &str = r#"# Dense closed meshes over a floor: a torus (1,024 triangles) and a bumpy
# sphere (320) under a square light narrower than the torus's tube. Their
# umbra on the floor is the joint umbra of many triangles.
ambient = 0.05

[[object]]
name = "floor"
casts_shadows = false
polygons = [[[-5.0, 0.0, -5.0], [-5.0, 0.0, 5.0], [5.0, 0.0, 5.0], [5.0, 0.0, -5.0]]]

[[object]]
name = "torus"
mesh = "meshes/torus.obj"

[[object]]
name = "blob"
mesh = "meshes/blob.obj"

[[light]]
type = "area"
vertices = [[-0.4, 5.0, -0.4], [0.4, 5.0, -0.4], [0.4, 5.0, 0.4], [-0.4, 5.0, 0.4]]
intensity = 40.0
color = [1.0, 0.97, 0.9]

[camera]
eye = [0.0, 5.5, 7.0]
target = [0.0, 0.5, 0.0]
up = [0.0, 1.0, 0.0]
fov_deg = 55.0
width = 800
height = 600
"#;
