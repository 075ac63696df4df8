//! Soft shadows of convex area lights: the penumbra and umbra BSP trees of
//! Chin & Feiner, *Fast Object-Precision Shadow Generation for Area Light
//! Sources Using BSP Trees* (1992), on the exact kernel of [`bsp_core`].
//!
//! For each area light, every occluder casts a **penumbra volume** (where
//! some of the light is hidden) and an **umbra volume** (where all of it
//! is), bounded by planes through the occluder's edges and the light's
//! vertices or the occluder's vertices and the light's edges
//! ([`cast_volumes`]). They are merged into one penumbra tree and one umbra
//! tree by the general Thibault-Naylor union ([`VolumeTree`]); every
//! fragment is then filtered down both: outside the penumbra tree it is
//! lit, inside the umbra tree it is in umbra, otherwise in penumbra
//! ([`AreaTrees`], [`shadow_area_light`]). Pieces that form one convex
//! body ([`convex_groups`]) add the body's umbra too, where they hide the
//! whole light only together (a closed surface that is not convex, for a
//! convex body inside it: moved in from a surface the grid bent, a core
//! of the kernel of one really concave, or several cores in local
//! kernels of one with no kernel, a torus); an exactly convex body's
//! penumbra volume is one convex volume too
//! ([`ConvexGroup::penumbra_planes`]). Where pieces
//! hide the light together in a region that is no convex volume (coplanar
//! pieces covering a concave polygon, [`FlatUnion`]; a plane region
//! inside a closed surface that is no convex body, [`section_unions`]; a
//! surface one face short of a convex body, a body holding the light in,
//! [`ConvexGroup::umbra_parts`]) that region comes in convex parts.
//! Closed convex bodies that touch face to face and make one convex body
//! together, whatever their objects (two boxes side by side, a stack),
//! add that body's umbra ([`convex_unions`]).
//! Where occluders hide the light only together and not as one convex
//! body, the umbra they make is bounded by curved surfaces no volume has:
//! [`dark::sees_none`] proves a region inside it dark, exactly, for the
//! callers to mark umbra.
//! [`compute_shadows`] runs point, directional and area lights together,
//! one mask bit each. [`closed_parts`] finds the closed parts of objects'
//! surfaces, whose faces turned away from a light clear of them cast
//! nothing.
//!
//! Every plane is a plane through three grid points and every side
//! decision is an exact predicate, so fragments partition their polygons
//! exactly.
//!
//! # Example
//!
//! ```
//! use area_shadow::{AreaSource, Class, SceneLight, compute_shadows};
//! use bsp_core::{BuildOptions, ConvexPolygon, GridPoint};
//! use svbsp::PieceFlags;
//!
//! let g = |x, y, z| GridPoint { x, y, z };
//! // A floor facing up, a square occluder above it, a square light above
//! // that, facing down.
//! let floor = ConvexPolygon::from_grid_points(&[g(-40, 0, 40), g(40, 0, 40), g(40, 0, -40), g(-40, 0, -40)], 0).unwrap();
//! let occluder = ConvexPolygon::from_grid_points(&[g(-4, 5, 4), g(4, 5, 4), g(4, 5, -4), g(-4, 5, -4)], 1).unwrap();
//! let light = AreaSource::from_grid_points(&[g(-1, 10, -1), g(1, 10, -1), g(1, 10, 1), g(-1, 10, 1)]).unwrap();
//! let out = compute_shadows(&[floor, occluder], &[PieceFlags::default(); 2], &[SceneLight::Area(light)], &BuildOptions::default()).unwrap();
//! let area = |class| -> f64 {
//!     out.fragments.iter().filter(|f| f.polygon.source() == 0 && Class::of(f, 0) == class).map(|f| f.polygon.area()).sum()
//! };
//! // Umbra: the square [-7, 7]^2 (the occluder from the light's far
//! // corners); penumbra reaches [-9, 9]^2.
//! assert!((area(Class::Umbra) - 14.0 * 14.0).abs() < 1e-9);
//! assert!((area(Class::Penumbra) - (18.0 * 18.0 - 14.0 * 14.0)).abs() < 1e-9);
//! assert!((area(Class::Lit) - (80.0 * 80.0 - 18.0 * 18.0)).abs() < 1e-9);
//! ```

mod closed_parts;
mod conform;
pub mod dark;
mod disjoint_sets;
mod error;
mod gridding;
mod groups;
mod hash;
mod merge_pieces;
mod pass;
mod pipeline;
mod source;
#[cfg(test)]
mod test_shapes;
mod tree;
mod volumes;

pub use bsp_core;
pub use closed_parts::{ClosedPart, closed_parts};
pub use conform::{ConformingMesh, MeshPoint, conform, conform_fragments};
pub use error::Error;
pub use gridding::{GridClass, grid_fragments, grid_polygon, halve, subdivide_adaptive};
pub use groups::{
    Blocker, ConvexGroup, FlatUnion, MAX_SOLID_WORK, convex_groups, convex_unions, edge_contact,
    flat_joints, flat_unions, holed_shells, one_way, section_unions, winding_number,
};
pub use merge_pieces::{merge_pair, merge_same_class};
pub use pass::{
    AreaLightStats, AreaTrees, Class, ShadowGroups, classify_fragments, shadow_area_light,
};
pub use pipeline::{
    LightFigures, SceneLight, Shadows, compute_shadows, compute_shadows_with_groups,
};
pub use source::{AreaSource, SourceSide};
pub use tree::{Partition, VolumeTree};
pub use volumes::{CastVolumes, VolumePlanes, cast_volumes, cast_volumes_within, volume_planes};
