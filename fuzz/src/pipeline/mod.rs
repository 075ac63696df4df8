//! Target `pipeline`: whole scene files through `umbra shadow`, `umbra dm`
//! and `umbra update`, as the command-line tool runs them.
//!
//! The other targets start from grid points. This one starts where a user
//! does: a scene file's text, with inline polygons in world units (boxes
//! and other closed surfaces, convex, concave or not quite closed,
//! rectangles, and free polygons that may be concave, non-planar, folded
//! or degenerate), object transforms (quarter and odd turns, mirrors), and
//! point, directional and area lights (some of them invalid). It runs what
//! lies between the file and the written mesh: reading and validation,
//! snapping, decomposition into convex pieces, both shadow pipelines, the
//! joint-umbra proofs, the point lights' passes over DM cells and the
//! output meshes.
//!
//! [`check_pipeline`] asks of every scene the library accepts:
//! - every output mesh passes its own check (indices, corner counts, finite
//!   values), no face is both lit and in umbra for a light, and no mask
//!   names a light the scene lacks;
//! - `umbra shadow` (Chin & Feiner's trees) and `umbra dm` (Chrysanthou &
//!   Slater's DM-trees) cut every input polygon into fragments of the same
//!   total area, and agree, polygon by polygon and light by light, on the
//!   area that sees all of the light: that region is exact in both,
//!   whatever their cells (off the half-unit lattice, up to the bend of
//!   the map that writes output points back onto the input polygons: see
//!   `measure::same_areas`). Not for a point light with a range: a fragment
//!   wholly beyond it has the umbra bit (FORMATS.md), so where a polygon
//!   straddles the range its lit area depends on how it was cut;
//! - a scene with a camera renders in three ways (or refuses with the
//!   field at fault);
//! - moving an object one step with `umbra update`'s path ends where a
//!   scene written at the moved place does (areas as above; for scenes
//!   whose coordinates are all on a half-unit lattice, so that the two
//!   grids hold the same points).
//!
//! An error is an accepted outcome (its message is formatted, so that
//! formatting cannot panic either), but the two pipelines must accept and
//! refuse the same scenes.

mod measure;

use crate::solids::{box_faces, point, solid};
use arbitrary::{Arbitrary, Unstructured};
use measure::{measure, same_areas};
use umbra::{
    DmOptions, Error, Method, Order, RenderOptions, Scene, View, dm_scene, dm_scene_moving,
    render_scene_with, scene_grid, shadow_scene,
};

/// One decoded input of the `pipeline` target; its `Debug` output is Rust
/// code. Coordinates are in half units (`3` is 1.5 in the scene file).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PipelineCase {
    /// The scene's objects, in file order.
    pub objects: Vec<ObjectCase>,
    /// The scene's lights, in file order.
    pub lights: Vec<LightCase>,
    /// The object moved, and its one step (half units).
    pub moving: Option<(usize, [i8; 3])>,
    /// A camera's eye (half units), looking at the origin: the scene is
    /// rendered too.
    pub camera: Option<[i8; 3]>,
}

/// One `[[object]]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjectCase {
    /// Inline polygons (half units).
    pub polygons: Vec<Vec<[i8; 3]>>,
    /// `two_sided`.
    pub two_sided: bool,
    /// `casts_shadows`.
    pub casts_shadows: bool,
    /// `rotate_deg` (degrees about X, Y, Z).
    pub rotate_deg: [i16; 3],
    /// `scale`, per axis, in halves (negative mirrors).
    pub scale: [i8; 3],
    /// `translate` (half units).
    pub translate: [i8; 3],
}

/// One `[[light]]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LightCase {
    /// A point light, with a `range` (half units) if given.
    Point {
        /// `position` (half units).
        position: [i8; 3],
        /// `range` (half units); falloff starts at half of it.
        range: Option<u8>,
    },
    /// A directional light.
    Directional {
        /// `direction` (the way light travels).
        direction: [i8; 3],
    },
    /// An area light (the corners may not make a valid one).
    Area {
        /// `vertices` (half units).
        corners: Vec<[i8; 3]>,
    },
}

/// The turns an object may take: quarter turns are exact up to the sines'
/// rounding, the others put corners off every lattice.
const TURNS: [i16; 6] = [0, 90, 180, 270, 45, 30];

