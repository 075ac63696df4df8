//! An independent occlusion oracle: a point sees a point of the light when
//! the open segment between them crosses no shadow-casting polygon
//! (Shewchuk's orientation predicate on the f64 coordinates, exact for
//! grid points; the query points are sample points, not grid points).

use bsp_core::ConvexPolygon;

fn orient(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let k = |v: [f64; 3]| robust::Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    };
    robust::orient3d(k(a), k(b), k(c), k(d))
}

/// Whether the open segment `pq` passes through convex polygon `poly`
/// (interior or boundary), its ends strictly on either side of its plane.
pub fn segment_crosses(p: [f64; 3], q: [f64; 3], poly: &[[f64; 3]]) -> bool {
    let (a, b, c) = (poly[0], poly[1], poly[2]);
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if sp == 0.0 || sq == 0.0 || (sp > 0.0) == (sq > 0.0) {
        return false;
    }
    // The segment's line passes inside when it turns the same way past
    // every edge.
    let n = poly.len();
    let signs: Vec<f64> = (0..n)
        .map(|i| orient(p, q, poly[i], poly[(i + 1) % n]))
        .collect();
    signs.iter().all(|s| *s >= 0.0) || signs.iter().all(|s| *s <= 0.0)
}

/// Whether `x` (a light point) is hidden from `p` (a point on `own`) by
/// one of `casters` not in `own`'s plane.
pub fn hidden(p: [f64; 3], x: [f64; 3], casters: &[ConvexPolygon], own: &ConvexPolygon) -> bool {
    casters.iter().any(|c| {
        !c.support().is_coincident(own.support())
            && !c.support().is_opposite(own.support())
            && segment_crosses(p, x, &c.vertices_f64())
    })
}

/// Points strictly inside a convex polygon with grid vertices: dyadic
/// combinations of a fan of its vertices.
pub fn interior_samples(poly: &ConvexPolygon, steps: u32) -> Vec<[f64; 3]> {
    let v = poly.vertices_f64();
    let mut out = Vec::new();
    let s = f64::from(steps);
    for i in 1..v.len() - 1 {
        for a in 1..steps {
            for b in 1..(steps - a) {
                let (wa, wb) = (f64::from(a) / s, f64::from(b) / s);
                let w0 = 1.0 - wa - wb;
                out.push(std::array::from_fn(|k| {
                    w0 * v[0][k] + wa * v[i][k] + wb * v[i + 1][k]
                }));
            }
        }
    }
    out
}
