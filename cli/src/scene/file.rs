//! The scene file as written (FORMATS.md §1), as serde reads it: every
//! field, its default, and triples checked to have three numbers.

use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    #[serde(default)]
    pub(super) ambient: f64,
    #[serde(default)]
    pub(super) object: Vec<ObjectSpec>,
    #[serde(default)]
    pub(super) light: Vec<LightSpec>,
    pub(super) camera: Option<CameraSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObjectSpec {
    pub(super) name: String,
    pub(super) mesh: Option<String>,
    #[serde(default, deserialize_with = "three_each")]
    pub(super) polygons: Option<Vec<Vec<[f64; 3]>>>,
    #[serde(default, deserialize_with = "three_each")]
    pub(super) translate: [f64; 3],
    #[serde(default, deserialize_with = "three_each")]
    pub(super) rotate_deg: [f64; 3],
    pub(super) scale: Option<ScaleSpec>,
    #[serde(default = "yes")]
    pub(super) casts_shadows: bool,
    #[serde(default)]
    pub(super) two_sided: bool,
}

#[derive(Debug, Deserialize)]
#[serde(untagged, expecting = "expected a number or an array [sx, sy, sz]")]
pub(super) enum ScaleSpec {
    Uniform(f64),
    PerAxis(#[serde(deserialize_with = "three_each")] [f64; 3]),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum LightType {
    Point,
    Directional,
    Area,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightSpec {
    #[serde(rename = "type")]
    pub(super) kind: LightType,
    #[serde(default, deserialize_with = "three_each")]
    pub(super) position: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "three_each")]
    pub(super) direction: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "three_each")]
    pub(super) vertices: Option<Vec<[f64; 3]>>,
    #[serde(default = "one")]
    pub(super) intensity: f64,
    #[serde(default = "white", deserialize_with = "three_each")]
    pub(super) color: [f64; 3],
    pub(super) falloff_start: Option<f64>,
    pub(super) range: Option<f64>,
    pub(super) falloff_exponent: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraSpec {
    #[serde(default = "default_eye", deserialize_with = "three_each")]
    pub(super) eye: [f64; 3],
    #[serde(default, deserialize_with = "three_each")]
    pub(super) target: [f64; 3],
    #[serde(default = "default_up", deserialize_with = "three_each")]
    pub(super) up: [f64; 3],
    #[serde(default = "default_fov")]
    pub(super) fov_deg: f64,
    #[serde(default = "default_width")]
    pub(super) width: u32,
    #[serde(default = "default_height")]
    pub(super) height: u32,
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
pub(super) struct Three([f64; 3]);

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
