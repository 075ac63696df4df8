//! Lines on a receiver plane: the 2D view that discontinuity meshes need.
//!
//! A line on a receiver is the receiver's support plane cut by another
//! plane. For a point that lies on the receiver, its side of the line is
//! its side of that plane, so the kernel's 3D predicates decide 2D
//! questions exactly, with no projection and no new arithmetic.

use crate::predicates::{self, PointFilter, Side};
use crate::{Error, GridPoint, ImplicitPoint, Plane};

/// A directed line on a receiver plane: `receiver ∩ plane`.
///
/// Orientation follows [`ConvexPolygon`](crate::ConvexPolygon)'s edges:
/// seen from the receiver's front, the left of the direction is **behind**
/// `plane`. A convex polygon on the receiver, counter-clockwise, is the set
/// of points behind all of its edge lines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ReceiverLine {
    receiver: Plane,
    plane: Plane,
}

/// How two lines on one receiver meet.
#[derive(Debug, Clone, PartialEq)]
pub enum LineMeeting {
    /// In exactly one point.
    Point(Box<ImplicitPoint>),
    /// Parallel and distinct: never.
    Parallel,
    /// The same line (in either direction).
    Coincident,
}

impl ReceiverLine {
    /// The line where `plane` cuts `receiver`; an error if `plane` is
    /// parallel to the receiver (or the receiver itself).
    pub fn new(receiver: Plane, plane: Plane) -> Result<Self, Error> {
        let n = receiver.normal();
        let m = plane.normal();
        let cross = [
            i128::from(n[1]) * i128::from(m[2]) - i128::from(n[2]) * i128::from(m[1]),
            i128::from(n[2]) * i128::from(m[0]) - i128::from(n[0]) * i128::from(m[2]),
            i128::from(n[0]) * i128::from(m[1]) - i128::from(n[1]) * i128::from(m[0]),
        ];
        if cross == [0, 0, 0] {
            return Err(Error::NoIntersection);
        }
        Ok(Self { receiver, plane })
    }

    /// The directed line from `p` to `q`, two distinct grid points on the
    /// receiver. Its plane holds the line and the receiver normal's dominant
    /// axis, as polygon edge planes do, so its coefficients stay small.
    pub fn through(receiver: Plane, p: GridPoint, q: GridPoint) -> Result<Self, Error> {
        if predicates::side_of_point(&receiver, p) != Side::On
            || predicates::side_of_point(&receiver, q) != Side::On
        {
            return Err(Error::NonPlanar);
        }
        if p == q {
            return Err(Error::TooFewVertices);
        }
        let plane = Plane::edge_plane(&receiver, p, q).ok_or(Error::TooFewVertices)?;
        Self::new(receiver, plane)
    }

    /// The receiver plane.
    pub fn receiver(&self) -> &Plane {
        &self.receiver
    }

    /// The plane that cuts the receiver along the line.
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The same line, directed the other way.
    pub fn flipped(&self) -> Self {
        Self {
            receiver: self.receiver,
            plane: self.plane.flipped(),
        }
    }

    /// Side of a grid point lying on the receiver: `Back` is the left.
    pub fn side_of_point(&self, p: GridPoint) -> Side {
        predicates::side_of_point(&self.plane, p)
    }

    /// Side of an implicit point lying on the receiver: `Back` is the left.
    pub fn side_of_implicit(&self, p: &ImplicitPoint) -> Side {
        p.side(&self.plane)
    }