fn polygons(u: &mut Unstructured<'_>) -> arbitrary::Result<Vec<Vec<[i8; 3]>>> {
    let mut out = match u.int_in_range(0..=5_u8)? {
        0 => {
            let lo = point(u, 6)?;
            let size = [
                u.int_in_range(1..=4)?,
                u.int_in_range(1..=4)?,
                u.int_in_range(1..=4)?,
            ];
            box_faces(lo, size)
        }
        1 => {
            // A rectangle facing up or down.
            let [x, y, z] = point(u, 6)?;
            let (w, d) = (u.int_in_range(1..=6)?, u.int_in_range(1..=6)?);
            vec![vec![
                [x, y, z + d],
                [x + w, y, z + d],
                [x + w, y, z],
                [x, y, z],
            ]]
        }
        2 => {
            // The floor.
            vec![vec![[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]
        }
        3 => solid(u)?,
        _ => {
            // Free polygons: concave, non-planar, folded or degenerate.
            let count = u.int_in_range(1..=3)?;
            let mut faces = Vec::with_capacity(count);
            for _ in 0..count {
                let corners = u.int_in_range(3..=7)?;
                faces.push(
                    (0..corners)
                        .map(|_| point(u, 8))
                        .collect::<Result<_, _>>()?,
                );
            }
            faces
        }
    };
    if u.ratio(1, 4)? {
        out.iter_mut().for_each(|p| p.reverse());
    }
    Ok(out)
}

impl<'a> Arbitrary<'a> for ObjectCase {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        let polygons = polygons(u)?;
        let transformed = u.ratio(1, 3)?;
        let mut turn =
            || -> arbitrary::Result<i16> { Ok(if transformed { *u.choose(&TURNS)? } else { 0 }) };
        let rotate_deg = [turn()?, turn()?, turn()?];
        let scale = if transformed {
            [*u.choose(&[2, 1, 4, -2])?, 2, *u.choose(&[2, 3, -2])?]
        } else {
            [2, 2, 2]
        };
        Ok(Self {
            polygons,
            two_sided: u.ratio(1, 5)?,
            casts_shadows: !u.ratio(1, 8)?,
            rotate_deg,
            scale,
            translate: if transformed { point(u, 4)? } else { [0; 3] },
        })
    }
}

impl<'a> Arbitrary<'a> for LightCase {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(match u.int_in_range(0..=5_u8)? {
            0 => Self::Point {
                position: point(u, 12)?,
                range: if u.ratio(1, 3)? {
                    Some(u.int_in_range(1..=30)?)
                } else {
                    None
                },
            },
            1 => Self::Directional {
                direction: point(u, 3)?,
            },
            2 => Self::Area {
                // Any corners: a triangle that may be degenerate, a
                // polygon that may not be convex or planar.
                corners: (0..u.int_in_range(3..=5)?)
                    .map(|_| point(u, 10))
                    .collect::<Result<_, _>>()?,
            },
            _ => {
                // A square facing down, over the scene, tilted or not.
                let [x, _, z] = point(u, 6)?;
                let y = u.int_in_range(4..=14)?;
                let s = u.int_in_range(1..=4)?;
                let tilt = u.int_in_range(0..=2)?;
                Self::Area {
                    corners: vec![
                        [x, y, z],
                        [x + s, y + tilt * s, z],
                        [x + s, y + tilt * s, z + s],
                        [x, y, z + s],
                    ],
                }
            }
        })
    }
}

impl<'a> Arbitrary<'a> for PipelineCase {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        let objects: Vec<ObjectCase> = (0..u.int_in_range(1..=5)?)
            .map(|_| ObjectCase::arbitrary(u))
            .collect::<Result<_, _>>()?;
        let lights = (0..u.int_in_range(1..=3)?)
            .map(|_| LightCase::arbitrary(u))
            .collect::<Result<_, _>>()?;
        let moving = if u.ratio(2, 3)? {
            Some((u.choose_index(objects.len())?, point(u, 3)?))
        } else {
            None
        };
        // (Bytes that run out decode as no camera.)
        let camera = if u.ratio(3, 4)? {
            None
        } else {
            Some(point(u, 24)?)
        };
        Ok(Self {
            objects,
            lights,
            moving,
            camera,
        })
    }
}

/// Decodes fuzzer bytes; `None` if they run out.
pub fn decode(data: &[u8]) -> Option<PipelineCase> {
    PipelineCase::arbitrary(&mut Unstructured::new(data)).ok()
}

