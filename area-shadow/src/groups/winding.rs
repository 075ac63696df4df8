//! The winding number of a grid point about a closed surface, exactly.
//!
//! Along a ray from the point, each face the ray crosses changes how
//! many times the surface wraps the points it passes: leaving through a
//! face (from behind its outward plane to in front) takes one off, so the
//! point's number is the count of faces the ray leaves through less the
//! count it enters through (it is 0 far away). A ray that meets an edge
//! or a corner of a face is tried again along another direction; every
//! test is an exact predicate on grid points.

use bsp_core::predicates::{Side, orient3d_f64, side_of_direction, side_of_point};
use bsp_core::{GridPoint, Plane};

/// Directions tried in turn until one meets no edge or corner: their
/// components share no factor and no short integer relation, so a ray
/// along one through a grid point rarely meets another grid point's edge.
const DIRECTIONS: [[i32; 3]; 6] = [
    [1_000_003, 700_001, 300_007],
    [-299_993, 1_000_033, 600_011],
    [400_009, -500_029, 1_000_081],
    [-1_000_099, -200_063, 800_077],
    [700_121, 900_007, -1_000_117],
    [-600_043, 300_089, -900_091],
];

/// The winding number of `point` about the closed surface of convex
/// `outlines` (grid points, counter-clockwise seen from the front of
/// `faces`: each outline's plane facing out): at least 1 inside, 0
/// outside. `None` when `point` lies in a face's plane (it may be on the
/// surface) or every direction tried meets an edge or a corner.
pub fn winding_number(point: GridPoint, outlines: &[&[GridPoint]], faces: &[Plane]) -> Option<i64> {
    let sides: Vec<Side> = faces.iter().map(|f| side_of_point(f, point)).collect();
    if sides.contains(&Side::On) {
        return None;
    }
    let from = point.to_f64();
    DIRECTIONS.iter().find_map(|&d| {
        let to: [f64; 3] = std::array::from_fn(|a| from[a] + f64::from(d[a]));
        let mut number = 0;
        for ((outline, face), &side) in outlines.iter().zip(faces).zip(&sides) {
            // The ray meets the plane ahead when it heads to the side the
            // point is not on.
            let heading = side_of_direction(face, d);
            if heading == Side::On || heading == side {
                continue;
            }
            match line_through(outline, from, to)? {
                true if side == Side::Back => number += 1,
                true => number -= 1,
                false => {}
            }
        }
        Some(number)
    })
}

/// Whether the line through `from` and `to` (crossing the outline's
/// plane) passes through the convex outline's interior; `None` when it
/// meets an edge or a corner. The line passes inside exactly when it
/// turns the same way about every edge.
fn line_through(outline: &[GridPoint], from: [f64; 3], to: [f64; 3]) -> Option<bool> {
    let n = outline.len();
    let mut turn = Side::On;
    for i in 0..n {
        let (a, b) = (outline[i].to_f64(), outline[(i + 1) % n].to_f64());
        match orient3d_f64(from, to, a, b) {
            // In one plane with the edge: it may touch it.
            Side::On => return None,
            s if turn == Side::On => turn = s,
            s if s != turn => return Some(false),
            _ => {}
        }
    }
    Some(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint::new(x, y, z).expect("grid point")
    }

    /// A box from (0,0,0) to (s,s,s): six quads facing out.
    fn cube(s: i64) -> Vec<Vec<GridPoint>> {
        vec![
            vec![p(0, 0, 0), p(0, s, 0), p(s, s, 0), p(s, 0, 0)],
            vec![p(0, 0, s), p(s, 0, s), p(s, s, s), p(0, s, s)],
            vec![p(0, 0, 0), p(s, 0, 0), p(s, 0, s), p(0, 0, s)],
            vec![p(0, s, 0), p(0, s, s), p(s, s, s), p(s, s, 0)],
            vec![p(0, 0, 0), p(0, 0, s), p(0, s, s), p(0, s, 0)],
            vec![p(s, 0, 0), p(s, s, 0), p(s, s, s), p(s, 0, s)],
        ]
    }

    fn planes(outlines: &[Vec<GridPoint>]) -> Vec<Plane> {
        outlines
            .iter()
            .map(|o| Plane::through(o[0], o[1], o[2]).expect("a plane"))
            .collect()
    }

    #[test]
    fn a_box_winds_once_about_its_inside_and_not_about_its_outside() {
        let faces = cube(10);
        let outlines: Vec<&[GridPoint]> = faces.iter().map(Vec::as_slice).collect();
        let planes = planes(&faces);
        assert_eq!(winding_number(p(5, 5, 5), &outlines, &planes), Some(1));
        assert_eq!(winding_number(p(1, 9, 3), &outlines, &planes), Some(1));
        assert_eq!(winding_number(p(15, 5, 5), &outlines, &planes), Some(0));
        assert_eq!(winding_number(p(-3, -4, 20), &outlines, &planes), Some(0));
        // On a face's plane: not decided.
        assert_eq!(winding_number(p(5, 5, 10), &outlines, &planes), None);
        assert_eq!(winding_number(p(20, 5, 10), &outlines, &planes), None);
        // Turned inside out, the surface winds -1 about its inside.
        let turned: Vec<Vec<GridPoint>> = faces
            .iter()
            .map(|o| o.iter().rev().copied().collect())
            .collect();
        let outlines: Vec<&[GridPoint]> = turned.iter().map(Vec::as_slice).collect();
        assert_eq!(
            winding_number(p(5, 5, 5), &outlines, &self::planes(&turned)),
            Some(-1)
        );
    }

    #[test]
    fn two_nested_boxes_wind_twice() {
        let mut faces = cube(30);
        faces.extend(cube(10).into_iter().map(|o| {
            o.into_iter()
                .map(|q| {
                    let [x, y, z] = q.to_i64();
                    p(x + 10, y + 10, z + 10)
                })
                .collect()
        }));
        let outlines: Vec<&[GridPoint]> = faces.iter().map(Vec::as_slice).collect();
        let planes = planes(&faces);
        assert_eq!(winding_number(p(15, 15, 15), &outlines, &planes), Some(2));
        assert_eq!(winding_number(p(5, 15, 25), &outlines, &planes), Some(1));
    }
}
