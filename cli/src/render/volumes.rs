//! `umbra render --method volumes`: Bergeron's general shadow volumes
//! counted along every sample's eye ray, with no object-space fragments.
//!
//! The scene's convex pieces are drawn as they are (z-buffer, or the scene
//! BSP's parts back to front). For
//! every sample the visible point is where its eye ray meets the plane of
//! the piece it shows; for every light, the shadow polygons of
//! [`svbsp::bergeron::BergeronVolumes`] that the segment from the eye to
//! that point crosses add their depth increments to the count at the eye,
//! and the point is in shadow when a count is positive. Which samples a
//! shadow polygon can touch is found in floating point (its part inside the
//! box of the eye and the scene, projected, with a margin); whether it is
//! crossed is decided exactly.
//!
//! A light lights a visible point when the point is not in shadow, the eye
//! sees the side of the piece the light is on, a one-sided piece faces it,
//! and the piece is not wholly beyond the light's range (FORMATS.md §1):
//! the same rules as the fragments. Point and directional lights only.

use std::collections::HashMap;

use bsp_core::predicates::{Side, orient3d_f64};
use illum::Sidedness;
use svbsp::bergeron::{BergeronVolumes, Model, ModelPolygon, ShadowPolygon};
use svbsp::{Light as VolumeLight, LightSource};

use super::bsp_order::back_to_front;
use super::raster::{EMPTY, Samples};
use super::{
    FragmentClass, Image, Order, Projection, SAMPLES_PER_SIDE, View, camera_of, draw_polygon,
    linear, near_distance, resolve, too_big,
};
use crate::decompose::{Pieces, SnappedLight};
use crate::error::{Error, Result};
use crate::illuminate::IllumLight;
use crate::scene::Scene;
use crate::shadow::illum_lights;
use crate::vec3::{dot, sub};

