//! A convex polygonal area light on the grid.

use crate::Error;
use bsp_core::predicates::Side;
use bsp_core::{ConvexPolygon, GridPoint, Plane, PolygonSide};

/// A convex polygonal light with grid-point vertices. It emits on the front
/// of its support plane (the side its counter-clockwise normal points to).
#[derive(Debug, Clone, PartialEq)]
pub struct AreaSource {
    polygon: ConvexPolygon,
}

/// Where an area light lies relative to a plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SourceSide {
    /// Every vertex on or behind the plane, one strictly behind.
    Back,
    /// Every vertex on or in front of the plane, one strictly in front.
    Front,
    /// Vertices strictly on both sides: the plane cuts the light.
    Both,
    /// The light lies in the plane.
    In,
}

impl AreaSource {
    /// The light of a polygon whose vertices are all grid points.
    pub fn new(polygon: ConvexPolygon) -> Result<Self, Error> {
        if polygon.len() < 3 || (0..polygon.len()).any(|k| polygon.vertex_grid_point(k).is_none()) {
            return Err(Error::LightNotOnGrid);
        }
        Ok(Self { polygon })
    }

    /// The light from grid points, counter-clockwise seen from the side it
    /// lights.
    pub fn from_grid_points(points: &[GridPoint]) -> Result<Self, Error> {
        let polygon =
            ConvexPolygon::from_grid_points(points, 0).map_err(|_| Error::LightNotOnGrid)?;
        Self::new(polygon)
    }

    /// The light's polygon.
    pub fn polygon(&self) -> &ConvexPolygon {
        &self.polygon
    }

    /// The support plane; the light emits in front of it.
    pub fn support(&self) -> &Plane {
        self.polygon.support()
    }

    /// The vertices, counter-clockwise.
    pub fn vertices(&self) -> impl Iterator<Item = GridPoint> + '_ {
        (0..self.polygon.len()).map(|k| self.polygon.vertex_grid_point(k).expect("checked in new"))
    }

    /// Where the light lies relative to `plane`, exactly.
    pub fn side_of(&self, plane: &Plane) -> SourceSide {
        match self.polygon.classify(plane) {
            PolygonSide::Back => SourceSide::Back,
            PolygonSide::Front => SourceSide::Front,
            PolygonSide::Both => SourceSide::Both,
            PolygonSide::Coplanar(_) => SourceSide::In,
        }
    }

    /// Whether a polygon with support `plane` can receive any of the light
    /// on its front: some of the light lies strictly in front of it.
    pub fn reaches_front_of(&self, plane: &Plane) -> bool {
        matches!(self.side_of(plane), SourceSide::Front | SourceSide::Both)
    }

    /// The light's side of a grid point's position (the point in front of
    /// the light's plane is lit by it, if nothing blocks).
    pub fn side_of_point(&self, p: GridPoint) -> Side {
        bsp_core::predicates::side_of_point(self.support(), p)
    }

    /// Whether the light lies clear of every solid whose surface has its
    /// vertices among `points`: all of them strictly in front of the
    /// light's plane, or their bounding box apart from the light's (a gap
    /// along some axis). A closed surface's faces turned away from a light
    /// clear of it hide nothing its faces towards the light do not; a
    /// light on the surface, or inside the solid, shines into it, and
    /// there they do.
    pub fn clear_of(&self, points: &[GridPoint]) -> bool {
        let support = self.support();
        if points
            .iter()
            .all(|&p| bsp_core::predicates::side_of_point(support, p) == Side::Front)
        {
            return true;
        }
        let light: Vec<GridPoint> = (0..self.polygon.len())
            .filter_map(|k| self.polygon.vertex_grid_point(k))
            .collect();
        match (GridBox::around(points), GridBox::around(&light)) {
            (Some(a), Some(b)) => a.apart_from(&b),
            _ => true,
        }
    }

    /// The centroid of the light, in grid coordinates.
    pub fn centroid(&self) -> [f64; 3] {
        self.polygon.centroid()
    }
}

/// The bounding box of grid points.
#[derive(Debug, Clone, Copy)]
pub(crate) struct GridBox {
    low: [i32; 3],
    high: [i32; 3],
}

impl GridBox {
    /// The box of `points`; `None` without any.
    pub(crate) fn around(points: &[GridPoint]) -> Option<Self> {
        let first = points.first()?;
        let mut b = Self {
            low: [first.x, first.y, first.z],
            high: [first.x, first.y, first.z],
        };
        for p in points {
            for (k, c) in [p.x, p.y, p.z].into_iter().enumerate() {
                b.low[k] = b.low[k].min(c);
                b.high[k] = b.high[k].max(c);
            }
        }
        Some(b)
    }

    /// Whether a gap separates the boxes along some axis (boxes that
    /// touch are not apart).
    pub(crate) fn apart_from(&self, other: &Self) -> bool {
        (0..3).any(|k| self.high[k] < other.low[k] || other.high[k] < self.low[k])
    }
}
