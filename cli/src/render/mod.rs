//! The software renderer of `umbra render`: the scene's fragments seen from
//! its camera, shaded with their exact shadows.
//!
//! Every fragment of [`ShadowResult::mesh`] is clipped to the near plane,
//! cut into a fan of triangles and drawn into a z-buffer of
//! [`SAMPLES_PER_SIDE`]² samples per pixel, with its per-vertex values
//! interpolated perspective-correctly. The samples of a pixel are averaged
//! (a box filter) in linear light, then encoded as 8-bit sRGB.
//!
//! What a sample shows depends on the [`View`]:
//!
//! - [`View::Shaded`]: a grey surface of albedo [`ALBEDO`] lit by the ambient
//!   term and every light's irradiance times its colour; see [`exposure`]
//!   for how that becomes a display value;
//! - [`View::Classes`]: lit, penumbra and umbra in flat colours, as in the
//!   papers' figures (see [`FragmentClass`]);
//! - [`View::Fragments`]: the classes, with every fragment outlined.
//!
//! Back faces of one-sided polygons are drawn like the rest: they receive
//! no light, so they are dark in the shaded view and umbra in the others.

mod bsp_order;
mod camera;
mod image;
mod raster;
mod volumes;

pub use camera::Projection;
pub use image::{Image, linear_to_srgb8, srgb8_to_linear};

use crate::decompose::Pieces;
use crate::error::{Error, Result};
use crate::mesh::OutputFace;
use crate::scene::{Camera, LightKind, Scene};
use crate::shadow::{ShadowOptions, ShadowResult, shadow_scene_with};

/// Gridding `render_scene` uses for scenes with area lights (cells of
/// 1/40 of the scene, 1/80 in penumbra).
pub const RENDER_GRID: u32 = 40;
use crate::vec3::{dot, sub};
use raster::{Corner, EMPTY, Samples};

/// Samples per pixel side: 3 x 3 samples per pixel.
pub const SAMPLES_PER_SIDE: usize = 3;

/// Largest image side, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// Albedo of every surface in the shaded view (a light grey).
pub const ALBEDO: f64 = 0.8;

/// What an image shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// Illuminated surfaces.
    Shaded,
    /// Lit, penumbra and umbra fragments in flat colours.
    Classes,
    /// The classes view with every fragment outlined.
    Fragments,
}

/// How shadows are found for an image.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// umbra's object-space fragments (`umbra shadow`), drawn.
    #[default]
    Fragments,
    /// Bergeron's general shadow volumes: each sample's visible point is in
    /// shadow when the eye ray crosses shadow polygons to a positive depth
    /// count (point and directional lights only).
    Volumes,
}

/// How visible surfaces are found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Order {
    /// A z-buffer: each sample keeps the nearest surface.
    #[default]
    ZBuffer,
    /// Back-to-front traversal of the scene BSP from the eye (the painter's
    /// algorithm, as the papers render); the same image wherever polygons
    /// do not interpenetrate.
    Bsp,
}

/// Everything `umbra render` can be asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderOptions {
    /// What the image shows.
    pub view: View,
    /// How shadows are found.
    pub method: Method,
    /// How visible surfaces are found.
    pub order: Order,
}

impl RenderOptions {
    /// A view with the default method and order.
    pub fn view(view: View) -> Self {
        Self {
            view,
            method: Method::default(),
            order: Order::default(),
        }
    }
}

/// A fragment's class for the figures, over all lights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FragmentClass {
    /// It sees all of at least one light.
    Lit,
    /// Neither lit nor umbra: it sees part of some light.
    Penumbra,
    /// It sees none of any light (also when the scene has no lights).
    Umbra,
}

impl FragmentClass {
    /// The class of a fragment of a scene with `lights` lights.
    pub fn of(face: &OutputFace, lights: usize) -> Self {
        Self::from_masks(face.lit_mask, face.umbra_mask, lights)
    }

    /// The class of the side of a fragment that the eye sees, where `seen`
    /// has bit `i` if light `i` is on that side: the lights on the other
    /// side light none of it.
    pub fn of_seen_side(face: &OutputFace, lights: usize, seen: u32) -> Self {
        Self::from_masks(face.lit_mask & seen, face.umbra_mask | !seen, lights)
    }

