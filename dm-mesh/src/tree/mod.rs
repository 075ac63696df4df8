//! One receiver's DM-tree: a 2D BSP whose leaves are the faces of a
//! winged-edge mesh (Chrysanthou & Slater).
//!
//! The root cell is the receiver polygon; its boundary edges bound the
//! subspace and are no nodes. Each light first splits the receiver by its
//! own plane (nothing arrives behind it). Then every *unit* (one occluder
//! under one light) is merged in: its single tree, a linear chain of the
//! penumbra volume's planes with the umbra chain at its back, is filtered
//! down the receiver's tree with the unit's region (the receiver clipped by
//! the penumbra planes) as Naylor's merge filters a linear tree, and at each
//! leaf it reaches the chain is grown in place: a plane that cuts the cell
//! becomes a node, the cell part in front keeps its list, and the innermost
//! part adds the occluder to its list (marked umbra past the umbra chain).
//! Only the planes that cut a cell make nodes, so every node's line spans
//! just its own cell (the sub-hyperplane is the mesh edge it made).
//!
//! A receiver many units reach is first cut into tiles
//! ([`ReceiverDm::tile`]): construction nodes like the light planes', never
//! removed, that keep every later subtree local.
//!
//! Every path from the root meets units in insertion order, so removing a
//! unit collapses the subtrees under its topmost nodes back into the cells
//! they were (merging faces, condensing straight vertices) and re-inserts
//! the later units into those cells only ([`ReceiverDm::remove_units`]).

use crate::cell::{Cell, CellClass, Entry};
use crate::critical::{Critical, UnitPlanes};
use area_shadow::{AreaSource, SourceSide};
use bsp_core::GridPoint;
use bsp_core::predicates::{self, Side};
use bsp_core::{ConvexPolygon, FaceKey, FaceSplit, Plane, PolygonSide, Split, WingedMesh};

mod removal;

/// The unit number of the light-plane splits made when a receiver is
/// created (they are never removed).
pub(crate) const LIGHT_UNIT: u32 = u32::MAX;

/// A node of the 2D BSP.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Node {
    /// A cell: a face of the mesh.
    Leaf(FaceKey),
    /// A split of the node's cell by `line` (the receiver cut by that
    /// plane): `back` behind it, `front` in front.
    Split {
        line: Plane,
        unit: u32,
        back: u32,
        front: u32,
    },
    /// A free arena slot.
    Free,
}

/// How much of a light can reach a receiver's front (or either side, when
/// it is two-sided).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Reach {
    /// None: every cell is in umbra for it.
    None,
    /// The receiver's plane cuts the light: unoccluded cells see part.
    Part,
    /// All of it, where nothing blocks.
    All,
}

/// What the receiver's units are: one occluder key under one light.
pub(crate) type UnitRef<K> = (K, u8);

/// One receiver's DM-tree and its cells.
#[derive(Debug, Clone)]
pub struct ReceiverDm<K> {
    polygon: ConvexPolygon,
    mesh: WingedMesh<Cell, ()>,
    nodes: Vec<Node>,
    /// The parent of each node (the root's is itself).
    parent: Vec<u32>,
    free: Vec<u32>,
    /// Per unit, the leaves where its single tree was grown (its topmost
    /// nodes, or cells it only listed or was culled in). Entries go stale
    /// when a collapse frees them and are checked before use.
    roots: Vec<Vec<u32>>,
    root: u32,
    reach: Vec<Reach>,
    units: Vec<Option<UnitRef<K>>>,
    next_unit: u32,
    /// Faces whose shape or list changed since [`Self::take_touched`]
    /// (some may be gone since).
    touched: Vec<FaceKey>,
    /// Whether changes are recorded in `touched` (not before the first
    /// illumination, which looks at every face anyway).
    tracking: bool,
}

