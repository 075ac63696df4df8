//! What the `pipeline` target measures of an output mesh: its faces' areas
//! per input polygon, lit per light, and the range rule.

use crate::vector::{cross, dot, sub};

/// Per input polygon (`source`), the total area of its faces and, per
/// light, the area and the perimeter of those that see all of it.
#[derive(Debug, Default)]
pub(super) struct Areas {
    total: Vec<f64>,
    lit: Vec<Vec<f64>>,
    lit_perimeter: Vec<Vec<f64>>,
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
    let n = double_vector_area(p);
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

/// Twice the vector area of the convex polygon `p` (its normal, by the
/// right-hand rule, as long as twice its area).
fn double_vector_area(p: &[[f64; 3]]) -> [f64; 3] {
    (1..p.len() - 1).fold([0.0; 3], |n, i| {
        let c = cross(sub(p[i], p[0]), sub(p[i + 1], p[0]));
        [n[0] + c[0], n[1] + c[1], n[2] + c[2]]
    })
}

/// Checks one output mesh and measures it. `ranges` holds, per light, the
/// position and range of a point light with a range: no lit face may lie
/// wholly beyond it.
pub(super) fn measure(
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
        let p = corners(mesh, face);
        for (i, range) in ranges.iter().enumerate() {
            let Some((light, range)) = *range else {
                continue;
            };
            if face.lit_mask >> i & 1 != 0 && distance_to_polygon(light, &p) > range * (1.0 + 1e-9)
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
            areas.lit_perimeter.resize(s + 1, vec![0.0; lights]);
        }
        let n = double_vector_area(&p);
        let a = 0.5 * dot(n, n).sqrt();
        areas.total[s] += a;
        let perimeter: f64 = (0..p.len())
            .map(|i| {
                let e = sub(p[(i + 1) % p.len()], p[i]);
                dot(e, e).sqrt()
            })
            .sum();
        for (i, lit) in areas.lit[s].iter_mut().enumerate() {
            if face.lit_mask >> i & 1 != 0 {
                *lit += a;
                areas.lit_perimeter[s][i] += perimeter;
            }
        }
    }
    Ok(areas)
}

/// Whether `a` and `b` agree polygon by polygon, in total and lit by each
/// light `compared` marks, to 1e-9 of each polygon's area: the outputs are
/// exact up to the rounding of their coordinates, and every polygon's
/// fragments tile it whatever its cuts.
///
/// A scene off the lattice is snapped, and its output points are moved
/// back onto the input polygons by a map that is bilinear on a convex quad
/// (`umbra`'s input frames): it moves each point by up to about a grid
/// `step`, and bends straight lines by a fraction of that. Two pipelines
/// that cut a lit region alike in the grid (exactly) but put vertices at
/// different places along its sides then write areas that differ by up to
/// the region's perimeter times that bend: a lit area may differ by four
/// grid steps times the larger lit perimeter. (`step` is 0 on the lattice,
/// where the map is the identity.)
pub(super) fn same_areas(
    what: &str,
    a: &Areas,
    b: &Areas,
    compared: &[bool],
    step: f64,
) -> Result<(), String> {
    let n = a.total.len().max(b.total.len());
    let get = |v: &[f64], s: usize| v.get(s).copied().unwrap_or(0.0);
    let per_light = |v: &[Vec<f64>], s: usize, i: usize| v.get(s).map_or(0.0, |l| l[i]);
    for s in 0..n {
        let (ta, tb) = (get(&a.total, s), get(&b.total, s));
        let tolerance = 1e-9 * ta.max(tb) + 1e-12;
        if (ta - tb).abs() > tolerance {
            return Err(format!("{what}: polygon {s} has area {ta} against {tb}"));
        }
        for i in (0..compared.len()).filter(|&i| compared[i]) {
            let (la, lb) = (per_light(&a.lit, s, i), per_light(&b.lit, s, i));
            let perimeter =
                per_light(&a.lit_perimeter, s, i).max(per_light(&b.lit_perimeter, s, i));
            if (la - lb).abs() > tolerance + 4.0 * step * perimeter {
                return Err(format!(
                    "{what}: polygon {s}, light {i}: lit area {la} against {lb}"
                ));
            }
        }
    }
    Ok(())
}
