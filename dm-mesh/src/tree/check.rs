//! The DM-tree's invariants, for tests and fuzz targets.

use super::{LIGHT_UNIT, Node, ReceiverDm, clip, tracked};
use crate::critical::UnitPlanes;
use bsp_core::{Plane, PolygonSide, Side, Split};

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Checks the tree against the mesh and itself: every leaf's face
    /// exists, points back at it and lies in the leaf's cell (the receiver
    /// clipped by the lines on its path, decided exactly), every node's line
    /// cuts its cell, the faces cover the receiver's area, every face is a
    /// leaf, parent links and the units' node lists are right, cells list
    /// only live units, construction lines of the receiver itself (light
    /// planes, tiles) are above every other node, the mesh's own
    /// invariants hold, and its table of planes holds the vertices' planes
    /// and the nodes' lines, nothing more.
    pub fn check_invariants(&self) -> Result<(), String> {
        self.mesh.check_invariants()?;
        self.mesh
            .check_plane_holds(self.nodes.iter().filter_map(|node| match node {
                Node::Split { line, .. } => Some(*line),
                _ => None,
            }))?;
        let mut leaves = 0;
        let mut area = 0.0;
        let mut stack = vec![(self.root, self.polygon.clone(), false)];
        while let Some((n, cell, below_unit)) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf(f) => {
                    leaves += 1;
                    let face = self.mesh.face(*f).ok_or("leaf without face")?;
                    if face.data.leaf != n {
                        return Err(format!("face of leaf {n} points at {}", face.data.leaf));
                    }
                    let live = |u: u32| self.unit(u).is_some();
                    if face.data.entries.iter().any(|e| !live(e.unit)) {
                        return Err(format!("leaf {n} lists a removed unit"));
                    }
                    if face.data.culled.iter().any(|u| !live(*u)) {
                        return Err(format!("leaf {n} culled a removed unit"));
                    }
                    for v in self.mesh.face_vertices(*f) {
                        if !self.mesh.contains_vertex(v) {
                            return Err(format!("leaf {n}: a face vertex is missing"));
                        }
                        if cell
                            .edges()
                            .any(|e| self.mesh.vertex_side(v, e) == Some(Side::Front))
                        {
                            return Err(format!("leaf {n}: a face vertex outside its cell"));
                        }
                    }
                    area += self
                        .mesh
                        .face_polygon(*f, 0)
                        .map_err(|e| e.to_string())?
                        .area();
                }
                Node::Split {
                    line,
                    unit,
                    back,
                    front,
                } => {
                    if *unit == LIGHT_UNIT && below_unit {
                        return Err(format!("node {n}: a receiver line below a unit's"));
                    }
                    for child in [back, front] {
                        if self.parent[*child as usize] != n {
                            return Err(format!("node {child}: parent is not {n}"));
                        }
                    }
                    if tracked(*unit) {
                        if self.unit(*unit).is_none() {
                            return Err(format!("node {n} of removed unit {unit}"));
                        }
                        let slot = self.slot[n as usize] as usize;
                        if self.unit_nodes(*unit).get(slot) != Some(&n) {
                            return Err(format!("node {n} missing from unit {unit}'s list"));
                        }
                    }
                    let (b, f) = match cell.split(self.mesh.plane(*line)) {
                        Split::Both(b, f) => (b, f),
                        _ => return Err(format!("node {n}: its line does not cut its cell")),
                    };
                    let below = below_unit || *unit != LIGHT_UNIT;
                    stack.push((*back, b, below));
                    stack.push((*front, f, below));
                }
                Node::Free => return Err(format!("free node {n} in the tree")),
            }
        }
        if leaves != self.cell_count() {
            return Err(format!("{leaves} leaves, {} faces", self.cell_count()));
        }
        let whole = self.polygon.area();
        if (area - whole).abs() > 1e-9 * whole {
            return Err(format!("faces cover {area} of {whole}"));
        }
        for (u, list) in self.unit_nodes.iter().enumerate() {
            for &n in list {
                match self.nodes.get(n as usize) {
                    Some(Node::Split { unit, .. }) if *unit as usize == u => {}
                    _ => return Err(format!("unit {u} lists node {n}, not its own")),
                }
            }
        }
        Ok(())
    }
}

impl<K: Copy + Ord> ReceiverDm<K> {
    /// Checks every cell's list against the units' planes (`planes(key,
    /// light)`), exactly: a cell lists a unit only if it lies in one of the
    /// unit's penumbra volumes, wholly inside or wholly outside its umbra as
    /// marked, and, outside the umbra, crossed by none of its internal
    /// discontinuities within their wedges; a cell whose area meets a
    /// unit's penumbra region and does not list it has culled it (and is in
    /// another's umbra) or is not reached by its light.
    pub(crate) fn check_lists<'p>(
        &self,
        planes: impl Fn(K, u8) -> &'p UnitPlanes,
    ) -> Result<(), String> {
        for (f, cell) in self.cells() {
            let polygon = self.mesh.face_polygon(f, 0).map_err(|e| e.to_string())?;
            for (u, (key, light)) in self.units() {
                let p = planes(key, light);
                let l = usize::from(light);
                let inside = |planes: &[Plane]| {
                    planes
                        .iter()
                        .all(|q| polygon.classify(q) == PolygonSide::Back)
                };
                let entry = cell.entries.iter().find(|e| e.unit == u);
                let Some(entry) = entry else {
                    let meets = p
                        .volumes
                        .penumbra
                        .iter()
                        .any(|part| clip(&polygon, part).is_some());
                    let excused =
                        cell.unreached(l) || (cell.culled.contains(&u) && cell.in_umbra(l));
                    if meets && !excused {
                        return Err(format!("a cell meets unit {u}'s penumbra, not listing it"));
                    }
                    continue;
                };
                if !p.volumes.penumbra.iter().any(|part| inside(part)) {
                    return Err(format!("a cell lists unit {u} outside its penumbra"));
                }
                let umbra = p.volumes.umbra.as_deref();
                match (entry.umbra.is_none(), umbra) {
                    (false, Some(umbra)) if inside(umbra) => {
                        if entry.umbra != p.umbra_sides {
                            return Err(format!("a cell hides other sides than unit {u}'s umbra"));
                        }
                    }
                    (false, _) => return Err(format!("a cell in unit {u}'s umbra is not")),
                    (true, Some(umbra)) if clip(&polygon, umbra).is_some() => {
                        return Err(format!("a cell straddles unit {u}'s umbra"));
                    }
                    (true, _) => {
                        for c in &p.internal {
                            let crossed = polygon.classify(&c.plane) == PolygonSide::Both
                                && clip(&polygon, &c.wedge).is_some_and(|part| {
                                    part.classify(&c.plane) == PolygonSide::Both
                                });
                            if crossed {
                                return Err(format!(
                                    "an internal discontinuity of unit {u} crosses a cell"
                                ));
                            }
                        }
                    }
                }
            }
        }
        Ok(())
    }
}
