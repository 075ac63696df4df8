//! An area light in a tilted plane whose corners' nearest grid points are
//! not coplanar (a user's scene that was refused): both commands take it as
//! one convex light, classify the floor under an occluder, and light it as
//! quadrature over the light says; and a pentagon written with few digits.

use crate::area::{face_points, floor_classes};
use crate::vectors::{cross, dot, sub};
use crate::{folder, umbra};
use umbra::load_ply;

/// The light's corners, a parallelogram tilted about 10 degrees about x
/// and 2 about z, facing down.
const LIGHT: [[f64; 3]; 4] = [
    [-1.3898948642456967, 3.5282534945275446, -0.6631425633241408],
    [
        -0.19145700534392707,
        3.4792339852393814,
        -0.6631425633241408,
    ],
    [-0.18358269696526763, 3.6717465054724556, 0.4013633257258893],
    [-1.3820205558670373, 3.7207660147606187, 0.4013633257258893],
];

/// The occluder: x in [-1.6, 0], z in [-0.93, 0.67] at y = 2, wider than
/// the light, so part of the floor sees none of it.
const OCCLUDER: [[f64; 2]; 2] = [[-1.6, 0.0], [-0.93, 0.67]];

fn scene() -> String {
    let corners: Vec<String> = LIGHT
        .iter()
        .map(|p| format!("[{:?}, {:?}, {:?}]", p[0], p[1], p[2]))
        .collect();
    let [[x0, x1], [z0, z1]] = OCCLUDER;
    format!(
        r#"
[[object]]
name = "floor"
polygons = [[[-3, 0, 3], [3, 0, 3], [3, 0, -3], [-3, 0, -3]]]

[[object]]
name = "occluder"
polygons = [[[{x0}, 2, {z1}], [{x1}, 2, {z1}], [{x1}, 2, {z0}], [{x0}, 2, {z0}]]]

[[light]]
type = "area"
vertices = [{}]
intensity = 1.5
"#,
        corners.join(", ")
    )
}

/// Irradiance at floor point `p` (normal +y) by midpoint quadrature over
/// the light (radiance 1.5), each sample blocked when its ray meets the
/// occluder.
fn quadrature(p: [f64; 3]) -> f64 {
    let [o, a, _, c] = LIGHT;
    let (e1, e2) = (sub(a, o), sub(c, o));
    let across = cross(e1, e2);
    let area = dot(across, across).sqrt();
    let normal = across.map(|c| c / area);
    let n = 400;
    let h = 1.0 / f64::from(n);
    let mut e = 0.0;
    for i in 0..n {
        for j in 0..n {
            let (s, t) = ((f64::from(i) + 0.5) * h, (f64::from(j) + 0.5) * h);
            let x = [0, 1, 2].map(|k| o[k] + s * e1[k] + t * e2[k]);
            let d = sub(x, p);
            let at = (2.0 - p[1]) / d[1];
            let (cx, cz) = (p[0] + at * d[0], p[2] + at * d[2]);
            let [[x0, x1], [z0, z1]] = OCCLUDER;
            if (0.0..1.0).contains(&at) && (x0..x1).contains(&cx) && (z0..z1).contains(&cz) {
                continue;
            }
            let r2 = dot(d, d);
            let r = r2.sqrt();
            // cos at the floor (normal +y) and at the light (its normal
            // faces the floor: -d . normal > 0).
            let cos_floor = d[1] / r;
            let cos_light = -dot(d, normal) / r;
            e += 1.5 * cos_floor * cos_light / r2 * area * h * h;
        }
    }
    e
}

#[test]
fn a_tilted_light_off_the_grid_shades_the_floor() {
    let dir = folder(&[("scene.toml", scene().as_str())]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{command}: {}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        let [lit, penumbra, umbra] = floor_classes(&mesh);
        assert!(
            (lit + penumbra + umbra - 36.0).abs() < 1e-9,
            "{command}: {lit} + {penumbra} + {umbra}"
        );
        assert!(
            lit > 5.0 && penumbra > 5.0 && umbra > 1.0,
            "{command}: lit {lit}, penumbra {penumbra}, umbra {umbra}"
        );
        let mut checked = 0;
        for (f, face) in mesh.faces.iter().enumerate() {
            if face.source != 0 {
                continue;
            }
            for (p, &v) in face_points(&mesh, f).into_iter().zip(&face.vertices) {
                let e = f64::from(mesh.vertices[v as usize].1);
                if face.umbra_mask & 1 != 0 {
                    assert!(e.abs() < 1e-6, "{command}: umbra vertex {p:?}: {e}");
                    continue;
                }
                checked += 1;
                if checked % 5 != 0 {
                    continue;
                }
                let truth = quadrature(p);
                assert!(
                    (e - truth).abs() <= 2e-3 * truth + 1e-5,
                    "{command}: vertex {p:?}: {e} vs {truth}"
                );
            }
        }
        assert!(checked > 20, "{command}: {checked} vertices checked");
    }
}

