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
//! chord clipped by them in turn is a few exact sides of its ends and of
//! the points where the `W_i` cross `L`: no polygon is made.
//!
//! Where the polygon is then cut again and again (a region filtered down a
//! tree, each part asking again), the chord itself is kept
//! ([`ConvexPolygon::chord_inside`]): a part of the polygon is crossed
//! exactly where a part of the open chord lies in it, two sides of the
//! chord's ends per cut ([`Chord::split`]).

use crate::grid::GridPoint;
use crate::plane::Plane;
use crate::polygon::{ConvexPolygon, PolygonSide};
use crate::predicates::{PointFilter, Side, side_of_implicit, side_of_point};

impl ConvexPolygon {
    /// Whether `plane` has points of the polygon's part behind every plane
    /// of `bounds` strictly on both sides, exact; the same answer as
    /// clipping the polygon by `bounds` (keeping what lies behind) and
    /// classifying the part (`Both`), without building it.
    pub fn crosses_inside(&self, plane: &Plane, bounds: &[Plane]) -> bool {
        self.chord_inside(plane, bounds).is_some()
    }

    /// The open chord along which `plane` crosses the polygon's part behind
    /// every plane of `bounds`, if it does: the chord through the polygon
    /// clipped by the bounds in turn, exact.
    pub fn chord_inside(&self, plane: &Plane, bounds: &[Plane]) -> Option<Chord> {
        if self.classify(plane) != PolygonSide::Both {
            return None;
        }
        let cutting = self.cutting_bounds(bounds)?;
        let mut chord = Chord {
            plane: *plane,
            ends: self.chord_ends(plane)?,
        };
        // Clipped by each bound in turn: an end strictly in front of it
        // moves to where it crosses the line (the other end, strictly
        // behind, keeps the open segment between them of positive length).
        let support = self.support();
        for bound in cutting {
            let (a, b) = (chord.side(0, support, bound), chord.side(1, support, bound));
            match (a, b) {
                (Side::Back, Side::Back) | (Side::Back, Side::On) | (Side::On, Side::Back) => {}
                (Side::Back, Side::Front) => {
                    chord.ends[1] = ChordEnd::on_line(support, plane, bound)?
                }
                (Side::Front, Side::Back) => {
                    chord.ends[0] = ChordEnd::on_line(support, plane, bound)?
                }
                _ => return None,
            }
        }
        Some(chord)
    }

    /// The bounds that cut the polygon, or `None` when one keeps nothing
    /// of its inside. The open chord of a plane that crosses the polygon
    /// lies inside it: a bound with every vertex on or behind it (one
    /// strictly) keeps all of it, one with none strictly behind keeps
    /// nothing. Only the bounds that cut the polygon need the chord's
    /// ends, the costly part.
    fn cutting_bounds<'a>(
        &self,
        bounds: &'a [Plane],
    ) -> Option<smallvec::SmallVec<[&'a Plane; 4]>> {
        let mut cutting = smallvec::SmallVec::new();
        for bound in bounds {
            match self.classify(bound) {
                PolygonSide::Back => {}
                PolygonSide::Both => cutting.push(bound),
                PolygonSide::Front | PolygonSide::Coplanar(_) => return None,
            }
        }
        Some(cutting)
    }

    /// The two ends of the chord of a plane that cuts the polygon (vertices
    /// strictly on both sides), in the polygon's vertex order: vertices on
    /// the plane, or where it crosses edges.
    fn chord_ends(&self, plane: &Plane) -> Option<[ChordEnd; 2]> {
        let n = self.len();
        let sides: smallvec::SmallVec<[Side; 8]> =
            (0..n).map(|i| self.vertex_side(i, plane)).collect();
        let mut ends: smallvec::SmallVec<[ChordEnd; 2]> = smallvec::SmallVec::new();
        for i in 0..n {
            let next = (i + 1) % n;
            if sides[i] == Side::On {
                ends.push(match self.vertex_grid_point(i) {
                    Some(p) => ChordEnd::Grid(p),
                    // The chord's line crosses the polygon's inside, so it
                    // runs along neither edge at the vertex: either edge's
                    // plane meets it there alone.
                    None => ChordEnd::on_line(self.support(), plane, self.edge(i))?,
                });
            } else if sides[next] != Side::On && sides[next] != sides[i] {
                // Edge `i` runs from vertex `i` to vertex `i + 1`.
                ends.push(ChordEnd::on_line(self.support(), plane, self.edge(i))?);
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
    ends: [ChordEnd; 2],
}

/// An end of a chord: a grid point, or where a plane crosses the chord's
/// line (the polygon's support and the chord's plane make the point's
/// other two planes: a third of an implicit point's size, for chords
/// carried by the thousand).
#[derive(Debug, Clone, Copy)]
enum ChordEnd {
    Grid(GridPoint),
    OnLine { plane: Plane, filter: PointFilter },
}

impl ChordEnd {
    /// Where `other` crosses the line of `plane` on `support`, if at one
    /// point.
    fn on_line(support: &Plane, plane: &Plane, other: &Plane) -> Option<Self> {
        let filter = PointFilter::new(support, plane, other)?;
        Some(Self::OnLine {
            plane: *other,
            filter,
        })
    }
}

impl Chord {
    /// The plane whose chord it is.
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The side of `q` end `i` lies on (the polygon's support `support`).
    fn side(&self, i: usize, support: &Plane, q: &Plane) -> Side {
        match &self.ends[i] {
            ChordEnd::Grid(p) => side_of_point(q, *p),
            ChordEnd::OnLine { plane, filter } => {
                side_of_implicit(filter, [support, &self.plane, plane], q)
            }
        }
    }

    /// The chord's parts strictly behind and strictly in front of `cut`,
    /// a plane that cuts the polygon (whose support is `support`): the
    /// chords through the polygon's back and front parts (within the same
    /// bounds), none where the part of the chord on that side is empty.
    /// Two exact sides, and where the chord crosses `cut`, its crossing
    /// point.
    pub fn split(&self, support: &Plane, cut: &Plane) -> (Option<Chord>, Option<Chord>) {
        let (a, b) = (self.side(0, support, cut), self.side(1, support, cut));
        let behind = a == Side::Back || b == Side::Back;
        let ahead = a == Side::Front || b == Side::Front;
        if !(behind && ahead) {
            let keep = || Some(self.clone());
            return (behind.then(keep).flatten(), ahead.then(keep).flatten());
        }
        // Ends strictly on either side: the cut crosses the line at one
        // point, inside the chord.
        let Some(crossing) = ChordEnd::on_line(support, &self.plane, cut) else {
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
}
