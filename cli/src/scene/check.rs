//! Validation of the scene file: each field checked, each object's
//! polygons read and placed, each light and the camera made, every error
//! naming its file and field.

use std::path::Path;

use super::file::{CameraSpec, LightSpec, LightType, ObjectSpec, ScaleSpec};
use super::{Camera, Falloff, InputPolygon, Light, LightKind, Object};
use crate::error::{Error, Result};
use crate::obj::ObjMesh;
use crate::transform::Transform;
use crate::vec3::{by_largest, cross, dot, norm, sub};

pub(super) struct Checker<'a> {
    pub(super) path: &'a Path,
}

impl Checker<'_> {
    pub(super) fn field(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::Field {
            path: self.path.to_path_buf(),
            field: field.into(),
            message: message.into(),
        }
    }

    pub(super) fn finite(&self, field: &str, values: &[f64]) -> Result<()> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(v) => Err(self.field(field, format!("{v} is not a finite number"))),
            None => Ok(()),
        }
    }

    pub(super) fn object(
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

    pub(super) fn light(&self, i: usize, spec: LightSpec) -> Result<Light> {
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

    pub(super) fn camera(&self, c: CameraSpec) -> Result<Camera> {
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
