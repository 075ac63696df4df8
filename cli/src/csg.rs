//! `umbra csg`: BSP set operations on closed OBJ meshes.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use bsp_core::{BspSolid, Containment, ConvexPolygon, Grid, GridPoint, Plane, Region, Side};
use svbsp::{BalancedOptions, IndexedMesh, SetOp, balanced_solid_labelled, boundary};

use crate::decompose::{GRID_MARGIN, convex_pieces};
use crate::error::{Error, Result};
use crate::obj::ObjMesh;
use crate::winding::Surface;

/// Computes `A op B` for two closed meshes read from `a_path` and
/// `b_path` (named in errors): the closed, T-junction-free boundary, with
/// its vertices in world coordinates.
///
/// Each solid's BSP labels its empty cells by the surface's winding
/// number there (module `winding`), so that inputs whose snapped surfaces
/// fold or cross themselves (features finer than a few grid steps: an
/// earlier result fed back in, with corners a hair apart) or have faces
/// in one plane facing both ways (solid on both sides) are read as the
/// solid they wind around. If the result does not close, it is made
/// anew from the inputs' regularized surfaces (`regularized`: a fold's
/// sheet inside the solid, which the result kept where it lay outside the
/// other solid, is gone).
///
/// A mesh without faces is the empty solid: an empty result, written by
/// an earlier operation as an empty OBJ file, can be read back and used.
///
/// Errors: a mesh that does not close, or encloses no volume or a
/// negative one once snapped to the grid, and a result that still does
/// not close (cells too small to hold a grid point keep their last
/// plane's side); it is refused rather than written open.
pub fn csg(
    a: &ObjMesh,
    a_path: &Path,
    b: &ObjMesh,
    b_path: &Path,
    op: SetOp,
) -> Result<IndexedMesh> {
    if a.faces.is_empty() && b.faces.is_empty() {
        return Ok(IndexedMesh::default());
    }
    let points = a
        .faces
        .iter()
        .chain(&b.faces)
        .flat_map(|f| f.vertices.iter());
    let grid = Grid::enclosing(points, GRID_MARGIN).map_err(|source| Error::Grid {
        path: a_path.to_path_buf(),
        source,
    })?;
    let a_faces = closed_pieces(a, a_path, &grid)?;
    let b_faces = closed_pieces(b, b_path, &grid)?;
    let options = BalancedOptions::default();
    let result = |a_solid: &BspSolid,
                  a_faces: &[ConvexPolygon],
                  b_solid: &BspSolid,
                  b_faces: &[ConvexPolygon]| {
        let mut mesh = boundary(a_solid, a_faces, b_solid, b_faces, op).mesh;
        for v in &mut mesh.vertices {
            *v = grid.grid_to_world(*v);
        }
        merge_equal_positions(mesh)
    };
    // Each empty cell is labelled by the surface's winding number there
    // (see `winding_solid`), not by its last plane's side, which is right
    // only for a surface that bounds a solid exactly. A snapped surface
    // that folds, or has faces in one plane facing both ways, can still
    // close, and the plain labels were then wrong far from the fold: a
    // block minus two boxes meeting along an edge, read back, held every
    // point far outside it; two solids each joined from two boxes along
    // part of a face, united, gave a surface twice around the box they
    // shared. Winding numbers cost no more here (two 9,800-triangle spheres:
    // 5.0-6.0 s either way, the boundary's cutting dominates).
    let a_solid = winding_solid(&a_faces, &options);
    let b_solid = winding_solid(&b_faces, &options);
    // (With no faces, a solid is empty: the other's faces all lie outside
    // it, and `boundary` keeps or drops them as the operation says.)
    let mut mesh = result(&a_solid, &a_faces, &b_solid, &b_faces);
    if open_edges(&mesh) > 0 {
        let a_faces = regularized(&a_solid, &a_faces);
        let b_faces = regularized(&b_solid, &b_faces);
        mesh = result(&a_solid, &a_faces, &b_solid, &b_faces);
    }
    let open = open_edges(&mesh);
    if open > 0 {
        return Err(Error::Csg {
            a: a_path.to_path_buf(),
            b: b_path.to_path_buf(),
            message: format!(
                "the result does not close ({open} edges without a matching opposite edge), so none is written: \
                 an input's surface folds over or crosses itself once snapped to the grid (step {:e}), \
                 where it has faces thinner than a few steps or corners closer than that",
                grid.cell_size()
            ),
        });
    }
    Ok(mesh)
}

