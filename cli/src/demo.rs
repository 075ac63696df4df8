//! Built-in scenes, written out as ordinary scene files and OBJ meshes.
//!
//! - `tetra`: Haines' SPD tetrahedra (recursive tetrahedra standing on a
//!   ground plane), the scene of the Chin-Feiner tables;
//! - `room` and `room1`: a furnished room (151 input polygons) under two
//!   or one square ceiling lights, like the 1992 paper's plates 3-6;
//! - `window`: the same room with a window, two boxes, a point light under
//!   the ceiling and sunlight coming through the window;
//! - `office` and `cubes`: the discontinuity-mesh scenes (`umbra dm`), see
//!   `demo_dm`;
//! - `meshes`: a torus and a bumpy sphere (dense closed meshes) over a
//!   floor, their umbra a joint one of many triangles, see `demo_meshes`.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use crate::vec3::{cross, dot, sub};

/// The names of the built-in scenes.
pub const DEMOS: &[&str] = &[
    "room", "room1", "tetra", "window", "office", "cubes", "meshes",
];

/// Recursion depth of the `tetra` demo: 4 gives 256 triangles.
pub const TETRA_DEPTH: u32 = 4;

/// The corners of the cube `[-1, 1]^3` with `x * y * z = +1`: a regular
/// tetrahedron.
const TETRA_CORNERS: [[f64; 3]; 4] = [
    [1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
];

/// The triangles of Haines' SPD `tetra` at `depth` (`4^depth` triangles;
/// depth 0 gives none), each wound counter-clockwise seen from outside.
///
/// A node at centre `c` with half-size `w` and depth greater than 1 holds
/// four children at `c + d * w / 2` with half-size `w / 2`, for the corners
/// `d` of the cube `[-1, 1]^3` with `x * y * z = +1`; a leaf is the
/// tetrahedron with vertices `c + w * d`. The root has centre `(0, 0, 0)` and half-size 1. The faces
/// opposite the corner `(-1, -1, 1)` of every leaf on the bottom lie in the
/// plane `x + y - z = 1`.
///
/// ```
/// assert_eq!(umbra::tetra_triangles(4).len(), 256);
/// ```
pub fn tetra_triangles(depth: u32) -> Vec<[[f64; 3]; 3]> {
    let mut out = Vec::new();
    if depth == 0 {
        return out;
    }
    let mut stack = vec![([0.0_f64; 3], 1.0_f64, depth)];
    while let Some((c, w, d)) = stack.pop() {
        if d > 1 {
            // Pushed in reverse so that children come out in corner order.
            for corner in TETRA_CORNERS.iter().rev() {
                let child = [0, 1, 2].map(|k| c[k] + corner[k] * w / 2.0);
                stack.push((child, w / 2.0, d - 1));
            }
            continue;
        }
        let v = TETRA_CORNERS.map(|corner| [0, 1, 2].map(|k| c[k] + w * corner[k]));
        for opposite in 0..4 {
            let mut t: Vec<[f64; 3]> = (0..4).filter(|&i| i != opposite).map(|i| v[i]).collect();
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            if dot(n, sub(t[0], v[opposite])) < 0.0 {
                t.swap(1, 2);
            }
            out.push([t[0], t[1], t[2]]);
        }
    }
    out
}

/// The files of a demo scene: the scene TOML (named `NAME.toml`) and the
/// meshes it names, as (relative path, contents).
#[derive(Debug, Clone, PartialEq)]
pub struct DemoFiles {
    /// The scene's name.
    pub name: String,
    /// The scene file's text.
    pub scene: String,
    /// The meshes, as (path relative to the scene file, OBJ text).
    pub meshes: Vec<(String, String)>,
    /// The `--grid` the demo runs with (scenes with area lights).
    pub grid: Option<u32>,
}

impl DemoFiles {
    /// The files of the demo called `name` (one of [`DEMOS`]).
    pub fn named(name: &str) -> Result<Self> {
        match name {
            "tetra" => Ok(tetra_files(TETRA_DEPTH)),
            "office" | "cubes" => {
                let mut meshes = window_files().meshes;
                let scene = if name == "office" {
                    meshes.push(("meshes/desk.obj".into(), crate::demo_dm::desk_obj()));
                    crate::demo_dm::office_scene()
                } else {
                    crate::demo_dm::cubes_scene()
                };
                Ok(DemoFiles {
                    name: name.to_string(),
                    scene,
                    meshes,
                    grid: None,
                })
            }
            "window" => Ok(window_files()),
            "meshes" => Ok(crate::demo_meshes::meshes_files()),
            "room" | "room1" => {
                let lights = if name == "room" { 2 } else { 1 };
                let window = window_files();
                Ok(DemoFiles {
                    name: name.to_string(),
                    scene: crate::demo_room::room_scene(lights),
                    meshes: window.meshes,
                    grid: Some(40),
                })
            }
            _ => Err(Error::UnknownDemo {
                name: name.to_string(),
                known: DEMOS.join(", "),
            }),
        }
    }

    /// Whether the demo is run with `umbra dm` (discontinuity meshes)
    /// rather than `umbra shadow`.
    pub fn runs_dm(&self) -> bool {
        matches!(self.name.as_str(), "office" | "cubes")
    }

    /// Writes the files into `dir` (created if needed; each file written
    /// atomically) and returns the scene file's path.
    pub fn write(&self, dir: &Path) -> Result<PathBuf> {
        let scene_path = dir.join(format!("{}.toml", self.name));
        let fail = |path: &Path, source| Error::Write {
            path: path.to_path_buf(),
            source,
        };
        std::fs::create_dir_all(dir).map_err(|e| fail(dir, e))?;
        for (relative, text) in &self.meshes {
            let path = dir.join(relative);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).map_err(|e| fail(parent, e))?;
            }
            write_atomic(&path, |w| w.write_all(text.as_bytes()))?;
        }
        write_atomic(&scene_path, |w| w.write_all(self.scene.as_bytes()))?;
        Ok(scene_path)
    }
}