    fn from_masks(lit_mask: u32, umbra_mask: u32, lights: usize) -> Self {
        let all = if lights >= 32 {
            u32::MAX
        } else {
            (1u32 << lights) - 1
        };
        if lit_mask & all != 0 {
            Self::Lit
        } else if umbra_mask & all == all {
            Self::Umbra
        } else {
            Self::Penumbra
        }
    }

    /// Its colour in the classes and fragments views (8-bit sRGB).
    pub fn srgb(self) -> [u8; 3] {
        match self {
            Self::Lit => LIT,
            Self::Penumbra => PENUMBRA,
            Self::Umbra => UMBRA,
        }
    }
}

/// Lit fragments: a pale yellow.
const LIT: [u8; 3] = [255, 232, 150];
/// Penumbra: light grey.
const PENUMBRA: [u8; 3] = [185, 185, 185];
/// Umbra: dark grey.
const UMBRA: [u8; 3] = [70, 70, 70];
/// Fragment outlines.
const OUTLINE: [u8; 3] = [0, 0, 0];
/// Where no surface is, in the classes and fragments views.
const BACKGROUND_CLASSES: [u8; 3] = [255, 255, 255];
/// Where no surface is, in the shaded view.
const BACKGROUND_SHADED: [u8; 3] = [0, 0, 0];

/// Exposure: the factor that brings the scene's irradiance to display
/// values, whatever its units.
///
/// The reference irradiance `E_ref` is the 90th percentile, over the
/// vertices of the mesh that receive direct light, of `ambient + sum_i E_i *
/// mean(colour_i)` (the ambient term if no vertex is lit, 1 if that is 0
/// too). A sample's linear colour `c = ALBEDO * (ambient + sum_i E_i *
/// colour_i)` is shown as `1 - exp(-1.75 * c / E_ref)` per channel: a
/// surface lit at the reference shows at 75 % of white (sRGB 225), brighter
/// ones saturate smoothly and nothing clips harshly. The function returns
/// `1.75 / E_ref`.
pub fn exposure(scene: &Scene, shadows: &ShadowResult) -> f64 {
    let mean_colour: Vec<f64> = scene
        .lights
        .iter()
        .map(|l| (l.color[0] + l.color[1] + l.color[2]) / 3.0)
        .collect();
    let mut lit: Vec<f64> = (0..shadows.mesh.vertices.len())
        .map(|v| {
            shadows
                .vertex_light_irradiance(v)
                .iter()
                .zip(&mean_colour)
                .map(|(e, c)| e * c)
                .sum::<f64>()
        })
        .filter(|&e| e > 0.0)
        .map(|e| e + scene.ambient)
        .collect();
    lit.sort_by(f64::total_cmp);
    let reference = match lit.len() {
        0 if scene.ambient > 0.0 => scene.ambient,
        0 => 1.0,
        n => lit[(n - 1) * 9 / 10],
    };
    1.75 / reference
}

/// Renders `scene` from its camera: computes its shadows
/// ([`shadow_scene_with`]) and draws them ([`render`]).
///
/// # Errors
///
/// If the scene has no `[camera]` (checked first), or the shadow pipeline
/// fails.
///
/// # Example
///
/// ```
/// use umbra::{Scene, View, render_scene};
///
/// let scene = Scene::from_toml_str(
///     r#"
///     [[object]]
///     name = "floor"
///     polygons = [[[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]]]
///     [[light]]
///     type = "point"
///     position = [0, 3, 0]
///     [camera]
///     eye = [0, 5, 6]
///     width = 32
///     height = 24
///     "#,
///     "floor.toml",
/// )?;
/// let image = render_scene(&scene, View::Shaded)?;
/// assert_eq!((image.width, image.height), (32, 24));
/// // The floor is under the light in the middle, the sky is black.
/// assert!(image.pixel(16, 16)[0] > 100);
/// assert_eq!(image.pixel(0, 0), [0, 0, 0]);
/// # Ok::<(), umbra::Error>(())
/// ```
pub fn render_scene(scene: &Scene, view: View) -> Result<Image> {
    render_scene_with(scene, &RenderOptions::view(view))
}

