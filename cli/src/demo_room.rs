//! The `room` and `room1` demos: a furnished room under two or one quad
//! ceiling lights, like the 1992 paper's plates 3-6 (its plate 6 has 151
//! input polygons and two lights; so does `room`).

use std::fmt::Write as _;

/// A box object: name, centre, size, rotation about y in degrees.
struct Furniture {
    name: &'static str,
    centre: [f64; 3],
    size: [f64; 3],
    turn_deg: f64,
}

const fn piece(name: &'static str, centre: [f64; 3], size: [f64; 3]) -> Furniture {
    Furniture {
        name,
        centre,
        size,
        turn_deg: 0.0,
    }
}

/// A chair at (x, z) with its back towards +z (`back = 1`) or -z (`-1`).
fn chair(prefix: &'static [&'static str; 6], x: f64, z: f64, back: f64) -> Vec<Furniture> {
    let mut out = vec![
        piece(prefix[0], [x, 0.45, z], [0.5, 0.06, 0.5]),
        piece(prefix[1], [x, 0.8, z + back * 0.22], [0.5, 0.64, 0.06]),
    ];
    for (k, (dx, dz)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        out.push(piece(
            prefix[2 + k],
            [x + dx * 0.21, 0.21, z + dz * 0.21],
            [0.05, 0.42, 0.05],
        ));
    }
    out
}

fn furniture() -> Vec<Furniture> {
    let mut out = vec![piece("table_top", [-2.0, 0.75, 1.0], [1.6, 0.08, 1.0])];
    for (name, dx, dz) in [
        ("table_leg_1", -0.7, -0.4),
        ("table_leg_2", 0.7, -0.4),
        ("table_leg_3", 0.7, 0.4),
        ("table_leg_4", -0.7, 0.4),
    ] {
        out.push(piece(
            name,
            [-2.0 + dx, 0.355, 1.0 + dz],
            [0.08, 0.71, 0.08],
        ));
    }
    out.extend(chair(
        &[
            "chair_a_seat",
            "chair_a_back",
            "chair_a_leg_1",
            "chair_a_leg_2",
            "chair_a_leg_3",
            "chair_a_leg_4",
        ],
        -2.0,
        2.0,
        1.0,
    ));
    out.extend(chair(
        &[
            "chair_b_seat",
            "chair_b_back",
            "chair_b_leg_1",
            "chair_b_leg_2",
            "chair_b_leg_3",
            "chair_b_leg_4",
        ],
        -2.0,
        0.0,
        -1.0,
    ));
    out.extend([
        piece("shelf_side_1", [4.8, 1.0, -2.6], [0.3, 2.0, 0.04]),
        piece("shelf_side_2", [4.8, 1.0, -1.4], [0.3, 2.0, 0.04]),
        piece("shelf_board_1", [4.8, 0.4, -2.0], [0.3, 0.04, 1.16]),
        piece("shelf_board_2", [4.8, 1.0, -2.0], [0.3, 0.04, 1.16]),
        piece("shelf_board_3", [4.8, 1.6, -2.0], [0.3, 0.04, 1.16]),
        piece("book", [4.8, 1.17, -2.3], [0.2, 0.3, 0.1]),
        Furniture {
            name: "crate",
            centre: [2.0, 0.5, -1.5],
            size: [1.0, 1.0, 1.0],
            turn_deg: 30.0,
        },
    ]);
    out
}

/// A square ceiling light of side `side` centred at (x, y, z), facing down.
fn ceiling_light(x: f64, y: f64, z: f64, side: f64, radiance: f64) -> String {
    let h = side / 2.0;
    // Counter-clockwise seen from below.
    format!(
        "[[light]]\ntype = \"area\"\nvertices = [[{}, {y}, {}], [{}, {y}, {}], [{}, {y}, {}], [{}, {y}, {}]]\nintensity = {radiance}\ncolor = [1.0, 0.97, 0.9]\n\n",
        x - h,
        z - h,
        x + h,
        z - h,
        x + h,
        z + h,
        x - h,
        z + h,
    )
}

/// The scene text of the room under `lights` (1 or 2) quad lights; its
/// meshes are the `window` demo's `meshes/room.obj` and `meshes/box.obj`.
pub(crate) fn room_scene(lights: usize) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# A furnished room 10 x 4 x 10 under {lights} square ceiling light(s): a\n\
         # table with two chairs, a shelf with a book, a crate; 151 input polygons\n\
         # like the 1992 paper's plate 6. Run with `umbra shadow --grid 40`.\n\
         ambient = 0.03\n"
    );
    s.push_str(ROOM_SHELL);
    for f in furniture() {
        let _ = writeln!(
            s,
            "[[object]]\nname = \"{}\"\nmesh = \"meshes/box.obj\"\nscale = [{}, {}, {}]\nrotate_deg = [0.0, {}, 0.0]\ntranslate = [{}, {}, {}]\n",
            f.name,
            f.size[0],
            f.size[1],
            f.size[2],
            f.turn_deg,
            f.centre[0],
            f.centre[1],
            f.centre[2]
        );
    }
    s.push_str(&ceiling_light(-1.5, 3.9, 0.5, 1.0, 4.0));
    if lights > 1 {
        s.push_str(&ceiling_light(1.5, 3.9, -1.0, 1.0, 4.0));
    }
    s.push_str(CAMERA);
    s
}

/// The room's shell: its OBJ (floor, ceiling, three walls) and the window
/// wall inline, shared with the `window` demo.
pub(crate) const ROOM_SHELL: &str = r#"[[object]]
name = "room"
mesh = "meshes/room.obj"

# The window wall, facing into the room: two concave (C-shaped) polygons
# around the window x in [-1, 1], y in [1.5, 3].
[[object]]
name = "window_wall"
polygons = [
    [[-5.0, 0.0, -5.0], [0.0, 0.0, -5.0], [0.0, 1.5, -5.0], [-1.0, 1.5, -5.0],
     [-1.0, 3.0, -5.0], [0.0, 3.0, -5.0], [0.0, 4.0, -5.0], [-5.0, 4.0, -5.0]],
    [[0.0, 0.0, -5.0], [5.0, 0.0, -5.0], [5.0, 4.0, -5.0], [0.0, 4.0, -5.0],
     [0.0, 3.0, -5.0], [1.0, 3.0, -5.0], [1.0, 1.5, -5.0], [0.0, 1.5, -5.0]],
]

"#;

const CAMERA: &str = r#"[camera]
eye = [0.0, 3.0, 4.8]
target = [0.0, 0.6, -2.0]
up = [0.0, 1.0, 0.0]
fov_deg = 65.0
width = 800
height = 600
"#;