/// Renders `scene` from its camera with shadows found by counting shadow
/// polygons along eye rays.
pub(crate) fn render_volumes(scene: &Scene, view: View, order: Order) -> Result<Image> {
    let camera = camera_of(scene)?;
    let pieces = Pieces::from_scene(scene)?;
    let grid = &pieces.grid;
    let lights = volume_lights(scene, &pieces)?;
    let projection = Projection::new(&camera);
    let near = near_distance(&camera);
    let n = SAMPLES_PER_SIDE;
    let (width, height) = (camera.width as usize * n, camera.height as usize * n);
    let corners: Vec<Vec<[f64; 3]>> = pieces.polygons.iter().map(|p| p.vertices_f64()).collect();
    let to_view = |v: &[f64; 3]| (projection.to_view(grid.grid_to_world(*v)), [0.0; 3]);
    let mut samples = match order {
        Order::ZBuffer => {
            let mut samples = Samples::new(width, height, view == View::Shaded)
                .ok_or_else(|| too_big(scene, &camera))?;
            for (id, piece) in corners.iter().enumerate() {
                let polygon: Vec<_> = piece.iter().map(to_view).collect();
                draw_polygon(&mut samples, &projection, &polygon, near, id as u32);
            }
            samples
        }
        Order::Bsp => {
            let mut samples = Samples::painter(width, height, view == View::Shaded)
                .ok_or_else(|| too_big(scene, &camera))?;
            for (id, part) in back_to_front(scene, &pieces, camera.eye)? {
                let polygon: Vec<_> = part.vertices_f64().iter().map(to_view).collect();
                draw_polygon(&mut samples, &projection, &polygon, near, id as u32);
            }
            samples
        }
    };

    // The visible point of every sample, in grid units.
    let eye = grid.world_to_grid(camera.eye);
    let normals: Vec<[f64; 3]> = pieces
        .polygons
        .iter()
        .map(|p| p.support().unit_normal_f64())
        .collect();
    let visible: Vec<Option<[f64; 3]>> = (0..width * height)
        .map(|k| {
            let id = samples.id[k];
            if id == EMPTY {
                return None;
            }
            let (x, y) = ((k % width) as f64 + 0.5, (k / width) as f64 + 0.5);
            let ray = projection.pixel_ray(x / n as f64, y / n as f64);
            let d = ray.map(|c| c * grid.scale());
            let (normal, origin) = (normals[id as usize], corners[id as usize][0]);
            let t = dot(normal, sub(origin, eye)) / dot(normal, d);
            Some([0, 1, 2].map(|i| eye[i] + t * d[i]))
        })
        .collect();

    let bounds = bounds_with(&corners, eye);
    let models = models(scene, &pieces);
    let mut lit = vec![0u32; width * height];
    for (i, light) in lights.iter().enumerate() {
        let receives: Vec<bool> = pieces
            .polygons
            .iter()
            .zip(&corners)
            .enumerate()
            .map(|(k, (piece, v))| {
                let light_point = match light.source {
                    LightSource::Point(p) => p.to_f64(),
                    LightSource::Directional(d) => [0, 1, 2].map(|a| v[0][a] - f64::from(d[a])),
                };
                let light_side = orient3d_f64(v[0], v[1], v[2], light_point);
                light_side != Side::On
                    && light_side == orient3d_f64(v[0], v[1], v[2], eye)
                    && (pieces.two_sided[k] || light.source.side(piece.support()) == Side::Front)
                    && !light.wholly_beyond_range(v)
            })
            .collect();
        let reach = light.range.map(|range| {
            corners
                .iter()
                .filter(|v| !light.wholly_beyond_range(v))
                .flat_map(|v| v.iter())
                .map(|&p| match light.source {
                    LightSource::Point(l) => distance(p, l.to_f64()),
                    LightSource::Directional(_) => 0.0,
                })
                .fold(range, f64::max)
        });
        let volumes = BergeronVolumes::build(&models, light, reach).map_err(|e| Error::Field {
            path: scene.path.clone(),
            field: format!("light[{i}]"),
            message: e.to_string(),
        })?;
        let shadowed = count_shadows(&volumes, eye, &visible, width, |polygon| {
            touched_samples(polygon, bounds, grid, &projection, near, width, height)
        });
        for k in 0..width * height {
            let id = samples.id[k];
            if id != EMPTY && receives[id as usize] && !shadowed[k] {
                lit[k] |= 1 << i;
            }
        }
    }

    if view == View::Shaded {
        shade(scene, &pieces, &mut samples, &visible, &normals, &lit)?;
    }
    let lit_colour = linear(FragmentClass::Lit.srgb());
    let umbra_colour = linear(FragmentClass::Umbra.srgb());
    Ok(resolve(
        &samples,
        |k, _| {
            if lit[k] != 0 {
                lit_colour
            } else {
                umbra_colour
            }
        },
        view,
        camera.width,
        camera.height,
    ))
}

/// The scene's lights for the volumes; area lights are refused.
fn volume_lights(scene: &Scene, pieces: &Pieces) -> Result<Vec<VolumeLight>> {
    scene
        .lights
        .iter()
        .zip(&pieces.lights)
        .enumerate()
        .map(|(i, (light, snapped))| {
            let range = light.falloff.map(|f| f.range * pieces.grid.scale());
            match snapped {
                SnappedLight::Point(p) => Ok(VolumeLight {
                    source: LightSource::Point(*p),
                    range,
                }),
                SnappedLight::Directional(d) => Ok(VolumeLight::directional(*d)),
                SnappedLight::Area(_) => Err(Error::Field {
                    path: scene.path.clone(),
                    field: format!("light[{i}]"),
                    message: "an area light: the volumes method takes point and directional \
                              lights only (use --method fragments)"
                        .into(),
                }),
            }
        })
        .collect()
}

