//! Output points put back onto the input polygons they lie on.
//!
//! The kernel works on the input snapped to a grid, so the corners of a
//! polygon's fragments lie on its snapped copy: within half a grid step of
//! the input polygon, not on it, and their areas add up to the snapped
//! copy's area. Written as they are, a small or thin polygon's fragments
//! miss its area by a visible fraction (a needle 150 grid steps wide, by
//! 6e-4).
//!
//! Planar polygons are mapped back exactly: each point of the snapped copy
//! goes where a map taking every snapped corner (and corner welded into a
//! side) to its input place, and every snapped side onto the input side,
//! takes it: bilinear for a convex quad in one piece, otherwise affine on
//! each triangle fanned from the polygon's convex pieces (of up to 1024
//! corners in all). Either moves each point by an average of its corners'
//! moves, however thin the polygon (the projective map through a quad's
//! corners, which would keep every line straight, moves the middle of a
//! needle by hundreds of grid steps). Within a piece the outlines are
//! conforming (each lists every vertex on its sides), and across pieces
//! the map is affine, so lines stay straight where one piece's vertex lies
//! inside another's side: with each vertex placed on the input polygon the
//! fragments still share their sides, and tile the input polygon exactly,
//! up to the rounding of their coordinates; a fragment corner at a polygon
//! corner is written as the input has it. The map works in the coordinate
//! plane that the input polygon's plane projects onto best, so a snapped
//! polygon bent into triangles maps onto the input plane as well. A
//! polygon whose map would turn a face over (a sliver thinner than its
//! corners' moves), and a polygon that is not planar, are written as
//! snapped.
//!
//! Nothing decided in the exact kernel changes: the map only moves where
//! the output coordinates are written, by at most about a grid step.

use std::collections::{HashMap, HashSet};

use bsp_core::{ConvexPolygon, Grid, GridPoint, VertexPosition};
use smallvec::SmallVec;

use crate::mesh::OutputMesh;
use crate::vec3::{cross, dot, norm, sub};
use crate::weld::Weld;

mod plane_map;

use plane_map::PlaneMap;

/// A planar input polygon counts as planar when its corners lie this close
/// to their mean plane, relative to its size.
const PLANARITY: f64 = 1e-9;

/// Per input polygon, the map from its snapped copy back onto it.
#[derive(Debug, Clone)]
pub struct InputFrames {
    grid: Grid,
    frames: Vec<Option<Box<Frame>>>,
}

/// One polygon's corners, snapped and as input, and the map between them.
#[derive(Debug, Clone)]
struct Frame {
    corners: SmallVec<[Corner; 4]>,
    /// The convex pieces the polygon was cut into, as indices of their
    /// corners in `corners`.
    pieces: Vec<SmallVec<[u16; 4]>>,
    /// `None` where no point moves: every snapped corner is its input
    /// corner (a scene on the grid), or the polygon is not mapped.
    map: Option<PlaneMap>,
    /// The input polygon's longest side.
    size: f64,
    /// The farthest any corner moved, snapped to input (world units).
    moved: f64,
}

/// A corner of an input polygon.
#[derive(Debug, Clone, Copy)]
struct Corner {
    /// Where it snapped.
    grid: GridPoint,
    /// As input (world units).
    input: [f64; 3],
}

impl InputFrames {
    /// No polygons yet; they will be snapped to `grid`.
    pub fn new(grid: Grid) -> Self {
        Self {
            grid,
            frames: Vec::new(),
        }
    }

    /// Adds the next input polygon: its corners as input (world units) and
    /// snapped, in the same order, and the other faces' corners welded into
    /// each of its sides (`inserted[i]` into the side from corner `i`, in
    /// order along it; see `weld`). A welded corner's input place is on
    /// the input side, where the weld found its input corner along it: the
    /// neighbour's corner, up to the weld's tolerance.
    /// `pieces` are the convex pieces the polygon was cut into: the map is
    /// affine on each (or bilinear on a lone quad), so that it keeps lines
    /// straight across the pieces' common sides, where one piece's vertex
    /// may lie inside the other's side.
    pub fn push(
        &mut self,
        input: &[[f64; 3]],
        snapped: &[GridPoint],
        inserted: &[Vec<Weld>],
        pieces: &[ConvexPolygon],
    ) {
        let n = input.len();
        let mut ring = Vec::with_capacity(n + inserted.iter().map(Vec::len).sum::<usize>());
        for (i, (&p, &g)) in input.iter().zip(snapped).enumerate() {
            ring.push((g, p));
            let Some(welded) = inserted.get(i) else {
                continue;
            };
            let q = input[(i + 1) % n];
            for w in welded {
                let t = w.along;
                ring.push((w.point, [0, 1, 2].map(|c| p[c] + t * (q[c] - p[c]))));
            }
        }
        let pieces: Vec<Vec<GridPoint>> = pieces
            .iter()
            .map(|p| {
                (0..p.len())
                    .filter_map(|k| p.vertex_grid_point(k))
                    .collect()
            })
            .collect();
        self.frames
            .push(Frame::new(&self.grid, &ring, &pieces).map(Box::new));
    }