/// Runs one input; panics on a violated invariant.
pub fn run(data: &[u8]) {
    let Some(case) = decode(data) else { return };
    if let Err(problem) = check_pipeline(&case) {
        panic!(
            "pipeline invariant violated: {problem}\n{case:?}\n{}",
            case.scene_text()
        );
    }
}

fn half(v: i8) -> f64 {
    f64::from(v) / 2.0
}

fn vector(p: [i8; 3]) -> String {
    format!("[{}, {}, {}]", half(p[0]), half(p[1]), half(p[2]))
}

impl PipelineCase {
    /// The scene file's text. Object `i` is named `o{i}`.
    pub fn scene_text(&self) -> String {
        let mut s = String::new();
        for (i, o) in self.objects.iter().enumerate() {
            let polygons: Vec<String> = o
                .polygons
                .iter()
                .map(|p| {
                    let corners: Vec<String> = p.iter().map(|&c| vector(c)).collect();
                    format!("[{}]", corners.join(", "))
                })
                .collect();
            s += &format!(
                "[[object]]\nname = \"o{i}\"\npolygons = [{}]\ntwo_sided = {}\ncasts_shadows = {}\n\
                 rotate_deg = [{}, {}, {}]\nscale = {}\ntranslate = {}\n\n",
                polygons.join(", "),
                o.two_sided,
                o.casts_shadows,
                o.rotate_deg[0],
                o.rotate_deg[1],
                o.rotate_deg[2],
                vector(o.scale),
                vector(o.translate),
            );
        }
        if let Some(eye) = self.camera {
            s += &format!(
                "[camera]\neye = {}\ntarget = [0, 0, 0]\nwidth = {RENDER_WIDTH}\nheight = {RENDER_HEIGHT}\n\n",
                vector(eye)
            );
        }
        for light in &self.lights {
            s += "[[light]]\n";
            match light {
                LightCase::Point { position, range } => {
                    s += &format!(
                        "type = \"point\"\nposition = {}\nintensity = 10.0\n",
                        vector(*position)
                    );
                    if let Some(r) = range {
                        let r = f64::from(*r) / 2.0;
                        s += &format!("range = {r}\nfalloff_start = {}\n", r / 2.0);
                    }
                }
                LightCase::Directional { direction } => {
                    s += &format!(
                        "type = \"directional\"\ndirection = {}\n",
                        vector(*direction)
                    );
                }
                LightCase::Area { corners } => {
                    let corners: Vec<String> = corners.iter().map(|&c| vector(c)).collect();
                    s += &format!(
                        "type = \"area\"\nvertices = [{}]\nintensity = 2.0\n",
                        corners.join(", ")
                    );
                }
            }
            s += "\n";
        }
        s
    }

    /// The case with the moving object `steps` steps further.
    fn moved(&self) -> Option<(PipelineCase, String, [f64; 3])> {
        let (i, by) = self.moving?;
        let mut moved = self.clone();
        let t = &mut moved.objects[i].translate;
        for k in 0..3 {
            t[k] = t[k].checked_add(by[k])?;
        }
        moved.moving = None;
        Some((
            moved,
            format!("o{i}"),
            [half(by[0]), half(by[1]), half(by[2])],
        ))
    }

    /// Per light, the position and range of a point light with a range
    /// (world units).
    fn ranges(&self) -> Vec<Option<([f64; 3], f64)>> {
        self.lights
            .iter()
            .map(|l| match l {
                LightCase::Point {
                    position,
                    range: Some(r),
                } => Some((position.map(half), f64::from(*r) / 2.0)),
                _ => None,
            })
            .collect()
    }

    /// Whether every coordinate of the scene is on the half-unit lattice
    /// (no odd turn, no scale off a half).
    fn on_lattice(&self) -> bool {
        self.objects.iter().all(|o| {
            o.rotate_deg.iter().all(|&d| d % 90 == 0) && o.scale.iter().all(|&s| s.abs() == 2)
        })
    }
}

/// What a case came to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// The scene was refused (a bad file: an error with its message).
    Refused,
    /// Both pipelines ran and agreed; `moved` if a move was checked too.
    Checked {
        /// Whether a move was compared with a scene built at its end.
        moved: bool,
    },
}

/// The image size of a case's camera.
const RENDER_WIDTH: u32 = 8;
const RENDER_HEIGHT: u32 = 6;

