//! An independent oracle: whether a point sees a point of the light is
//! whether the segment between them crosses a shadow-casting polygon
//! (orientation exact on f64 input, Shewchuk's predicates via `robust`).

use bsp_core::{ConvexPolygon, GridPoint};

pub fn gp(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).unwrap()
}

fn orient(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let p = |v: [f64; 3]| robust::Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// Whether the open segment `pq` crosses triangle `abc` through its
/// interior or an edge.
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

/// A shadow-casting polygon with its exact (grid) outline.
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

/// Whether the segment from `point` (on polygon `own`) to `light_point` is
/// blocked by a caster not in `own`'s plane.
pub fn blocked(
    point: [f64; 3],
    light_point: [f64; 3],
    casters: &[Caster],
    own: &ConvexPolygon,
) -> bool {
    casters.iter().any(|Caster { polygon, outline }| {
        !polygon.support().is_coincident(own.support())
            && (1..outline.len() - 1).any(|i| {
                segment_hits_triangle(point, light_point, outline[0], outline[i], outline[i + 1])
            })
    })
}

/// Points strictly inside a convex light with grid vertices: dyadic
/// combinations of its vertices (exact in f64) spread over it. Boundary
/// points are left out: a light vertex or edge may lie in an occluder's
/// plane and be seen past it along a set of measure zero.
pub fn light_samples(light: &ConvexPolygon) -> Vec<[f64; 3]> {
    let v: Vec<[f64; 3]> = (0..light.len())
        .map(|k| light.vertex_grid_point(k).unwrap().to_f64())
        .collect();
    let mut out = Vec::new();
    let c0 = v[0];
    for i in 1..v.len() - 1 {
        let (a, b) = (v[i], v[i + 1]);
        for s in 1..16 {
            for t in 1..(16 - s) {
                let (s, t) = (f64::from(s) / 16.0, f64::from(t) / 16.0);
                let w0 = 1.0 - s - t;
                out.push([
                    w0 * c0[0] + s * a[0] + t * b[0],
                    w0 * c0[1] + s * a[1] + t * b[1],
                    w0 * c0[2] + s * a[2] + t * b[2],
                ]);
            }
        }
    }
    out
}

/// The points of a light the oracle looks at: its corners and
/// [`light_samples`].
pub fn light_targets(light: &area_shadow::AreaSource) -> Vec<[f64; 3]> {
    light
        .vertices()
        .map(GridPoint::to_f64)
        .chain(light_samples(light.polygon()))
        .collect()
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
