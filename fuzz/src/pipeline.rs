//! Target `pipeline`: whole scene files through `umbra shadow`, `umbra dm`
//! and `umbra update`, as the command-line tool runs them.
//!
//! The other targets start from grid points. This one starts where a user
//! does: a scene file's text, with inline polygons in world units (boxes,
//! rectangles and free polygons that may be concave, non-planar, folded or
//! degenerate), object transforms (quarter and odd turns, mirrors), and
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
//!   whatever their cells. Not for a point light with a range: a fragment
//!   wholly beyond it has the umbra bit (FORMATS.md), so where a polygon
//!   straddles the range its lit area depends on how it was cut;
//! - moving an object one step with `umbra update`'s path ends where a
//!   scene written at the moved place does (areas as above; for scenes
//!   whose coordinates are all on a half-unit lattice, so that the two
//!   grids hold the same points).
//!
//! An error is an accepted outcome (its message is formatted, so that
//! formatting cannot panic either), but the two pipelines must accept and
//! refuse the same scenes.

use arbitrary::{Arbitrary, Unstructured};
use umbra::{DmOptions, Error, Scene, dm_scene, dm_scene_moving, shadow_scene};

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

fn small(u: &mut Unstructured<'_>, half_extent: i8) -> arbitrary::Result<i8> {
    u.int_in_range(-half_extent..=half_extent)
}

fn point(u: &mut Unstructured<'_>, half_extent: i8) -> arbitrary::Result<[i8; 3]> {
    Ok([
        small(u, half_extent)?,
        small(u, half_extent)?,
        small(u, half_extent)?,
    ])
}

