//! The discontinuity-mesh demos, run with `umbra dm`:
//!
//! - `office`: a closed room with four desks (`meshes/desk.obj`: a top on
//!   four legs, one object each), a monitor on each desk and a filing
//!   cabinet under one square ceiling light: 156 input polygons, the size
//!   of the Chrysanthou-Slater scenes;
//! - `cubes`: fifteen cubes placed and turned at random (a fixed seed) in
//!   the same room under the same light.

use std::fmt::Write as _;

/// The room's shell: `meshes/room.obj` (floor, ceiling, three walls) and
/// the fourth wall, all facing inward.
const SHELL: &str = r#"[[object]]
name = "room"
mesh = "meshes/room.obj"

[[object]]
name = "front_wall"
polygons = [[[-5.0, 0.0, -5.0], [5.0, 0.0, -5.0], [5.0, 4.0, -5.0], [-5.0, 4.0, -5.0]]]

[[light]]
type = "area"
vertices = [[-0.5, 3.9, -0.5], [0.5, 3.9, -0.5], [0.5, 3.9, 0.5], [-0.5, 3.9, 0.5]]
intensity = 6.0
color = [1.0, 0.97, 0.9]

[camera]
eye = [0.0, 3.2, 4.8]
target = [0.0, 0.5, -1.0]
up = [0.0, 1.0, 0.0]
fov_deg = 65.0
width = 800
height = 600

"#;

fn cuboid(s: &mut String, name: &str, centre: [f64; 3], size: [f64; 3], turn: [f64; 3]) {
    let _ = writeln!(
        s,
        "[[object]]\nname = \"{name}\"\nmesh = \"meshes/box.obj\"\nscale = [{}, {}, {}]\nrotate_deg = [{}, {}, {}]\ntranslate = [{}, {}, {}]\n",
        size[0], size[1], size[2], turn[0], turn[1], turn[2], centre[0], centre[1], centre[2]
    );
}

/// The faces of the box `centre ± size / 2`, facing outward.
fn box_faces(centre: [f64; 3], size: [f64; 3]) -> Vec<Vec<[f64; 3]>> {
    box_faces_by(|i, j, k| {
        let pick = |axis: usize, high: usize| centre[axis] + (high as f64 - 0.5) * size[axis];
        [pick(0, i), pick(1, j), pick(2, k)]
    })
}

/// The faces of the parallelepiped with corners `corner(i, j, k)` (each
/// index 0 or 1 along one edge direction, a right-handed frame), facing
/// outward.
fn box_faces_by(corner: impl Fn(usize, usize, usize) -> [f64; 3]) -> Vec<Vec<[f64; 3]>> {
    // Each face counter-clockwise seen from outside.
    vec![
        vec![
            corner(0, 0, 0),
            corner(0, 0, 1),
            corner(0, 1, 1),
            corner(0, 1, 0),
        ],
        vec![
            corner(1, 0, 0),
            corner(1, 1, 0),
            corner(1, 1, 1),
            corner(1, 0, 1),
        ],
        vec![
            corner(0, 0, 0),
            corner(1, 0, 0),
            corner(1, 0, 1),
            corner(0, 0, 1),
        ],
        vec![
            corner(0, 1, 0),
            corner(0, 1, 1),
            corner(1, 1, 1),
            corner(1, 1, 0),
        ],
        vec![
            corner(0, 0, 0),
            corner(0, 1, 0),
            corner(1, 1, 0),
            corner(1, 0, 0),
        ],
        vec![
            corner(0, 0, 1),
            corner(1, 0, 1),
            corner(1, 1, 1),
            corner(0, 1, 1),
        ],
    ]
}

/// A desk at the origin (top 1.6 x 0.8 at height 0.74, four legs): 30
/// faces, one object.
pub(crate) fn desk_obj() -> String {
    let mut parts = vec![("top", box_faces([0.0, 0.74, 0.0], [1.6, 0.04, 0.8]))];
    let mut legs = Vec::new();
    for (dx, dz) in [(-0.75, -0.35), (0.75, -0.35), (0.75, 0.35), (-0.75, 0.35)] {
        legs.extend(box_faces([dx, 0.36, dz], [0.05, 0.72, 0.05]));
    }
    parts.push(("legs", legs));
    crate::demo::obj_text("desk: a top on four legs, facing outward", &parts)
}

