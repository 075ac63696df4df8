//! The scene file (FORMATS.md §1): parsed into typed structs, validated once,
//! with every object's polygons read and placed in the scene.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::error::{Error, Result};
use crate::obj::ObjMesh;
use crate::transform::Transform;
use crate::vec3::{by_largest, cross, dot, norm, sub};

/// Most lights a scene may have: one bit each in `lit_mask` / `umbra_mask`.
pub const MAX_LIGHTS: usize = 32;

/// A loaded and validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The scene file (used in messages; meshes are relative to its folder).
    pub path: PathBuf,
    /// Ambient term added to every irradiance in images.
    pub ambient: f64,
    /// Objects in scene-file order.
    pub objects: Vec<Object>,
    /// Lights in scene-file order (bit `i` of the masks is light `i`).
    pub lights: Vec<Light>,
    /// The camera, for images.
    pub camera: Option<Camera>,
}

/// An object of the scene with its polygons placed in the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// Unique name.
    pub name: String,
    /// The OBJ file the polygons came from (resolved against the scene's
    /// folder), or `None` for inline polygons.
    pub mesh: Option<PathBuf>,
    /// The placement applied to the polygons.
    pub transform: Transform,
    /// Whether the object blocks light (whichever side faces it).
    pub casts_shadows: bool,
    /// Whether the object receives light on both sides.
    pub two_sided: bool,
    /// The input polygons, in file order, in scene coordinates.
    pub polygons: Vec<InputPolygon>,
}

/// One input polygon, in scene coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct InputPolygon {
    /// Vertices, counter-clockwise seen from the front (a mirroring transform
    /// has already reversed them back to that order).
    pub vertices: Vec<[f64; 3]>,
    /// The line of the OBJ `f` statement, for polygons read from a mesh.
    pub line: Option<usize>,
    /// The OBJ `o` / `g` name in force, if any.
    pub group: Option<String>,
}

/// A light of the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Light {
    /// Where and what kind.
    pub kind: LightKind,
    /// Point: radiant intensity; area: radiance; directional: irradiance.
    pub intensity: f64,
    /// Colour, for images only.
    pub color: [f64; 3],
    /// Sphere of influence (point lights only).
    pub falloff: Option<Falloff>,
}

/// The geometry of a light.
#[derive(Debug, Clone, PartialEq)]
pub enum LightKind {
    /// A point light.
    Point {
        /// Its position.
        position: [f64; 3],
    },
    /// A light at infinity.
    Directional {
        /// The direction light travels (non-zero, not normalised).
        direction: [f64; 3],
    },
    /// A convex planar polygon emitting on the side its counter-clockwise
    /// normal points to.
    Area {
        /// Its vertices, counter-clockwise seen from the lit side.
        vertices: Vec<[f64; 3]>,
    },
}

/// Bergeron's sphere of influence of a point light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Falloff {
    /// Distance where the intensity starts to decrease (`>= 0`).
    pub start: f64,
    /// Distance where it reaches zero (`> start`).
    pub range: f64,
    /// Shape of the decrease (`> 0`).
    pub exponent: f64,
}

impl Falloff {
    /// The factor at distance `r`: 1 up to `start`,
    /// `((range - r) / (range - start))^exponent` between, 0 from `range` on.
    pub fn factor(&self, r: f64) -> f64 {
        if r <= self.start {
            1.0
        } else if r >= self.range {
            0.0
        } else {
            ((self.range - r) / (self.range - self.start)).powf(self.exponent)
        }
    }
}

/// The camera of a scene, for images.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: [f64; 3],
    /// Point looked at.
    pub target: [f64; 3],
    /// Up direction.
    pub up: [f64; 3],
    /// Vertical field of view in degrees.
    pub fov_deg: f64,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

// ---- The file as written -------------------------------------------------

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default)]
    ambient: f64,
    #[serde(default)]
    object: Vec<ObjectSpec>,
    #[serde(default)]
    light: Vec<LightSpec>,
    camera: Option<CameraSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectSpec {
    name: String,
    mesh: Option<String>,
    #[serde(default, deserialize_with = "three_each")]
    polygons: Option<Vec<Vec<[f64; 3]>>>,
    #[serde(default, deserialize_with = "three_each")]
    translate: [f64; 3],
    #[serde(default, deserialize_with = "three_each")]
    rotate_deg: [f64; 3],
    scale: Option<ScaleSpec>,
    #[serde(default = "yes")]
    casts_shadows: bool,
    #[serde(default)]
    two_sided: bool,
}