    /// Input polygon `source` moved: its snapped copy by `units` grid
    /// units, the input by `by` world units.
    pub fn translate(&mut self, source: u32, units: [i64; 3], by: [f64; 3]) {
        let Some(Some(frame)) = self.frames.get_mut(source as usize) else {
            return;
        };
        let moved = |g: GridPoint| {
            let g = g.to_i64();
            GridPoint::new(g[0] + units[0], g[1] + units[1], g[2] + units[2]).ok()
        };
        let mut ring = Vec::with_capacity(frame.corners.len());
        for corner in &frame.corners {
            let p = corner.input;
            // Off the grid: the pieces could not move there either.
            let Some(g) = moved(corner.grid) else {
                return;
            };
            ring.push((g, [p[0] + by[0], p[1] + by[1], p[2] + by[2]]));
        }
        let pieces: Option<Vec<Vec<GridPoint>>> = frame
            .pieces
            .iter()
            .map(|p| {
                p.iter()
                    .map(|&i| moved(frame.corners[i as usize].grid))
                    .collect()
            })
            .collect();
        let Some(pieces) = pieces else {
            return;
        };
        self.frames[source as usize] = Frame::new(&self.grid, &ring, &pieces).map(Box::new);
    }

    /// `mesh` with every face's corners moved onto its input polygon, and,
    /// per vertex of the result, the vertex of `mesh` it came from. A
    /// vertex shared by faces of polygons that place it differently is
    /// written once for each place.
    pub fn place(&self, mesh: OutputMesh) -> (OutputMesh, Vec<u32>) {
        if !mesh.faces.iter().any(|f| self.frame(f.source).is_some()) {
            let origin = (0..mesh.vertices.len() as u32).collect();
            return (mesh, origin);
        }
        let OutputMesh {
            vertices,
            mut faces,
        } = mesh;
        let mut placed: Vec<([f64; 3], f32)> = Vec::with_capacity(vertices.len());
        let mut origin: Vec<u32> = Vec::with_capacity(vertices.len());
        // Per vertex of `mesh`: its first placement; further ones (other
        // polygons' places for it) in `others`.
        let mut first = vec![u32::MAX; vertices.len()];
        let mut others: HashMap<(u32, [u64; 3]), u32> = HashMap::new();
        // Polygons whose map would turn a face over (a sliver thinner than
        // its corners' moves) are written as snapped.
        let turned: HashSet<u32> = faces
            .iter()
            .filter(|face| {
                self.frame(face.source).is_some_and(|frame| {
                    let corners = face.vertices.iter().map(|&v| vertices[v as usize].0);
                    frame.turns_over(&self.grid, corners)
                })
            })
            .map(|face| face.source)
            .collect();
        for face in &mut faces {
            let frame = self
                .frame(face.source)
                .filter(|_| !turned.contains(&face.source));
            for slot in &mut face.vertices {
                let v = *slot;
                let (p, e) = vertices[v as usize];
                let q = frame.map_or(p, |f| f.place(&self.grid, p));
                let bits = q.map(f64::to_bits);
                let f = first[v as usize];
                *slot = if f == u32::MAX {
                    first[v as usize] = placed.len() as u32;
                    placed.push((q, e));
                    origin.push(v);
                    placed.len() as u32 - 1
                } else if placed[f as usize].0.map(f64::to_bits) == bits {
                    f
                } else {
                    *others.entry((v, bits)).or_insert_with(|| {
                        placed.push((q, e));
                        origin.push(v);
                        placed.len() as u32 - 1
                    })
                };
            }
        }
        (
            OutputMesh {
                vertices: placed,
                faces,
            },
            origin,
        )
    }
}

impl InputFrames {
    /// The frame of input polygon `source`, if it moves points.
    fn frame(&self, source: u32) -> Option<&Frame> {
        self.frames
            .get(source as usize)
            .and_then(Option::as_deref)
            .filter(|f| f.map.is_some())
    }
}

impl Frame {
    /// Whether placing the face of `corners` (world units) would turn it
    /// over in the coordinate plane of the map: its doubled area changes
    /// sign by more than 1e-12 of the polygon's size squared. (A sliver
    /// the snapping made of a line of the input, three corners in line,
    /// comes out flat: that is right; and one far below a grid step may
    /// turn by a rounding.)
    fn turns_over(&self, grid: &Grid, corners: impl Iterator<Item = [f64; 3]>) -> bool {
        let Some(map) = &self.map else {
            return false;
        };
        let corners: SmallVec<[[f64; 3]; 8]> = corners.collect();
        let flat: SmallVec<[[f64; 2]; 8]> = corners.iter().map(|&p| map.flat(p)).collect();
        let before = doubled_area(&flat);
        // No point moves farther than a corner did, so the doubled area
        // changes by at most twice that times the perimeter: a face wider
        // than that cannot turn over, and is not placed twice.
        let perimeter: f64 = (0..flat.len())
            .map(|i| {
                let (a, b) = (flat[i], flat[(i + 1) % flat.len()]);
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
            })
            .sum();
        if before.abs() > 2.0 * self.moved * perimeter * (1.0 + 1e-6) {
            return false;
        }
        let placed: SmallVec<[[f64; 2]; 8]> = corners
            .iter()
            .map(|&p| map.flat(self.place(grid, p)))
            .collect();
        let after = doubled_area(&placed);
        after * before.signum() < -1e-12 * self.size * self.size
    }