/// Renders `scene` from its camera with the given options: as
/// [`render_scene`] for [`Method::Fragments`]; for [`Method::Volumes`] the
/// scene's pieces are drawn and every sample counts shadow polygons
/// (Bergeron) along its eye ray.
///
/// # Errors
///
/// If the scene has no `[camera]`, the shadow pipeline fails, or (volumes)
/// the scene has an area light.
///
/// # Example
///
/// ```
/// use umbra::{Method, Order, RenderOptions, Scene, View, render_scene_with};
///
/// let scene = Scene::from_toml_str(
///     r#"
///     [[object]]
///     name = "floor"
///     polygons = [[[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]]]
///     [[object]]
///     name = "card"
///     polygons = [[[-1, 1.5, 1], [1, 1.5, 1], [1, 1.5, -1], [-1, 1.5, -1]]]
///     two_sided = true
///     [[light]]
///     type = "point"
///     position = [0, 3, 0]
///     [camera]
///     eye = [0, 5, 6]
///     width = 32
///     height = 24
///     "#,
///     "card.toml",
/// )?;
/// let options = |method| RenderOptions { view: View::Classes, method, order: Order::ZBuffer };
/// let fragments = render_scene_with(&scene, &options(Method::Fragments))?;
/// let volumes = render_scene_with(&scene, &options(Method::Volumes))?;
/// // The two methods draw the same shadow away from its edges.
/// let same = fragments.rgb.chunks(3).zip(volumes.rgb.chunks(3)).filter(|(a, b)| a == b).count();
/// assert!(same > 32 * 24 * 9 / 10);
/// # Ok::<(), umbra::Error>(())
/// ```
pub fn render_scene_with(scene: &Scene, options: &RenderOptions) -> Result<Image> {
    if options.method == Method::Volumes {
        return volumes::render_volumes(scene, options.view, options.order);
    }
    camera_of(scene)?;
    // Soft shadows need vertices inside the penumbra to show its gradient.
    let has_area_light = scene
        .lights
        .iter()
        .any(|l| matches!(l.kind, crate::scene::LightKind::Area { .. }));
    let shadow_options = ShadowOptions {
        grid: has_area_light.then_some(RENDER_GRID),
        adaptive: None,
    };
    let shadows = shadow_scene_with(scene, &shadow_options)?;
    render_with(scene, &shadows, options)
}

/// Draws the fragments of `shadows` (computed for `scene`) from the scene's
/// camera.
///
/// # Errors
///
/// If the scene has no `[camera]`, or its image is larger than
/// [`MAX_IMAGE_SIDE`] on a side.
///
/// # Panics
///
/// If `shadows` was not computed for `scene` (a face naming a vertex that
/// does not exist, fewer per-light values than lights).
pub fn render(scene: &Scene, shadows: &ShadowResult, view: View) -> Result<Image> {
    render_with(scene, shadows, &RenderOptions::view(view))
}

