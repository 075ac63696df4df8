//! Whether a plane crosses the part of a convex polygon inside other
//! planes, decided on the plane's chord through the polygon, without
//! clipping.
//!
//! A plane that cuts a convex polygon `P` meets it in a chord, an open
//! segment of the line `L` (the plane on the polygon's support) inside `P`.
//! The part of `P` behind planes `W_1..W_k` has points strictly on both
//! sides of the plane exactly when the open chord meets the open region
//! behind every `W_i`. Along the chord, each `W_i` keeps all of it, none of
//! it, a prefix or a suffix (its side is affine along the line), so the
//! answer is a few exact sides of the chord's ends and of the points where
//! the `W_i` cross `L`: no polygon is made.

use crate::plane::Plane;
use crate::polygon::{ConvexPolygon, PolygonSide};
use crate::predicates::{PointFilter, Side, side_of_implicit};

/// One end of a chord: a polygon vertex on the plane, or where the plane
/// crosses an edge.
enum End<'a> {
    Vertex(usize),
    Crossing {
        filter: PointFilter,
        planes: [&'a Plane; 3],
    },
}

/// What a bounding plane keeps of the open chord (ends in chord order).
enum Keeps<'a> {
    All,
    Nothing,
    /// From the first end up to where the plane crosses `L`.
    Prefix(&'a Plane),
    /// From where the plane crosses `L` to the second end.
    Suffix(&'a Plane),
}

impl ConvexPolygon {
    /// Whether `plane` has points of the polygon's part behind every plane
    /// of `bounds` strictly on both sides, exact; the same answer as
    /// clipping the polygon by `bounds` (keeping what lies behind) and
    /// classifying the part (`Both`), without building it.
    pub fn crosses_inside(&self, plane: &Plane, bounds: &[Plane]) -> bool {
        if self.classify(plane) != PolygonSide::Both {
            return false;
        }
        // The open chord lies inside the polygon: a bound with every vertex
        // on or behind it (one strictly) keeps all of it, one with none
        // strictly behind keeps nothing. Only the bounds that cut the
        // polygon need the chord's ends, the costly part.
        let mut cutting: smallvec::SmallVec<[&Plane; 4]> = smallvec::SmallVec::new();
        for bound in bounds {
            match self.classify(bound) {
                PolygonSide::Back => {}
                PolygonSide::Both => cutting.push(bound),
                PolygonSide::Front | PolygonSide::Coplanar(_) => return false,
            }
        }
        if cutting.is_empty() {
            return true;
        }
        let Some([first, second]) = self.chord_ends(plane) else {
            return false;
        };
        let side = |end: &End, q: &Plane| match end {
            End::Vertex(i) => self.vertex_side(*i, q),
            End::Crossing { filter, planes } => side_of_implicit(filter, *planes, q),
        };
        let mut keeps: smallvec::SmallVec<[Keeps; 4]> = smallvec::SmallVec::new();
        for bound in cutting {
            let k = match (side(&first, bound), side(&second, bound)) {
                (Side::Back, Side::Back) => Keeps::All,
                (Side::Back, _) => Keeps::Prefix(bound),
                (_, Side::Back) => Keeps::Suffix(bound),
                _ => Keeps::Nothing,
            };
            if matches!(k, Keeps::Nothing) {
                return false;
            }
            keeps.push(k);
        }
        // A suffix from `s` and a prefix up to `p` overlap when `s` comes
        // first: where `s` crosses `L` lies strictly behind `p`.
        for s in keeps.iter().filter_map(|k| match k {
            Keeps::Suffix(s) => Some(*s),
            _ => None,
        }) {
            let Some(filter) = PointFilter::new(self.support(), plane, s) else {
                // Not reached: `s` separates the chord's ends, so it meets L.
                return false;
            };
            let at = [self.support(), plane, s];
            for p in keeps.iter().filter_map(|k| match k {
                Keeps::Prefix(p) => Some(*p),
                _ => None,
            }) {
                if side_of_implicit(&filter, at, p) != Side::Back {
                    return false;
                }
            }
        }
        true
    }

    /// The two ends of the chord of a plane that cuts the polygon (vertices
    /// strictly on both sides), in the polygon's vertex order.
    fn chord_ends<'a>(&'a self, plane: &'a Plane) -> Option<[End<'a>; 2]> {
        let n = self.len();
        let sides: smallvec::SmallVec<[Side; 8]> =
            (0..n).map(|i| self.vertex_side(i, plane)).collect();
        let mut ends: smallvec::SmallVec<[End; 2]> = smallvec::SmallVec::new();
        for i in 0..n {
            let next = (i + 1) % n;
            if sides[i] == Side::On {
                ends.push(End::Vertex(i));
            } else if sides[next] != Side::On && sides[next] != sides[i] {
                // Edge `i` runs from vertex `i` to vertex `i + 1`.
                let planes = [self.support(), self.edge(i), plane];
                let filter = PointFilter::new(planes[0], planes[1], planes[2])?;
                ends.push(End::Crossing { filter, planes });
            }
        }
        let mut ends = ends.into_iter();
        match (ends.next(), ends.next(), ends.next()) {
            (Some(a), Some(b), None) => Some([a, b]),
            // A convex polygon with vertices strictly on both sides meets
            // the line in exactly two boundary points.
            _ => None,
        }
    }
}
