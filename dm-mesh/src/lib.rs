//! Discontinuity meshes kept as 2D BSP trees in a winged-edge structure,
//! updated incrementally as objects move (Chrysanthou & Slater,
//! *Incremental Updates to Scenes Illuminated by Area Light Sources*).
//!
//! Every receiving polygon of a [`DmScene`] has a DM-tree
//! ([`ReceiverDm`]): a 2D BSP on the receiver's plane whose leaves are the
//! convex faces of a [`bsp_core::WingedMesh`]. Each occluder, under each
//! area light, merges in its penumbra and umbra boundaries (the planes of
//! its penumbra and umbra volumes, from [`area_shadow::volume_planes`]), and
//! every cell keeps the list of occluders that block part of a light from it,
//! those that block all of it marked umbra ([`Cell`], [`CellClass`]). Every
//! vertex is exact (a grid point or three planes) and every side decision
//! goes through [`bsp_core::predicates`].
//!
//! [`DmScene::illuminate`] gives the irradiance at every cell vertex by the
//! paper's three cases, asking [`illum`] for the visible part of a light only
//! past the occluders every cell around the vertex lists (along the
//! receiver's normal, or one set with [`DmScene::set_receiver_normal`]: the
//! input polygon's, of which the receiver is a snapped copy). Objects can be
//! added, removed and moved ([`DmScene::add_object`],
//! [`DmScene::remove_object`], [`DmScene::move_object`], or
//! [`DmScene::translate_object`] by whole grid steps). A removal drops
//! the occluder from the lists of the cells it covered and deletes its
//! discontinuity nodes by the paper's three steps ([`Deletion::Local`], the
//! default): the node's edge leaves the mesh, the subtree with the smaller
//! expected cost `D_a * size_b` is kept and its dangling lines expanded
//! across the node's cell, the other subtree's cells are inserted into it,
//! and cells no discontinuity separates any more are merged. Once
//! [`DmScene::illuminate`] has run, every change illuminates the receivers
//! it touched as it updates them, each right after its own update (while
//! one thread still updates a big receiver, another illuminates the small
//! ones), so vertex irradiance is current after every change. An
//! application that draws the cells reads again only the receivers a
//! change listed ([`DmScene::receivers_changed_since`] the
//! [`DmScene::revision`] it kept before: a box's move on the 10k-polygon
//! hall lists 31 of its 10k receivers); every other receiver keeps its
//! cells, keys and values. `examples/frames.rs` runs such a frame loop
//! (`cargo run --release -p dm-mesh --example frames`).
//! [`Deletion::Collapse`] instead collapses the subtrees the occluder grew
//! and merges the later occluders there again. A removal is cheapest for
//! the occluders merged last, whose nodes lie at the bottom of the trees:
//! a move leaves the moved object's there, and
//! [`DmScene::build_movable`] puts the objects an application declares
//! movable there from the start. Re-illumination evaluates
//! only vertices whose covering occluders changed. A receiver that many
//! occluders reach starts as a balanced tree of tiles (construction lines,
//! about one tile per four units), so that every change stays within the
//! tiles an occluder met rather than spanning half of a big floor.
//!
//! Receivers are independent: casting and illumination run over them in
//! parallel with rayon (and a big receiver's vertices in parallel chunks).
//! Every tree sees its own units in the same order whatever the thread
//! count, so results are identical with any number of threads; call the
//! library inside `rayon::ThreadPool::install` to choose it.
//!
//! Polygons of one object that form a convex body (a box, a triangulated
//! sphere, [`area_shadow::convex_groups`]) hide light together. Under a
//! light the body is wholly in front of, an exactly convex closed body
//! casts one unit in place of its polygons
//! ([`DmOptions::convex_bodies`]): its penumbra volume is one convex set of
//! planes (those separating it from the light,
//! [`area_shadow::ConvexGroup::penumbra_planes`]), its umbra the body's,
//! its internal discontinuities the EV and VE surfaces of its silhouette,
//! and a vertex's visible part is computed past the body's polygons that
//! have the vertex on their outer side. A box then puts one region into a
//! floor's tree per light instead of one per face facing the light (the
//! 3k-box hall: 39 % fewer cells), and no face's penumbra plane through an
//! edge between two faces the light sees. Otherwise (a body that reaches
//! the light's plane, or a nearly convex surface) each polygon casts its
//! own unit and the body is an occluder whose one volume is its umbra, so
//! that cells where nothing of the light is seen are umbra. Bodies are
//! added, removed and moved with their object. Closed convex bodies that
//! touch face to face and make one convex body together (boxes side by
//! side, a stack; [`area_shadow::convex_unions`]) hide the light together
//! too: a joint body, with that body's umbra only, joins them whatever
//! their objects, and is found again for the touching sets each change
//! leaves and enters. So do coplanar polygons of several objects sharing
//! whole edges ([`area_shadow::flat_joints`]: two panels side by side).
//!
//! Inside each penumbra the internal EV and VE discontinuities (a light
//! vertex crossing an occluder edge, an occluder vertex crossing a light
//! edge) split the cells too, where their wedges cross them, so that the
//! irradiance is smooth inside every cell; an edge or vertex that the
//! occluder's own object hides on both sides casts none (the light's part
//! in view cannot change there). Which occluders can shadow which
//! receivers is found through a uniform grid of receiver boxes and penumbra
//! boxes ([`OverlapKind::Grid`], the default) or the paper's shadow overlap
//! cube ([`OverlapKind::Cube`]: direction tiles around each light); the
//! grid gives a few per cent fewer pairs on the benchmark scenes
//! ([`DmScene::overlap_figures`]). [`DmScene::check_invariants`] checks
//! every tree, mesh and occluder list against the occluders' volumes,
//! exactly.
//!
//! # Example
//!
//! ```
//! use area_shadow::AreaSource;
//! use bsp_core::{ConvexPolygon, GridPoint};
//! use dm_mesh::{CellClass, DmLight, DmOptions, DmScene};
//! use svbsp::PieceFlags;
//!
//! let g = |x, y, z| GridPoint { x, y, z };
//! let floor = ConvexPolygon::from_grid_points(&[g(-40, 0, 40), g(40, 0, 40), g(40, 0, -40), g(-40, 0, -40)], 0).unwrap();
//! let square = |x: i32| ConvexPolygon::from_grid_points(&[g(x - 4, 5, 4), g(x + 4, 5, 4), g(x + 4, 5, -4), g(x - 4, 5, -4)], 1).unwrap();
//! let light = AreaSource::from_grid_points(&[g(-1, 10, -1), g(1, 10, -1), g(1, 10, 1), g(-1, 10, 1)]).unwrap();
//! // The square (object 1) will move: declared movable, its shadow's
//! // nodes go to the bottom of the floor's tree.
//! let (mut scene, ids) = DmScene::build_movable(
//!     vec![DmLight::new(light, 1.0).unwrap()],
//!     vec![(vec![floor], PieceFlags::default()), (vec![square(0)], PieceFlags::default())],
//!     &[1],
//!     DmOptions::default(),
//! ).unwrap();
//! let floor_id = scene.object_pieces(ids[0]).unwrap()[0];
//! let area = |scene: &DmScene, class| -> f64 {
//!     let dm = scene.receiver(floor_id).unwrap();
//!     dm.cells().filter(|(_, c)| dm.class(c, 0) == class)
//!         .map(|(f, _)| dm.mesh().face_polygon(f, 0).unwrap().area()).sum()
//! };
//! // The umbra is [-7, 7]^2, the penumbra reaches [-9, 9]^2.
//! assert!((area(&scene, CellClass::Umbra) - 14.0 * 14.0).abs() < 1e-9);
//! assert!((area(&scene, CellClass::Penumbra) - (18.0 * 18.0 - 14.0 * 14.0)).abs() < 1e-9);
//! // Move the occluder 10 units along x: the umbra moves with it, and the
//! // floor is among the receivers to read again.
//! let before = scene.revision();
//! scene.translate_object(ids[1], [10, 0, 0]).unwrap();
//! assert!(scene.receivers_changed_since(before).any(|p| p == floor_id));
//! assert_eq!(scene.piece_polygon(scene.object_pieces(ids[1]).unwrap()[0]), Some(&square(10)));
//! assert!((area(&scene, CellClass::Umbra) - 14.0 * 14.0).abs() < 1e-9);
//! let stats = scene.illuminate();
//! assert!(stats.vertices > 0);
//! ```

mod cell;
mod critical;
mod error;
mod hash;
mod illuminate;
mod marks;
mod order;
mod overlap;
mod scene;
mod surface;
mod tree;

pub use area_shadow;
pub use bsp_core;
pub use cell::{Cell, CellClass, Entry, Sides};
pub use error::Error;
pub use illuminate::IllumStats;
pub use overlap::{OverlapFigures, OverlapKind};
pub use scene::{DmLight, DmOptions, DmScene, ObjectId, PieceId};
pub use tree::{Deletion, ReceiverDm, Region};