/// Draws the fragments of `shadows` (computed for `scene`) from the scene's
/// camera in the given [`Order`] (the method is that of `shadows`:
/// fragments).
///
/// # Errors
///
/// As [`render`]; with [`Order::Bsp`], also if the scene cannot be cut into
/// pieces again or the eye is too far from it.
///
/// # Panics
///
/// As [`render`].
pub fn render_with(
    scene: &Scene,
    shadows: &ShadowResult,
    options: &RenderOptions,
) -> Result<Image> {
    let view = options.view;
    let camera = camera_of(scene)?;
    let projection = Projection::new(&camera);
    let n = SAMPLES_PER_SIDE;
    let (width, height) = (camera.width as usize * n, camera.height as usize * n);
    let samples = match options.order {
        Order::ZBuffer => Samples::new(width, height, view == View::Shaded),
        Order::Bsp => Samples::painter(width, height, view == View::Shaded),
    };
    let mut samples = samples.ok_or_else(|| too_big(scene, &camera))?;
    let exposed_albedo = ALBEDO * exposure(scene, shadows);
    let near = near_distance(&camera);
    let mesh = &shadows.mesh;
    let mut classes = Vec::with_capacity(mesh.faces.len());
    let mut polygons: Vec<Vec<([f64; 3], [f64; 3])>> = Vec::with_capacity(mesh.faces.len());
    for face in &mesh.faces {
        let seen = lights_on_seen_side(scene, shadows, face, camera.eye);
        classes.push(FragmentClass::of_seen_side(face, shadows.lights, seen));
        polygons.push(
            face.vertices
                .iter()
                .map(|&v| {
                    let value = if view == View::Shaded {
                        shaded_value(scene, shadows, v as usize, seen).map(|c| exposed_albedo * c)
                    } else {
                        [0.0; 3]
                    };
                    (projection.to_view(mesh.vertices[v as usize].0), value)
                })
                .collect(),
        );
    }
    match options.order {
        Order::ZBuffer => {
            for (id, polygon) in polygons.iter().enumerate() {
                draw_polygon(&mut samples, &projection, polygon, near, id as u32);
            }
        }
        Order::Bsp => {
            let pieces = Pieces::from_scene(scene)?;
            let mut faces_of: Vec<Vec<usize>> = vec![Vec::new(); pieces.input_polygons];
            for (id, face) in mesh.faces.iter().enumerate() {
                faces_of[face.source as usize].push(id);
            }
            for (piece, part) in bsp_order::back_to_front(scene, &pieces, camera.eye)? {
                let region: Vec<[f64; 3]> = part
                    .vertices_f64()
                    .iter()
                    .map(|&v| projection.to_view(pieces.grid.grid_to_world(v)))
                    .collect();
                for &id in &faces_of[pieces.input_of[piece] as usize] {
                    let inside = bsp_order::clip_to_region(&polygons[id], &region);
                    draw_polygon(&mut samples, &projection, &inside, near, id as u32);
                }
            }
        }
    }
    let class_colour: Vec<[f32; 3]> = classes.iter().map(|c| linear(c.srgb())).collect();
    Ok(resolve(
        &samples,
        |_, id| class_colour[id as usize],
        view,
        camera.width,
        camera.height,
    ))
}

/// Draws a convex polygon (view frame, with values) as fragment `id`:
/// clipped to the near plane, then a fan of triangles.
fn draw_polygon(
    samples: &mut Samples,
    projection: &Projection,
    polygon: &[([f64; 3], [f64; 3])],
    near: f64,
    id: u32,
) {
    let n = SAMPLES_PER_SIDE as f64;
    let clipped = clip_near(polygon, near);
    let corners: Vec<Corner> = clipped
        .iter()
        .map(|&(v, value)| {
            let [x, y] = projection.view_to_pixel(v);
            Corner {
                xy: [x * n, y * n],
                depth: v[2],
                value,
            }
        })
        .collect();
    for i in 1..corners.len().saturating_sub(1) {
        samples.triangle([corners[0], corners[i], corners[i + 1]], id);
    }
}

/// The scene's camera, checked for size.
fn camera_of(scene: &Scene) -> Result<Camera> {
    let camera = scene.camera.ok_or_else(|| Error::Field {
        path: scene.path.clone(),
        field: "camera".into(),
        message: "images need a [camera] table (eye, target, up, fov_deg, width, height)".into(),
    })?;
    for (field, side) in [
        ("camera.width", camera.width),
        ("camera.height", camera.height),
    ] {
        if side > MAX_IMAGE_SIDE {
            return Err(Error::Field {
                path: scene.path.clone(),
                field: field.into(),
                message: format!("{side} pixels; images are at most {MAX_IMAGE_SIDE} on a side"),
            });
        }
    }
    Ok(camera)
}

/// The error for an image whose samples the memory cannot hold.
fn too_big(scene: &Scene, camera: &Camera) -> Error {
    Error::Field {
        path: scene.path.clone(),
        field: "camera.width".into(),
        message: format!(
            "{} x {} pixels: not enough memory for the image's {} samples a pixel",
            camera.width,
            camera.height,
            SAMPLES_PER_SIDE * SAMPLES_PER_SIDE
        ),
    }
}