/// A box from `lo` to `lo + size`, its faces wound outwards.
fn box_faces(lo: [i8; 3], size: [i8; 3]) -> Vec<Vec<[i8; 3]>> {
    let [x0, y0, z0] = lo;
    let [x1, y1, z1] = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
    vec![
        vec![[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],
        vec![[x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]],
        vec![[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0]],
        vec![[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],
        vec![[x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]],
        vec![[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
    ]
}

fn polygons(u: &mut Unstructured<'_>) -> arbitrary::Result<Vec<Vec<[i8; 3]>>> {
    let mut out = match u.int_in_range(0..=4_u8)? {
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
        Ok(Self {
            objects,
            lights,
            moving,
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

/// Per input polygon (`source`), the total area of its faces and, per
/// light, the area of those that see all of it.
#[derive(Debug, Default)]
struct Areas {
    total: Vec<f64>,
    lit: Vec<Vec<f64>>,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn corners(mesh: &umbra::OutputMesh, face: &umbra::OutputFace) -> Vec<[f64; 3]> {
    face.vertices
        .iter()
        .map(|&v| mesh.vertices[v as usize].0)
        .collect()
}

/// The distance from `x` to the convex planar polygon `p`.
fn distance_to_polygon(x: [f64; 3], p: &[[f64; 3]]) -> f64 {
    let edge_distance = |a: [f64; 3], b: [f64; 3]| {
        let (d, w) = (sub(b, a), sub(x, a));
        let t = (dot(w, d) / dot(d, d).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        let e = sub(w, [d[0] * t, d[1] * t, d[2] * t]);
        dot(e, e).sqrt()
    };
    let edges = (0..p.len()).map(|i| edge_distance(p[i], p[(i + 1) % p.len()]));
    let nearest_edge = edges.fold(f64::INFINITY, f64::min);
    let n = (1..p.len() - 1).fold([0.0; 3], |n, i| {
        let c = cross(sub(p[i], p[0]), sub(p[i + 1], p[0]));
        [n[0] + c[0], n[1] + c[1], n[2] + c[2]]
    });
    let inside = (0..p.len()).all(|i| {
        let (a, b) = (p[i], p[(i + 1) % p.len()]);
        dot(cross(sub(b, a), sub(x, a)), n) >= 0.0
    });
    let length = dot(n, n).sqrt();
    if inside && length > 0.0 {
        (dot(sub(x, p[0]), n) / length).abs()
    } else {
        nearest_edge
    }
}

fn face_area(mesh: &umbra::OutputMesh, face: &umbra::OutputFace) -> f64 {
    let p = corners(mesh, face);
    let mut n = [0.0; 3];
    for i in 1..p.len() - 1 {
        let (a, b, c) = (p[0], p[i], p[i + 1]);
        let (u, v) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        n[0] += u[1] * v[2] - u[2] * v[1];
        n[1] += u[2] * v[0] - u[0] * v[2];
        n[2] += u[0] * v[1] - u[1] * v[0];
    }
    0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}

/// Checks one output mesh and measures it. `ranges` holds, per light, the
/// position and range of a point light with a range: no lit face may lie
/// wholly beyond it.
fn measure(
    what: &str,
    mesh: &umbra::OutputMesh,
    ranges: &[Option<([f64; 3], f64)>],
) -> Result<Areas, String> {
    mesh.check().map_err(|e| format!("{what}: {e}"))?;
    let lights = ranges.len();
    let all = if lights >= 32 {
        u32::MAX
    } else {
        (1_u32 << lights) - 1
    };
    let mut areas = Areas::default();
    for (k, face) in mesh.faces.iter().enumerate() {
        if face.lit_mask & face.umbra_mask != 0 {
            return Err(format!("{what}: face {k} is lit and umbra for one light"));
        }
        if (face.lit_mask | face.umbra_mask) & !all != 0 {
            return Err(format!(
                "{what}: face {k} has a mask bit past {lights} lights"
            ));
        }
        for (i, range) in ranges.iter().enumerate() {
            let Some((light, range)) = *range else {
                continue;
            };
            if face.lit_mask >> i & 1 != 0
                && distance_to_polygon(light, &corners(mesh, face)) > range * (1.0 + 1e-9)
            {
                return Err(format!(
                    "{what}: face {k} is lit by light {i} beyond its range"
                ));
            }
        }
        let s = face.source as usize;
        if areas.total.len() <= s {
            areas.total.resize(s + 1, 0.0);
            areas.lit.resize(s + 1, vec![0.0; lights]);
        }
        let a = face_area(mesh, face);
        areas.total[s] += a;
        for (i, lit) in areas.lit[s].iter_mut().enumerate() {
            if face.lit_mask >> i & 1 != 0 {
                *lit += a;
            }
        }
    }
    Ok(areas)
}

/// Whether `a` and `b` agree polygon by polygon, to 1e-9 of each polygon's
/// area (the outputs are exact up to the rounding of their coordinates):
/// in total, and lit by each light `compared` marks.
fn same_areas(what: &str, a: &Areas, b: &Areas, compared: &[bool]) -> Result<(), String> {
    let n = a.total.len().max(b.total.len());
    let get = |v: &[f64], s: usize| v.get(s).copied().unwrap_or(0.0);
    for s in 0..n {
        let (ta, tb) = (get(&a.total, s), get(&b.total, s));
        let tolerance = 1e-9 * ta.max(tb) + 1e-12;
        if (ta - tb).abs() > tolerance {
            return Err(format!("{what}: polygon {s} has area {ta} against {tb}"));
        }
        let lit = |x: &Areas, i| x.lit.get(s).map_or(0.0, |l: &Vec<f64>| l[i]);
        for i in (0..compared.len()).filter(|&i| compared[i]) {
            let (la, lb) = (lit(a, i), lit(b, i));
            if (la - lb).abs() > tolerance {
                return Err(format!(
                    "{what}: polygon {s}, light {i}: lit area {la} against {lb}"
                ));
            }
        }
    }
    Ok(())
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
            same_areas("shadow against dm", &shadow, &dm, &compared)?;
        }
        (Err(a), Err(b)) => {
            let _ = (a.to_string(), b.to_string());
            return Ok(Outcome::Refused);
        }
        (Ok(_), Err(e)) => return Err(format!("dm refused what shadow took: {e}")),
        (Err(e), Ok(_)) => return Err(format!("shadow refused what dm took: {e}")),
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
    same_areas("update against rebuild", &updated, &rebuilt, &compared)?;
    Ok(Outcome::Checked { moved: true })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pseudo_random_bytes as bytes;

    #[test]
    fn seed_corpus_replays() {
        let files = crate::corpus_files("pipeline").expect("corpus/pipeline is readable");
        assert!(files.len() >= 8, "only {} seed files", files.len());
        for (name, data) in files {
            let case = decode(&data).expect("decodes");
            if let Err(problem) = check_pipeline(&case) {
                panic!("corpus/pipeline/{name}: {problem}\n{case:?}");
            }
        }
    }

    #[test]
    fn pseudo_random_inputs_pass() {
        let (mut checked, mut moved, mut refused) = (0, 0, 0);
        for seed in 0..300 {
            let data = bytes(seed, 40 + (seed % 120) as usize);
            let Some(case) = decode(&data) else { continue };
            match check_pipeline(&case) {
                Ok(Outcome::Refused) => refused += 1,
                Ok(Outcome::Checked { moved: m }) => {
                    checked += 1;
                    moved += usize::from(m);
                }
                Err(problem) => panic!("seed {seed}: {problem}\n{case:?}\n{}", case.scene_text()),
            }
        }
        eprintln!("{checked} checked ({moved} with a move), {refused} refused");
        assert!(
            checked > 100 && moved > 30,
            "{checked} checked, {moved} moved, {refused} refused"
        );
    }

    /// Found by libFuzzer: a point light with a range (light 0) and an
    /// area light. A polygon straddles the range; the fragments `dm` cut
    /// from it along the area light's shadow are not those `shadow` cut,
    /// and each pipeline gives the umbra bit to its fragments wholly beyond
    /// the range (FORMATS.md), so their lit areas for light 0 differ (5.24
    /// against 5.60). The oracle, not the pipelines, was wrong: lit areas
    /// are compared for lights without a range, and no lit face may lie
    /// wholly beyond one.
    #[test]
    fn a_range_straddled_where_an_area_light_cuts() {
        let case = PipelineCase {
            objects: vec![
                ObjectCase {
                    polygons: vec![
                        vec![[-8, 3, -6], [3, 1, 0], [-7, 3, -5]],
                        vec![[-2, -4, -7], [-3, -8, 3], [0, 3, -3], [5, -8, 1]],
                    ],
                    two_sided: true,
                    casts_shadows: true,
                    rotate_deg: [0, 0, 0],
                    scale: [2, 2, 2],
                    translate: [0, 0, 0],
                },
                ObjectCase {
                    polygons: vec![vec![
                        [2, -4, 2],
                        [-4, 5, -6],
                        [8, 4, 0],
                        [0, 8, -8],
                        [-7, 2, 7],
                        [7, 7, 7],
                    ]],
                    two_sided: false,
                    casts_shadows: true,
                    rotate_deg: [0, 0, 180],
                    scale: [-2, 2, -2],
                    translate: [3, -4, -1],
                },
            ],
            lights: vec![
                LightCase::Point {
                    position: [1, -9, -9],
                    range: Some(12),
                },
                LightCase::Area {
                    corners: vec![[-3, 7, 0], [0, 10, 0], [0, 10, 3], [-3, 7, 3]],
                },
            ],
            moving: Some((0, [-3, -3, -3])),
        };
        assert_eq!(check_pipeline(&case), Ok(Outcome::Checked { moved: true }));
    }

    /// Writes the seed corpus (run by hand when the decoder changes): the
    /// first inputs of each outcome.
    #[test]
    #[ignore = "rewrites corpus/pipeline; run by hand"]
    fn regenerate_seed_corpus() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/pipeline");
        std::fs::create_dir_all(&dir).unwrap();
        let (mut refused, mut plain, mut moved) = (0, 0, 0);
        for seed in 0..200_u64 {
            let data = bytes(20_000 + seed, 60 + seed as usize % 100);
            let Some(case) = decode(&data) else { continue };
            let count = match check_pipeline(&case) {
                Ok(Outcome::Refused) => &mut refused,
                Ok(Outcome::Checked { moved: false }) => &mut plain,
                Ok(Outcome::Checked { moved: true }) => &mut moved,
                Err(problem) => panic!("seed {seed}: {problem}"),
            };
            if *count < 6 {
                *count += 1;
                std::fs::write(dir.join(format!("seed-{seed:03}")), data).unwrap();
            }
        }
    }
}