    /// How this line meets `other` (on the same receiver), exactly.
    pub fn meet(&self, other: &ReceiverLine) -> LineMeeting {
        match PointFilter::new(&self.receiver, &self.plane, &other.plane) {
            Some(_) => LineMeeting::Point(Box::new(
                ImplicitPoint::new(self.receiver, self.plane, other.plane)
                    .expect("the filter found a single point"),
            )),
            None => {
                // No single point: the three planes share a line (every 3x3
                // minor vanishes) or the lines are parallel.
                let minors =
                    predicates::exact_homogeneous(&self.receiver, &self.plane, &other.plane);
                if minors.iter().all(|m| *m == 0) {
                    LineMeeting::Coincident
                } else {
                    LineMeeting::Parallel
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::GRID_LIMIT;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    /// The plane y = 0 facing +y.
    fn floor() -> Plane {
        Plane::through(g(0, 0, 0), g(0, 0, 1), g(1, 0, 0)).unwrap()
    }

    #[test]
    fn left_is_behind() {
        // Seen from +y, going +x, the left is -z.
        let line = ReceiverLine::through(floor(), g(0, 0, 0), g(10, 0, 0)).unwrap();
        assert_eq!(line.side_of_point(g(5, 0, -3)), Side::Back);
        assert_eq!(line.side_of_point(g(5, 0, 3)), Side::Front);
        assert_eq!(line.side_of_point(g(-7, 0, 0)), Side::On);
        assert_eq!(line.flipped().side_of_point(g(5, 0, -3)), Side::Front);
        // Agrees with a polygon's edge planes: a counter-clockwise square
        // lies behind every edge line.
        let sq = [g(0, 0, 0), g(0, 0, 4), g(4, 0, 4), g(4, 0, 0)];
        let polygon = crate::ConvexPolygon::from_grid_points(&sq, 0).unwrap();
        assert_eq!(polygon.support(), &floor());
        for i in 0..4 {
            let line = ReceiverLine::through(floor(), sq[i], sq[(i + 1) % 4]).unwrap();
            assert_eq!(line.side_of_point(g(2, 0, 2)), Side::Back);
            assert_eq!(line.plane(), polygon.edge(i));
        }
    }

    #[test]
    fn lines_meet_in_a_point_or_not_at_all() {
        let a = ReceiverLine::through(floor(), g(0, 0, 0), g(10, 0, 10)).unwrap();
        let b = ReceiverLine::through(floor(), g(0, 0, 10), g(10, 0, 0)).unwrap();
        let LineMeeting::Point(p) = a.meet(&b) else {
            panic!("crossing lines")
        };
        assert_eq!(p.to_f64(), [5.0, 0.0, 5.0]);
        assert_eq!(a.side_of_implicit(&p), Side::On);
        assert_eq!(p.side(&floor()), Side::On);
        let c = ReceiverLine::through(floor(), g(0, 0, 1), g(10, 0, 11)).unwrap();
        assert_eq!(a.meet(&c), LineMeeting::Parallel);
        let d = ReceiverLine::through(floor(), g(20, 0, 20), g(-3, 0, -3)).unwrap();
        assert_eq!(a.meet(&d), LineMeeting::Coincident);
        assert_eq!(a.meet(&a.flipped()), LineMeeting::Coincident);
    }

    #[test]
    fn bad_lines_are_errors() {
        assert!(ReceiverLine::through(floor(), g(0, 1, 0), g(1, 0, 0)).is_err());
        assert!(ReceiverLine::through(floor(), g(1, 0, 0), g(1, 0, 0)).is_err());
        let parallel = Plane::through(g(0, 5, 0), g(0, 5, 1), g(1, 5, 0)).unwrap();
        assert_eq!(
            ReceiverLine::new(floor(), parallel),
            Err(Error::NoIntersection)
        );
        assert_eq!(
            ReceiverLine::new(floor(), floor().flipped()),
            Err(Error::NoIntersection)
        );
    }

    #[test]
    fn tilted_receiver_at_the_grid_limits() {
        let l = GRID_LIMIT;
        let receiver = Plane::through(g(-l, -l, -l), g(l, -l + 3, -l), g(-l, l, l - 7)).unwrap();
        let (p, q, r) = (g(-l, -l, -l), g(l, -l + 3, -l), g(-l, l, l - 7));
        let a = ReceiverLine::through(receiver, p, q).unwrap();
        let b = ReceiverLine::through(receiver, q, r).unwrap();
        let c = ReceiverLine::through(receiver, r, p).unwrap();
        // The triangle p q r: each vertex on two lines, strictly on one side
        // of the third, and the three meet pairwise at the vertices.
        assert_eq!(a.side_of_point(r), b.side_of_point(p));
        assert_eq!(b.side_of_point(p), c.side_of_point(q));
        assert_ne!(a.side_of_point(r), Side::On);
        let LineMeeting::Point(v) = a.meet(&b) else {
            panic!("adjacent edges meet")
        };
        assert_eq!(c.side_of_implicit(&v), a.side_of_point(r));
        assert!(v.same_point(&ImplicitPoint::new(receiver, *a.plane(), *b.plane()).unwrap()));
    }
}