#[derive(Debug, Deserialize)]
#[serde(untagged, expecting = "expected a number or an array [sx, sy, sz]")]
enum ScaleSpec {
    Uniform(f64),
    PerAxis(#[serde(deserialize_with = "three_each")] [f64; 3]),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
enum LightType {
    Point,
    Directional,
    Area,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LightSpec {
    #[serde(rename = "type")]
    kind: LightType,
    #[serde(default, deserialize_with = "three_each")]
    position: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "three_each")]
    direction: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "three_each")]
    vertices: Option<Vec<[f64; 3]>>,
    #[serde(default = "one")]
    intensity: f64,
    #[serde(default = "white", deserialize_with = "three_each")]
    color: [f64; 3],
    falloff_start: Option<f64>,
    range: Option<f64>,
    falloff_exponent: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraSpec {
    #[serde(default = "default_eye", deserialize_with = "three_each")]
    eye: [f64; 3],
    #[serde(default, deserialize_with = "three_each")]
    target: [f64; 3],
    #[serde(default = "default_up", deserialize_with = "three_each")]
    up: [f64; 3],
    #[serde(default = "default_fov")]
    fov_deg: f64,
    #[serde(default = "default_width")]
    width: u32,
    #[serde(default = "default_height")]
    height: u32,
}

/// Reads the vectors of `T` (`[f64; 3]`, or options and lists of them) as
/// arrays of exactly three numbers: serde reads an array of four or more
/// into a `[f64; 3]` and drops the rest without a word.
fn three_each<'de, D, T>(deserializer: D) -> std::result::Result<T, D::Error>
where
    D: serde::Deserializer<'de>,
    T: OfThrees,
    T::Given: Deserialize<'de>,
{
    T::Given::deserialize(deserializer).map(T::from_given)
}

/// Three numbers, exactly.
#[derive(Deserialize)]
#[serde(try_from = "Vec<f64>")]
struct Three([f64; 3]);

impl TryFrom<Vec<f64>> for Three {
    type Error = String;

    fn try_from(numbers: Vec<f64>) -> std::result::Result<Self, String> {
        <[f64; 3]>::try_from(numbers.as_slice())
            .map(Three)
            .map_err(|_| {
                format!(
                    "invalid length {}, expected an array of 3 numbers",
                    numbers.len()
                )
            })
    }
}

/// A type made of `[f64; 3]`s, read through [`Three`]s.
trait OfThrees: Sized {
    type Given;
    fn from_given(given: Self::Given) -> Self;
}

impl OfThrees for [f64; 3] {
    type Given = Three;
    fn from_given(given: Three) -> Self {
        given.0
    }
}

impl<T: OfThrees> OfThrees for Option<T> {
    type Given = Option<T::Given>;
    fn from_given(given: Self::Given) -> Self {
        given.map(T::from_given)
    }
}

impl<T: OfThrees> OfThrees for Vec<T> {
    type Given = Vec<T::Given>;
    fn from_given(given: Self::Given) -> Self {
        given.into_iter().map(T::from_given).collect()
    }
}

fn yes() -> bool {
    true
}
fn one() -> f64 {
    1.0
}
fn white() -> [f64; 3] {
    [1.0; 3]
}
fn default_eye() -> [f64; 3] {
    [0.0, 2.0, 8.0]
}
fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}
fn default_fov() -> f64 {
    45.0
}
fn default_width() -> u32 {
    800
}
fn default_height() -> u32 {
    600
}

// ---- Loading and validation ----------------------------------------------

impl Scene {
    /// Reads and validates a scene file and every mesh it names.
    pub fn load(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = crate::read::input_text(path)?;
        Self::from_toml_str(&text, path)
    }

