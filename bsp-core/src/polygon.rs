//! Convex polygons with implicit vertices, and their exact splitting.

use crate::predicates::{self, PointFilter, Side, cross_of_differences, dot_i128, side_of_point};
use crate::{Error, GridPoint, Plane};
use smallvec::SmallVec;

/// How a coplanar polygon faces relative to a plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Facing {
    /// The polygon's support plane is the plane itself.
    Same,
    /// The polygon's support plane is the plane, flipped.
    Opposite,
}

/// Where a polygon lies relative to a plane, without constructing parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PolygonSide {
    /// Every vertex on or behind the plane, one strictly behind.
    Back,
    /// Every vertex on or in front of the plane, one strictly in front.
    Front,
    /// Vertices strictly on both sides: a split makes two parts.
    Both,
    /// Every vertex on the plane.
    Coplanar(Facing),
}

/// The result of [`ConvexPolygon::split`].
// Results are matched at once and the parts moved on; boxing them would
// cost two allocations per cut on the hottest path of every tree.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Split {
    /// The polygon is behind the plane (touching it at most along an edge or
    /// a vertex); it is unchanged.
    Back,
    /// The polygon is in front of the plane; it is unchanged.
    Front,
    /// The plane cuts the polygon: `(back part, front part)`.
    Both(ConvexPolygon, ConvexPolygon),
    /// The polygon lies in the plane.
    Coplanar(Facing),
}

/// The result of [`ConvexPolygon::behind`].
#[derive(Debug, Clone, PartialEq)]
pub enum Behind {
    /// All of the polygon is behind the plane (touching it at most along
    /// an edge or a vertex).
    All,
    /// The plane cuts the polygon: its part behind.
    Part(ConvexPolygon),
    /// Nothing of it (with area) is behind: it is in front, or in the
    /// plane.
    Nothing,
}

/// [`ConvexPolygon::split`], or its back part alone.
#[allow(clippy::large_enum_variant)] // (as `Split`)
enum Cut {
    Back,
    Front,
    Both(ConvexPolygon, Option<ConvexPolygon>),
    Coplanar(Facing),
}

/// A vertex of a polygon: an input grid point, or the intersection of the
/// polygon's support plane with its two edge planes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Vertex {
    Grid(GridPoint),
    Implicit(PointFilter),
}

/// Vertex `i` and edge `i`, the edge that starts at it, stored together:
/// a polygon is then one allocation, and a split walks one array.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Corner {
    vertex: Vertex,
    edge: Plane,
}

/// The edge planes of a polygon, in order: see [`ConvexPolygon::edges`].
#[derive(Debug, Clone)]
pub struct Edges<'a>(std::slice::Iter<'a, Corner>);

impl<'a> Iterator for Edges<'a> {
    type Item = &'a Plane;

    #[inline]
    fn next(&mut self) -> Option<&'a Plane> {
        self.0.next().map(|c| &c.edge)
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.0.size_hint()
    }
}

impl DoubleEndedIterator for Edges<'_> {
    #[inline]
    fn next_back(&mut self) -> Option<Self::Item> {
        self.0.next_back().map(|c| &c.edge)
    }
}

impl ExactSizeIterator for Edges<'_> {}

/// A strictly convex planar polygon in the plane-based representation.
///
/// It is a support plane and a cycle of edge planes; the polygon is the part
/// of the support plane behind every edge plane. Vertex `i` is the
/// intersection of the support plane with edge planes `i - 1` and `i`; edge
/// `i` runs from vertex `i` to vertex `i + 1`, counter-clockwise seen from
/// the front of the support plane. Vertices are never rounded: those of the
/// input are grid points, those made by splitting are implicit, and either
/// kind is turned into `f64` only on demand.
///
/// Every polygon carries `source`, the index of the input polygon it came
/// from, through every split.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexPolygon {
    support: Plane,
    corners: Box<[Corner]>,
    source: u32,
}

