//! Joint umbra in the output: a penumbra face whose corners all see none of
//! an area light is handed to [`area_shadow::dark::sees_none`] with the
//! occluders between it and the light, and turns umbra for that light when
//! proven dark.
//!
//! The blockers are the shadow-casting pieces, the convex groups they make
//! (with the shells of open surfaces closed over their hole, a cup's, or
//! holes, a tube's) and the open sheets of one object ([`sheet_bodies`]).
//!
//! `umbra shadow` finds those occluders with a uniform grid of their boxes
//! and the shaft between the face and the light; `umbra dm` (and
//! `update`) takes the objects its cell lists name. Faces stay whole.

use std::collections::HashMap;

use area_shadow::dark::{Body, Shaft, sees_none, sheet_bodies};
use area_shadow::{AreaSource, Blocker, ShadowGroups, holed_shells};
use bsp_core::ConvexPolygon;

use crate::decompose::Pieces;

/// Cells of the uniform grid along each axis.
const GRID_CELLS: usize = 32;

/// Blockers spanning more grid cells than this are checked for every
/// query (a floor), and queries spanning more look at every blocker.
const MAX_SPAN: usize = 4096;

/// The shadow-casting pieces of a scene and the convex groups they make
/// (flat polygons and bodies), with their bounding boxes (grid units), to
/// find those between a face and a light.
pub(crate) struct Occluders<'a> {
    polygons: Vec<(&'a ConvexPolygon, Bounds)>,
    bodies: Vec<(Body, Bounds)>,
    /// Per object: its polygons and bodies (indices).
    by_object: Vec<(Vec<usize>, Vec<usize>)>,
    index: GridIndex,
}

type Bounds = ([f64; 3], [f64; 3]);

/// A blocker: polygon `k` or body `k`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
enum Item {
    Polygon(usize),
    Body(usize),
}