    /// Parses and validates scene text; `path` names the file in messages
    /// and its folder is where `mesh` paths start.
    ///
    /// ```
    /// let scene = umbra::Scene::from_toml_str(
    ///     r#"
    ///     [[object]]
    ///     name = "floor"
    ///     polygons = [[[0, 0, 0], [1, 0, 0], [1, 0, -1]]]
    ///     [[light]]
    ///     type = "point"
    ///     position = [0, 5, 0]
    ///     "#,
    ///     "inline.toml",
    /// )?;
    /// assert_eq!(scene.polygon_count(), 1);
    /// # Ok::<(), umbra::Error>(())
    /// ```
    pub fn from_toml_str(text: &str, path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let file: SceneFile = toml::from_str(text).map_err(|e| {
            let (line, column) = e
                .span()
                .map(|span| line_column(text, span.start))
                .unwrap_or((1, 1));
            Error::Toml {
                path: path.to_path_buf(),
                line,
                column,
                message: e.message().trim_end().to_string(),
            }
        })?;
        let check = Checker { path };
        let base = path.parent().unwrap_or(Path::new(""));

        check.finite("ambient", &[file.ambient])?;
        if file.ambient < 0.0 {
            return Err(check.field("ambient", "must not be negative"));
        }

        let mut objects: Vec<Object> = Vec::with_capacity(file.object.len());
        for (i, spec) in file.object.into_iter().enumerate() {
            objects.push(check.object(i, spec, base, &objects)?);
        }

        if file.light.len() > MAX_LIGHTS {
            return Err(check.field(
                "light",
                format!(
                    "{} lights; at most {MAX_LIGHTS} (one bit each in lit_mask and umbra_mask)",
                    file.light.len()
                ),
            ));
        }
        let lights = file
            .light
            .into_iter()
            .enumerate()
            .map(|(i, spec)| check.light(i, spec))
            .collect::<Result<Vec<_>>>()?;

        let camera = file.camera.map(|c| check.camera(c)).transpose()?;

        let scene = Self {
            path: path.to_path_buf(),
            ambient: file.ambient,
            objects,
            lights,
            camera,
        };
        if scene.polygon_count() == 0 {
            return Err(Error::EmptyScene {
                path: path.to_path_buf(),
            });
        }
        Ok(scene)
    }

    /// Number of input polygons, all objects together.
    pub fn polygon_count(&self) -> usize {
        self.objects.iter().map(|o| o.polygons.len()).sum()
    }

    /// Every input polygon with its object index, in input-polygon order
    /// (objects in scene order, faces in file order): the `n`-th item is
    /// input polygon `n`, the number written as `source`.
    pub fn input_polygons(&self) -> impl Iterator<Item = (usize, &InputPolygon)> + '_ {
        self.objects
            .iter()
            .enumerate()
            .flat_map(|(i, o)| o.polygons.iter().map(move |p| (i, p)))
    }
}

fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

struct Checker<'a> {
    path: &'a Path,
}