/// Renders a scene both pipelines took in three ways (shaded from the
/// fragments in a z-buffer, outlined fragments in BSP order, Bergeron's
/// volumes): each gives an image of the camera's size, or refuses with the
/// field at fault: the volumes method an area light, BSP order an eye too
/// far from the scene.
fn check_renders(scene: &Scene) -> Result<(), String> {
    let ways = [
        (View::Shaded, Method::Fragments, Order::ZBuffer),
        (View::Fragments, Method::Fragments, Order::Bsp),
        (View::Classes, Method::Volumes, Order::ZBuffer),
    ];
    for (view, method, order) in ways {
        match render_scene_with(
            scene,
            &RenderOptions {
                view,
                method,
                order,
            },
        ) {
            Ok(image) => {
                if (image.width, image.height) != (RENDER_WIDTH, RENDER_HEIGHT)
                    || image.rgb.len() != (RENDER_WIDTH * RENDER_HEIGHT * 3) as usize
                {
                    return Err(format!(
                        "{method:?} render: {} x {} image",
                        image.width, image.height
                    ));
                }
            }
            Err(Error::Field { field, .. })
                if (method == Method::Volumes && field.starts_with("light["))
                    || (order == Order::Bsp && field == "camera.eye") => {}
            Err(e) => return Err(format!("{method:?} render in {order:?} order refused: {e}")),
        }
    }
    Ok(())
}

/// Runs the case through both pipelines and a move, and checks; returns
/// what it came to, or `Err` with the first violated invariant.
pub fn check_pipeline(case: &PipelineCase) -> Result<Outcome, String> {
    let text = case.scene_text();
    let scene = match Scene::from_toml_str(&text, "fuzz.toml") {
        Ok(scene) => scene,
        Err(e) => {
            let _ = e.to_string();
            return Ok(Outcome::Refused);
        }
    };
    let ranges = case.ranges();

    let compared: Vec<bool> = ranges.iter().map(Option::is_none).collect();
    let dm = dm_scene(&scene).and_then(|run| run.output());
    match (shadow_scene(&scene), dm) {
        (Ok(shadow), Ok((dm, _))) => {
            let shadow = measure("shadow", &shadow.mesh, &ranges)?;
            let dm = measure("dm", &dm, &ranges)?;
            // The grid step, where output points move back onto the input.
            let step = if case.on_lattice() {
                0.0
            } else {
                scene_grid(&scene, None)
                    .map_err(|e| format!("no grid for a scene both pipelines took: {e}"))?
                    .cell_size()
            };
            same_areas("shadow against dm", &shadow, &dm, &compared, step)?;
        }
        (Err(a), Err(b)) => {
            let _ = (a.to_string(), b.to_string());
            return Ok(Outcome::Refused);
        }
        (Ok(_), Err(e)) => return Err(format!("dm refused what shadow took: {e}")),
        (Err(e), Ok(_)) => return Err(format!("shadow refused what dm took: {e}")),
    }
    if case.camera.is_some() {
        check_renders(&scene)?;
    }
    let Some((moved_case, name, by)) = case.moved() else {
        return Ok(Outcome::Checked { moved: false });
    };
    // The update: built with the way on its grid, then one step.
    let updated =
        dm_scene_moving(&scene, DmOptions::default(), &name, by, 1).and_then(|mut run| {
            run.move_steps(&scene, &name, by, 1, |_, _, _| {})?;
            run.output()
        });
    let updated = match updated {
        Ok((mesh, _)) => measure("update", &mesh, &ranges)?,
        // A way the grid cannot hold is refused; nothing else is.
        Err(Error::Field { field, .. }) if field == "--by" => {
            return Ok(Outcome::Checked { moved: false });
        }
        Err(e) => return Err(format!("update refused a scene dm took: {e}")),
    };
    let rebuilt = Scene::from_toml_str(&moved_case.scene_text(), "moved.toml")
        .and_then(|scene| dm_scene(&scene))
        .and_then(|run| run.output())
        .map_err(|e| format!("the moved scene failed: {e}"))?;
    let rebuilt = measure("rebuilt", &rebuilt.0, &ranges)?;
    if !case.on_lattice() {
        // Two grids round turned corners differently: the moved scene's
        // meshes are only checked one by one.
        return Ok(Outcome::Checked { moved: false });
    }
    same_areas("update against rebuild", &updated, &rebuilt, &compared, 0.0)?;
    Ok(Outcome::Checked { moved: true })
}

#[cfg(test)]
mod tests;