/// One model per shadow-casting object: its input polygons, each with its
/// snapped outline and its pieces.
fn models(scene: &Scene, pieces: &Pieces) -> Vec<Model> {
    let mut models: Vec<Model> = vec![Model::default(); scene.objects.len()];
    let mut pieces_of: Vec<Vec<usize>> = vec![Vec::new(); pieces.input_polygons];
    for (k, &input) in pieces.input_of.iter().enumerate() {
        pieces_of[input as usize].push(k);
    }
    for (input, (object, polygon)) in scene.input_polygons().enumerate() {
        if !scene.objects[object].casts_shadows || pieces_of[input].is_empty() {
            continue;
        }
        // Snapping succeeded when the pieces were made.
        let Ok((boundary, _)) = pieces.grid.snap_all(&polygon.vertices) else {
            continue;
        };
        models[object].polygons.push(ModelPolygon {
            boundary,
            pieces: pieces_of[input]
                .iter()
                .map(|&k| pieces.polygons[k].clone())
                .collect(),
        });
    }
    models
}

/// For every sample, whether its visible point is in shadow: the depth
/// counts at the eye plus the increments of the shadow polygons crossed.
/// `touched` gives the rectangle of samples (columns, rows; rows of
/// `width` samples) a shadow polygon may cross.
fn count_shadows(
    volumes: &BergeronVolumes,
    eye: [f64; 3],
    visible: &[Option<[f64; 3]>],
    width: usize,
    touched: impl Fn(&ShadowPolygon) -> SampleRect,
) -> Vec<bool> {
    let start = volumes.eye_counts(eye);
    let mut main = vec![start[0]; visible.len()];
    let mut twisted: HashMap<(u32, usize), i32> = HashMap::new();
    for polygon in volumes.shadow_polygons() {
        let (columns, rows) = touched(polygon);
        for k in rows.flat_map(|y| columns.clone().map(move |x| y * width + x)) {
            let Some(p) = visible[k] else { continue };
            let c = polygon.crossing(eye, p);
            if c == 0 {
                continue;
            }
            if polygon.counter == 0 {
                main[k] += c;
            } else {
                *twisted.entry((polygon.counter, k)).or_insert(0) += c;
            }
        }
    }
    (0..visible.len())
        .map(|k| {
            main[k] > 0
                || (1..start.len())
                    .any(|c| start[c] + twisted.get(&(c as u32, k)).copied().unwrap_or(0) > 0)
        })
        .collect()
}

/// A rectangle of samples: columns, rows.
type SampleRect = (std::ops::Range<usize>, std::ops::Range<usize>);

/// The samples whose eye segment may cross `polygon`: those under the
/// projection of its part inside `bounds` (an open polygon's rays cut where
/// they leave the box), with a margin of two samples; all of them if that
/// part comes nearer to the eye than the near plane.
fn touched_samples(
    polygon: &ShadowPolygon,
    bounds: [[f64; 3]; 2],
    grid: &bsp_core::Grid,
    projection: &Projection,
    near: f64,
    width: usize,
    height: usize,
) -> SampleRect {
    let mut corners = polygon.vertices.clone();
    if !polygon.closed {
        // Out along the rays until past the box.
        let reach = distance(bounds[0], bounds[1]);
        let n = corners.len();
        for (ray, base) in [(0, 1), (n - 1, n - 2)] {
            let step = sub(corners[ray], corners[base]);
            let k = reach / dot(step, step).sqrt() + 1.0;
            corners[ray] = [0, 1, 2].map(|i| corners[base][i] + k * step[i]);
        }
    }
    let inside = clip_to_box(&corners, bounds);
    if inside.is_empty() {
        return (0..0, 0..0);
    }
    let n = SAMPLES_PER_SIDE as f64;
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for &v in &inside {
        let view = projection.to_view(grid.grid_to_world(v));
        if view[2] <= near {
            return (0..width, 0..height);
        }
        let [x, y] = projection.view_to_pixel(view);
        for (a, c) in [x * n, y * n].into_iter().enumerate() {
            lo[a] = lo[a].min(c);
            hi[a] = hi[a].max(c);
        }
    }
    let first = |c: f64| (c - 2.0).floor().max(0.0) as usize;
    let last = |c: f64, size: usize| ((c + 2.0).ceil().max(0.0) as usize).min(size);
    let (x0, x1) = (first(lo[0]), last(hi[0], width));
    let (y0, y1) = (first(lo[1]), last(hi[1], height));
    (x0..x1.max(x0), y0..y1.max(y0))
}