/// The region of a unit on a receiver: `polygon` clipped by `planes`.
pub(crate) fn clip(polygon: &ConvexPolygon, planes: &[Plane]) -> Option<ConvexPolygon> {
    let mut piece = polygon.clone();
    for plane in planes {
        piece = match piece.split(plane) {
            Split::Back => piece,
            Split::Both(back, _) => back,
            Split::Front | Split::Coplanar(_) => return None,
        };
    }
    Some(piece)
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// A receiver's tree before any occluder: the light planes' splits.
    pub(crate) fn new(polygon: ConvexPolygon, two_sided: bool, lights: &[AreaSource]) -> Self {
        let mesh = WingedMesh::from_polygon(&polygon, Cell::default(), ());
        let face = mesh.faces().next().map(|(k, _)| k).expect("one face");
        let mut dm = Self {
            polygon,
            mesh,
            nodes: vec![Node::Leaf(face)],
            parent: vec![0],
            free: Vec::new(),
            roots: Vec::new(),
            root: 0,
            reach: Vec::with_capacity(lights.len()),
            units: Vec::new(),
            next_unit: 0,
            touched: Vec::new(),
            tracking: false,
        };
        for (i, light) in lights.iter().enumerate() {
            let reach = match light.side_of(dm.polygon.support()) {
                SourceSide::In => Reach::None,
                SourceSide::Front => Reach::All,
                SourceSide::Back if two_sided => Reach::All,
                SourceSide::Back => Reach::None,
                SourceSide::Both => Reach::Part,
            };
            dm.reach.push(reach);
            let bit = 1_u32 << i;
            let leaves = dm.leaves(dm.root);
            for leaf in leaves {
                if reach == Reach::None {
                    dm.cell_mut(leaf).unreached |= bit;
                    continue;
                }
                match dm.split_leaf(leaf, light.support(), LIGHT_UNIT) {
                    Ok((back, _)) => dm.cell_mut(back).unreached |= bit,
                    Err(Side::Back) => dm.cell_mut(leaf).unreached |= bit,
                    Err(_) => {}
                }
            }
        }
        dm
    }

    /// Splits a receiver that has no unit yet into about `2^depth` tiles
    /// by construction lines (the receiver cut by axis-aligned planes
    /// through grid points, halving the longer side of the receiver's box
    /// each time), so that the tree starts balanced: a unit's discontinuity
    /// nodes then stay within the tiles its region meets, and removing it
    /// collapses and re-merges only there, not half of a big receiver.
    /// The tile nodes are never removed, like the light planes' splits.
    pub(crate) fn tile(&mut self, depth: u32) {
        if depth == 0 || !self.units.is_empty() {
            return;
        }
        let n = self.polygon.support().normal();
        // Cut across the axes other than the normal's dominant one.
        let dominant = (0..3)
            .max_by_key(|&a| (n[a].unsigned_abs(), std::cmp::Reverse(a)))
            .unwrap_or(1);
        let axes = [(dominant + 1) % 3, (dominant + 2) % 3];
        let mut lo = [i64::MAX; 2];
        let mut hi = [i64::MIN; 2];
        for k in 0..self.polygon.len() {
            let Some(g) = self.polygon.vertex_grid_point(k) else {
                return;
            };
            let g = g.to_i64();
            for (i, &a) in axes.iter().enumerate() {
                lo[i] = lo[i].min(g[a]);
                hi[i] = hi[i].max(g[a]);
            }
        }
        for leaf in self.leaves(self.root) {
            self.tile_leaf(leaf, axes, lo, hi, depth);
        }
    }

    fn tile_leaf(&mut self, leaf: u32, axes: [usize; 2], lo: [i64; 2], hi: [i64; 2], depth: u32) {
        let mut stack = vec![(leaf, lo, hi, depth)];
        while let Some((leaf, lo, hi, depth)) = stack.pop() {
            if depth == 0 {
                continue;
            }
            let i = if hi[0] - lo[0] >= hi[1] - lo[1] { 0 } else { 1 };
            if hi[i] - lo[i] < 2 {
                continue;
            }
            let c = lo[i] + (hi[i] - lo[i]) / 2;
            // The plane x_a = c through three grid points, with the lower
            // half behind it.
            let at = |da: i32, db: i32| {
                let mut p = [0_i32; 3];
                p[axes[i]] = c as i32;
                p[axes[1 - i]] = da;
                p[3 - axes[0] - axes[1]] = db;
                GridPoint {
                    x: p[0],
                    y: p[1],
                    z: p[2],
                }
            };
            let Some(plane) = Plane::through(at(0, 0), at(1, 0), at(0, 1)) else {
                continue;
            };
            let mut below = at(0, 0);
            match axes[i] {
                0 => below.x -= 1,
                1 => below.y -= 1,
                _ => below.z -= 1,
            }
            let plane = if predicates::side_of_point(&plane, below) == Side::Front {
                plane.flipped()
            } else {
                plane
            };
            let (mut lower_hi, mut upper_lo) = (hi, lo);
            lower_hi[i] = c;
            upper_lo[i] = c;
            match self.split_leaf(leaf, &plane, LIGHT_UNIT) {
                Ok((back, front)) => {
                    stack.push((back, lo, lower_hi, depth - 1));
                    stack.push((front, upper_lo, hi, depth - 1));
                }
                Err(Side::Back) => stack.push((leaf, lo, lower_hi, depth - 1)),
                Err(_) => stack.push((leaf, upper_lo, hi, depth - 1)),
            }
        }
    }

    /// Whether no light reaches the receiver at all (no occluder can
    /// change anything on it).
    pub(crate) fn in_the_dark(&self) -> bool {
        self.reach.iter().all(|r| *r == Reach::None)
    }

    /// Forgets the changes so far and records those from now on (called by
    /// the first illumination, which looks at every face).
    pub(crate) fn start_tracking(&mut self) {
        self.touched.clear();
        self.tracking = true;
    }

    /// Whether some face changed since the last [`Self::take_touched`].
    pub(crate) fn has_touched(&self) -> bool {
        !self.touched.is_empty()
    }

    /// The faces changed since the last call (each once, those still
    /// there), and forgets them.
    pub(crate) fn take_touched(&mut self) -> Vec<FaceKey> {
        let mut out = std::mem::take(&mut self.touched);
        out.sort_unstable();
        out.dedup();
        out.retain(|f| self.mesh.face(*f).is_some());
        out
    }

    /// The receiver polygon.
    pub fn polygon(&self) -> &ConvexPolygon {
        &self.polygon
    }

    /// The winged-edge mesh of the cells.
    pub fn mesh(&self) -> &WingedMesh<Cell, ()> {
        &self.mesh
    }

    /// The cells (faces of the mesh) with their occluder lists.
    pub fn cells(&self) -> impl Iterator<Item = (FaceKey, &Cell)> + '_ {
        self.mesh.faces().map(|(k, f)| (k, &f.data))
    }

    /// What light `light` does to `cell` (a cell of this receiver).
    pub fn class(&self, cell: &Cell, light: usize) -> CellClass {
        if cell.in_umbra(light) {
            CellClass::Umbra
        } else if cell.occluded(light) || self.reach[light] == Reach::Part {
            CellClass::Penumbra
        } else {
            CellClass::Lit
        }
    }

    /// The occluder piece and light of a unit listed in a cell's entries.
    pub fn unit_source(&self, unit: u32) -> Option<(K, usize)> {
        self.unit(unit).map(|(k, l)| (k, usize::from(l)))
    }

    /// Inner nodes of the tree.
    pub fn node_count(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| matches!(n, Node::Split { .. }))
            .count()
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.mesh.counts().2
    }

    /// The occluder and light of a unit.
    pub(crate) fn unit(&self, unit: u32) -> Option<UnitRef<K>> {
        self.units.get(unit as usize).copied().flatten()
    }

    /// The units, in insertion order.
    pub(crate) fn units(&self) -> impl Iterator<Item = (u32, UnitRef<K>)> + '_ {
        self.units
            .iter()
            .enumerate()
            .filter_map(|(u, v)| v.map(|v| (u as u32, v)))
    }

    /// The recorded roots of `unit` (see [`Self::remove_units`]).
    fn roots_of(&mut self, unit: u32) -> &mut Vec<u32> {
        let u = unit as usize;
        if self.roots.len() <= u {
            self.roots.resize_with(u + 1, Vec::new);
        }
        &mut self.roots[u]
    }

    fn face_of(&self, leaf: u32) -> FaceKey {
        match self.nodes[leaf as usize] {
            Node::Leaf(f) => f,
            _ => unreachable!("not a leaf"),
        }
    }

    fn cell_mut(&mut self, leaf: u32) -> &mut Cell {
        let f = self.face_of(leaf);
        if self.tracking {
            self.touched.push(f);
        }
        self.mesh.face_data_mut(f).expect("a leaf's face exists")
    }

    fn cell(&self, leaf: u32) -> &Cell {
        &self
            .mesh
            .face(self.face_of(leaf))
            .expect("a leaf's face")
            .data
    }

    fn alloc(&mut self, node: Node, parent: u32) -> u32 {
        match self.free.pop() {
            Some(k) => {
                self.nodes[k as usize] = node;
                self.parent[k as usize] = parent;
                k
            }
            None => {
                self.nodes.push(node);
                self.parent.push(parent);
                (self.nodes.len() - 1) as u32
            }
        }
    }

    /// The leaves under `node`.
    fn leaves(&self, node: u32) -> Vec<u32> {
        let mut out = Vec::new();
        let mut stack = vec![node];
        while let Some(n) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf(_) => out.push(n),
                Node::Split { back, front, .. } => {
                    stack.push(*front);
                    stack.push(*back);
                }
                Node::Free => {}
            }
        }
        out
    }

    /// Splits a leaf's cell by `plane`: the leaf becomes a node, and the
    /// new back and front leaves come back; `Err(side)` when the plane does
    /// not cut the cell, which lies on that side of it.
    fn split_leaf(&mut self, leaf: u32, plane: &Plane, unit: u32) -> Result<(u32, u32), Side> {
        let face = self.face_of(leaf);
        let (back, front) = match self.mesh.split_face(face, plane) {
            FaceSplit::Split { back, front, .. } => (back, front),
            FaceSplit::NotSplit(side) => return Err(side),
        };
        let b = self.alloc(Node::Leaf(back), leaf);
        let f = self.alloc(Node::Leaf(front), leaf);
        self.nodes[leaf as usize] = Node::Split {
            line: *plane,
            unit,
            back: b,
            front: f,
        };
        self.cell_mut(b).leaf = b;
        self.cell_mut(f).leaf = f;
        Ok((b, f))
    }

    /// Filters `piece` (inside `node`'s cell) down to the leaves it covers
    /// with area, each with its part.
    fn descend(&self, node: u32, piece: ConvexPolygon) -> Vec<(u32, ConvexPolygon)> {
        let mut out = Vec::new();
        let mut stack = vec![(node, piece)];
        while let Some((n, piece)) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf(_) => out.push((n, piece)),
                Node::Split {
                    line, back, front, ..
                } => match piece.split(line) {
                    Split::Back => stack.push((*back, piece)),
                    Split::Front => stack.push((*front, piece)),
                    Split::Both(b, f) => {
                        stack.push((*front, f));
                        stack.push((*back, b));
                    }
                    Split::Coplanar(_) => {}
                },
                Node::Free => {}
            }
        }
        out
    }

    /// Appends a unit (occluder `key` under light `light`, with its volume
    /// planes) and merges its single tree in. Returns its unit number.
    pub(crate) fn insert(&mut self, key: K, light: u8, planes: &UnitPlanes) -> u32 {
        let unit = self.next_unit;
        self.next_unit += 1;
        debug_assert_eq!(self.units.len(), unit as usize);
        self.units.push(Some((key, light)));
        self.merge_unit(self.root, None, unit, light, planes);
        unit
    }

    /// Merges unit `unit`'s single tree into the subtree at `node`, whose
    /// cell is `cell` (`None`: the whole receiver).
    fn merge_unit(
        &mut self,
        node: u32,
        cell: Option<&ConvexPolygon>,
        unit: u32,
        light: u8,
        planes: &UnitPlanes,
    ) {
        if self.reach[usize::from(light)] == Reach::None {
            return;
        }
        for part in &planes.volumes.penumbra {
            // The quick reject: the receiver (or cell) clipped by the
            // penumbra planes, exactly.
            let Some(mut region) = clip(&self.polygon, part) else {
                continue;
            };
            if let Some(cell) = cell {
                let Some(inside) = clip(&region, cell.edges()) else {
                    continue;
                };
                region = inside;
            }
            for (leaf, piece) in self.descend(node, region) {
                let umbra = planes.volumes.umbra.as_deref();
                self.grow_leaf(leaf, &piece, part, umbra, unit, light);
                if !planes.internal.is_empty() {
                    self.grow_internal(leaf, &planes.internal, unit);
                }
            }
        }
    }

    /// Grows the unit's single tree at one leaf whose cell meets the
    /// unit's penumbra region in `piece` (with area).
    fn grow_leaf(
        &mut self,
        leaf: u32,
        piece: &ConvexPolygon,
        penumbra: &[Plane],
        umbra: Option<&[Plane]>,
        unit: u32,
        light: u8,
    ) {
        let cell = self.cell(leaf);
        if cell.has_unit(unit) || cell.unreached(usize::from(light)) {
            return;
        }
        let in_umbra = cell.in_umbra(usize::from(light));
        self.roots_of(unit).push(leaf);
        if in_umbra {
            // Umbra already: the occluder changes nothing here, unless the
            // occluder making the umbra goes; remember it for then.
            self.cell_mut(leaf).culled.push(unit);
            return;
        }
        let Some(inner) = self.chain(leaf, penumbra, unit) else {
            return;
        };
        self.cell_mut(inner).add(Entry {
            unit,
            light,
            umbra: false,
        });
        let Some(umbra) = umbra else { return };
        if clip(piece, umbra).is_none() {
            return;
        }
        if let Some(core) = self.chain(inner, umbra, unit) {
            self.cell_mut(core).add(Entry {
                unit,
                light,
                umbra: true,
            });
        }
    }

    /// Splits the cells of the subtree at `node` that list `unit` outside
    /// its umbra by its internal discontinuities, each where its wedge
    /// crosses the cell.
    fn grow_internal(&mut self, node: u32, internal: &[Critical], unit: u32) {
        let mut cells: Vec<(u32, ConvexPolygon)> = self
            .leaves(node)
            .into_iter()
            .filter(|&n| {
                self.cell(n)
                    .entries
                    .iter()
                    .any(|e| e.unit == unit && !e.umbra)
            })
            .filter_map(|n| {
                let polygon = self.mesh.face_polygon(self.face_of(n), 0).ok()?;
                Some((n, polygon))
            })
            .collect();
        for critical in internal {
            let mut next = Vec::with_capacity(cells.len());
            for (leaf, polygon) in cells {
                // The plane must cut the cell (cheap, no polygon made),
                // and then the cell's part inside the wedge.
                let crosses = polygon.classify(&critical.plane) == PolygonSide::Both
                    && clip(&polygon, &critical.wedge)
                        .is_some_and(|part| part.classify(&critical.plane) == PolygonSide::Both);
                if !crosses {
                    next.push((leaf, polygon));
                    continue;
                }
                // The cell's polygon and its face split alike (the same
                // exact predicates on the same vertices).
                match (
                    polygon.split(&critical.plane),
                    self.split_leaf(leaf, &critical.plane, unit).ok(),
                ) {
                    (Split::Both(b, f), Some((back, front))) => {
                        next.extend([(back, b), (front, f)])
                    }
                    (_, Some((back, front))) => {
                        for n in [back, front] {
                            if let Ok(p) = self.mesh.face_polygon(self.face_of(n), 0) {
                                next.push((n, p));
                            }
                        }
                    }
                    (_, None) => next.push((leaf, polygon)),
                }
            }
            cells = next;
        }
    }

    /// Splits the cell at `leaf` by `planes` in turn, following the back;
    /// the innermost leaf, or `None` if a plane leaves the cell in front.
    fn chain(&mut self, leaf: u32, planes: &[Plane], unit: u32) -> Option<u32> {
        let mut cur = leaf;
        for plane in planes {
            match self.split_leaf(cur, plane, unit) {
                Ok((back, _)) => cur = back,
                Err(Side::Front) => return None,
                Err(_) => {}
            }
        }
        Some(cur)
    }

    /// Checks the tree against the mesh: every leaf's face exists and
    /// points back at it, every face is a leaf, units on every path come in
    /// insertion order, and the mesh's own invariants.
    pub fn check_invariants(&self) -> Result<(), String> {
        self.mesh.check_invariants()?;
        let mut leaves = 0;
        let mut stack = vec![(self.root, 0_u32)];
        while let Some((n, min)) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf(f) => {
                    leaves += 1;
                    let face = self.mesh.face(*f).ok_or("leaf without face")?;
                    if face.data.leaf != n {
                        return Err(format!("face of leaf {n} points at {}", face.data.leaf));
                    }
                    if face
                        .data
                        .entries
                        .iter()
                        .any(|e| self.unit(e.unit).is_none())
                    {
                        return Err(format!("leaf {n} lists a removed unit"));
                    }
                }
                Node::Split {
                    unit, back, front, ..
                } => {
                    let rank = if *unit == LIGHT_UNIT { 0 } else { unit + 1 };
                    if rank < min {
                        return Err(format!("node {n}: unit {unit} below a later unit"));
                    }
                    stack.push((*back, rank));
                    stack.push((*front, rank));
                }
                Node::Free => return Err(format!("free node {n} in the tree")),
            }
        }
        if leaves != self.cell_count() {
            return Err(format!("{leaves} leaves, {} faces", self.cell_count()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    #[test]
    fn tiles_partition_the_receiver() {
        let floor = ConvexPolygon::from_grid_points(
            &[g(-40, 0, 40), g(40, 0, 40), g(40, 0, -40), g(-40, 0, -40)],
            0,
        )
        .unwrap();
        let light =
            AreaSource::from_grid_points(&[g(-1, 10, -1), g(1, 10, -1), g(1, 10, 1), g(-1, 10, 1)])
                .unwrap();
        let mut dm: ReceiverDm<u32> = ReceiverDm::new(floor.clone(), false, &[light]);
        dm.tile(3);
        dm.check_invariants().unwrap();
        assert_eq!(dm.cell_count(), 8);
        let total: f64 = dm
            .cells()
            .map(|(f, _)| dm.mesh().face_polygon(f, 0).unwrap().area())
            .sum();
        assert!((total - floor.area()).abs() <= 1e-9 * floor.area());
        // The tiles are equal quarters and eighths of the floor.
        for (f, _) in dm.cells() {
            let area = dm.mesh().face_polygon(f, 0).unwrap().area();
            assert!((area - floor.area() / 8.0).abs() <= 1e-9 * floor.area());
        }
    }
}