/// Nothing nearer to the eye than this is drawn: a thousandth of the
/// distance from the eye to the target.
fn near_distance(camera: &Camera) -> f64 {
    let d: f64 = (0..3)
        .map(|i| (camera.target[i] - camera.eye[i]).powi(2))
        .sum();
    1e-3 * d.sqrt()
}

/// `ambient + sum_i E_i * colour_i` at vertex `v`, over the lights whose
/// bit is set in `seen` (linear, before albedo and exposure).
fn shaded_value(scene: &Scene, shadows: &ShadowResult, v: usize, seen: u32) -> [f64; 3] {
    let mut c = [scene.ambient; 3];
    let per_light = shadows.vertex_light_irradiance(v).iter();
    for (i, (e, light)) in per_light.zip(&scene.lights).enumerate() {
        if seen & (1 << i) != 0 {
            for (ch, out) in c.iter_mut().enumerate() {
                *out += e * light.color[ch];
            }
        }
    }
    c
}

/// The lights (bit `i`: light `i`) on the side of the fragment's plane that
/// the eye sees. The irradiance of a fragment is that of the side facing
/// each light: a one-sided polygon seen from the back, or a two-sided one
/// seen from the side away from a light, receives none of that light.
/// Lights in the plane, and degenerate fragments, count as seen.
fn lights_on_seen_side(
    scene: &Scene,
    shadows: &ShadowResult,
    face: &OutputFace,
    eye: [f64; 3],
) -> u32 {
    let corners: Vec<[f64; 3]> = face
        .vertices
        .iter()
        .map(|&v| shadows.mesh.vertices[v as usize].0)
        .collect();
    // Newell's normal: robust for any planar polygon, zero if degenerate.
    let mut normal = [0.0; 3];
    for (i, a) in corners.iter().enumerate() {
        let b = corners[(i + 1) % corners.len()];
        normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
        normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
        normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let Some(&origin) = corners.first() else {
        return u32::MAX;
    };
    let side = |d: [f64; 3]| dot(normal, d);
    let eye_side = side(sub(eye, origin));
    let mut seen = 0;
    for (i, light) in scene.lights.iter().enumerate() {
        let light_side = match &light.kind {
            LightKind::Point { position } => side(sub(*position, origin)),
            LightKind::Directional { direction } => -side(*direction),
            LightKind::Area { vertices } => {
                let k = 1.0 / vertices.len() as f64;
                let centre = vertices.iter().fold([0.0; 3], |c, v| {
                    [c[0] + k * v[0], c[1] + k * v[1], c[2] + k * v[2]]
                });
                side(sub(centre, origin))
            }
        };
        if eye_side * light_side >= 0.0 {
            seen |= 1 << i;
        }
    }
    seen
}

/// The part of a convex polygon (view frame, with values) at depth `near`
/// or more (Sutherland-Hodgman against one plane). Values are affine on the
/// polygon, so cutting an edge interpolates them linearly.
fn clip_near(polygon: &[([f64; 3], [f64; 3])], near: f64) -> Vec<([f64; 3], [f64; 3])> {
    if polygon.iter().all(|(v, _)| v[2] >= near) {
        return polygon.to_vec();
    }
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for (i, &(a, va)) in polygon.iter().enumerate() {
        let (b, vb) = polygon[(i + 1) % polygon.len()];
        let (a_in, b_in) = (a[2] >= near, b[2] >= near);
        if a_in {
            out.push((a, va));
        }
        if a_in != b_in {
            let t = (near - a[2]) / (b[2] - a[2]);
            let lerp = |x: [f64; 3], y: [f64; 3]| [0, 1, 2].map(|k| x[k] + t * (y[k] - x[k]));
            let mut p = lerp(a, b);
            p[2] = near;
            out.push((p, lerp(va, vb)));
        }
    }
    out
}

/// Averages the samples of every pixel (in linear light) into an sRGB image;
/// `class_colour(k, id)` is the linear class colour of sample `k`, which
/// shows fragment `id`.
fn resolve(
    samples: &Samples,
    class_colour: impl Fn(usize, u32) -> [f32; 3],
    view: View,
    width: u32,
    height: u32,
) -> Image {
    let background = linear(match view {
        View::Shaded => BACKGROUND_SHADED,
        View::Classes | View::Fragments => BACKGROUND_CLASSES,
    });
    let outline = linear(OUTLINE);
    let sample = |x: usize, y: usize| -> [f32; 3] {
        let k = y * samples.width + x;
        let id = samples.id[k];
        if id == EMPTY {
            return background;
        }
        match view {
            View::Shaded => samples.value[k].map(|c| 1.0 - (-c).exp()),
            View::Classes => class_colour(k, id),
            View::Fragments => {
                if is_outline(samples, x, y) {
                    outline
                } else {
                    class_colour(k, id)
                }
            }
        }
    };
    let n = SAMPLES_PER_SIDE;
    let scale = 1.0 / (n * n) as f32;
    let mut rgb = Vec::with_capacity(width as usize * height as usize * 3);
    for py in 0..height as usize {
        for px in 0..width as usize {
            let mut sum = [0.0f32; 3];
            for sy in 0..n {
                for sx in 0..n {
                    let c = sample(px * n + sx, py * n + sy);
                    for ch in 0..3 {
                        sum[ch] += c[ch];
                    }
                }
            }
            rgb.extend(sum.map(|s| linear_to_srgb8(s * scale)));
        }
    }
    Image { width, height, rgb }
}

/// Whether a sample is on a fragment's outline: a neighbouring sample (one
/// sample away, a third of a pixel) shows another fragment or nothing.
fn is_outline(samples: &Samples, x: usize, y: usize) -> bool {
    let id = samples.id[y * samples.width + x];
    let differs = |nx: usize, ny: usize| samples.id[ny * samples.width + nx] != id;
    (x > 0 && differs(x - 1, y))
        || (x + 1 < samples.width && differs(x + 1, y))
        || (y > 0 && differs(x, y - 1))
        || (y + 1 < samples.height && differs(x, y + 1))
}

pub(crate) fn linear(srgb: [u8; 3]) -> [f32; 3] {
    srgb.map(srgb8_to_linear)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_the_part_in_front() {
        // A square in the plane x = 0 from depth -1 to 3, value = depth.
        let square: Vec<([f64; 3], [f64; 3])> = [[0.0, -1.0], [0.0, 3.0], [1.0, 3.0], [1.0, -1.0]]
            .iter()
            .map(|&[y, z]| ([0.0, y, z], [z; 3]))
            .collect();
        let clipped = clip_near(&square, 1.0);
        assert_eq!(clipped.len(), 4);
        for (v, value) in &clipped {
            assert!(v[2] >= 1.0);
            assert!((value[0] - v[2]).abs() < 1e-12);
        }
        assert!(clip_near(&square, 5.0).is_empty());
        assert_eq!(clip_near(&square, -2.0), square);
    }

    #[test]
    fn classes_follow_the_masks() {
        let face = |lit_mask, umbra_mask| OutputFace {
            vertices: vec![0, 1, 2],
            source: 0,
            lit_mask,
            umbra_mask,
        };
        assert_eq!(FragmentClass::of(&face(0b10, 0b01), 2), FragmentClass::Lit);
        assert_eq!(FragmentClass::of(&face(0, 0b11), 2), FragmentClass::Umbra);
        assert_eq!(
            FragmentClass::of(&face(0, 0b01), 2),
            FragmentClass::Penumbra
        );
        assert_eq!(FragmentClass::of(&face(0, 0), 0), FragmentClass::Umbra);
        // Seen from the side of light 0 only: light 1 lights none of it.
        let seen = FragmentClass::of_seen_side;
        assert_eq!(seen(&face(0b10, 0b01), 2, 0b01), FragmentClass::Umbra);
        assert_eq!(seen(&face(0b10, 0b01), 2, 0b10), FragmentClass::Lit);
        assert_eq!(seen(&face(0b01, 0), 2, 0b01), FragmentClass::Lit);
        assert_eq!(seen(&face(0, 0), 2, 0b01), FragmentClass::Penumbra);
    }
}