impl<'a> Occluders<'a> {
    /// The pieces that cast shadows, and the convex groups they make;
    /// `objects[k]` is piece `k`'s object.
    pub(crate) fn new(pieces: &'a Pieces, groups: &'a ShadowGroups, objects: &[u32]) -> Self {
        let object_count = objects.iter().map(|&o| o as usize + 1).max().unwrap_or(0);
        let mut by_object = vec![(Vec::new(), Vec::new()); object_count];
        let (mut polygons, mut bodies) = (Vec::new(), Vec::new());
        // Pieces on a closed body or in a flat group block nothing the
        // group does not.
        let mut covered = vec![false; pieces.polygons.len()];
        for group in groups.bodies.iter().chain(&groups.joint_bodies) {
            let corners: Vec<[f64; 3]> = group
                .pieces
                .iter()
                .flat_map(|&k| pieces.polygons[k as usize].vertices_f64())
                .collect();
            let mut members: Vec<u32> = group.pieces.iter().map(|&k| objects[k as usize]).collect();
            members.sort_unstable();
            members.dedup();
            if let Some(shell) = group.shell() {
                for &o in &members {
                    by_object[o as usize].1.push(bodies.len());
                }
                bodies.push((shell, bounds(&corners)));
            }
            let covers = match group.blocker(&pieces.polygons) {
                Some(Blocker::Body(body)) => {
                    let closed = body.is_closed();
                    for &o in &members {
                        by_object[o as usize].1.push(bodies.len());
                    }
                    bodies.push((body, bounds(&corners)));
                    closed
                }
                Some(Blocker::Polygon(polygon)) => {
                    for &o in &members {
                        by_object[o as usize].0.push(polygons.len());
                    }
                    polygons.push((polygon, bounds(&corners)));
                    true
                }
                None => false,
            };
            if covers {
                for &k in &group.pieces {
                    covered[k as usize] = true;
                }
            }
        }
        // Sheets open on some side (a tent of triangles): one body each,
        // besides their pieces, for regions that see only covered faces.
        let mut grouped: Vec<&[u32]> = groups
            .bodies
            .iter()
            .chain(&groups.joint_bodies)
            .map(|g| g.pieces.as_slice())
            .collect();
        grouped.sort_unstable();
        // A body of pieces `members` (of one object): listed by that
        // object, with the box around the pieces.
        let add_body = |by_object: &mut Vec<(Vec<usize>, Vec<usize>)>,
                        bodies: &mut Vec<(Body, Bounds)>,
                        members: &[u32],
                        body: Body| {
            let corners: Vec<[f64; 3]> = members
                .iter()
                .flat_map(|&k| pieces.polygons[k as usize].vertices_f64())
                .collect();
            by_object[objects[members[0] as usize] as usize]
                .1
                .push(bodies.len());
            bodies.push((body, bounds(&corners)));
        };
        let owners: Vec<Option<u32>> = (0..pieces.polygons.len())
            .map(|k| pieces.casts_shadows[k].then_some(objects[k]))
            .collect();
        for (sheet, body) in sheet_bodies(&pieces.polygons, &owners) {
            if grouped.binary_search(&sheet.as_slice()).is_ok() {
                continue;
            }
            add_body(&mut by_object, &mut bodies, &sheet, body);
        }
        // Surfaces open at several holes (a tube), or that close less one
        // input polygon: their shells.
        for (members, shell) in holed_shells(&pieces.polygons, &owners, &pieces.input_of) {
            add_body(&mut by_object, &mut bodies, &members, shell);
        }
        for (k, p) in pieces.polygons.iter().enumerate() {
            if pieces.casts_shadows[k] && !covered[k] {
                by_object[objects[k] as usize].0.push(polygons.len());
                polygons.push((p, bounds(&p.vertices_f64())));
            }
        }
        let boxes = polygons
            .iter()
            .enumerate()
            .map(|(k, (_, b))| (Item::Polygon(k), *b))
            .chain(
                bodies
                    .iter()
                    .enumerate()
                    .map(|(k, (_, b))| (Item::Body(k), *b)),
            );
        let index = GridIndex::new(boxes.collect());
        Self {
            polygons,
            bodies,
            by_object,
            index,
        }
    }

    /// The blockers whose boxes meet the box around `region` and `light`:
    /// every one a segment between them can cross.
    pub(crate) fn near(
        &self,
        region: &ConvexPolygon,
        light: &AreaSource,
    ) -> (Vec<&ConvexPolygon>, Vec<&Body>) {
        let (around, shaft) = between(region, light);
        let items = self.index.meeting(&around);
        self.resolve(items.into_iter(), &shaft)
    }

    /// The blockers of `objects` whose boxes meet the box around `region`
    /// and `light`.
    fn of_objects(
        &self,
        objects: &[u32],
        region: &ConvexPolygon,
        light: &AreaSource,
    ) -> (Vec<&ConvexPolygon>, Vec<&Body>) {
        let (_, shaft) = between(region, light);
        let mut items: Vec<Item> = objects
            .iter()
            .filter_map(|&o| self.by_object.get(o as usize))
            .flat_map(|(ps, bs)| {
                ps.iter()
                    .map(|&k| Item::Polygon(k))
                    .chain(bs.iter().map(|&k| Item::Body(k)))
            })
            .collect();
        items.sort_unstable();
        items.dedup();
        self.resolve(items.into_iter(), &shaft)
    }

    /// The items that reach into the shaft between a region and a light
    /// (its box first).
    fn resolve(
        &self,
        items: impl Iterator<Item = Item>,
        shaft: &Shaft,
    ) -> (Vec<&ConvexPolygon>, Vec<&Body>) {
        let (mut polygons, mut bodies) = (Vec::new(), Vec::new());
        for item in items {
            match item {
                Item::Polygon(k) => {
                    let (polygon, _) = &self.polygons[k];
                    if !shaft.misses(&polygon.vertices_f64()) {
                        polygons.push(*polygon);
                    }
                }
                Item::Body(k) => {
                    let (body, b) = &self.bodies[k];
                    if !shaft.misses_box(&[b.0, b.1]) {
                        bodies.push(body);
                    }
                }
            }
        }
        (polygons, bodies)
    }
}