    /// The frame of the polygon of `ring` corners (each snapped, and as
    /// input), in order, cut into `pieces` (their corners, ring points).
    fn new(grid: &Grid, ring: &[(GridPoint, [f64; 3])], pieces: &[Vec<GridPoint>]) -> Option<Self> {
        let mut corners: SmallVec<[Corner; 4]> = SmallVec::new();
        for &(grid, input) in ring {
            match corners.last() {
                // A repeated input corner (it snaps to the same point).
                Some(c) if c.input == input => continue,
                // Two corners snapped to one: the snapped copy has fewer.
                Some(c) if c.grid == grid => return None,
                _ => corners.push(Corner { grid, input }),
            }
        }
        while corners.len() > 1
            && corners.first().map(|c| c.input) == corners.last().map(|c| c.input)
        {
            corners.pop();
        }
        if corners.len() > 1 && corners.first().map(|c| c.grid) == corners.last().map(|c| c.grid) {
            return None;
        }
        if corners.len() < 3 {
            return None;
        }
        let from: SmallVec<[[f64; 3]; 4]> = corners.iter().map(|c| grid.to_world(c.grid)).collect();
        let to: SmallVec<[[f64; 3]; 4]> = corners.iter().map(|c| c.input).collect();
        // Each piece's corners as ring indices.
        let pieces: Option<Vec<SmallVec<[u16; 4]>>> = pieces
            .iter()
            .map(|p| {
                p.iter()
                    .map(|g| corners.iter().position(|c| c.grid == *g).map(|i| i as u16))
                    .collect()
            })
            .collect();
        let pieces = pieces?;
        let exact = from == to;
        let map = if exact {
            None
        } else {
            PlaneMap::new(&from, &to, &pieces)
        };
        let n = to.len();
        let size = (0..n)
            .map(|i| norm(sub(to[i], to[(i + 1) % n])))
            .fold(0.0, f64::max);
        let moved = from
            .iter()
            .zip(&to)
            .map(|(p, q)| norm(sub(*p, *q)))
            .fold(0.0, f64::max);
        Some(Self {
            corners,
            pieces,
            map,
            size,
            moved,
        })
    }

    /// Where the point `p` (world units) of the snapped polygon's pieces
    /// lies on the input polygon.
    fn place(&self, grid: &Grid, p: [f64; 3]) -> [f64; 3] {
        let Some(map) = &self.map else {
            return p;
        };
        // A snapped corner, as closely as an implicit point's coordinates
        // come out (a fragment's corner is the meet of planes): the input
        // corner itself, the same for every polygon that has it.
        let at = grid.world_to_grid(p);
        let corner = |g: GridPoint| {
            let g = g.to_f64();
            (0..3).all(|a| (at[a] - g[a]).abs() <= VertexPosition::coordinate_error(g[a]))
        };
        match self.corners.iter().find(|c| corner(c.grid)) {
            Some(c) => c.input,
            None => map.apply(p),
        }
    }
}

/// The doubled signed area of a polygon.
fn doubled_area(corners: &[[f64; 2]]) -> f64 {
    let Some(&o) = corners.first() else {
        return 0.0;
    };
    let mut area = 0.0;
    for (i, a) in corners.iter().enumerate() {
        let b = corners[(i + 1) % corners.len()];
        area += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    }
    area
}

/// The unit normal of a planar polygon (counter-clockwise seen from its
/// front), `None` when it is degenerate or its corners stray from their
/// mean plane by more than [`PLANARITY`] of its size.
pub(crate) fn planar_normal(corners: &[[f64; 3]]) -> Option<[f64; 3]> {
    let n = corners.len();
    // Relative to corner 0: far from the origin the products of absolute
    // coordinates would cancel to noise.
    let &o = corners.first()?;
    let mut normal = [0.0; 3];
    for i in 0..n {
        let c = cross(sub(corners[i], o), sub(corners[(i + 1) % n], o));
        normal = [normal[0] + c[0], normal[1] + c[1], normal[2] + c[2]];
    }
    let length = norm(normal);
    if !(length > 0.0 && length.is_finite()) {
        return None;
    }
    let normal = normal.map(|x| x / length);
    let centroid = centroid(corners);
    let size = (0..n)
        .map(|i| norm(sub(corners[i], corners[(i + 1) % n])))
        .fold(0.0, f64::max);
    let planar = corners
        .iter()
        .all(|&p| dot(normal, sub(p, centroid)).abs() <= PLANARITY * size);
    planar.then_some(normal)
}

fn centroid(points: &[[f64; 3]]) -> [f64; 3] {
    points
        .iter()
        .fold([0.0; 3], |s, p| [s[0] + p[0], s[1] + p[1], s[2] + p[2]])
        .map(|x| x / points.len() as f64)
}
