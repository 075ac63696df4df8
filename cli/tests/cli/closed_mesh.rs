//! A bumpy closed mesh (an icosphere of 320 triangles, its corners pushed
//! in and out, so no body of its pieces is convex) over a floor, under a
//! light smaller than it: each triangle casts its own shadow, none an
//! umbra that reaches the floor, and the floor under the mesh is a joint
//! umbra of many of them. A ray oracle checks that every umbra floor face
//! sees none of the light, and both `umbra shadow` and `umbra dm` find
//! most of the joint umbra under the mesh (the same oracle on a grid
//! measures it): the umbrae of a convex core of the mesh's kernel and of
//! its flat sections, and in `umbra dm` cells proven dark past them.

use crate::area::face_points;
use crate::open_box::crosses;
use crate::vectors::inner_points;
use crate::{folder, umbra};
use umbra::load_ply;

/// The mesh's triangles, counter-clockwise seen from outside: an
/// icosahedron split twice, its corners on radii 0.94 to 1.06 about (0,
/// 2.5, 0).
fn bumpy_sphere() -> Vec<[[f64; 3]; 3]> {
    umbra::shapes::bumpy_sphere([0.0, 2.5, 0.0], 1.0, 0.06, 2)
}

fn scene() -> String {
    mesh_scene(
        3,
        "blob",
        &bumpy_sphere(),
        "[[-0.4, 6, -0.4], [0.4, 6, -0.4], [0.4, 6, 0.4], [-0.4, 6, 0.4]]",
    )
}

/// A scene of a square floor (input polygon 0: x, z in `[-half, half]`,
/// facing up), a mesh of `triangles` named `name` over it and one area
/// light with corners `light` (a TOML array).
pub(crate) fn mesh_scene(
    half: i32,
    name: &str,
    triangles: &[[[f64; 3]; 3]],
    light: &str,
) -> String {
    let triangles: Vec<String> = triangles
        .iter()
        .map(|t| {
            let corners: Vec<String> = t
                .iter()
                .map(|c| format!("[{:.6}, {:.6}, {:.6}]", c[0], c[1], c[2]))
                .collect();
            format!("[{}]", corners.join(", "))
        })
        .collect();
    format!(
        r#"
[[object]]
name = "floor"
polygons = [[[-{half}, 0, -{half}], [-{half}, 0, {half}], [{half}, 0, {half}], [{half}, 0, -{half}]]]

[[object]]
name = "{name}"
polygons = [{}]

[[light]]
type = "area"
vertices = {light}
"#,
        triangles.join(", ")
    )
}

#[test]
fn a_bumpy_closed_mesh_hides_its_joint_umbra() {
    let dir = folder(&[("scene.toml", &scene())]);
    let light: Vec<[f64; 3]> = (0..5 * 5)
        .map(|k| {
            [
                -0.4 + 0.2 * (k % 5) as f64,
                6.0,
                -0.4 + 0.2 * (k / 5) as f64,
            ]
        })
        .collect();
    // The mesh within 1.06 of (0, 2.5, 0), the light within 0.4 of the
    // axis 6 high: its shadow within 4 of it.
    let truth = true_floor_umbra(&bumpy_sphere(), &light, [-4.0, 4.0], [-4.0, 4.0]);
    for command in ["shadow", "dm"] {
        let floor = floor_umbra(dir.path(), command, &light);
        let umbra_area = floor.umbra_area;
        // The floor right under the mesh sees none of the light past it,
        // and no triangle hides all of it alone. The core of the kernel
        // (radius 0.9 or so) has an umbra of radius about 1.25 on the
        // floor; a disc of radius 1 at least is umbra.
        assert!(
            umbra_area > std::f64::consts::PI,
            "{command}: floor umbra {umbra_area}"
        );
        // And most of the true umbra: 5.83, of which `umbra shadow` finds
        // 5.52 (the kernel's core and the sections), `umbra dm` 5.66.
        assert!(
            umbra_area > 0.9 * truth,
            "{command}: floor umbra {umbra_area} of {truth}"
        );
        assert!(
            floor.umbra_at([0.0, 0.0]),
            "{command}: the floor under the mesh is not umbra (umbra area {umbra_area})"
        );
    }
}