/// Writes the demo `name` into `dir`; returns the scene file's path.
pub fn write_demo(name: &str, dir: &Path) -> Result<PathBuf> {
    DemoFiles::named(name)?.write(dir)
}

/// OBJ text of triangles or polygons, with shared vertices and one group
/// per named part.
pub(crate) fn obj_text(comment: &str, parts: &[(&str, Vec<Vec<[f64; 3]>>)]) -> String {
    let mut index: HashMap<[u64; 3], usize> = HashMap::new();
    let mut vertices = String::new();
    let mut faces = String::new();
    for (group, polygons) in parts {
        let _ = writeln!(faces, "g {group}");
        for polygon in polygons {
            faces.push('f');
            for p in polygon {
                let key = p.map(f64::to_bits);
                let next = index.len() + 1;
                let i = *index.entry(key).or_insert_with(|| {
                    let _ = writeln!(vertices, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
                    next
                });
                let _ = write!(faces, " {i}");
            }
            faces.push('\n');
        }
    }
    format!(
        "# {comment}\n# written by umbra {}\n{vertices}{faces}",
        env!("CARGO_PKG_VERSION")
    )
}

fn tetra_files(depth: u32) -> DemoFiles {
    let triangles: Vec<Vec<[f64; 3]>> = tetra_triangles(depth).iter().map(|t| t.to_vec()).collect();
    let count = triangles.len();
    let mesh = obj_text(
        &format!("Haines SPD tetra, depth {depth}: {count} triangles, wound outward"),
        &[("tetra", triangles)],
    );
    let scene = format!(
        r#"# Haines' SPD "tetra" (depth {depth}, {count} triangles), the test scene of
# Chin & Feiner's shadow papers. The bottom faces of the tetrahedra lie in the
# plane x + y - z = 1; the ground lies in that plane too, facing the
# tetrahedra and the light (its normal is (-1, -1, 1)).
ambient = 0.05

[[object]]
name = "tetra"
mesh = "meshes/tetra.obj"

[[object]]
name = "ground"
casts_shadows = false
polygons = [[[-16.0, 0.0, -17.0], [0.0, -16.0, -17.0], [16.0, 0.0, 15.0], [0.0, 16.0, 15.0]]]

[[light]]
type = "point"
position = [2.0, -18.0, -5.0]     # x + y - z = -11: the tetrahedra's side of the ground
intensity = 360.0

[camera]
eye = [1.022846, -3.177154, -2.174512]
target = [-0.004103, -0.004103, 0.216539]
up = [-0.816497, -0.816497, 0.816497]
fov_deg = 45.0
width = 512
height = 512
"#
    );
    DemoFiles {
        name: "tetra".into(),
        scene,
        meshes: vec![("meshes/tetra.obj".into(), mesh)],
        grid: None,
    }
}

/// A quad `o, o + a, o + a + b, o + b`: its front is the side `a x b`
/// points to.
fn quad(o: [f64; 3], a: [f64; 3], b: [f64; 3]) -> Vec<[f64; 3]> {
    let add = |p: [f64; 3], q: [f64; 3]| [p[0] + q[0], p[1] + q[1], p[2] + q[2]];
    vec![o, add(o, a), add(add(o, a), b), add(o, b)]
}

fn window_files() -> DemoFiles {
    // The room: x in [-5, 5], y in [0, 4], z in [-5, 5], every surface
    // facing inward. The wall z = -5 has the window and is inline below.
    let room = obj_text(
        "room: floor, ceiling and three walls, facing inward",
        &[
            (
                "floor",
                vec![quad([-5.0, 0.0, -5.0], [0.0, 0.0, 10.0], [10.0, 0.0, 0.0])],
            ),
            (
                "ceiling",
                vec![quad([-5.0, 4.0, -5.0], [10.0, 0.0, 0.0], [0.0, 0.0, 10.0])],
            ),
            (
                "walls",
                vec![
                    quad([-5.0, 0.0, 5.0], [0.0, 4.0, 0.0], [10.0, 0.0, 0.0]),
                    quad([-5.0, 0.0, -5.0], [0.0, 4.0, 0.0], [0.0, 0.0, 10.0]),
                    quad([5.0, 0.0, -5.0], [0.0, 0.0, 10.0], [0.0, 4.0, 0.0]),
                ],
            ),
        ],
    );
    // A unit cube centred at the origin, facing outward.
    let h = 0.5;
    let cube = obj_text(
        "unit cube centred at the origin, facing outward",
        &[(
            "box",
            vec![
                quad([-h, -h, -h], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
                quad([h, -h, -h], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
                quad([-h, -h, -h], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
                quad([-h, h, -h], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
                quad([-h, -h, -h], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
                quad([-h, -h, h], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ],
        )],
    );
    let scene = format!(
        "# A room 10 x 4 x 10 with a window in the wall z = -5, two boxes, a lamp\n\
         # under the ceiling and sunlight coming in through the window.\n\
         ambient = 0.05\n\n{}{WINDOW_REST}",
        crate::demo_room::ROOM_SHELL
    );
    DemoFiles {
        name: "window".into(),
        scene,
        meshes: vec![
            ("meshes/room.obj".into(), room),
            ("meshes/box.obj".into(), cube),
        ],
        grid: None,
    }
}

/// The `window` scene after the room's shell: boxes, lights, camera.
const WINDOW_REST: &str = r#"[[object]]
name = "table"
mesh = "meshes/box.obj"
scale = [1.5, 0.8, 1.0]
translate = [-2.0, 0.4, 1.0]

[[object]]
name = "crate"
mesh = "meshes/box.obj"
rotate_deg = [0.0, 30.0, 0.0]
translate = [2.0, 0.5, -1.5]

[[light]]
type = "point"
position = [0.0, 3.5, 0.5]
intensity = 12.0
color = [1.0, 0.95, 0.85]
falloff_start = 6.0
range = 14.0

[[light]]
type = "directional"
direction = [0.25, -0.5, 1.0]    # travels into the room through the window
intensity = 0.8
color = [1.0, 1.0, 0.9]

[camera]
eye = [0.0, 2.0, 4.5]
target = [0.0, 1.2, -5.0]
up = [0.0, 1.0, 0.0]
fov_deg = 60.0
width = 800
height = 600
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tetra_counts_and_bottom_plane() {
        assert_eq!(tetra_triangles(1).len(), 4);
        assert_eq!(tetra_triangles(4).len(), 256);
        assert_eq!(tetra_triangles(5).len(), 1024);
        let on_ground = tetra_triangles(4)
            .iter()
            .filter(|t| t.iter().all(|p| (p[0] + p[1] - p[2] - 1.0).abs() < 1e-12))
            .count();
        // One bottom face per leaf on the bottom layer: 3^(depth - 1).
        assert_eq!(on_ground, 27);
        for t in tetra_triangles(4) {
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            let c = [0, 1, 2].map(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0);
            if t.iter().all(|p| (p[0] + p[1] - p[2] - 1.0).abs() < 1e-12) {
                // Bottom faces face away from the tetrahedra, along (1, 1, -1).
                assert!(dot(n, [1.0, 1.0, -1.0]) > 0.0, "{c:?}");
            }
        }
    }
}
