//! An independent oracle: a point is lit iff the segment to the light
//! crosses no shadow-casting polygon (orientation tests exact on f64 input,
//! Shewchuk's predicates via `robust`).

use bsp_core::{ConvexPolygon, GridPoint};
use svbsp::LightSource;

pub fn orient(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let p = |v: [f64; 3]| robust::Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// Whether the segment `pq` crosses triangle `abc` (closed: touching an
/// edge counts, so that a sight line through the shared edge of two
/// triangles of a mesh is blocked).
fn segment_hits_triangle(p: [f64; 3], q: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    let sp = orient(a, b, c, p);
    let sq = orient(a, b, c, q);
    if sp == 0.0 || sq == 0.0 || (sp > 0.0) == (sq > 0.0) {
        return false;
    }
    let s1 = orient(p, q, a, b);
    let s2 = orient(p, q, b, c);
    let s3 = orient(p, q, c, a);
    (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0)
}

/// Whether `p` lies within rounding of triangle `abc` (within `1e-9` of
/// its plane, inside or on its edges).
fn touches_triangle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    let sub = |u: [f64; 3], v: [f64; 3]| [u[0] - v[0], u[1] - v[1], u[2] - v[2]];
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let n = cross(sub(b, a), sub(c, a));
    let len = dot(n, n).sqrt();
    if len == 0.0 || (dot(n, sub(p, a)) / len).abs() > 1e-9 {
        return false;
    }
    [(a, b), (b, c), (c, a)].iter().all(|&(u, v)| {
        let e = sub(v, u);
        dot(cross(e, sub(p, u)), n) / (len * dot(e, e).sqrt()) >= -1e-9
    })
}

/// Whether `point` sees the light past every casting polygon except those
/// in its own plane (they meet the sight line at its start at most; the
/// rounded sample may sit a hair behind them). `None` if the point lies on
/// another casting polygon (polygons may pierce each other): its sight line
/// starts on it, and the sample's rounding, not the scene, would decide.
pub fn sees_light(
    point: [f64; 3],
    light: LightSource,
    casters: &[Caster],
    own: &ConvexPolygon,
) -> Option<bool> {
    let on_another = casters.iter().any(|Caster { polygon, outline }| {
        !polygon.support().is_coincident(own.support())
            && (1..outline.len() - 1)
                .any(|i| touches_triangle(point, outline[0], outline[i], outline[i + 1]))
    });
    if on_another {
        return None;
    }
    let target = match light {
        LightSource::Point(p) => p.to_f64(),
        LightSource::Directional(d) => [
            point[0] - f64::from(d[0]) * 1e6,
            point[1] - f64::from(d[1]) * 1e6,
            point[2] - f64::from(d[2]) * 1e6,
        ],
    };
    Some(!casters.iter().any(|Caster { polygon, outline }| {
        !polygon.support().is_coincident(own.support())
            && (1..outline.len() - 1).any(|i| {
                segment_hits_triangle(point, target, outline[0], outline[i], outline[i + 1])
            })
    }))
}

/// Interior sample points of a fragment: its centroid and each vertex
/// moved a fifth of the way to it.
pub fn samples(polygon: &ConvexPolygon) -> Vec<[f64; 3]> {
    let c = polygon.centroid();
    let mut out = vec![c];
    for v in polygon.vertices_f64() {
        out.push([
            0.8 * v[0] + 0.2 * c[0],
            0.8 * v[1] + 0.2 * c[1],
            0.8 * v[2] + 0.2 * c[2],
        ]);
    }
    out
}

/// A shadow-casting input polygon with its exact (grid) outline.
pub struct Caster {
    pub polygon: ConvexPolygon,
    pub outline: Vec<[f64; 3]>,
}

impl Caster {
    pub fn new(p: &ConvexPolygon) -> Self {
        let outline = (0..p.len())
            .map(|i| p.vertex_grid_point(i).map(GridPoint::to_f64).unwrap())
            .collect();
        Self {
            polygon: p.clone(),
            outline,
        }
    }
}
