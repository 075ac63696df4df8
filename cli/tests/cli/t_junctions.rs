//! A plate made of a big quad and two small ones along its edge, meeting
//! it in a T-junction: watertight in the input, so its shadow under a
//! point light has no light in it. Snapped apart, the junction's corner
//! and the big quad's edge would leave a crack a grid step wide at most,
//! and a thin lit wedge across the shadow on the floor; welded (the corner
//! made the big quad's too), the shadow is whole.

use crate::area::floor_classes;
use crate::input_frames::assert_on_input;
use crate::{folder, umbra};
use umbra::load_ply;

/// The point light.
const LIGHT: [f64; 3] = [0.23, 3.1, 0.37];

/// The plate's corners turned by `turn` radians about y and tilted, at
/// about y = 1.4: the big quad's, then the two small ones', each quad
/// counter-clockwise seen from above.
fn plate(turn: f64) -> [[[f64; 3]; 4]; 3] {
    let (s, c) = turn.sin_cos();
    let at = |x: f64, z: f64| -> [f64; 3] {
        [
            0.13 + c * x + s * z,
            1.4 + 0.11 * x - 0.07 * z,
            -0.21 - s * x + c * z,
        ]
    };
    // The small quads share the big one's edge x = 0, split at z = m.
    let m = 0.3 + 0.4 * (turn * 3.7).sin().abs();
    [
        [at(0.0, 0.0), at(0.0, 1.0), at(1.0, 1.0), at(1.0, 0.0)],
        [at(-1.0, 0.0), at(-1.0, m), at(0.0, m), at(0.0, 0.0)],
        [at(-1.0, m), at(-1.0, 1.0), at(0.0, 1.0), at(0.0, m)],
    ]
}

fn scene(turn: f64) -> String {
    let quads: Vec<String> = plate(turn)
        .iter()
        .map(|q| {
            let corners: Vec<String> = q
                .iter()
                .map(|p| format!("[{:?}, {:?}, {:?}]", p[0], p[1], p[2]))
                .collect();
            format!("[{}]", corners.join(", "))
        })
        .collect();
    format!(
        "[[object]]\nname = \"floor\"\npolygons = [[[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]]]\n\n\
         [[object]]\nname = \"plate\"\npolygons = [{}]\ntwo_sided = true\n\n\
         [[light]]\ntype = \"point\"\nposition = [{:?}, {:?}, {:?}]\nintensity = 5.0\n",
        quads.join(", "),
        LIGHT[0],
        LIGHT[1],
        LIGHT[2]
    )
}

/// Where the light casts `p` on the floor (x, z).
fn cast(p: [f64; 3]) -> [f64; 2] {
    let t = LIGHT[1] / (LIGHT[1] - p[1]);
    [
        LIGHT[0] + t * (p[0] - LIGHT[0]),
        LIGHT[2] + t * (p[2] - LIGHT[2]),
    ]
}