/// A tilted pentagon light written with nine significant digits (its
/// vertices up to 2e-9 off one plane), over a bare floor: both commands
/// take it, and every floor vertex gets light from it.
#[test]
fn a_rounded_tilted_pentagon_light_is_taken() {
    let scene = r#"
[[object]]
name = "floor"
polygons = [[[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]]

[[light]]
type = "area"
vertices = [[0.331859078, 2.93521907, 0.694760983], [0.00707110885, 2.99002162, 0.605084061], [-0.0653802043, 3.08958008, -0.129351962], [0.486330607, 3.03143682, -0.262917521], [0.770614682, 2.95642145, 0.0368352651]]
intensity = 1.0
"#;
    let dir = folder(&[("scene.toml", scene)]);
    for command in ["shadow", "dm"] {
        let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{command}: {}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        assert!(mesh.faces.iter().all(|f| f.lit_mask == 1), "{command}");
        assert!(mesh.vertices.iter().all(|(_, e)| *e > 0.0), "{command}");
    }
}

/// A one-sided quad over a floor, and a tilted triangle light crossing the
/// floor's plane: the part of the light in front of the quad lies below
/// the floor, so the quad sees none of it (sampled segments agree). The
/// triangle's own plane holds grid points too sparsely to halve it in a
/// proof, so it is snapped onto a plane that holds them densely; the
/// quad is then proven umbra.
#[test]
fn a_quad_that_sees_a_tilted_triangle_only_below_the_floor_is_umbra() {
    let scene = r#"
[[object]]
name = "floor"
polygons = [[[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]]]

[[object]]
name = "quad"
polygons = [[[-0.42326865331708707, -0.90600422025459659, -1], [0.57298834401784871, -0.81956351652552439, -1], [0.57298834401784871, -0.81956351652552439, 1], [-0.42326865331708707, -0.90600422025459659, 1]]]
translate = [0.12059871529015886, 1.0582998304569451, -0.15326538264757122]
rotate_deg = [-23.944372442942246, 47.458375291776321, 0]
scale = [0.56695087603180971, 0.44878095731694573, 1.1969455468970165]

[[light]]
type = "area"
vertices = [[-1.1575838019248348, -0.1982945797119009, -1.4568135662675603], [-1.0604545867219479, 0.091563397705811816, -1.6703250650443702], [-1.6040091416277682, 0.33254635617886347, -1.4413392674263601]]
intensity = 1.0
"#;
    let light = [
        [
            -1.1575838019248348,
            -0.1982945797119009,
            -1.4568135662675603,
        ],
        [
            -1.060454586721948,
            0.091_563_397_705_811_82,
            -1.6703250650443702,
        ],
        [-1.6040091416277682, 0.33254635617886347, -1.44133926742636],
    ];
    let dir = folder(&[("scene.toml", scene)]);
    let run = umbra(dir.path(), &["shadow", "scene.toml", "-o", "out.ply"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
    let quad: Vec<usize> = (0..mesh.faces.len())
        .filter(|&f| mesh.faces[f].source == 1)
        .collect();
    assert!(!quad.is_empty());
    for &f in &quad {
        let corners = face_points(&mesh, f);
        let normal = cross(sub(corners[1], corners[0]), sub(corners[2], corners[0]));
        // The premise: every sampled segment from the face to a point of
        // the light in front of it crosses the floor (y = 0, |x|, |z| < 4).
        for p in crate::vectors::inner_points(&corners) {
            for i in 0..=20 {
                for j in 0..=(20 - i) {
                    let (u, v) = (f64::from(i) / 20.0, f64::from(j) / 20.0);
                    let l: [f64; 3] = std::array::from_fn(|k| {
                        light[0][k]
                            + u * (light[1][k] - light[0][k])
                            + v * (light[2][k] - light[0][k])
                    });
                    if dot(normal, sub(l, p)) <= 0.0 {
                        continue;
                    }
                    let t = p[1] / (p[1] - l[1]);
                    let x = [p[0] + t * (l[0] - p[0]), p[2] + t * (l[2] - p[2])];
                    assert!(
                        l[1] < 0.0 && x[0].abs() < 4.0 && x[1].abs() < 4.0,
                        "face {f} sees {l:?} from {p:?}"
                    );
                }
            }
        }
        assert_eq!(mesh.faces[f].umbra_mask, 1, "face {f} of the quad");
    }
}