impl ConvexPolygon {
    /// A polygon from grid points in counter-clockwise order (seen from the
    /// front).
    ///
    /// Repeated and collinear vertices are dropped first. Errors: fewer than
    /// three vertices remain, zero area, points not in one plane, or a
    /// polygon that is not convex.
    pub fn from_grid_points(points: &[GridPoint], source: u32) -> Result<Self, Error> {
        let mut pts: SmallVec<[GridPoint; 8]> = SmallVec::new();
        for &p in points {
            if pts.last() != Some(&p) {
                pts.push(p);
            }
        }
        while pts.len() > 1 && pts.first() == pts.last() {
            pts.pop();
        }
        remove_collinear(&mut pts);
        if pts.len() < 3 {
            return Err(Error::TooFewVertices);
        }
        let area = vector_area(&pts);
        if area == [0, 0, 0] {
            return Err(Error::ZeroArea);
        }
        let mut support = Plane::through(pts[0], pts[1], pts[2]).ok_or(Error::TooFewVertices)?;
        if pts.iter().any(|&p| side_of_point(&support, p) != Side::On) {
            return Err(Error::NonPlanar);
        }
        let n = support.normal();
        let along =
            i128::from(n[0]) * area[0] + i128::from(n[1]) * area[1] + i128::from(n[2]) * area[2];
        if along < 0 {
            support = support.flipped();
        }
        check_convex(&pts, &support)?;

        let count = pts.len();
        let corners = (0..count)
            .map(|i| {
                Ok(Corner {
                    vertex: Vertex::Grid(pts[i]),
                    edge: Plane::edge_plane(&support, pts[i], pts[(i + 1) % count])
                        .ok_or(Error::ZeroArea)?,
                })
            })
            .collect::<Result<Box<[Corner]>, Error>>()?;
        Ok(Self {
            support,
            corners,
            source,
        })
    }

    /// A polygon from its support plane and its cycle of edge planes, with
    /// every vertex implicit.
    ///
    /// Errors: fewer than three edges, consecutive edge planes that do not
    /// meet the support plane in one point, or a cycle that does not bound a
    /// strictly convex polygon (some vertex not strictly behind every
    /// non-adjacent edge plane).
    pub fn from_planes(support: Plane, edges: &[Plane], source: u32) -> Result<Self, Error> {
        let n = edges.len();
        if n < 3 {
            return Err(Error::TooFewVertices);
        }
        let corners = (0..n)
            .map(|i| {
                let prev = &edges[(i + n - 1) % n];
                let filter =
                    PointFilter::new(&support, prev, &edges[i]).ok_or(Error::NoIntersection)?;
                Ok(Corner {
                    vertex: Vertex::Implicit(filter),
                    edge: edges[i],
                })
            })
            .collect::<Result<Box<[Corner]>, Error>>()?;
        let polygon = Self {
            support,
            corners,
            source,
        };
        polygon
            .check_strictly_inside()
            .map_err(|_| Error::NonConvex)?;
        Ok(polygon)
    }

    /// The support plane; the polygon's front is its front.
    #[inline]
    pub fn support(&self) -> &Plane {
        &self.support
    }

