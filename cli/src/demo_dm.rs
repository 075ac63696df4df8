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
    let corner = |i: usize, j: usize, k: usize| -> [f64; 3] {
        let pick = |axis: usize, high: usize| centre[axis] + (high as f64 - 0.5) * size[axis];
        [pick(0, i), pick(1, j), pick(2, k)]
    };
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

/// The `cubes` scene text: 15 cubes of side 0.6, random positions and
/// orientations (seed 1995), inside the room.
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
        let turn = [
            rng.next(0.0, 90.0),
            rng.next(0.0, 90.0),
            rng.next(0.0, 90.0),
        ];
        cuboid(&mut s, &format!("cube_{k}"), centre, [0.6; 3], turn);
    }
    s
}
