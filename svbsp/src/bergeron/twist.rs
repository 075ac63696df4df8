//! Non-planar polygons that are L-twisted: seen from the light, two of
//! their edges cross, so the polygon's outline folds over itself and no
//! facing (towards or away from the light) describes it.

use bsp_core::GridPoint;
use bsp_core::predicates::{Side, orient3d_f64};

use super::apex::{Apex, f};
use crate::LightSource;

/// Whether the polygon with corners `boundary` (grid points, in order) is
/// not planar and is L-twisted for `light`: two edges that share no corner
/// cross in the projection from the light (a central projection for a
/// point light, a parallel one for a directional light). Exact.
///
/// Two edges cross when each one's endpoints lie strictly on either side
/// of the plane through the light and the other edge. (For a point light
/// this also accepts edges whose projections cross on opposite sides of
/// the light, which needs a polygon wrapped around it.)
pub fn is_l_twisted(boundary: &[GridPoint], light: &LightSource) -> bool {
    if boundary.len() < 4 || is_planar(boundary) {
        return false;
    }
    let apex = Apex::of(light);
    let v: Vec<[f64; 3]> = boundary.iter().map(|&p| f(p)).collect();
    let n = v.len();
    let straddles = |a: [f64; 3], b: [f64; 3], p: [f64; 3], q: [f64; 3]| {
        let l = apex.beside(a);
        let (sp, sq) = (orient3d_f64(l, a, b, p), orient3d_f64(l, a, b, q));
        sp != Side::On && sq != Side::On && sp != sq
    };
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        // Edges i and j share no corner: j from i + 2 to n - 1, and not the
        // edge before i.
        for j in i + 2..n {
            if (j + 1) % n == i {
                continue;
            }
            let (c, d) = (v[j], v[(j + 1) % n]);
            if straddles(a, b, c, d) && straddles(c, d, a, b) {
                return true;
            }
        }
    }
    false
}

/// Whether every corner lies in one plane (exact; all collinear counts as
/// planar).
fn is_planar(boundary: &[GridPoint]) -> bool {
    let v: Vec<[f64; 3]> = boundary.iter().map(|&p| f(p)).collect();
    let n = v.len();
    let base = (1..n)
        .flat_map(|i| (i + 1..n).map(move |k| (i, k)))
        .find(|&(i, k)| !collinear([v[0], v[i], v[k]]));
    match base {
        None => true,
        Some((i, k)) => v
            .iter()
            .all(|&p| orient3d_f64(v[0], v[i], v[k], p) == Side::On),
    }
}

/// Whether three grid points are collinear: their cross product is zero
/// (coordinates below `2^25`, so every product is exact in `f64`).
fn collinear(t: [[f64; 3]; 3]) -> bool {
    let u = [0, 1, 2].map(|i| t[1][i] - t[0][i]);
    let w = [0, 1, 2].map(|i| t[2][i] - t[0][i]);
    u[1] * w[2] - u[2] * w[1] == 0.0
        && u[2] * w[0] - u[0] * w[2] == 0.0
        && u[0] * w[1] - u[1] * w[0] == 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    #[test]
    fn a_bent_quad_is_twisted_only_where_its_edges_cross() {
        // A quad whose corners alternate in height: planar seen from above
        // it is a square (not twisted); seen from the side its edges cross.
        let quad = [g(0, 0, 0), g(10, 4, 0), g(10, 0, 10), g(0, 4, 10)];
        assert!(!is_l_twisted(&quad, &LightSource::Point(g(5, 50, 5))));
        assert!(!is_l_twisted(&quad, &LightSource::Directional([0, -1, 0])));
        // From the side along x, corners 0 and 1 swap heights against 2
        // and 3: edges 0-1 and 2-3 cross.
        assert!(is_l_twisted(&quad, &LightSource::Directional([0, 0, 1])));
        assert!(is_l_twisted(&quad, &LightSource::Point(g(5, 2, -40))));
        // A planar quad never is.
        let flat = [g(0, 0, 0), g(10, 0, 0), g(10, 0, 10), g(0, 0, 10)];
        assert!(!is_l_twisted(&flat, &LightSource::Directional([0, 0, 1])));
    }
}
