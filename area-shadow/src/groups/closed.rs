//! Closed surfaces (every directed edge matched by its reverse once) as
//! the boundary of a body: which way they face, which of their vertices
//! stand out of their faces' planes, and the volume they enclose.

use super::hull::convex_hull;
use super::solid::distinct_planes;
use super::{MAX_SOLID_WORK, edge_set};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{GridPoint, Plane};
use std::borrow::Cow;

/// A closed surface (every directed edge matched by its reverse once)
/// seen as the boundary of a body.
pub(super) struct ClosedFaces {
    /// Its vertices, ascending.
    pub(super) vertices: Vec<GridPoint>,
    /// Each piece's plane, turned to have the body behind it.
    pub(super) faces: Vec<Plane>,
    /// Per vertex: whether it stands in front of some face (the surface
    /// is not convex there).
    pub(super) out: Vec<bool>,
    /// Whether the pieces face into the body.
    pub(super) faces_in: bool,
}

impl ClosedFaces {
    /// The closed surface of `outlines` (with support planes `supports`,
    /// all facing out or all in: taken to face the way fewer vertices
    /// stand out of); `None` when it is not closed, lies in one plane, or
    /// is too big to check ([`MAX_SOLID_WORK`]).
    pub(super) fn of(outlines: &[&[GridPoint]], supports: &[Plane]) -> Option<Self> {
        let edges = edge_set(outlines)?;
        if edges.keys().any(|&(a, b)| !edges.contains_key(&(b, a))) {
            return None;
        }
        let mut vertices: Vec<GridPoint> =
            outlines.iter().flat_map(|o| o.iter().copied()).collect();
        vertices.sort_unstable();
        vertices.dedup();
        if supports.len().saturating_mul(vertices.len()) > MAX_SOLID_WORK {
            return None;
        }
        // Which vertices stand in front of some face (facing out), and
        // which behind some face (facing in).
        let (mut ahead, mut behind) = (vec![false; vertices.len()], vec![false; vertices.len()]);
        for plane in supports {
            for (k, &p) in vertices.iter().enumerate() {
                match side_of_point(plane, p) {
                    Side::Front => ahead[k] = true,
                    Side::Back => behind[k] = true,
                    Side::On => {}
                }
            }
        }
        // A closed surface in one plane is a two-sided sheet, not a body.
        if !ahead.contains(&true) && !behind.contains(&true) {
            return None;
        }
        let count = |flags: &[bool]| flags.iter().filter(|f| **f).count();
        let faces_in = count(&ahead) > count(&behind);
        let (faces, out) = if faces_in {
            (supports.iter().map(Plane::flipped).collect(), behind)
        } else {
            (supports.to_vec(), ahead)
        };
        Some(Self {
            vertices,
            faces,
            out,
            faces_in,
        })
    }

    /// The faces' planes turned to have the body behind them if the
    /// pieces (with `supports`) face in when `faces_in`.
    pub(super) fn faces_turned(&self, faces_in: bool, supports: &[Plane]) -> Cow<'_, [Plane]> {
        if faces_in == self.faces_in {
            Cow::Borrowed(&self.faces)
        } else if faces_in {
            Cow::Owned(supports.iter().map(Plane::flipped).collect())
        } else {
            Cow::Owned(supports.to_vec())
        }
    }

    /// The planes of the convex hull of the vertices, facing out.
    pub(super) fn hull(&self) -> Option<Vec<Plane>> {
        let hull = convex_hull(&self.vertices)?;
        Some(distinct_planes(
            hull.into_iter().map(|(_, plane)| plane).collect(),
        ))
    }
}

/// The volume a closed surface of convex `outlines` encloses, positive
/// when they turn counter-clockwise seen from outside (floating point:
/// only its sign is used, where it is far from zero).
pub(super) fn signed_volume(outlines: &[&[GridPoint]]) -> f64 {
    let Some(origin) = outlines.first().and_then(|o| o.first()) else {
        return 0.0;
    };
    let o = origin.to_f64();
    let at = |p: &GridPoint| -> [f64; 3] {
        let p = p.to_f64();
        [p[0] - o[0], p[1] - o[1], p[2] - o[2]]
    };
    let det = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
    };
    outlines
        .iter()
        .map(|outline| {
            let first = at(&outline[0]);
            (1..outline.len().saturating_sub(1))
                .map(|i| det(first, at(&outline[i]), at(&outline[i + 1])))
                .sum::<f64>()
        })
        .sum::<f64>()
        / 6.0
}
