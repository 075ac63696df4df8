//! Building winged-edge meshes from polygons.

use super::planes::PlaneTable;
use super::{Edge, Face, VertexKey, VertexPosition, WingedMesh};
use crate::predicates::{self, Side};
use crate::{ConvexPolygon, EdgeKey, Error, FaceKey, GridPoint, ImplicitPoint, Plane};
use slotmap::SlotMap;

impl<E> Edge<E> {
    /// An edge `start -> end` with `face` on its left and the outside on its
    /// right, its wings still to be linked by the builder.
    fn unlinked(start: VertexKey, end: VertexKey, face: FaceKey, line: Plane, data: E) -> Self {
        Self {
            start,
            end,
            left: Some(face),
            right: None,
            left_prev: EdgeKey::default(),
            left_next: EdgeKey::default(),
            right_prev: EdgeKey::default(),
            right_next: EdgeKey::default(),
            line,
            right_in_front: true,
            data,
        }
    }
}

impl<F: Clone, E: Clone> WingedMesh<F, E> {
    /// A mesh of one face: the polygon, its edges carrying `edge_data`.
    pub fn from_polygon(polygon: &ConvexPolygon, face_data: F, edge_data: E) -> Self {
        let mut mesh = Self {
            vertices: SlotMap::with_key(),
            planes: PlaneTable::default(),
            edges: SlotMap::with_key(),
            faces: SlotMap::with_key(),
            supports: Vec::new(),
        };
        let support = mesh.planes.intern(*polygon.support());
        mesh.supports.push(support);
        let n = polygon.len();
        let vertices: Vec<VertexKey> = (0..n)
            .map(|i| {
                let position = match polygon.vertex_grid_point(i) {
                    Some(p) => VertexPosition::Grid(p),
                    None => {
                        let [a, b, c] = polygon.vertex_planes(i);
                        VertexPosition::Implicit(
                            ImplicitPoint::new(*a, *b, *c).expect("a polygon's vertex is a point"),
                        )
                    }
                };
                mesh.insert_vertex(position, EdgeKey::default())
            })
            .collect();
        let face = mesh.faces.insert(Face {
            plane: 0,
            edge: EdgeKey::default(),
            data: face_data,
        });
        let edges: Vec<EdgeKey> = (0..n)
            .map(|i| {
                mesh.edges.insert(Edge::unlinked(
                    vertices[i],
                    vertices[(i + 1) % n],
                    face,
                    *polygon.edge(i),
                    edge_data.clone(),
                ))
            })
            .collect();
        for i in 0..n {
            let (prev, next) = (edges[(i + n - 1) % n], edges[(i + 1) % n]);
            let e = &mut mesh.edges[edges[i]];
            e.left_prev = prev;
            e.left_next = next;
            // The outside walks the boundary the other way.
            e.right_prev = next;
            e.right_next = prev;
            mesh.vertices[vertices[i]].edge = edges[i];
        }
        mesh.faces[face].edge = edges[0];
        mesh
    }