    /// The edge planes in order; edge `i` runs from vertex `i` to vertex
    /// `i + 1`, and the polygon lies behind each.
    #[inline]
    pub fn edges(&self) -> Edges<'_> {
        Edges(self.corners.iter())
    }

    /// Edge plane `i` (see [`edges`](Self::edges)).
    #[inline]
    pub fn edge(&self, i: usize) -> &Plane {
        &self.corners[i].edge
    }

    /// Number of vertices (and edges).
    #[inline]
    pub fn len(&self) -> usize {
        self.corners.len()
    }

    /// Always false: a polygon has at least three vertices.
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The index of the input polygon this one came from.
    #[inline]
    pub fn source(&self) -> u32 {
        self.source
    }

    /// The same polygon with another source index.
    pub fn with_source(mut self, source: u32) -> Self {
        self.source = source;
        self
    }

    /// The three planes whose intersection is vertex `i`.
    #[inline]
    pub fn vertex_planes(&self, i: usize) -> [&Plane; 3] {
        let n = self.len();
        [
            &self.support,
            &self.corners[(i + n - 1) % n].edge,
            &self.corners[i].edge,
        ]
    }

    /// Vertex `i` if it is an input grid point.
    pub fn vertex_grid_point(&self, i: usize) -> Option<GridPoint> {
        match self.corners[i].vertex {
            Vertex::Grid(p) => Some(p),
            Vertex::Implicit(_) => None,
        }
    }

    /// The vertices in order, when every one is an input grid point.
    pub fn grid_corners(&self) -> Option<Vec<GridPoint>> {
        (0..self.len()).map(|i| self.vertex_grid_point(i)).collect()
    }

    /// Side of vertex `i` with respect to `plane`, exact.
    #[inline(always)]
    pub fn vertex_side(&self, i: usize, plane: &Plane) -> Side {
        match &self.corners[i].vertex {
            Vertex::Grid(p) => side_of_point(plane, *p),
            Vertex::Implicit(filter) => match filter.side(plane) {
                Some(side) => side,
                None => self.implicit_side_exact(i, plane),
            },
        }
    }

    /// Side of implicit vertex `i` where the filter is uncertain, exact.
    /// Edge `i` runs from the vertex along `support.normal × edge.normal`
    /// (the polygon lies behind its edge planes), so a grid-point neighbour
    /// on `plane` at either end of an edge through the vertex decides it by
    /// a 3x3 determinant.
    #[inline(never)]
    fn implicit_side_exact(&self, i: usize, plane: &Plane) -> Side {
        let planes = self.vertex_planes(i);
        if planes.iter().any(|p| p.is_coincident(plane)) {
            return Side::On;
        }
        let n = self.len();
        let prev = (i + n - 1) % n;
        // Vertex i + 1 ends edge i: the vertex lies back along the edge.
        if let Vertex::Grid(g) = self.corners[(i + 1) % n].vertex
            && side_of_point(plane, g) == Side::On
        {
            return predicates::side_along_line(plane, &self.support, self.edge(i), false);
        }
        // Vertex i - 1 starts edge i - 1: the vertex lies forward along it.
        if let Vertex::Grid(g) = self.corners[prev].vertex
            && side_of_point(plane, g) == Side::On
        {
            return predicates::side_along_line(plane, &self.support, self.edge(prev), true);
        }
        // The plane holds a line through the vertex: two of its planes'.
        let [s, e0, e1] = planes;
        if predicates::in_pencil(e0, e1, plane)
            || predicates::in_pencil(s, e0, plane)
            || predicates::in_pencil(s, e1, plane)
        {
            return Side::On;
        }
        predicates::exact_side_of_implicit(planes, plane)
    }

    /// Vertex `i` in grid units, as `f64` (for output and illumination).
    pub fn vertex_f64(&self, i: usize) -> [f64; 3] {
        match &self.corners[i].vertex {
            Vertex::Grid(p) => p.to_f64(),
            Vertex::Implicit(filter) => predicates::implicit_to_f64(filter, self.vertex_planes(i)),
        }
    }

    /// All vertices in grid units, as `f64`, counter-clockwise.
    pub fn vertices_f64(&self) -> Vec<[f64; 3]> {
        (0..self.len()).map(|i| self.vertex_f64(i)).collect()
    }

    /// Area in squared grid units (from `f64` vertices).
    pub fn area(&self) -> f64 {
        let v = self.vertices_f64();
        let n = self.support.unit_normal_f64();
        let mut twice = 0.0;
        for i in 1..v.len() - 1 {
            let c = cross(sub(v[i], v[0]), sub(v[i + 1], v[0]));
            twice += c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
        }
        0.5 * twice
    }

    /// Area centroid in grid units.
    pub fn centroid(&self) -> [f64; 3] {
        let v = self.vertices_f64();
        let n = self.support.unit_normal_f64();
        let (mut total, mut acc) = (0.0, [0.0; 3]);
        for i in 1..v.len() - 1 {
            let c = cross(sub(v[i], v[0]), sub(v[i + 1], v[0]));
            let a = c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
            total += a;
            for k in 0..3 {
                acc[k] += a * (v[0][k] + v[i][k] + v[i + 1][k]) / 3.0;
            }
        }
        if total == 0.0 {
            return v[0];
        }
        acc.map(|c| c / total)
    }

    /// The polygon moved by `d` grid steps, its source kept. Exact: its
    /// corners must be grid points (every input polygon's are), and the
    /// moved corners give the polygon [`Self::from_grid_points`] makes of
    /// them. Errors: a corner that is a cut's implicit point
    /// ([`Error::ImplicitVertex`]), or one moved past
    /// [`GRID_LIMIT`](crate::GRID_LIMIT) ([`Error::CoordinateRange`]).
    pub fn translated(&self, d: [i64; 3]) -> Result<Self, Error> {
        let corners = self.grid_corners().ok_or(Error::ImplicitVertex)?;
        let moved = corners
            .iter()
            .map(|p| {
                let g = p.to_i64();
                GridPoint::new(
                    g[0].saturating_add(d[0]),
                    g[1].saturating_add(d[1]),
                    g[2].saturating_add(d[2]),
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        Self::from_grid_points(&moved, self.source)
    }

    /// The same region facing the other way (support plane flipped, vertex
    /// order reversed).
    pub fn flipped(&self) -> Self {
        // Reversed, vertex k is old vertex -k and edge k (from it to vertex
        // k + 1) is old edge -k - 1.
        let n = self.len();
        Self {
            support: self.support.flipped(),
            corners: (0..n)
                .map(|k| Corner {
                    vertex: self.corners[(n - k) % n].vertex,
                    edge: self.corners[n - 1 - k].edge,
                })
                .collect(),
            source: self.source,
        }
    }

    /// Where the polygon lies relative to `plane`, exact, without building
    /// parts.
    pub fn classify(&self, plane: &Plane) -> PolygonSide {
        if let Some(facing) = self.coincident_facing(plane) {
            return PolygonSide::Coplanar(facing);
        }
        let (mut back, mut front) = (false, false);
        for i in 0..self.len() {
            match self.vertex_side(i, plane) {
                Side::Back => back = true,
                Side::Front => front = true,
                Side::On => {}
            }
            if back && front {
                return PolygonSide::Both;
            }
        }
        match (back, front) {
            (true, _) => PolygonSide::Back,
            (false, true) => PolygonSide::Front,
            (false, false) => PolygonSide::Coplanar(self.facing(plane)),
        }
    }

    /// `Some(facing)` if `plane` is the support plane or its opposite: the
    /// common case of a fragment meeting its own plane in a tree, answered
    /// without testing vertices.
    #[inline]
    fn coincident_facing(&self, plane: &Plane) -> Option<Facing> {
        if *plane == self.support {
            Some(Facing::Same)
        } else if plane.is_opposite(&self.support) {
            Some(Facing::Opposite)
        } else {
            None
        }
    }

    fn facing(&self, plane: &Plane) -> Facing {
        // Every vertex is on `plane` and the polygon has area, so `plane` is
        // the support plane or its opposite.
        if *plane == self.support {
            Facing::Same
        } else {
            Facing::Opposite
        }
    }

    /// Splits the polygon by `plane`, every decision exact.
    ///
    /// A part is made only where vertices lie strictly on both sides, so no
    /// part has zero area and none is lost: the parts tile the polygon.
    pub fn split(&self, plane: &Plane) -> Split {
        match self.cut(plane, true) {
            Cut::Back => Split::Back,
            Cut::Front => Split::Front,
            Cut::Coplanar(facing) => Split::Coplanar(facing),
            Cut::Both(back, front) => Split::Both(back, front.expect("the front part was made")),
        }
    }

    /// The polygon's part behind `plane`, as [`Self::split`] finds it,
    /// without making the front part (clipping keeps one side only).
    pub fn behind(&self, plane: &Plane) -> Behind {
        match self.cut(plane, false) {
            Cut::Back => Behind::All,
            Cut::Both(back, _) => Behind::Part(back),
            Cut::Front | Cut::Coplanar(_) => Behind::Nothing,
        }
    }

    /// [`Self::split`], the front part made only if `front`.
    fn cut(&self, plane: &Plane, front: bool) -> Cut {
        if let Some(facing) = self.coincident_facing(plane) {
            return Cut::Coplanar(facing);
        }
        let n = self.len();
        // Most calls find the polygon on one side: the sides are kept in a
        // fixed array (no length checks), and a heap list only for long
        // polygons.
        let mut inline = [Side::On; 8];
        let mut heap = Vec::new();
        let sides: &mut [Side] = if n <= inline.len() {
            &mut inline[..n]
        } else {
            heap.resize(n, Side::On);
            &mut heap
        };
        let (mut backs, mut fronts) = (0, 0);
        for (i, slot) in sides.iter_mut().enumerate() {
            let s = self.vertex_side(i, plane);
            backs += usize::from(s == Side::Back);
            fronts += usize::from(s == Side::Front);
            *slot = s;
        }
        let sides = &*sides;
        match (backs > 0, fronts > 0) {
            (true, true) => {
                // The vertices strictly on one side of the plane are
                // consecutive (the polygon is convex): each part's run
                // begins after the edge that enters its side. Each crossing
                // vertex is made once and shared by both parts (a plane and
                // its flip give the same filter data); a convex polygon
                // crosses a plane on at most two edges.
                let (mut enter_back, mut enter_front) = (0, 0);
                let mut crossings: [(usize, Vertex); 2] =
                    [(usize::MAX, Vertex::Grid(GridPoint::default())); 2];
                let mut count = 0;
                for e in 0..n {
                    let (from, to) = (sides[e], sides[next(e, n)]);
                    if from == to {
                        continue;
                    }
                    match to {
                        Side::Back => enter_back = e,
                        Side::Front => enter_front = e,
                        Side::On => {}
                    }
                    if from != Side::On && to != Side::On {
                        let filter = PointFilter::new(&self.support, self.edge(e), plane).expect(
                            "an edge whose ends lie strictly on both sides meets the plane in a point",
                        );
                        crossings[count] = (e, Vertex::Implicit(filter));
                        count += 1;
                    }
                }
                let crossings = &crossings[..count];
                let back = self.part(sides, crossings, enter_back, backs, *plane);
                let front = front
                    .then(|| self.part(sides, crossings, enter_front, fronts, plane.flipped()));
                Cut::Both(back, front)
            }
            (true, false) => Cut::Back,
            (false, true) => Cut::Front,
            (false, false) => Cut::Coplanar(self.facing(plane)),
        }
    }

    /// The part of a polygon cut by a plane whose `kept` vertices strictly
    /// on its side follow edge `enter`; `closing` is the plane oriented
    /// with that part behind it.
    fn part(
        &self,
        sides: &[Side],
        crossings: &[(usize, Vertex)],
        enter: usize,
        kept: usize,
        closing: Plane,
    ) -> ConvexPolygon {
        let n = self.len();
        let mut corners: Vec<Corner> = Vec::with_capacity(kept + 2);
        // The vertex between the closing plane and the entering edge, then
        // the kept vertices with the edges that start at them.
        corners.push(Corner {
            vertex: self.vertex_on_cut(enter, enter, sides, crossings),
            edge: self.corners[enter].edge,
        });
        let mut last = enter;
        for _ in 0..kept {
            last = next(last, n);
            corners.push(self.corners[last]);
        }
        // The vertex between the last kept edge and the closing plane.
        corners.push(Corner {
            vertex: self.vertex_on_cut(next(last, n), last, sides, crossings),
            edge: closing,
        });
        ConvexPolygon {
            support: self.support,
            corners: corners.into_boxed_slice(),
            source: self.source,
        }
    }

    /// The vertex where edge `edge` meets the cut: old vertex `old` (one of
    /// the edge's ends) if it lies on the cutting plane, else the edge's
    /// crossing vertex.
    fn vertex_on_cut(
        &self,
        old: usize,
        edge: usize,
        sides: &[Side],
        crossings: &[(usize, Vertex)],
    ) -> Vertex {
        if sides[old] == Side::On {
            return self.corners[old].vertex;
        }
        crossings
            .iter()
            .find(|(e, _)| *e == edge)
            .map(|(_, v)| *v)
            .expect("an edge entering or leaving the kept side strictly crosses the plane")
    }

    /// Checks the representation: at least three vertices; each vertex on
    /// its three planes; each strictly behind every other edge plane (strict
    /// convexity, no zero-length edge). Exact. Used by tests and fuzzing.
    pub fn check_invariants(&self) -> Result<(), String> {
        let n = self.len();
        if n < 3 {
            return Err(format!("{n} vertices"));
        }
        for i in 0..n {
            for (k, plane) in self.vertex_planes(i).into_iter().enumerate() {
                if self.vertex_side(i, plane) != Side::On {
                    return Err(format!("vertex {i} is not on its plane {k}"));
                }
            }
        }
        self.check_strictly_inside()
    }

    /// Every vertex strictly behind every edge plane it is not on: strict
    /// convexity, no zero-length edge.
    fn check_strictly_inside(&self) -> Result<(), String> {
        let n = self.len();
        for i in 0..n {
            for (j, edge) in self.edges().enumerate() {
                if j != i && j != (i + n - 1) % n && self.vertex_side(i, edge) != Side::Back {
                    return Err(format!("vertex {i} is not strictly behind edge {j}"));
                }
            }
        }
        Ok(())
    }
}

/// The index after `i` around a cycle of `n` (no division on the hot path).
#[inline(always)]
fn next(i: usize, n: usize) -> usize {
    if i + 1 == n { 0 } else { i + 1 }
}

/// Drops vertices collinear with their neighbours until none is left.
fn remove_collinear(pts: &mut SmallVec<[GridPoint; 8]>) {
    let mut changed = true;
    while changed && pts.len() >= 3 {
        changed = false;
        let n = pts.len();
        for i in 0..n {
            let (a, b, c) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
            if predicates::collinear(a, b, c) {
                pts.remove(i);
                changed = true;
                break;
            }
        }
    }
}

/// Twice the vector area, `sum p_i x p_(i+1)`, exact.
fn vector_area(pts: &[GridPoint]) -> [i128; 3] {
    let mut acc = [0_i128; 3];
    let n = pts.len();
    for i in 0..n {
        let [ax, ay, az] = pts[i].to_i64().map(i128::from);
        let [bx, by, bz] = pts[(i + 1) % n].to_i64().map(i128::from);
        acc[0] += ay * bz - az * by;
        acc[1] += az * bx - ax * bz;
        acc[2] += ax * by - ay * bx;
    }
    acc
}

/// Strict convexity of a planar cycle: every turn to the left of `support`
/// and the edge directions winding around once.
fn check_convex(pts: &[GridPoint], support: &Plane) -> Result<(), Error> {
    let n = pts.len();
    let normal = support.normal();
    for i in 0..n {
        let turn = cross_of_differences(pts[i], pts[(i + 1) % n], pts[(i + 2) % n]);
        if dot_i128(turn, normal) <= 0 {
            return Err(Error::NonConvex);
        }
    }
    // All left turns still allow a star that winds twice; in a convex
    // polygon each coordinate of the edge direction changes sign at most
    // twice around the cycle.
    for axis in 0..3 {
        let signs: SmallVec<[i64; 8]> = (0..n)
            .map(|i| {
                (i64::from(pts[(i + 1) % n].to_array()[axis]) - i64::from(pts[i].to_array()[axis]))
                    .signum()
            })
            .filter(|&d| d != 0)
            .collect();
        let changes = (0..signs.len())
            .filter(|&i| signs[i] != signs[(i + 1) % signs.len()])
            .count();
        if changes > 2 {
            return Err(Error::NonConvex);
        }
    }
    Ok(())
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