/// The solid of the closed surface `faces` as a balanced tree whose cells
/// are inside where the surface winds around them (a positive winding
/// number just off the pieces above them), and by their last plane's side
/// where no ray from those pieces counts cleanly.
fn winding_solid(faces: &[ConvexPolygon], options: &BalancedOptions) -> BspSolid {
    if faces.is_empty() {
        return BspSolid::empty();
    }
    let surface = Surface::new(faces);
    let label = |path: &[(Plane, Side)], pieces: &[ConvexPolygon]| {
        surface
            .winding_in(path, pieces)
            .map(|w| if w > 0 { Region::In } else { Region::Out })
    };
    balanced_solid_labelled(faces.to_vec(), options, &label)
}

/// The boundary of the region a solid's winding labels put inside, cut
/// from its own surface `faces`: the pieces with the solid behind them,
/// those with it in front turned over, none of those with the same
/// region on both sides (a fold's sheet inside the solid, or a flap
/// outside it).
fn regularized(solid: &BspSolid, faces: &[ConvexPolygon]) -> Vec<ConvexPolygon> {
    faces
        .iter()
        .enumerate()
        .flat_map(|(i, face)| {
            // Kept pieces keyed by whether they are turned over.
            let turn = |class| match class {
                Containment::BoundarySame => Some(false),
                Containment::BoundaryOpposite => Some(true),
                Containment::Inside | Containment::Outside => None,
            };
            solid
                .partition_polygon_by(face, turn)
                .into_iter()
                .filter_map(move |(piece, turn)| {
                    let piece = if turn? { piece.flipped() } else { piece };
                    Some(piece.with_source(i as u32))
                })
        })
        .collect()
}

/// The directed edges of `mesh` (by vertex index) that no face runs the
/// other way, counted with multiplicity: zero for a closed surface.
fn open_edges(mesh: &IndexedMesh) -> usize {
    let mut edges: HashMap<(u32, u32), i64> = HashMap::new();
    for face in &mesh.faces {
        for (i, &p) in face.iter().enumerate() {
            let q = face[(i + 1) % face.len()];
            *edges.entry((p.min(q), p.max(q))).or_insert(0) += if p < q { 1 } else { -1 };
        }
    }
    edges.values().map(|c| c.unsigned_abs() as usize).sum()
}

/// The mesh with vertices of equal world coordinates made one: exact
/// points a hair apart (1e-10 at a million units) round to one `f64`
/// position, and a face between them had no area (two corners of a quad
/// at one place). Each face keeps its corners once around, and a face
/// left with fewer than three goes: its edges collapsed with its
/// neighbours', which the surface stays closed along.
fn merge_equal_positions(mesh: IndexedMesh) -> IndexedMesh {
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut vertices = Vec::with_capacity(mesh.vertices.len());
    let new_index: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|v| {
            // (+ 0.0 makes -0.0 the same key as 0.0.)
            let key = v.map(|c| (c + 0.0).to_bits());
            *index.entry(key).or_insert_with(|| {
                vertices.push(*v);
                vertices.len() as u32 - 1
            })
        })
        .collect();
    let mut faces = Vec::with_capacity(mesh.faces.len());
    let mut face_polygon = Vec::with_capacity(mesh.faces.len());
    for (face, polygon) in mesh.faces.iter().zip(&mesh.face_polygon) {
        let mut corners: Vec<u32> = face.iter().map(|&i| new_index[i as usize]).collect();
        corners.dedup();
        while corners.len() > 1 && corners.first() == corners.last() {
            corners.pop();
        }
        if corners.len() >= 3 {
            faces.push(corners);
            face_polygon.push(*polygon);
        }
    }
    IndexedMesh {
        vertices,
        faces,
        face_polygon,
    }
}

