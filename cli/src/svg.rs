//! `umbra svg`: a plan view of one input polygon's fragments, the picture
//! that finds geometry bugs fastest.

use std::fmt::Write as _;
use std::path::Path;

use crate::error::{Error, Result};
use crate::mesh::OutputMesh;
use crate::scene::Scene;

/// Side of the drawing's longer edge, in SVG units.
const SIZE: f64 = 600.0;

/// Fill of a fragment by its masks over `lights` lights: lit if it sees all
/// of some light, umbra if it sees none of any, penumbra otherwise.
fn fill(lit_mask: u32, umbra_mask: u32, lights: usize) -> &'static str {
    let all = if lights >= 32 {
        u32::MAX
    } else {
        (1u32 << lights) - 1
    };
    if lit_mask != 0 {
        "#ffe9a0"
    } else if umbra_mask & all == all {
        "#555555"
    } else {
        "#cccccc"
    }
}

/// The SVG of the fragments of input polygon `polygon` in `mesh` (the
/// output of `umbra shadow` for `scene`), seen from the polygon's front,
/// in its own plane. Each fragment is filled by its class and outlined;
/// its masks are in its `<title>`.
pub fn fragments_svg(scene: &Scene, mesh: &OutputMesh, polygon: u32) -> Result<String> {
    let Some((_, input)) = scene.input_polygons().nth(polygon as usize) else {
        return Err(Error::Field {
            path: scene.path.clone(),
            field: "polygon".into(),
            message: format!(
                "the scene has {} input polygons; there is no polygon {polygon}",
                scene.polygon_count()
            ),
        });
    };
    // A frame in the polygon's plane: u along its first edge, w = n x u.
    let v = &input.vertices;
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |a: [f64; 3]| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let mut n = [0.0; 3];
    for k in 1..v.len().saturating_sub(1) {
        let c = cross(sub(v[k], v[0]), sub(v[k + 1], v[0]));
        n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
    }
    let n = unit(n);
    let u = unit(sub(v[1], v[0]));
    let w = cross(n, u);
    let plan = |p: [f64; 3]| {
        let d = sub(p, v[0]);
        (
            d[0] * u[0] + d[1] * u[1] + d[2] * u[2],
            d[0] * w[0] + d[1] * w[1] + d[2] * w[2],
        )
    };
    let faces: Vec<_> = mesh.faces.iter().filter(|f| f.source == polygon).collect();
    let points: Vec<(f64, f64)> = faces
        .iter()
        .flat_map(|f| {
            f.vertices
                .iter()
                .map(|&i| plan(mesh.vertices[i as usize].0))
        })
        .collect();
    let (mut lo, mut hi) = (
        (f64::INFINITY, f64::INFINITY),
        (f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for &(x, y) in &points {
        lo = (lo.0.min(x), lo.1.min(y));
        hi = (hi.0.max(x), hi.1.max(y));
    }
    let span = (hi.0 - lo.0).max(hi.1 - lo.1).max(f64::MIN_POSITIVE);
    let mut scale = SIZE / span;
    if points.is_empty() {
        // No fragment (a polygon of zero area, dropped): an empty picture
        // of the margins alone.
        (lo, hi, scale) = ((0.0, 0.0), (0.0, 0.0), 1.0);
    }
    let margin = 10.0;
    // SVG's y runs down: flip so the plan is seen from the polygon's front.
    let to_svg = |(x, y): (f64, f64)| ((x - lo.0) * scale + margin, (hi.1 - y) * scale + margin);
    let (width, height) = (
        (hi.0 - lo.0) * scale + 2.0 * margin,
        (hi.1 - lo.1) * scale + 2.0 * margin,
    );
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.1}" height="{height:.1}" viewBox="0 0 {width:.1} {height:.1}">"#
    );
    let _ = writeln!(
        svg,
        "<title>input polygon {polygon}: {} fragments</title>",
        faces.len()
    );
    for f in &faces {
        let pts: Vec<String> = f
            .vertices
            .iter()
            .map(|&i| {
                let (x, y) = to_svg(plan(mesh.vertices[i as usize].0));
                format!("{x:.3},{y:.3}")
            })
            .collect();
        let _ = writeln!(
            svg,
            r#"<polygon points="{}" fill="{}" stroke="black" stroke-width="0.5"><title>lit_mask {} umbra_mask {}</title></polygon>"#,
            pts.join(" "),
            fill(f.lit_mask, f.umbra_mask, scene.lights.len()),
            f.lit_mask,
            f.umbra_mask
        );
    }
    svg.push_str("</svg>\n");
    Ok(svg)
}

/// Writes an SVG (atomically).
pub fn save_svg(path: &Path, svg: &str) -> Result<()> {
    crate::atomic::write_atomic(path, |w| w.write_all(svg.as_bytes()))
}