/// The part of a convex polygon inside a box (Sutherland-Hodgman against
/// its six faces; floating point, for culling only).
fn clip_to_box(polygon: &[[f64; 3]], bounds: [[f64; 3]; 2]) -> Vec<[f64; 3]> {
    let mut out = polygon.to_vec();
    for axis in 0..3 {
        for (limit, keep_below) in [(bounds[0][axis], false), (bounds[1][axis], true)] {
            let inside = |p: &[f64; 3]| {
                if keep_below {
                    p[axis] <= limit
                } else {
                    p[axis] >= limit
                }
            };
            let input = std::mem::take(&mut out);
            for (i, a) in input.iter().enumerate() {
                let b = &input[(i + 1) % input.len()];
                if inside(a) {
                    out.push(*a);
                }
                if inside(a) != inside(b) {
                    let t = (limit - a[axis]) / (b[axis] - a[axis]);
                    out.push([0, 1, 2].map(|k| a[k] + t * (b[k] - a[k])));
                }
            }
        }
    }
    out
}

/// The box of every piece corner and the eye, grown by a hundredth of its
/// size (grid units).
fn bounds_with(corners: &[Vec<[f64; 3]>], eye: [f64; 3]) -> [[f64; 3]; 2] {
    let mut b = [eye, eye];
    for &p in corners.iter().flatten() {
        for i in 0..3 {
            b[0][i] = b[0][i].min(p[i]);
            b[1][i] = b[1][i].max(p[i]);
        }
    }
    let margin = 0.01 * distance(b[0], b[1]) + 1.0;
    [b[0].map(|c| c - margin), b[1].map(|c| c + margin)]
}

/// The shaded view's values: ambient plus every light that lights the
/// sample, exposed like the fragments' images (the reference is the 90th
/// percentile over the lit samples).
fn shade(
    scene: &Scene,
    pieces: &Pieces,
    samples: &mut Samples,
    visible: &[Option<[f64; 3]>],
    normals: &[[f64; 3]],
    lit: &[u32],
) -> Result<()> {
    let lights = illum_lights(scene, pieces)?;
    let mut values: Vec<[f64; 3]> = vec![[0.0; 3]; visible.len()];
    let mut lit_values = Vec::new();
    for (k, p) in visible.iter().enumerate() {
        let Some(p) = p else { continue };
        let id = samples.id[k] as usize;
        let world = pieces.grid.grid_to_world(*p);
        let sidedness = if pieces.two_sided[id] {
            Sidedness::TwoSided
        } else {
            Sidedness::OneSided
        };
        let mut c = [scene.ambient; 3];
        let mut grey = 0.0;
        for (i, (light, scene_light)) in lights.iter().zip(&scene.lights).enumerate() {
            if lit[k] & (1 << i) == 0 {
                continue;
            }
            let e = match light {
                IllumLight::Point(l) => l.irradiance(world, normals[id], sidedness),
                IllumLight::Directional(l) => l.irradiance(normals[id], sidedness),
                IllumLight::Area(_) => 0.0,
            };
            for (ch, out) in c.iter_mut().enumerate() {
                *out += e * scene_light.color[ch];
            }
            grey += e * scene_light.color.iter().sum::<f64>() / 3.0;
        }
        if grey > 0.0 {
            lit_values.push(grey + scene.ambient);
        }
        values[k] = c;
    }
    lit_values.sort_by(f64::total_cmp);
    let reference = match lit_values.len() {
        0 if scene.ambient > 0.0 => scene.ambient,
        0 => 1.0,
        n => lit_values[(n - 1) * 9 / 10],
    };
    let scale = super::ALBEDO * 1.75 / reference;
    samples.set_values(values.iter().map(|c| c.map(|x| (scale * x) as f32)));
    Ok(())
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}
