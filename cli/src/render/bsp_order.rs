//! Back-to-front traversal of the scene BSP from the eye, as the papers
//! render: the painter's algorithm with an order that is right by
//! construction, instead of a z-buffer.
//!
//! The scene's convex pieces are put in a [`SceneBsp`] and visited back to
//! front from the eye. Every part of a piece that the tree made is drawn
//! with whatever lies in it: the fragments of the piece's input polygon
//! (clipped to the part, in floating point: it only draws) for
//! `--method fragments`, or the part itself for `--method volumes`. A later
//! part covers an earlier one wherever both show, with no depth test. The
//! result equals the z-buffer's wherever polygons do not interpenetrate.

use bsp_core::{BuildOptions, ConvexPolygon, Grid, GridPoint, SceneBsp, Viewpoint};

use crate::decompose::Pieces;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::vec3::{cross, dot, sub};

/// The scene's pieces as BSP parts in back-to-front order from `eye`
/// (world units): each part with the index of the piece it came from.
///
/// The eye is rounded to the nearest grid point for the order (half a grid
/// cell at most: only polygons seen edge-on within that distance could
/// swap, and they cover no sample).
///
/// # Errors
///
/// If the eye lies so far from the scene that its grid coordinates do not
/// fit 32 bits (over a hundred times the scene's size).
pub(crate) fn back_to_front(
    scene: &Scene,
    pieces: &Pieces,
    eye: [f64; 3],
) -> Result<Vec<(usize, ConvexPolygon)>> {
    let view = Viewpoint::Point(eye_point(scene, &pieces.grid, eye)?);
    let bsp = SceneBsp::build(pieces.polygons.clone(), &BuildOptions::default());
    Ok(bsp
        .back_to_front(view)
        .map(|(_, part)| (part.source() as usize, part.clone()))
        .collect())
}

fn eye_point(scene: &Scene, grid: &Grid, eye: [f64; 3]) -> Result<GridPoint> {
    let g = grid.world_to_grid(eye).map(f64::round);
    let fits = |c: f64| c.abs() < f64::from(i32::MAX);
    if !g.iter().all(|&c| fits(c)) {
        return Err(Error::Field {
            path: scene.path.clone(),
            field: "camera.eye".into(),
            message: "too far from the scene for --order bsp (use --order zbuffer)".into(),
        });
    }
    Ok(GridPoint {
        x: g[0] as i32,
        y: g[1] as i32,
        z: g[2] as i32,
    })
}

/// The part of a convex polygon (points with values) inside a coplanar
/// convex polygon `region` (Sutherland-Hodgman against the planes through
/// each edge of `region` across its plane). Values are affine on the
/// polygon, so they are interpolated linearly.
pub(crate) fn clip_to_region(
    polygon: &[([f64; 3], [f64; 3])],
    region: &[[f64; 3]],
) -> Vec<([f64; 3], [f64; 3])> {
    let m = region.len();
    if m < 3 {
        return Vec::new();
    }
    // Newell's normal of the region.
    let mut normal = [0.0; 3];
    for (i, a) in region.iter().enumerate() {
        let b = region[(i + 1) % m];
        normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
        normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
        normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let mut out = polygon.to_vec();
    for i in 0..m {
        let (a, b) = (region[i], region[(i + 1) % m]);
        // Inside is to the left of a -> b seen from the normal's side.
        let inward = cross(normal, sub(b, a));
        let side = |p: [f64; 3]| dot(inward, sub(p, a));
        let input = std::mem::take(&mut out);
        for (k, &(p, vp)) in input.iter().enumerate() {
            let (q, vq) = input[(k + 1) % input.len()];
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push((p, vp));
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                let lerp = |x: [f64; 3], y: [f64; 3]| [0, 1, 2].map(|c| x[c] + t * (y[c] - x[c]));
                out.push((lerp(p, q), lerp(vp, vq)));
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_to_a_region_keeps_the_overlap_and_its_values() {
        // A 4 x 2 rectangle in z = 0, value = x, against the unit square
        // [1, 2] x [0, 1] (either orientation).
        let rect: Vec<([f64; 3], [f64; 3])> = [[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]]
            .iter()
            .map(|&[x, y]| ([x, y, 0.0], [x; 3]))
            .collect();
        let square = [
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        for region in [square.to_vec(), square.iter().rev().copied().collect()] {
            let clipped = clip_to_region(&rect, &region);
            assert_eq!(clipped.len(), 4);
            for (p, v) in &clipped {
                assert!((1.0..=2.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1]));
                assert!((v[0] - p[0]).abs() < 1e-12);
            }
        }
        // Disjoint: nothing.
        let far = [[9.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 1.0, 0.0]];
        assert!(clip_to_region(&rect, &far).is_empty());
    }
}
