//! The exact plane-based kernel of umbra.
//!
//! Every decision umbra makes (which side of a plane, coplanar or not, on an
//! edge or not) is made here, exactly. Input coordinates are snapped once to
//! an integer [`Grid`]; every stored [`Plane`] passes through three grid
//! points and so has bounded integer coefficients; every vertex made by
//! splitting is *implicit*, the intersection of three planes, and is never
//! rounded to decide anything. The [`predicates`] module decides sides with a
//! floating-point filter backed by exact 256-bit arithmetic, so splits never
//! crack, overlap or lose area, and results do not depend on the order of
//! floating-point operations.
//!
//! On top of the predicates: [`ConvexPolygon`] splitting (and, without
//! splitting, whether a plane crosses a polygon's part inside other planes,
//! with that plane's [`Chord`] kept as the polygon is cut), the scene BSP
//! ([`SceneBsp`], an autopartition with front-to-back traversal from a point
//! or a direction), BSP solids ([`BspSolid`], Thibault-Naylor in / out
//! trees), winged-edge meshes with exact vertices ([`WingedMesh`]) and lines
//! on a receiver plane ([`ReceiverLine`]) for 2D subdivisions.
//!
//! # Example
//!
//! ```
//! use bsp_core::{ConvexPolygon, Grid, Plane, Split};
//!
//! let grid = Grid::new([0.0; 3], [4.0; 3]).unwrap();
//! let snap = |p: [f64; 3]| grid.snap(p).unwrap();
//! // A unit square in the plane z = 1, and the plane x = 2 cutting it.
//! let square = ConvexPolygon::from_grid_points(
//!     &[snap([1.0, 1.0, 1.0]), snap([3.0, 1.0, 1.0]), snap([3.0, 3.0, 1.0]), snap([1.0, 3.0, 1.0])],
//!     0,
//! )
//! .unwrap();
//! let cut = Plane::through(snap([2.0, 0.0, 0.0]), snap([2.0, 1.0, 0.0]), snap([2.0, 0.0, 1.0])).unwrap();
//! match square.split(&cut) {
//!     Split::Both(back, front) => {
//!         // The halves tile the square exactly.
//!         let total = back.area() + front.area();
//!         assert!((total - square.area()).abs() <= 1e-12 * square.area());
//!         assert_eq!(back.len() + front.len(), 8);
//!     }
//!     other => panic!("expected a cut, got {other:?}"),
//! }
//! ```

mod autopartition;
mod chord;
mod error;
mod grid;
mod lattice;
mod line2d;
mod planar_snap;
mod plane;
mod polygon;
pub mod predicates;
mod scene_bsp;
mod solid;
mod winged_edge;

pub use autopartition::BuildOptions;
pub use chord::Chord;
pub use error::Error;
pub use grid::{GRID_BITS, GRID_LIMIT, Grid, GridPoint};
pub use lattice::PlaneLattice;
pub use line2d::{LineMeeting, ReceiverLine};
pub use plane::{NORMAL_LIMIT, OFFSET_LIMIT, Plane};
pub use polygon::{Behind, ConvexPolygon, Edges, Facing, PolygonSide, Split};
pub use predicates::{ImplicitPoint, Side};
pub use scene_bsp::{Location, SceneBsp, SceneChild, SceneNode, Traversal, Viewpoint};
pub use solid::{BspSolid, Containment, LeafLabel, PointClass, Region, SolidChild, SolidNode};
pub use winged_edge::{
    Edge, EdgeKey, Face, FaceKey, FaceSide, FaceSplit, PlaneRef, Vertex, VertexKey, VertexPosition,
    WingedMesh,
};