/// The box around a region and a light, and the shaft between them.
fn between(region: &ConvexPolygon, light: &AreaSource) -> (Bounds, Shaft) {
    let corners = region.vertices_f64();
    let source: Vec<[f64; 3]> = light.vertices().map(|p| p.to_f64()).collect();
    let around = bounds(&corners.iter().chain(&source).copied().collect::<Vec<_>>());
    (around, Shaft::new(&corners, &source))
}

fn bounds(points: &[[f64; 3]]) -> Bounds {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// Boxes in a uniform grid of cells over their union, to find those that
/// may meet a query box without looking at all.
struct GridIndex {
    origin: [f64; 3],
    cell: [f64; 3],
    cells: HashMap<[usize; 3], Vec<Item>>,
    /// Boxes spanning too many cells: checked for every query.
    wide: Vec<Item>,
    all: Vec<Item>,
}

impl GridIndex {
    fn new(boxes: Vec<(Item, Bounds)>) -> Self {
        let whole = bounds(
            &boxes
                .iter()
                .flat_map(|(_, (a, b))| [*a, *b])
                .collect::<Vec<_>>(),
        );
        let origin = whole.0;
        let cell =
            std::array::from_fn(|k| ((whole.1[k] - whole.0[k]) / GRID_CELLS as f64).max(1.0));
        let mut index = Self {
            origin,
            cell,
            cells: HashMap::new(),
            wide: Vec::new(),
            all: boxes.iter().map(|(item, _)| *item).collect(),
        };
        for (item, b) in boxes {
            let [lo, hi] = index.span(&b);
            if (0..3).map(|k| hi[k] - lo[k] + 1).product::<usize>() > MAX_SPAN {
                index.wide.push(item);
                continue;
            }
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        index.cells.entry([x, y, z]).or_default().push(item);
                    }
                }
            }
        }
        index
    }

    /// The cells a box covers, low and high (clamped to the grid).
    fn span(&self, (a, b): &Bounds) -> [[usize; 3]; 2] {
        let at = |v: f64, k: usize| {
            (((v - self.origin[k]) / self.cell[k]).floor().max(0.0) as usize).min(GRID_CELLS)
        };
        [
            std::array::from_fn(|k| at(a[k], k)),
            std::array::from_fn(|k| at(b[k], k)),
        ]
    }

    /// The items whose cells meet the box (a superset of those whose boxes
    /// do), each once, in order.
    fn meeting(&self, around: &Bounds) -> Vec<Item> {
        let [lo, hi] = self.span(around);
        if (0..3).map(|k| hi[k] - lo[k] + 1).product::<usize>() > MAX_SPAN {
            return self.all.clone();
        }
        let mut items = self.wide.clone();
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    if let Some(list) = self.cells.get(&[x, y, z]) {
                        items.extend_from_slice(list);
                    }
                }
            }
        }
        items.sort_unstable();
        items.dedup();
        items
    }
}

/// The lights among `lights` (bit `i` for `areas[i]`) proven to be hidden
/// from all of `region` (a face of a receiver, two-sided or not) past the
/// blockers of `objects` (those a DM cell lists).
pub(crate) fn proven_dark_past(
    region: &ConvexPolygon,
    two_sided: bool,
    lights: u32,
    areas: &[&AreaSource],
    occluders: &Occluders<'_>,
    objects: &[u32],
) -> u32 {
    let mut dark = 0;
    for (i, light) in areas.iter().enumerate() {
        if lights & (1 << i) == 0 {
            continue;
        }
        let (polygons, bodies) = occluders.of_objects(objects, region, light);
        if sees_none(region, two_sided, light, &polygons, &bodies) {
            dark |= 1 << i;
        }
    }
    dark
}
