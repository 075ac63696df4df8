//! Direct illumination for umbra, in plain `f64`.
//!
//! - [`contour_integral`]: Lambert's contour integral (Chin & Feiner 1992),
//!   the irradiance from a convex polygonal Lambertian light, clipped by the
//!   receiver's horizon; [`AreaLight`] is a validated light polygon.
//! - [`VisiblePart`]: the part of an area light visible from a point past
//!   convex occluders (polygons, or convex solids by their silhouettes:
//!   [`Occluder`]), as convex pieces whose contour integrals add up to the
//!   irradiance (plain floating-point clipping: it never decides topology);
//!   past many occluders [`visible_irradiance`] takes the outlines of that
//!   part instead, one polygon boolean (`i_overlay`) in the light's plane.
//! - [`PointLight`], [`DirectionalLight`]: `I cos / r^2` with Bergeron's
//!   sphere of influence ([`Falloff`]); one- or two-sided receivers
//!   ([`Sidedness`]).
//! - [`OccluderIndex`]: a bounding-volume hierarchy of occluder outlines
//!   that finds the occluders that may lie between a point and an area
//!   light.
//! - [`vertex_plan`]: the 1992 paper's vertex-sharing rules.
//! - [`area_irradiance_batch`], [`evaluate_batch`]: many receivers in
//!   parallel, results independent of the thread count.
//!
//! Points and vectors are `[f64; 3]` ([`Vec3`]); normals are unit vectors.
//! Irradiance is not divided by pi. The crate does not use the scene BSP.
//!
//! ```
//! use illum::{AreaLight, Sidedness, VisiblePart, visible_irradiance};
//!
//! // The Cornell box light, counter-clockwise seen from below: it emits -y.
//! let light = AreaLight::new(
//!     &[
//!         [343.0, 548.8, 227.0],
//!         [343.0, 548.8, 332.0],
//!         [213.0, 548.8, 332.0],
//!         [213.0, 548.8, 227.0],
//!     ],
//!     1.0,
//! )?;
//! let (p, up) = ([278.0, 0.0, 279.6], [0.0, 1.0, 0.0]);
//! let e = light.irradiance(p, up, Sidedness::OneSided);
//! assert!((e - 0.044632472).abs() < 1e-9);
//!
//! // A square occluder right above the point hides part of the light.
//! let occluder = [[250.0, 200.0, 250.0], [300.0, 200.0, 250.0], [300.0, 200.0, 300.0]];
//! let mut scratch = VisiblePart::new();
//! let shadowed = visible_irradiance(&light, &[occluder], p, up, Sidedness::OneSided, &mut scratch);
//! assert!(shadowed < e && shadowed > 0.0);
//! # Ok::<(), illum::IllumError>(())
//! ```

mod angle;
mod area_light;
mod batch;
mod contour_integral;
mod error;
mod occluder_index;
mod point_light;
mod sharing;
mod vec3;
mod visibility;

pub use area_light::AreaLight;
pub use batch::{Receiver, area_irradiance_batch, evaluate_batch};
pub use contour_integral::{contour_integral, contour_integral_sum};
pub use error::IllumError;
pub use occluder_index::OccluderIndex;
pub use point_light::{DirectionalLight, Falloff, PointLight, Sidedness};
pub use sharing::{FragmentClass, VertexPlan, VertexValue, vertex_plan};
pub use vec3::Vec3;
pub use visibility::{AsOccluder, Occluder, VisiblePart, visible_irradiance};

/// The rayon the batch functions run on: call them inside
/// `rayon::ThreadPool::install` to choose the number of threads.
pub use rayon;