/// The area of the floor (y = 0) that sees none of the points `light`
/// past `triangles`, by the ray oracle at the middles of squares 0.1 wide
/// tiling `[x0, x1] x [z0, z1]` (which must hold all of the shadow).
pub(crate) fn true_floor_umbra(
    triangles: &[[[f64; 3]; 3]],
    light: &[[f64; 3]],
    [x0, x1]: [f64; 2],
    [z0, z1]: [f64; 2],
) -> f64 {
    let step = 0.1;
    let (nx, nz) = (
        ((x1 - x0) / step).round() as u32,
        ((z1 - z0) / step).round() as u32,
    );
    let mut dark = 0;
    for i in 0..nx {
        for j in 0..nz {
            let p = [
                x0 + step * (f64::from(i) + 0.5),
                0.0,
                z0 + step * (f64::from(j) + 0.5),
            ];
            let hidden = |l: &[f64; 3]| {
                triangles
                    .iter()
                    .any(|t| crosses(p, *l, &t[..]) != Some(false))
            };
            if light.iter().all(hidden) {
                dark += 1;
            }
        }
    }
    f64::from(dark) * step * step
}

/// The floor's faces in a run's output ([`floor_umbra`]).
pub(crate) struct Floor {
    /// The area of its faces in umbra.
    pub(crate) umbra_area: f64,
    /// Its faces' corners, and whether each is umbra.
    faces: Vec<(Vec<[f64; 3]>, bool)>,
}

impl Floor {
    /// Whether the floor face holding `[x, z]` is umbra.
    pub(crate) fn umbra_at(&self, point: [f64; 2]) -> bool {
        self.faces
            .iter()
            .find(|(corners, _)| contains_xz(corners, point))
            .expect("a floor face holds the point")
            .1
    }
}

/// Runs `umbra COMMAND scene.toml` in `dir` on a scene of a floor
/// (input polygon 0, in the plane y = 0) and one mesh over it, and checks
/// by a ray oracle that every floor face in umbra sees none of the
/// points `light` (on the scene's one light): no segment from points
/// inside it to them misses the mesh.
pub(crate) fn floor_umbra(dir: &std::path::Path, command: &str, light: &[[f64; 3]]) -> Floor {
    let out = format!("{command}.ply");
    let run = umbra(dir, &[command, "scene.toml", "-o", &out]);
    assert_eq!(run.code, 0, "{command}: {}", run.stderr);
    let mesh = load_ply(&dir.join(&out)).unwrap();
    let faces: Vec<Vec<[f64; 3]>> = (0..mesh.faces.len())
        .map(|f| face_points(&mesh, f))
        .collect();
    let sources: Vec<(u32, u32)> = mesh
        .faces
        .iter()
        .map(|f| (f.source, f.umbra_mask))
        .collect();
    let occluders: Vec<&Vec<[f64; 3]>> = (0..faces.len())
        .filter(|&f| sources[f].0 != 0)
        .map(|f| &faces[f])
        .collect();
    let mut umbra_area = 0.0;
    for f in (0..faces.len()).filter(|&f| sources[f].0 == 0 && sources[f].1 & 1 != 0) {
        umbra_area += area_xz(&faces[f]);
        for p in inner_points(&faces[f]) {
            for &l in light {
                let hits: Vec<Option<bool>> = occluders.iter().map(|q| crosses(p, l, q)).collect();
                assert!(
                    hits.contains(&Some(true)) || hits.contains(&None),
                    "{command}: umbra floor face {f} sees the light from {p:?} at {l:?}"
                );
            }
        }
    }
    let faces = faces
        .into_iter()
        .zip(sources)
        .filter(|(_, (source, _))| *source == 0)
        .map(|(corners, (_, mask))| (corners, mask & 1 != 0))
        .collect();
    Floor { umbra_area, faces }
}

/// Whether a floor face (convex, in the plane y = 0) holds the point
/// `[x, z]` (or has it on its border).
fn contains_xz(face: &[[f64; 3]], [x, z]: [f64; 2]) -> bool {
    let n = face.len();
    let side = |i: usize| {
        let (a, b) = (face[i], face[(i + 1) % n]);
        (b[0] - a[0]) * (z - a[2]) - (b[2] - a[2]) * (x - a[0])
    };
    (0..n).all(|i| side(i) >= 0.0) || (0..n).all(|i| side(i) <= 0.0)
}

/// The area of a floor face (convex, in the plane y = 0).
fn area_xz(face: &[[f64; 3]]) -> f64 {
    let n = face.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (a, b) = (face[i], face[(i + 1) % n]);
            a[0] * b[2] - b[0] * a[2]
        })
        .sum();
    twice.abs() / 2.0
}
