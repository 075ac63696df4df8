//! How much of a scene's output a move changes: the least work any
//! correct update must do.
//!
//! An update that leaves the discontinuity meshes as a rebuild would must
//! write every cell the rebuild's output has and the old output lacks
//! (a new region, or an old one with a new vertex on its boundary), and
//! give a value to every vertex that is new or whose irradiance changed.
//! Set beside the output of a from-scratch build, these shares bound a
//! move's cost from below in units of a rebuild: an update that made its
//! cells no faster than a rebuild makes them cannot take a smaller share
//! of the rebuild's time.
//!
//! Cells and vertices are matched by position: the output coordinates
//! rounded to 2^-32 of a world unit (a figure, not a decision of the
//! library: two builds round the same exact point alike, or one unit of
//! the last place apart, which crosses a rounding boundary about once in
//! a billion).

use std::collections::{HashMap, HashSet};
use umbra::{OutputFace, OutputMesh};

/// Shares of an output that are new after a change.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputChange {
    /// Cells of the new output that the old one does not have.
    pub new_cells: usize,
    /// Cells of the new output.
    pub cells: usize,
    /// Vertices of the new output (per receiver) that the old one lacks,
    /// or has with another irradiance.
    pub new_values: usize,
    /// Vertices of the new output, per receiver.
    pub vertices: usize,
}

impl OutputChange {
    /// What `after` has that `before` does not.
    pub fn between(before: &OutputMesh, after: &OutputMesh) -> Self {
        let old_cells: HashSet<CellKey> =
            before.faces.iter().map(|f| cell_key(before, f)).collect();
        let new_cells = after
            .faces
            .iter()
            .filter(|f| !old_cells.contains(&cell_key(after, f)))
            .count();
        let old_values = vertex_values(before);
        let new_values = vertex_values(after);
        let changed = new_values
            .iter()
            .filter(|(key, e)| old_values.get(key).is_none_or(|old| !same_value(*old, **e)))
            .count();
        OutputChange {
            new_cells,
            cells: after.faces.len(),
            new_values: changed,
            vertices: new_values.len(),
        }
    }

    /// New cells as a share of all cells.
    pub fn cell_share(&self) -> f64 {
        self.new_cells as f64 / self.cells.max(1) as f64
    }

    /// New vertex values as a share of all vertices.
    pub fn value_share(&self) -> f64 {
        self.new_values as f64 / self.vertices.max(1) as f64
    }
}

/// The irradiance of each vertex of each receiver (a point where two
/// receivers meet has a value on each).
fn vertex_values(mesh: &OutputMesh) -> HashMap<(u32, [i64; 3]), f32> {
    mesh.faces
        .iter()
        .flat_map(|f| {
            f.vertices.iter().map(|&v| {
                let (p, e) = mesh.vertices[v as usize];
                ((f.source, position_key(p)), e)
            })
        })
        .collect()
}

/// A cell: its polygon, class masks and sorted corner positions.
type CellKey = (u32, u32, u32, Vec<[i64; 3]>);

fn cell_key(mesh: &OutputMesh, face: &OutputFace) -> CellKey {
    let mut corners: Vec<[i64; 3]> = face
        .vertices
        .iter()
        .map(|&v| position_key(mesh.vertices[v as usize].0))
        .collect();
    corners.sort_unstable();
    (face.source, face.lit_mask, face.umbra_mask, corners)
}

fn position_key(p: [f64; 3]) -> [i64; 3] {
    p.map(|c| (c * 4_294_967_296.0).round() as i64)
}

/// Irradiance values the same but for the order of a sum's terms.
fn same_value(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-6 * a.abs().max(b.abs()).max(1e-3)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, irradiance: f32) -> OutputMesh {
        OutputMesh {
            vertices: vec![
                ([x, 0.0, 0.0], irradiance),
                ([x + 1.0, 0.0, 0.0], irradiance),
                ([x + 1.0, 0.0, 1.0], 0.5),
                ([x, 0.0, 1.0], 0.5),
            ],
            faces: vec![OutputFace {
                vertices: vec![0, 1, 2, 3],
                source: 0,
                lit_mask: 0,
                umbra_mask: 0,
            }],
        }
    }

    #[test]
    fn the_same_output_has_nothing_new() {
        let a = square(0.0, 1.0);
        let change = OutputChange::between(&a, &a.clone());
        assert_eq!((change.new_cells, change.new_values), (0, 0));
        assert_eq!((change.cells, change.vertices), (1, 4));
    }

    #[test]
    fn a_moved_cell_and_changed_values_are_new() {
        let moved = OutputChange::between(&square(0.0, 1.0), &square(1.0, 1.0));
        // The cell moved; two of its corners were there, with the same
        // values.
        assert_eq!(moved.new_cells, 1);
        assert_eq!(moved.new_values, 2);
        let relit = OutputChange::between(&square(0.0, 1.0), &square(0.0, 0.75));
        assert_eq!(relit.new_cells, 0);
        assert_eq!(relit.new_values, 2);
        assert!((relit.value_share() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_point_on_two_receivers_keeps_a_value_on_each() {
        // Two receivers meet along x = 1 and light it differently.
        let mut a = square(0.0, 1.0);
        let mut other = square(1.0, 0.25);
        other.faces[0].source = 1;
        let offset = a.vertices.len() as u32;
        a.vertices.extend(other.vertices);
        a.faces.extend(other.faces.into_iter().map(|mut f| {
            f.vertices.iter_mut().for_each(|v| *v += offset);
            f
        }));
        let change = OutputChange::between(&a, &a.clone());
        assert_eq!((change.new_values, change.vertices), (0, 8));
    }

    #[test]
    fn a_cell_of_another_class_is_new() {
        let a = square(0.0, 1.0);
        let mut b = a.clone();
        b.faces[0].umbra_mask = 1;
        assert_eq!(OutputChange::between(&a, &b).new_cells, 1);
    }
}
