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
//!
//! Where the polygon is then cut again and again (a region filtered down a
//! tree, each part asking again), the chord itself can be kept
//! ([`ConvexPolygon::chord_inside`]): a part of the polygon is crossed
//! exactly where a part of the open chord lies in it, two sides of the
//! chord's ends per cut ([`Chord::split`]).

use crate::plane::Plane;
use crate::polygon::{ConvexPolygon, PolygonSide};
use crate::predicates::{ImplicitPoint, PointFilter, Side, side_of_implicit};
use crate::winged_edge::VertexPosition;

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

    /// The open chord along which `plane` crosses the polygon's part behind
    /// every plane of `bounds`, if it does (as [`Self::crosses_inside`]
    /// says): the chord through the polygon clipped by the bounds, exact.
    pub fn chord_inside(&self, plane: &Plane, bounds: &[Plane]) -> Option<Chord> {
        if self.classify(plane) != PolygonSide::Both {
            return None;
        }
        let mut cutting: smallvec::SmallVec<[&Plane; 4]> = smallvec::SmallVec::new();
        for bound in bounds {
            match self.classify(bound) {
                PolygonSide::Back => {}
                PolygonSide::Both => cutting.push(bound),
                PolygonSide::Front | PolygonSide::Coplanar(_) => return None,
            }
        }
        let [first, second] = self.chord_ends(plane)?;
        let position = |end: End| match end {
            End::Vertex(i) => self.vertex_position(i),
            End::Crossing { filter, planes } => {
                VertexPosition::Implicit(ImplicitPoint::from_parts(planes.map(|p| *p), filter))
            }
        };
        let mut chord = Chord {
            plane: *plane,
            ends: [position(first), position(second)],
        };
        // Clipped by each bound in turn: an end strictly in front of it
        // moves to where it crosses the line (the other end, strictly
        // behind, keeps the open segment between them of positive length).
        for bound in cutting {
            let (a, b) = (chord.ends[0].side(bound), chord.ends[1].side(bound));
            match (a, b) {
                (Side::Back, Side::Back) | (Side::Back, Side::On) | (Side::On, Side::Back) => {}
                (Side::Back, Side::Front) => {
                    chord.ends[1] = chord.crossing(self.support(), bound)?
                }
                (Side::Front, Side::Back) => {
                    chord.ends[0] = chord.crossing(self.support(), bound)?
                }
                _ => return None,
            }
        }
        Some(chord)
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

/// The open segment along which a plane crosses the part of a convex
/// polygon behind some bounding planes ([`ConvexPolygon::chord_inside`]),
/// between its two ends, exact points.
#[derive(Debug, Clone)]
pub struct Chord {
    plane: Plane,
    ends: [VertexPosition; 2],
}

impl Chord {
    /// The plane whose chord it is.
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The chord's parts strictly behind and strictly in front of `cut`,
    /// a plane that cuts the polygon (whose support is `support`): the
    /// chords through the polygon's back and front parts (within the same
    /// bounds), none where the part of the chord on that side is empty.
    /// Two exact sides, and where the chord crosses `cut`, its crossing
    /// point.
    pub fn split(&self, support: &Plane, cut: &Plane) -> (Option<Chord>, Option<Chord>) {
        let (a, b) = (self.ends[0].side(cut), self.ends[1].side(cut));
        let behind = a == Side::Back || b == Side::Back;
        let ahead = a == Side::Front || b == Side::Front;
        if !(behind && ahead) {
            let keep = || Some(self.clone());
            return (behind.then(keep).flatten(), ahead.then(keep).flatten());
        }
        // Ends strictly on either side: the cut crosses the line at one
        // point, inside the chord.
        let Some(crossing) = self.crossing(support, cut) else {
            // Not reached (the three planes meet in one point); both
            // parts keep all of it, a superset of the truth.
            return (Some(self.clone()), Some(self.clone()));
        };
        let mut back = self.clone();
        let mut front = self.clone();
        let ahead_end = usize::from(a == Side::Back);
        back.ends[ahead_end] = crossing;
        front.ends[1 - ahead_end] = crossing;
        (Some(back), Some(front))
    }

    /// Where `plane` crosses the chord's line (on `support`).
    fn crossing(&self, support: &Plane, plane: &Plane) -> Option<VertexPosition> {
        ImplicitPoint::new(*support, self.plane, *plane)
            .ok()
            .map(VertexPosition::Implicit)
    }
}