/// How far inside the convex polygon `hull` (counter-clockwise in x, z as
/// seen from above: clockwise in (x, z) coordinates) the point `q` lies;
/// negative outside.
fn depth_inside(hull: &[[f64; 2]], q: [f64; 2]) -> f64 {
    let n = hull.len();
    (0..n)
        .map(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % n]);
            let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
            let len = (dx * dx + dz * dz).sqrt();
            // Seen from above (+y), counter-clockwise: the inside is to the
            // right in (x, z).
            ((q[0] - a[0]) * dz - (q[1] - a[1]) * dx) / len
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn a_t_junction_casts_a_whole_shadow() {
    for k in 0..8 {
        let turn = 0.37 + 0.71 * f64::from(k);
        let dir = folder(&[("scene.toml", &scene(turn))]);
        let run = umbra(dir.path(), &["shadow", "scene.toml", "-o", "out.ply"]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
        // The welded big quad, cut at the corner on its side, still tiles
        // its input quad.
        let input = umbra::Scene::from_toml_str(&scene(turn), "scene.toml").unwrap();
        assert_on_input(&input, &mesh, &format!("turn {turn}"));
        // The big quad's welded corner is written where the strips' corner
        // is: no crack between them in the output either.
        let [big, low, high] = plate(turn);
        let joint = low[2];
        let nearest = mesh
            .faces
            .iter()
            .filter(|f| f.source == 1)
            .flat_map(|f| f.vertices.iter().map(|&v| mesh.vertices[v as usize].0))
            .map(|p| {
                (0..3)
                    .map(|a| (p[a] - joint[a]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest <= 1e-12,
            "turn {turn}: the welded corner is {nearest:e} off"
        );
        // The plate's shadow: the cast outline (the plate is a rectangle,
        // planar, so its shadow is the quadrilateral of its cast corners).
        let outline: Vec<[f64; 2]> = [low[0], high[1], big[2], big[3]]
            .iter()
            .map(|&p| cast(p))
            .collect();
        let mut lit_inside = Vec::new();
        for face in mesh.faces.iter().filter(|f| f.source == 0) {
            if face.lit_mask & 1 == 0 {
                continue;
            }
            let n = face.vertices.len() as f64;
            let centre = face.vertices.iter().fold([0.0; 2], |acc, &v| {
                let p = mesh.vertices[v as usize].0;
                [acc[0] + p[0] / n, acc[1] + p[2] / n]
            });
            let depth = depth_inside(&outline, centre);
            if depth > 1e-4 {
                lit_inside.push((centre, depth));
            }
        }
        assert!(
            lit_inside.is_empty(),
            "turn {turn}: lit floor faces inside the plate's shadow: {lit_inside:?}"
        );
    }
}

/// A triangle whose edge holds a neighbour's corner, turned so that the
/// grid moves the corner off the edge: welded, the triangle is cut from
/// its far corner, with no sliver along the edge (a nearly straight
/// triangle of the edge's two ends and the welded corner, its plane
/// anywhere: its corners' irradiance would take that plane's normal).
#[test]
fn a_welded_face_has_no_sliver() {
    use umbra::{Pieces, Scene};
    let mut welded = 0;
    for k in 0..16 {
        let turn = 0.29 + 0.83 * f64::from(k);
        let (s, c) = turn.sin_cos();
        let shift = 0.0173 * f64::from(k);
        let at = |x: f64, y: f64, z: f64| -> String {
            let p = [
                c * x + s * z + 0.17 + shift,
                y * 0.9 + 0.1 * x + 1.3 - 0.7 * shift,
                -s * x + c * z - 0.11 + 0.3 * shift,
            ];
            format!("[{:?}, {:?}, {:?}]", p[0], p[1], p[2])
        };
        // The triangle's edge from (1, 0, 0) to (0, 0, 1) holds the two
        // neighbours' shared corner.
        let text = format!(
            "[[object]]\nname = \"t\"\npolygons = [[{}, {}, {}], [{}, {}, {}], [{}, {}, {}]]\n",
            at(0.0, 0.0, 0.0),
            at(1.0, 0.0, 0.0),
            at(0.0, 0.0, 1.0),
            at(1.0, 0.0, 0.0),
            at(1.0, 0.0, 1.0),
            at(0.63, 0.0, 0.37),
            at(0.63, 0.0, 0.37),
            at(1.0, 0.0, 1.0),
            at(0.0, 0.0, 1.0),
        );
        let dir = folder(&[("scene.toml", &text)]);
        let scene = Scene::load(dir.path().join("scene.toml")).unwrap();
        let pieces = Pieces::from_scene(&scene).unwrap();
        let whole: f64 = pieces.pieces_of(0).map(|p| p.area()).sum();
        welded += usize::from(pieces.pieces_of(0).count() > 1);
        for piece in pieces.pieces_of(0) {
            assert!(
                piece.area() > 1e-3 * whole,
                "turn {turn}: a sliver of area {} of {whole}",
                piece.area()
            );
        }
    }
    // (The triangle took the corner, mostly off its plane or its edge.)
    assert!(welded >= 8, "{welded} of 16 cut");
}

/// The faces of the box `[-1, 1]^3`, counter-clockwise seen from outside,
/// the top cut in three strips and one side in two (their corners on the
/// unsplit neighbours' edges), or whole.
pub(crate) fn box_faces(split: bool) -> Vec<Vec<[f64; 3]>> {
    let mut faces = vec![
        vec![
            [-1.0, -1.0, -1.0],
            [-1.0, -1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [-1.0, 1.0, -1.0],
        ],
        vec![
            [-1.0, -1.0, -1.0],
            [1.0, -1.0, -1.0],
            [1.0, -1.0, 1.0],
            [-1.0, -1.0, 1.0],
        ],
        vec![
            [-1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [1.0, 1.0, -1.0],
            [1.0, -1.0, -1.0],
        ],
        vec![
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ],
    ];
    let (xs, ys): (&[f64], &[f64]) = if split {
        (&[-1.0, -0.3, 0.4, 1.0], &[-1.0, 0.2, 1.0])
    } else {
        (&[-1.0, 1.0], &[-1.0, 1.0])
    };
    for w in xs.windows(2) {
        faces.push(vec![
            [w[0], 1.0, -1.0],
            [w[0], 1.0, 1.0],
            [w[1], 1.0, 1.0],
            [w[1], 1.0, -1.0],
        ]);
    }
    for w in ys.windows(2) {
        faces.push(vec![
            [1.0, w[0], -1.0],
            [1.0, w[1], -1.0],
            [1.0, w[1], 1.0],
            [1.0, w[0], 1.0],
        ]);
    }
    faces
}

fn box_scene(split: bool) -> String {
    let faces: Vec<String> = box_faces(split).iter().map(|f| format!("{f:?}")).collect();
    format!(
        "[[object]]\nname = \"floor\"\npolygons = [[[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]]]\n\n\
         [[object]]\nname = \"box\"\npolygons = [{}]\ntranslate = [0.1, 1.5, -0.2]\n\
         rotate_deg = [17, 33, -11]\nscale = [0.5, 0.4, 0.6]\n\n\
         [[light]]\ntype = \"area\"\nvertices = [[-0.3, 4, -0.3], [0.3, 4, -0.3], [0.3, 4, 0.3], [-0.3, 4, 0.3]]\nintensity = 10\n",
        faces.join(", ")
    )
}

/// Welded, the box with faces split in strips is closed, and hides the
/// light from the floor as the whole box does: its umbra is the body's,
/// not the little each face hides alone (unwelded: 65 % of it). The welded
/// corners lie up to half a grid step off their edges, and the body the
/// box blocks as may be moved in by up to 64 grid steps (module
/// `area_shadow::groups::solid`): about 2e-4 of this umbra's area.
#[test]
fn a_box_split_in_strips_shades_the_floor_as_the_whole_box() {
    let dir = folder(&[
        ("whole.toml", &box_scene(false)),
        ("split.toml", &box_scene(true)),
    ]);
    for command in ["shadow", "dm"] {
        let umbra_area = |name: &str| {
            let run = umbra(dir.path(), &[command, name, "-o", "out.ply"]);
            assert_eq!(run.code, 0, "{}", run.stderr);
            floor_classes(&load_ply(&dir.path().join("out.ply")).unwrap())[2]
        };
        let (whole, split) = (umbra_area("whole.toml"), umbra_area("split.toml"));
        assert!(whole > 2.0, "{command}: {whole}");
        assert!(
            split <= whole * (1.0 + 1e-9) && split >= whole * (1.0 - 2e-4),
            "{command}: {split} vs {whole}"
        );
    }
}
