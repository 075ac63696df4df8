//! The neutral output mesh that the PLY and OBJ writers take.

/// Classified fragments with shared vertices, ready to be written.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct OutputMesh {
    /// Vertex positions (world units) with their direct irradiance from all
    /// lights, ambient excluded.
    pub vertices: Vec<([f64; 3], f32)>,
    /// Faces in output order.
    pub faces: Vec<OutputFace>,
}

/// One output fragment.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct OutputFace {
    /// Indices into [`OutputMesh::vertices`], counter-clockwise seen from the
    /// front, as the input polygon.
    pub vertices: Vec<u32>,
    /// Index of the input polygon the fragment lies in.
    pub source: u32,
    /// Bit `i`: the fragment sees all of light `i`.
    pub lit_mask: u32,
    /// Bit `i`: the fragment sees none of light `i`.
    pub umbra_mask: u32,
}

/// An irradiance as the output's 32-bit float: past its range (a point
/// light a 1e-20th of a unit away) the largest float, not infinity.
pub(crate) fn irradiance_f32(e: f64) -> f32 {
    (e as f32).min(f32::MAX)
}

impl OutputMesh {
    /// Checks that every face has 3 to 255 vertices, all of which exist (the
    /// writers rely on it).
    pub fn check(&self) -> Result<(), String> {
        for (k, face) in self.faces.iter().enumerate() {
            if face.vertices.len() < 3 || face.vertices.len() > 255 {
                return Err(format!(
                    "face {k} has {} vertices; a face needs 3 to 255",
                    face.vertices.len()
                ));
            }
            if let Some(&v) = face
                .vertices
                .iter()
                .find(|&&v| v as usize >= self.vertices.len())
            {
                return Err(format!(
                    "face {k} names vertex {v}, but there are {}",
                    self.vertices.len()
                ));
            }
        }
        Ok(())
    }
}
