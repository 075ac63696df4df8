//! The scene file (FORMATS.md §1): parsed into typed structs, validated once,
//! with every object's polygons read and placed in the scene.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::transform::Transform;

mod check;
mod file;

use check::Checker;
use file::SceneFile;

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
    /// The falloff the illumination applies ([`illum::Falloff`], whose
    /// `factor` is 1 up to `start`, `((range - r) / (range - start))^exponent`
    /// between, 0 from `range` on); an error for figures it refuses.
    pub fn to_illum(&self) -> std::result::Result<illum::Falloff, illum::IllumError> {
        illum::Falloff::new(self.start, self.range, self.exponent)
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

#[cfg(test)]
mod tests;
