//! The `umbra` library: scene files and OBJ meshes in; convex planar pieces
//! on one exact grid for the shadow kernels; PLY, OBJ and JSON out.
//!
//! - [`Scene`] reads and validates a scene file (FORMATS.md §1) and the OBJ
//!   meshes it names ([`ObjMesh`]), applying each object's [`Transform`];
//! - [`Pieces`] snaps every input polygon to one [`bsp_core::Grid`] and cuts
//!   it into convex planar [`bsp_core::ConvexPolygon`]s, each remembering its
//!   input polygon (the `source` of the output);
//! - [`InputFrames`] puts the output's points back onto the input polygons
//!   they lie on (the kernel's are on the snapped copies), so that each
//!   polygon's fragments tile it, not its copy;
//! - [`OutputMesh`] is what the writers take: [`save_ply`] (FORMATS.md §2,
//!   binary or ASCII; [`load_ply`] reads it back), [`save_obj`], and
//!   [`Stats`] (FORMATS.md §3); every file is written with [`write_atomic`],
//!   so a failed run leaves no partial file;
//! - [`render_scene`] draws the scene from its camera with its shadows into
//!   an [`Image`] (PNG through [`Image::save_png`]), in one of the [`View`]s;
//! - [`write_demo`] writes the built-in scenes; [`tetra_triangles`] is
//!   Haines' SPD tetrahedra.
//!
//! Errors are one [`Error`] type whose messages name the file and the line
//! or field. Nothing here prints.
//!
//! # Example
//!
//! ```
//! use umbra::{Pieces, Scene};
//!
//! // An L-shaped floor (concave) under a point light.
//! let scene = Scene::from_toml_str(
//!     r#"
//!     [[object]]
//!     name = "floor"
//!     polygons = [[[0, 0, 0], [0, 0, 2], [2, 0, 2], [2, 0, 1], [1, 0, 1], [1, 0, 0]]]
//!
//!     [[light]]
//!     type = "point"
//!     position = [1, 3, 1]
//!     "#,
//!     "floor.toml",
//! )?;
//! let pieces = Pieces::from_scene(&scene)?;
//! assert_eq!(pieces.input_polygons, 1);
//! assert!(pieces.polygons.len() >= 2);
//! // Every piece names the one input polygon it came from.
//! assert!(pieces.input_of.iter().all(|&i| i == 0));
//! # Ok::<(), umbra::Error>(())
//! ```

mod atomic;
mod closed_surface;
mod csg;
mod dark;
mod decompose;
mod demo;
mod demo_dm;
mod demo_meshes;
mod demo_room;
mod dm;
mod dm_lights;
mod error;
mod illuminate;
mod input_frame;
mod mesh;
mod obj;
mod obj_out;
mod ply;
mod read;
mod render;
mod scene;
mod shadow;
pub mod shapes;
mod stats;
mod svg;
mod transform;
mod vec3;
mod weld;
mod winding;

pub use atomic::{Outputs, write_atomic};
pub use bsp_core;
pub use csg::{csg, save_csg_obj};
pub use decompose::{
    DIRECTION_SCALE, GRID_MARGIN, Motion, Pieces, SnappedLight, convex_pieces, integer_direction,
    scene_grid,
};
pub use demo::{DEMOS, DemoFiles, TETRA_DEPTH, tetra_triangles, write_demo};
pub use dm::{DmFigures, DmRun, DmStats, UpdateFigures, dm_scene, dm_scene_moving, dm_scene_with};
pub use dm_mesh::{Deletion, DmOptions, OverlapKind};
pub use error::{Error, Result};
pub use input_frame::InputFrames;
pub use mesh::{OutputFace, OutputMesh};
pub use obj::{ObjFace, ObjMesh};
pub use obj_out::{save_obj, stage_obj, write_obj};
pub use ply::{PlyEncoding, load_ply, read_ply, save_ply, stage_ply, write_ply};
pub use render::{
    ALBEDO, FragmentClass, Image, MAX_IMAGE_SIDE, Method, Order, Projection, RenderOptions,
    SAMPLES_PER_SIDE, View, exposure, linear_to_srgb8, render, render_scene, render_scene_with,
    render_with, srgb8_to_linear,
};
pub use scene::{Camera, Falloff, InputPolygon, Light, LightKind, MAX_LIGHTS, Object, Scene};
pub use shadow::{ShadowOptions, ShadowResult, shadow_scene, shadow_scene_with};
pub use stats::{LightStats, Seconds, Stats};
pub use svg::{fragments_svg, save_svg};
pub use transform::Transform;
