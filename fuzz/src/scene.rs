//! What the scene targets share: the floor of `area` and `shadows`, the
//! exact partition check and the sample points of a fragment, and exact
//! orientation and segment-against-triangle occlusion.

use bsp_core::{ConvexPolygon, GridPoint};

pub(crate) fn gp(p: [i64; 3]) -> GridPoint {
    GridPoint::new(p[0], p[1], p[2]).expect("small coordinates")
}

/// The floor at y = 0, 40 units wide, facing up, and the triangles that
/// are not degenerate, in order: the scene's pieces.
pub(crate) fn floor_and(triangles: &[[[i64; 3]; 3]]) -> Vec<ConvexPolygon> {
    let floor = ConvexPolygon::from_grid_points(
        &[
            gp([-20, 0, 20]),
            gp([20, 0, 20]),
            gp([20, 0, -20]),
            gp([-20, 0, -20]),
        ],
        0,
    )
    .expect("the floor");
    let mut pieces = vec![floor];
    for t in triangles {
        if let Ok(p) = ConvexPolygon::from_grid_points(&t.map(gp), 0) {
            pieces.push(p);
        }
    }
    pieces
}

/// That the fragments (with their pieces' indices as sources) partition
/// every piece: valid, in their piece's plane, areas adding up.
pub(crate) fn check_partition<'a>(
    pieces: &[ConvexPolygon],
    fragments: impl IntoIterator<Item = &'a ConvexPolygon>,
) -> Result<(), String> {
    let mut area = vec![0.0; pieces.len()];
    for f in fragments {
        f.check_invariants()?;
        let k = f.source() as usize;
        if f.support() != pieces[k].support() {
            return Err(format!("a fragment of piece {k} left its plane"));
        }
        area[k] += f.area();
    }
    for (k, p) in pieces.iter().enumerate() {
        if (area[k] - p.area()).abs() > 1e-9 * p.area() {
            return Err(format!(
                "piece {k}: fragments cover {} of {}",
                area[k],
                p.area()
            ));
        }
    }
    Ok(())
}

/// Points strictly inside a fragment: its centroid, and each vertex moved
/// a fifth of the way to it.
pub(crate) fn samples(f: &ConvexPolygon) -> Vec<[f64; 3]> {
    let centroid = f.centroid();
    let mut samples = vec![centroid];
    samples.extend(
        f.vertices_f64()
            .iter()
            .map(|v| [0, 1, 2].map(|i| 0.8 * v[i] + 0.2 * centroid[i])),
    );
    samples
}

/// Shewchuk's exact orientation of `d` against the plane through `a`, `b`,
/// `c`.
pub(crate) fn orient(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let p = |v: [f64; 3]| robust::Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// Whether the open segment `pq` crosses the closed triangle `t`.
pub(crate) fn crosses(p: [f64; 3], q: [f64; 3], t: &[[f64; 3]; 3]) -> bool {
    let (sp, sq) = (orient(t[0], t[1], t[2], p), orient(t[0], t[1], t[2], q));
    if sp == 0.0 || sq == 0.0 || (sp > 0.0) == (sq > 0.0) {
        return false;
    }
    let s = [
        orient(p, q, t[0], t[1]),
        orient(p, q, t[1], t[2]),
        orient(p, q, t[2], t[0]),
    ];
    s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)
}

/// Whether `p` lies within rounding of the closed triangle `t` (the
/// samples' coordinates are rounded): within `1e-9` of its plane, inside
/// or on its edges.
pub(crate) fn touches(p: [f64; 3], t: &[[f64; 3]; 3]) -> bool {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let len = dot(n, n).sqrt();
    if len == 0.0 || (dot(n, sub(p, t[0])) / len).abs() > 1e-9 {
        return false;
    }
    // Inside or within 1e-9 of an edge, seen along the normal.
    (0..3).all(|i| {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        let e = sub(b, a);
        dot(cross(e, sub(p, a)), n) / (len * dot(e, e).sqrt()) >= -1e-9
    })
}