impl Checker<'_> {
    fn field(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::Field {
            path: self.path.to_path_buf(),
            field: field.into(),
            message: message.into(),
        }
    }

    fn finite(&self, field: &str, values: &[f64]) -> Result<()> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(v) => Err(self.field(field, format!("{v} is not a finite number"))),
            None => Ok(()),
        }
    }

    fn object(
        &self,
        i: usize,
        spec: ObjectSpec,
        base: &Path,
        earlier: &[Object],
    ) -> Result<Object> {
        let at = |f: &str| format!("object[{i}].{f}");
        if spec.name.trim().is_empty() {
            return Err(self.field(at("name"), "must not be empty"));
        }
        if let Some(j) = earlier.iter().position(|o| o.name == spec.name) {
            return Err(self.field(
                at("name"),
                format!("`{}` is already the name of object[{j}]", spec.name),
            ));
        }
        self.finite(&at("translate"), &spec.translate)?;
        self.finite(&at("rotate_deg"), &spec.rotate_deg)?;
        let scale = match spec.scale {
            None => [1.0; 3],
            Some(ScaleSpec::Uniform(s)) => [s; 3],
            Some(ScaleSpec::PerAxis(s)) => s,
        };
        self.finite(&at("scale"), &scale)?;
        if scale.contains(&0.0) {
            return Err(self.field(at("scale"), "scale factors must not be zero"));
        }
        let transform = Transform {
            scale,
            rotate_deg: spec.rotate_deg,
            translate: spec.translate,
        };

        let (mesh, raw) = match (spec.mesh, spec.polygons) {
            (Some(_), Some(_)) => {
                return Err(self.field(
                    format!("object[{i}]"),
                    "has both `mesh` and `polygons`; give one",
                ));
            }
            (None, None) => {
                return Err(self.field(
                    format!("object[{i}]"),
                    "needs `mesh` (an OBJ file) or `polygons`",
                ));
            }
            (Some(mesh), None) => {
                let file = base.join(&mesh);
                let obj = ObjMesh::load(&file)?;
                let raw = obj
                    .faces
                    .into_iter()
                    .map(|f| InputPolygon {
                        vertices: f.vertices,
                        line: Some(f.line),
                        group: f.group,
                    })
                    .collect::<Vec<_>>();
                (Some(file), raw)
            }
            (None, Some(polygons)) => {
                let mut raw = Vec::with_capacity(polygons.len());
                for (k, vertices) in polygons.into_iter().enumerate() {
                    let field = at(&format!("polygons[{k}]"));
                    if vertices.len() < 3 {
                        return Err(self.field(
                            field,
                            format!(
                                "a polygon needs at least 3 vertices, found {}",
                                vertices.len()
                            ),
                        ));
                    }
                    for v in &vertices {
                        self.finite(&field, v)?;
                    }
                    raw.push(InputPolygon {
                        vertices,
                        line: None,
                        group: None,
                    });
                }
                (None, raw)
            }
        };

        let rotation = transform.rotation();
        let mirrors = transform.mirrors();
        let polygons = raw
            .into_iter()
            .map(|mut p| {
                for v in &mut p.vertices {
                    *v = transform.apply_with(&rotation, *v);
                }
                if mirrors {
                    p.vertices.reverse();
                }
                p
            })
            .collect();
        Ok(Object {
            name: spec.name,
            mesh,
            transform,
            casts_shadows: spec.casts_shadows,
            two_sided: spec.two_sided,
            polygons,
        })
    }

    fn light(&self, i: usize, spec: LightSpec) -> Result<Light> {
        let at = |f: &str| format!("light[{i}].{f}");
        let name = match spec.kind {
            LightType::Point => "point",
            LightType::Directional => "directional",
            LightType::Area => "area",
        };
        let not_for = |field: &str, present: bool| -> Result<()> {
            if present {
                Err(self.field(at(field), format!("not a field of a {name} light")))
            } else {
                Ok(())
            }
        };
        let needs = |field: &str| self.field(at(field), format!("a {name} light needs `{field}`"));
        self.finite(&at("intensity"), &[spec.intensity])?;
        if spec.intensity < 0.0 {
            return Err(self.field(at("intensity"), "must not be negative"));
        }
        self.finite(&at("color"), &spec.color)?;
        if spec.color.iter().any(|&c| c < 0.0) {
            return Err(self.field(at("color"), "components must not be negative"));
        }

        let kind = match spec.kind {
            LightType::Point => {
                not_for("direction", spec.direction.is_some())?;
                not_for("vertices", spec.vertices.is_some())?;
                let position = spec.position.ok_or_else(|| needs("position"))?;
                self.finite(&at("position"), &position)?;
                LightKind::Point { position }
            }
            LightType::Directional => {
                not_for("position", spec.position.is_some())?;
                not_for("vertices", spec.vertices.is_some())?;
                let direction = spec.direction.ok_or_else(|| needs("direction"))?;
                self.finite(&at("direction"), &direction)?;
                if direction == [0.0; 3] {
                    return Err(self.field(at("direction"), "must not be zero"));
                }
                LightKind::Directional { direction }
            }
            LightType::Area => {
                not_for("position", spec.position.is_some())?;
                not_for("direction", spec.direction.is_some())?;
                let vertices = spec.vertices.ok_or_else(|| needs("vertices"))?;
                for v in &vertices {
                    self.finite(&at("vertices"), v)?;
                }
                let vertices =
                    check_convex_planar(&vertices).map_err(|m| self.field(at("vertices"), m))?;
                LightKind::Area { vertices }
            }
        };

        let has_falloff =
            spec.range.is_some() || spec.falloff_start.is_some() || spec.falloff_exponent.is_some();
        let falloff = if !has_falloff {
            None
        } else {
            if spec.kind != LightType::Point {
                let field = if spec.range.is_some() {
                    "range"
                } else if spec.falloff_start.is_some() {
                    "falloff_start"
                } else {
                    "falloff_exponent"
                };
                return Err(self.field(at(field), "only point lights have a sphere of influence"));
            }
            let range = spec.range.ok_or_else(|| {
                self.field(
                    at("range"),
                    "`falloff_start` and `falloff_exponent` need `range`",
                )
            })?;
            let start = spec.falloff_start.unwrap_or(0.0);
            let exponent = spec.falloff_exponent.unwrap_or(1.0);
            self.finite(&at("range"), &[range])?;
            self.finite(&at("falloff_start"), &[start])?;
            self.finite(&at("falloff_exponent"), &[exponent])?;
            if start < 0.0 {
                return Err(self.field(at("falloff_start"), "must not be negative"));
            }
            if range <= start {
                return Err(self.field(
                    at("range"),
                    format!("must be greater than falloff_start ({start})"),
                ));
            }
            if exponent <= 0.0 {
                return Err(self.field(at("falloff_exponent"), "must be positive"));
            }
            Some(Falloff {
                start,
                range,
                exponent,
            })
        };
        Ok(Light {
            kind,
            intensity: spec.intensity,
            color: spec.color,
            falloff,
        })
    }

    fn camera(&self, c: CameraSpec) -> Result<Camera> {
        self.finite("camera.eye", &c.eye)?;
        self.finite("camera.target", &c.target)?;
        self.finite("camera.up", &c.up)?;
        self.finite("camera.fov_deg", &[c.fov_deg])?;
        if c.eye == c.target {
            return Err(self.field("camera.target", "must differ from camera.eye"));
        }
        let view = sub(c.target, c.eye);
        if !view.iter().all(|x| x.is_finite()) {
            return Err(self.field("camera.eye", "too far from camera.target"));
        }
        // Each scaled to a largest component of 1 first: the products
        // overflowed for huge vectors (an eye 1e200 away, an up of 1e300)
        // and underflowed for tiny ones.
        let (view, up) = (by_largest(view), by_largest(c.up));
        if norm(cross(view, up)) <= 1e-12 * norm(view) * norm(up) {
            return Err(self.field("camera.up", "must not be zero or parallel to the view"));
        }
        if !(c.fov_deg > 0.0 && c.fov_deg < 180.0) {
            return Err(self.field("camera.fov_deg", "must be between 0 and 180 degrees"));
        }
        if c.width == 0 {
            return Err(self.field("camera.width", "image size must be positive"));
        }
        if c.height == 0 {
            return Err(self.field("camera.height", "image size must be positive"));
        }
        Ok(Camera {
            eye: c.eye,
            target: c.target,
            // (Only its direction counts.)
            up,
            fov_deg: c.fov_deg,
            width: c.width,
            height: c.height,
        })
    }
}