/// The `office` scene text.
pub(crate) fn office_scene() -> String {
    let mut s = String::from(
        "# An office under one square ceiling light: four desks (30 polygons each)\n\
         # with a monitor on each and a filing cabinet, 156 input polygons. Run\n\
         # with `umbra dm`; move a desk (19 % of the scene) with\n\
         # `umbra update office.toml --move desk_1 --by 0.1,0,0 --steps 5`.\n\
         ambient = 0.03\n\n",
    );
    s.push_str(SHELL);
    for (k, (x, z)) in [(-2.5, -2.0), (2.5, -2.0), (-2.5, 2.0), (2.5, 2.0)]
        .into_iter()
        .enumerate()
    {
        let d = k + 1;
        let _ = writeln!(
            s,
            "[[object]]\nname = \"desk_{d}\"\nmesh = \"meshes/desk.obj\"\ntranslate = [{x}, 0.0, {z}]\n"
        );
        cuboid(
            &mut s,
            &format!("monitor_{d}"),
            [x, 0.96, z - 0.2],
            [0.5, 0.4, 0.05],
            [0.0, 10.0, 0.0],
        );
    }
    cuboid(
        &mut s,
        "cabinet",
        [4.5, 0.6, 0.0],
        [0.6, 1.2, 0.5],
        [0.0; 3],
    );
    s
}

/// A small deterministic generator (64-bit LCG, Knuth's constants): the
/// demo must be the same on every machine.
struct Lcg(u64);

impl Lcg {
    /// A number in `[lo, hi)`, rounded to 1/1000.
    fn next(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let unit = (self.0 >> 11) as f64 / (1_u64 << 53) as f64;
        ((lo + unit * (hi - lo)) * 1000.0).round() / 1000.0
    }
}

/// A cube of side about `side` centred near `centre`, turned by the
/// rotation of the integer quaternion `q`, as an object of inline
/// polygons: its edges are the columns of the rotation's integer matrix
/// (`n` times the rotation, `n = |q|^2`) scaled by a multiple of 1/1024,
/// so every corner is a dyadic point that the scene's grid holds exactly
/// and every face stays exactly planar. (Turned by `rotate_deg`, the
/// corners would be rounded to the grid and the faces bent, and the cube
/// would be no exactly convex body.)
fn turned_cube(s: &mut String, name: &str, centre: [f64; 3], side: f64, q: [i64; 4]) {
    let [a, b, c, d] = q;
    let n = a * a + b * b + c * c + d * d;
    let m = [
        [
            a * a + b * b - c * c - d * d,
            2 * (b * c - a * d),
            2 * (b * d + a * c),
        ],
        [
            2 * (b * c + a * d),
            a * a - b * b + c * c - d * d,
            2 * (c * d - a * b),
        ],
        [
            2 * (b * d - a * c),
            2 * (c * d + a * b),
            a * a - b * b - c * c + d * d,
        ],
    ];
    let dyadic = |x: f64| (x * 1024.0).round() / 1024.0;
    let step = dyadic(side / n as f64);
    let centre = centre.map(dyadic);
    let corner = |i: usize, j: usize, k: usize| -> [f64; 3] {
        let half = |h: usize| h as f64 - 0.5;
        std::array::from_fn(|axis| {
            let e = |col: usize| m[axis][col] as f64 * step;
            centre[axis] + half(i) * e(0) + half(j) * e(1) + half(k) * e(2)
        })
    };
    let faces = box_faces_by(corner);
    let polygon = |f: &Vec<[f64; 3]>| -> String {
        let points: Vec<String> = f
            .iter()
            .map(|p| format!("[{}, {}, {}]", p[0], p[1], p[2]))
            .collect();
        format!("[{}]", points.join(", "))
    };
    let polygons: Vec<String> = faces.iter().map(polygon).collect();
    let _ = writeln!(
        s,
        "[[object]]\nname = \"{name}\"\npolygons = [\n  {},\n]\n",
        polygons.join(",\n  ")
    );
}

/// The `cubes` scene text: 15 cubes of side about 0.6, random positions
/// and orientations (seed 1995), inside the room.
pub(crate) fn cubes_scene() -> String {
    let mut s = String::from(
        "# Fifteen randomly placed and turned cubes in a room under a square\n\
         # ceiling light (seed 1995). Run with `umbra dm`; move one with\n\
         # `umbra update cubes.toml --move cube_1 --by 0.1,0,0`.\n\
         ambient = 0.03\n\n",
    );
    s.push_str(SHELL);
    let mut rng = Lcg(1995);
    for k in 1..=15 {
        let centre = [rng.next(-4.0, 4.0), rng.next(0.5, 3.0), rng.next(-4.0, 4.0)];
        // A turn: an integer quaternion with components in -3..=3, not 0.
        let q = loop {
            let q: [i64; 4] = std::array::from_fn(|_| rng.next(-3.0, 4.0).floor() as i64);
            if q != [0; 4] {
                break q;
            }
        };
        turned_cube(&mut s, &format!("cube_{k}"), centre, 0.6, q);
    }
    s
}