/// The mesh's faces as convex pieces on the grid (none for a mesh without
/// faces, the empty solid); an error unless the snapped faces close up
/// (every directed edge matched by its reverse) around a positive volume.
fn closed_pieces(mesh: &ObjMesh, path: &Path, grid: &Grid) -> Result<Vec<ConvexPolygon>> {
    let mut pieces = Vec::new();
    // The faces' edges as snapped, before they are cut into convex pieces:
    // a piece drops a corner in line with its neighbours, which a face
    // beside it may share (a face split in two along a neighbour), and the
    // edges would no longer pair.
    let mut edges: HashMap<(GridPoint, GridPoint), i64> = HashMap::new();
    let mut faces = Vec::with_capacity(mesh.faces.len());
    for face in &mesh.faces {
        let (snapped, _) = grid
            .snap_all(&face.vertices)
            .map_err(|source| Error::Grid {
                path: path.to_path_buf(),
                source,
            })?;
        let n = snapped.len();
        for i in 0..n {
            let (p, q) = (snapped[i], snapped[(i + 1) % n]);
            if p != q {
                *edges.entry((p, q)).or_insert(0) += 1;
                *edges.entry((q, p)).or_insert(0) -= 1;
            }
        }
        faces.push(snapped);
    }
    for face in without_sheets(faces) {
        for piece in convex_pieces(&face) {
            let k = pieces.len() as u32;
            pieces.push(piece.with_source(k));
        }
    }
    let open = edges.values().filter(|&&c| c != 0).count() / 2;
    if mesh.faces.is_empty() {
        // The empty solid.
        return Ok(pieces);
    }
    if open > 0 {
        return Err(Error::Field {
            path: path.to_path_buf(),
            field: "faces".into(),
            message: format!(
                "the mesh is not closed ({open} edges without a matching opposite edge); set operations need closed meshes"
            ),
        });
    }
    let volume = six_volume(&pieces);
    if volume == 0 {
        return Err(Error::Field {
            path: path.to_path_buf(),
            field: "faces".into(),
            message: format!(
                "the mesh encloses no volume once snapped to the grid (step {:e}): it is smaller or thinner than a step",
                grid.cell_size()
            ),
        });
    }
    // A surface wound inwards winds -1 times around its inside, so its
    // solid would be empty and the mesh silently ignored: more likely a
    // mistake in the file, or a flat body that snapping turned inside out
    // (a tetrahedron with its four corners in one plane, turned), than
    // what was meant. (Labelled by last planes, as they once were, such a
    // solid was all the space around the mesh.)
    if volume < 0 {
        return Err(Error::Field {
            path: path.to_path_buf(),
            field: "faces".into(),
            message: format!(
                "the mesh encloses a negative volume once snapped to the grid (step {:e}): its faces are wound inwards (clockwise seen from outside), or it is thinner than a step",
                grid.cell_size()
            ),
        });
    }
    Ok(pieces)
}

/// The faces as one layer of surface: a face written again the same way
/// round counts once (a surface given twice bounds the same solid), and
/// a face and its reverse (the same corners the other way round: a
/// two-sided sheet, inside a solid or made by snapping a slab thinner
/// than a step) both go. Such a pair bounds no volume, and a repeated
/// face none more, but their faces would split the solid's BSP as walls.
fn without_sheets(faces: Vec<Vec<GridPoint>>) -> Vec<Vec<GridPoint>> {
    // Each face's corner cycle, consecutive repeats dropped, from its
    // least corner.
    let cycle = |corners: &[GridPoint]| -> Vec<GridPoint> {
        let mut c: Vec<GridPoint> = corners.to_vec();
        c.dedup();
        while c.len() > 1 && c.first() == c.last() {
            c.pop();
        }
        let least = (0..c.len()).min_by_key(|&i| c[i]).unwrap_or(0);
        c.rotate_left(least);
        c
    };
    let mut seen = HashSet::new();
    let once: Vec<(Vec<GridPoint>, Vec<GridPoint>)> = faces
        .into_iter()
        .map(|face| (cycle(&face), face))
        .filter(|(c, _)| c.len() < 3 || seen.insert(c.clone()))
        .collect();
    once.into_iter()
        .filter(|(c, _)| {
            let mut reverse = c.clone();
            reverse.reverse();
            c.len() < 3 || !seen.contains(&cycle(&reverse))
        })
        .map(|(_, face)| face)
        .collect()
}