/// How far (relative to its size) an area light's vertex may lie off the
/// plane that fits the others: six significant digits. Snapping puts the
/// light in one plane anyway (`ConvexPolygon::snap_planar`).
const LIGHT_PLANARITY: f64 = 1e-6;

/// The sine of the turn at an area light's vertex at or below which the
/// vertex is in line with its neighbours (and dropped).
const LIGHT_STRAIGHT: f64 = 1e-7;

/// Checks that an area light's vertices form a convex planar polygon with
/// non-zero area (in `f64`, relative to its size; the exact check runs
/// again after snapping) and returns them without the vertices in line
/// with their neighbours (a square given with a vertex mid-edge, say).
fn check_convex_planar(given: &[[f64; 3]]) -> std::result::Result<Vec<[f64; 3]>, String> {
    let n = given.len();
    if n < 3 {
        return Err(format!(
            "an area light needs at least 3 vertices, found {n}"
        ));
    }
    // Checked relative to vertex 0 and scaled to unit size, so that no
    // square overflows however large the coordinates.
    let origin = given[0];
    let scale = given
        .iter()
        .flat_map(|p| (0..3).map(move |k| (p[k] - origin[k]).abs()))
        .fold(0.0, f64::max);
    if !scale.is_finite() {
        return Err("its extent overflows a 64-bit float".into());
    }
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let v: Vec<[f64; 3]> = given
        .iter()
        .map(|p| [0, 1, 2].map(|k| (p[k] - origin[k]) / scale))
        .collect();
    let size = (0..n)
        .map(|i| norm(sub(v[(i + 1) % n], v[i])))
        .fold(0.0, f64::max);
    for i in 0..n {
        if norm(sub(v[(i + 1) % n], v[i])) <= 1e-12 * size {
            return Err(format!("vertices {i} and {} coincide", (i + 1) % n));
        }
    }
    // Newell's vector area.
    let mut area = [0.0; 3];
    for i in 0..n {
        let c = cross(v[i], v[(i + 1) % n]);
        for k in 0..3 {
            area[k] += 0.5 * c[k];
        }
    }
    let a = norm(area);
    if a <= 1e-12 * size * size {
        return Err("the polygon encloses no area (degenerate)".into());
    }
    let unit = area.map(|c| c / a);
    // Off the plane through the centroid with Newell's normal (the best
    // fit): the farthest vertex is the one named.
    let centroid: [f64; 3] =
        std::array::from_fn(|k| v.iter().map(|p| p[k]).sum::<f64>() / n as f64);
    let (farthest, off) = v
        .iter()
        .map(|p| dot(unit, sub(*p, centroid)).abs())
        .enumerate()
        .fold(
            (0, 0.0),
            |best, (i, d)| if d > best.1 { (i, d) } else { best },
        );
    if off > LIGHT_PLANARITY * size {
        return Err(format!(
            "vertex {farthest} lies {off:e} off the plane of the others (not planar)"
        ));
    }
    let mut kept = Vec::with_capacity(n);
    let mut turning = 0.0;
    for i in 0..n {
        let e0 = sub(v[(i + 1) % n], v[i]);
        let e1 = sub(v[(i + 2) % n], v[(i + 1) % n]);
        let s = dot(cross(e0, e1), unit);
        let (straight, along) = (LIGHT_STRAIGHT * norm(e0) * norm(e1), dot(e0, e1));
        if s.abs() <= straight && along > 0.0 {
            continue;
        }
        if s <= straight {
            let how = if along > 0.0 { "reflex" } else { "turns back" };
            return Err(format!("not convex at vertex {} ({how})", (i + 1) % n));
        }
        turning += s.atan2(along);
        kept.push(given[(i + 1) % n]);
    }
    if (turning - std::f64::consts::TAU).abs() > 1e-6 {
        return Err("not convex (the outline winds more than once)".into());
    }
    // Vertex i + 1 was looked at in step i: the list starts at vertex 1.
    kept.rotate_right(1);
    Ok(kept)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &str) -> Result<Scene> {
        Scene::from_toml_str(text, "s.toml")
    }

    const TRI: &str = "[[object]]\nname = \"t\"\npolygons = [[[0,0,0],[1,0,0],[0,1,0]]]\n";

    #[test]
    fn defaults_and_transforms() {
        let scene = load(&format!(
            "{TRI}scale = [2, 1, 1]\nrotate_deg = [0, 0, 90]\ntranslate = [1, 1, 1]\n"
        ))
        .unwrap();
        let o = &scene.objects[0];
        assert!(o.casts_shadows && !o.two_sided);
        let v = &o.polygons[0].vertices;
        // (1,0,0) -> (2,0,0) -> Rz90 (0,2,0) -> (1,3,1).
        assert!((v[1][0] - 1.0).abs() < 1e-12 && (v[1][1] - 3.0).abs() < 1e-12);
        assert_eq!(scene.ambient, 0.0);
        assert!(scene.lights.is_empty() && scene.camera.is_none());
    }

    #[test]
    fn mirroring_keeps_the_front() {
        let scene = load(&format!("{TRI}scale = [-1, 1, 1]\n")).unwrap();
        let v = &scene.objects[0].polygons[0].vertices;
        assert_eq!(v, &vec![[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]);
    }

    #[test]
    fn toml_errors_have_line_and_column() {
        let e = load(&format!("{TRI}colour = 1\n")).unwrap_err().to_string();
        assert!(e.starts_with("s.toml:4:1: unknown field `colour`"), "{e}");
        let e = load("ambient = \n").unwrap_err().to_string();
        assert!(e.starts_with("s.toml:1:"), "{e}");
    }

    #[test]
    fn area_lights_drop_vertices_in_line_and_allow_rounded_digits() {
        let area = |v: &str| -> Vec<[f64; 3]> {
            let scene = load(&format!(
                "{TRI}[[light]]\ntype = \"area\"\nvertices = {v}\n"
            ))
            .unwrap();
            let LightKind::Area { vertices } = &scene.lights[0].kind else {
                panic!("an area light")
            };
            vertices.clone()
        };
        // A square with a vertex mid-edge is the square.
        assert_eq!(
            area("[[-0.3,3,-0.3],[0,3,-0.3],[0.3,3,-0.3],[0.3,3,0.3],[-0.3,3,0.3]]"),
            [
                [-0.3, 3.0, -0.3],
                [0.3, 3.0, -0.3],
                [0.3, 3.0, 0.3],
                [-0.3, 3.0, 0.3]
            ]
        );
        // A tilted pentagon written with nine significant digits: its
        // vertices lie up to 2e-9 off one plane, and it is taken whole.
        let pentagon = "[[0.331859078,2.93521907,0.694760983],[0.00707110885,2.99002162,0.605084061],\
                        [-0.0653802043,3.08958008,-0.129351962],[0.486330607,3.03143682,-0.262917521],\
                        [0.770614682,2.95642145,0.0368352651]]";
        assert_eq!(area(pentagon).len(), 5);
    }

    #[test]
    fn semantic_errors_name_the_field() {
        let cases = [
            (format!("{TRI}{TRI}"), "object[1].name: `t` is already"),
            (
                format!("{TRI}scale = nan\n"),
                "object[0].scale: NaN is not a finite",
            ),
            (
                format!("{TRI}[[light]]\ntype = \"area\"\nvertices = [[0,0,0],[1,0,0],[2,0,0]]\n"),
                "light[0].vertices: the polygon encloses no area",
            ),
            (
                format!(
                    "{TRI}[[light]]\ntype = \"area\"\nvertices = [[0,0,0],[2,0,0],[1,0,-0.2],[1,0,-2]]\n"
                ),
                "light[0].vertices: not convex at vertex 2 (reflex)",
            ),
            (
                format!(
                    "{TRI}[[light]]\ntype = \"area\"\nvertices = [[0,0,0],[1,0,0],[1,1,-1],[0,0,-1]]\n"
                ),
                "not planar",
            ),
            (
                format!("{TRI}[[light]]\ntype = \"directional\"\ndirection = [0,0,0]\n"),
                "light[0].direction: must not be zero",
            ),
            (
                format!(
                    "{TRI}[[light]]\ntype = \"point\"\nposition = [0,0,0]\nrange = 2\nfalloff_start = 3\n"
                ),
                "light[0].range: must be greater",
            ),
            (
                format!("{TRI}[[light]]\ntype = \"point\"\n"),
                "light[0].position: a point light needs",
            ),
            (
                format!(
                    "{TRI}[[light]]\ntype = \"directional\"\ndirection = [0,-1,0]\nposition = [0,0,0]\n"
                ),
                "light[0].position: not a field of a directional light",
            ),
            (
                "[[object]]\nname = \"a\"\n".to_string(),
                "object[0]: needs `mesh`",
            ),
            ("ambient = 0.1\n".to_string(), "the scene has no polygons"),
        ];
        for (text, expected) in cases {
            let e = load(&text).unwrap_err().to_string();
            assert!(e.contains(expected), "{e} / {expected}");
        }
    }

    #[test]
    fn at_most_32_lights() {
        let light = "[[light]]\ntype = \"point\"\nposition = [0,5,0]\n";
        assert!(load(&format!("{TRI}{}", light.repeat(32))).is_ok());
        let e = load(&format!("{TRI}{}", light.repeat(33)))
            .unwrap_err()
            .to_string();
        assert!(e.contains("light: 33 lights; at most 32"), "{e}");
    }

    #[test]
    fn falloff_factor() {
        let f = Falloff {
            start: 1.0,
            range: 3.0,
            exponent: 2.0,
        };
        assert_eq!(f.factor(0.5), 1.0);
        assert!((f.factor(2.0) - 0.25).abs() < 1e-15);
        assert_eq!(f.factor(3.5), 0.0);
    }
}