    /// A mesh glued from polygons with grid-point vertices: equal grid
    /// points are one vertex, and an edge used by two polygons (once in
    /// each direction) is one edge between their faces. Every polygon
    /// carries `face_data` and every edge `edge_data`.
    ///
    /// Errors: a vertex that is not a grid point, an edge used twice in
    /// the same direction or by more than two polygons (inconsistent
    /// orientation or a non-manifold edge), or a vertex where the boundary
    /// passes more than once.
    pub fn from_polygons(
        polygons: &[ConvexPolygon],
        face_data: F,
        edge_data: E,
    ) -> Result<Self, Error> {
        use std::collections::HashMap;
        let mut mesh = Self {
            vertices: SlotMap::with_key(),
            planes: PlaneTable::default(),
            edges: SlotMap::with_key(),
            faces: SlotMap::with_key(),
            supports: Vec::new(),
        };
        let mut vertex_of: HashMap<GridPoint, VertexKey> = HashMap::new();
        let mut edge_of: HashMap<(VertexKey, VertexKey), EdgeKey> = HashMap::new();
        let mut plane_of: HashMap<Plane, u32> = HashMap::new();
        let mut loops: Vec<(FaceKey, Vec<EdgeKey>)> = Vec::new();
        let mut polygon_of: HashMap<FaceKey, usize> = HashMap::new();
        for (index, polygon) in polygons.iter().enumerate() {
            let n = polygon.len();
            let mut keys = Vec::with_capacity(n);
            for i in 0..n {
                let p = polygon.vertex_grid_point(i).ok_or(Error::NonPlanar)?;
                let key = *vertex_of.entry(p).or_insert_with(|| {
                    mesh.insert_vertex(VertexPosition::Grid(p), EdgeKey::default())
                });
                keys.push(key);
            }
            let plane = *plane_of.entry(*polygon.support()).or_insert_with(|| {
                let support = mesh.planes.intern(*polygon.support());
                mesh.supports.push(support);
                (mesh.supports.len() - 1) as u32
            });
            let face = mesh.faces.insert(Face {
                plane,
                edge: EdgeKey::default(),
                data: face_data.clone(),
            });
            polygon_of.insert(face, index);
            let mut walk = Vec::with_capacity(n);
            for i in 0..n {
                let (a, b) = (keys[i], keys[(i + 1) % n]);
                if edge_of.contains_key(&(a, b)) {
                    return Err(Error::NonConvex);
                }
                let e = match edge_of.get(&(b, a)) {
                    Some(&e) if mesh.edges[e].right.is_none() => {
                        mesh.edges[e].right = Some(face);
                        // The left polygon's edge plane may be this face's
                        // support (a cube's neighbours): then pick another
                        // plane through the edge. Either way, record which
                        // side of it this face is on.
                        let left = mesh.edges[e].left.expect("glued edges have a left face");
                        let left_polygon = &polygons[polygon_of[&left]];
                        if mesh.edges[e].line.is_coincident(polygon.support()) {
                            let (Some(p), Some(q)) = (
                                polygon.vertex_grid_point(i),
                                polygon.vertex_grid_point((i + 1) % n),
                            ) else {
                                return Err(Error::NonPlanar);
                            };
                            mesh.edges[e].line = line_between(p, q, left_polygon, polygon)
                                .ok_or(Error::NonConvex)?;
                        }
                        let line = mesh.edges[e].line;
                        mesh.edges[e].right_in_front = (0..n)
                            .filter_map(|k| polygon.vertex_grid_point(k))
                            .map(|v| predicates::side_of_point(&line, v))
                            .any(|side| side == Side::Front);
                        e
                    }
                    Some(_) => return Err(Error::NonConvex),
                    None => mesh.edges.insert(Edge::unlinked(
                        a,
                        b,
                        face,
                        *polygon.edge(i),
                        edge_data.clone(),
                    )),
                };
                edge_of.insert((a, b), e);
                mesh.vertices[a].edge = e;
                walk.push(e);
            }
            mesh.faces[face].edge = walk[0];
            loops.push((face, walk));
        }
        for (face, walk) in &loops {
            let n = walk.len();
            for i in 0..n {
                mesh.set_next(walk[i], Some(*face), walk[(i + 1) % n]);
                mesh.set_prev(walk[(i + 1) % n], Some(*face), walk[i]);
            }
        }
        // The outside walks each boundary edge end -> start; at its start it
        // continues along the boundary edge that ends there.
        let mut boundary_ending_at: HashMap<VertexKey, EdgeKey> = HashMap::new();
        for (k, e) in &mesh.edges {
            if e.right.is_none() && boundary_ending_at.insert(e.end, k).is_some() {
                return Err(Error::NonConvex);
            }
        }
        let boundary: Vec<EdgeKey> = boundary_ending_at.values().copied().collect();
        for e in boundary {
            let start = mesh.edges[e].start;
            let next = *boundary_ending_at.get(&start).ok_or(Error::NonConvex)?;
            mesh.edges[e].right_next = next;
            mesh.edges[next].right_prev = e;
        }
        Ok(mesh)
    }
}

/// A plane through the segment `pq`, an edge shared by two polygons in
/// different planes, that is neither polygon's support plane, oriented with
/// `left` behind it. Small integer directions keep the coefficients within
/// the kernel's bounds.
fn line_between(
    p: GridPoint,
    q: GridPoint,
    left: &ConvexPolygon,
    right: &ConvexPolygon,
) -> Option<Plane> {
    const DIRECTIONS: [[i64; 3]; 7] = [
        [1, 0, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 1, 0],
        [1, 0, 1],
        [0, 1, 1],
        [1, 1, 1],
    ];
    let e = [
        i64::from(q.x) - i64::from(p.x),
        i64::from(q.y) - i64::from(p.y),
        i64::from(q.z) - i64::from(p.z),
    ];
    for d in DIRECTIONS {
        let normal = [
            e[1] * d[2] - e[2] * d[1],
            e[2] * d[0] - e[0] * d[2],
            e[0] * d[1] - e[1] * d[0],
        ];
        let Some(plane) = Plane::with_normal_through(normal, p) else {
            continue;
        };
        if plane.is_coincident(left.support()) || plane.is_coincident(right.support()) {
            continue;
        }
        // The left polygon has a vertex off the plane (it is not the
        // polygon's support): it decides the orientation.
        let side = (0..left.len())
            .filter_map(|k| left.vertex_grid_point(k))
            .map(|v| predicates::side_of_point(&plane, v))
            .find(|&s| s != Side::On)?;
        return Some(if side == Side::Back {
            plane
        } else {
            plane.flipped()
        });
    }
    None
}