/// Six times the volume a closed surface of grid-point polygons encloses
/// (positive when they face out), exactly: each polygon's fan of
/// triangles with the origin, `det[a, b, c]`.
fn six_volume(pieces: &[ConvexPolygon]) -> i128 {
    let mut sum = 0_i128;
    for piece in pieces {
        let corners: Vec<[i128; 3]> = (0..piece.len())
            .filter_map(|i| piece.vertex_grid_point(i))
            .map(|g| g.to_i64().map(i128::from))
            .collect();
        for k in 1..corners.len().saturating_sub(1) {
            let [a, b, c] = [corners[0], corners[k], corners[k + 1]];
            sum += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
    }
    sum
}

/// Writes the mesh as OBJ (atomically).
pub fn save_csg_obj(path: &Path, mesh: &IndexedMesh) -> Result<()> {
    let mut text = String::new();
    mesh.write_obj(&mut text)
        .expect("writing to a String cannot fail");
    crate::atomic::write_atomic(path, |w| w.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube's six quads (counter-clockwise seen from outside).
    fn cube() -> IndexedMesh {
        let faces: Vec<Vec<u32>> = vec![
            vec![0, 2, 3, 1],
            vec![4, 5, 7, 6],
            vec![0, 1, 5, 4],
            vec![2, 6, 7, 3],
            vec![0, 4, 6, 2],
            vec![1, 3, 7, 5],
        ];
        IndexedMesh {
            vertices: (0..8)
                .map(|i| [i & 1, i >> 1 & 1, i >> 2 & 1].map(f64::from))
                .collect(),
            face_polygon: (0..faces.len() as u32).collect(),
            faces,
        }
    }

    /// A closed cube has no open edge; a face given twice leaves its four
    /// edges open once each (used twice one way, once the other); without
    /// its top, the top's four edges are open.
    #[test]
    fn open_edges_are_counted_with_their_multiplicity() {
        let mut mesh = cube();
        assert_eq!(open_edges(&mesh), 0);
        mesh.faces.push(mesh.faces[0].clone());
        assert_eq!(open_edges(&mesh), 4);
        mesh.faces.pop();
        mesh.faces.remove(1);
        assert_eq!(open_edges(&mesh), 4);
    }

    /// The volume the pieces enclose, welded (and whether they close).
    fn enclosed(pieces: &[ConvexPolygon]) -> (f64, bool) {
        let mesh = svbsp::weld(pieces);
        (mesh.volume(), open_edges(&mesh) == 0)
    }

    /// A surface of two boxes that overlap, both wound out (winding number
    /// 2 where they do), and of a box with a smaller one inside it wound
    /// in (0 inside that): their winding solids' regularized surfaces are
    /// the union's (the faces inside the other box gone) and the hollow
    /// box's, closed. As given, they would enclose 80 and 56.
    #[test]
    fn a_regularized_surface_bounds_what_its_winding_number_puts_inside() {
        use crate::winding::tests::cuboid;
        let options = BalancedOptions::default();
        let mut overlapping = cuboid([0, 0, 0], [4, 4, 4]);
        overlapping.extend(cuboid([2, 1, 1], [6, 3, 3]));
        let mut hollow = cuboid([0, 0, 0], [4, 4, 4]);
        hollow.extend(
            cuboid([1, 1, 1], [3, 3, 3])
                .iter()
                .map(ConvexPolygon::flipped),
        );
        for (faces, given, regular) in [(overlapping, 80.0, 72.0), (hollow, 56.0, 56.0)] {
            let (volume, _) = enclosed(&faces);
            assert!((volume - given).abs() < 1e-9, "{volume}");
            let solid = winding_solid(&faces, &options);
            let (volume, closed) = enclosed(&regularized(&solid, &faces));
            assert!(closed && (volume - regular).abs() < 1e-9, "{volume}");
        }
    }
}
