//! Balanced BSP solids from closed boundaries: axis-aligned splits at the
//! top, Thibault-Naylor autopartitions at the bottom.
//!
//! [`BspSolid::from_boundary`] is an autopartition: every splitting plane is
//! a face's plane. For a convex or star-shaped surface nearly every face has
//! all others behind it, so the tree is a chain as deep as the mesh is
//! large, and filtering a polygon down it costs time linear in the mesh.
//! Here the faces are first divided by axis-aligned planes through grid
//! points (`x = c`, at the median of the face centroids along the widest
//! axis, in the spirit of the octree-embedded BSPs of Nehring-Wirxel,
//! Trettner & Kobbelt 2021) until a cell holds few faces; the faces of each
//! cell are then autopartitioned as usual.
//!
//! The leaves keep the autopartition's labels (an empty region in front of
//! its last plane is outside, one behind is inside). That stays right in a
//! cell holding part of the surface: an empty region of the cell's
//! autopartition is convex, holds no surface, and touches the face whose
//! plane bounds it. An axis split is used only if it leaves faces on both
//! sides (so no cell is empty of surface, where no face could tell its
//! label) and lies in no face's plane.

use bsp_core::{
    BspSolid, BuildOptions, ConvexPolygon, LeafLabel, Plane, PolygonSide, Region, Side, SolidChild,
    SolidNode, Split,
};

/// How [`balanced_solid`] divides the faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BalancedOptions {
    /// A cell with at most this many faces is autopartitioned.
    pub leaf_faces: usize,
    /// Options of the autopartitions of the cells.
    pub autopartition: BuildOptions,
}

impl Default for BalancedOptions {
    fn default() -> Self {
        Self {
            leaf_faces: 24,
            // In a cell of a closed surface nearly every candidate scores
            // alike (all other faces behind it): the first face does about
            // as well as the best of eight (a few % more nodes), and no
            // scoring at all is needed.
            autopartition: BuildOptions {
                candidates: 1,
                ..BuildOptions::default()
            },
        }
    }
}

/// The solid bounded by `faces` (a closed polyhedron's faces, outward), as a
/// balanced tree. Meaningful only if the faces close up, like
/// [`BspSolid::from_boundary`].
pub fn balanced_solid(faces: Vec<ConvexPolygon>, options: &BalancedOptions) -> BspSolid {
    balanced_solid_labelled(faces, options, &|_, _| None)
}

/// [`balanced_solid`], its empty regions labelled by `label` where it
/// answers ([`BspSolid::from_boundary_labelled`]; the planes bounding a
/// region start with the axis splits above its cell).
pub fn balanced_solid_labelled(
    faces: Vec<ConvexPolygon>,
    options: &BalancedOptions,
    label: LeafLabel<'_>,
) -> BspSolid {
    let mut nodes: Vec<SolidNode> = Vec::new();
    let mut root = SolidChild::Leaf(Region::Out);
    // (faces of the cell, where its subtree hangs).
    // Each face travels with the centroid of its input face: fragments
    // inherit it, which is good enough to place medians and saves
    // converting implicit vertices at every level.
    let faces: Faces = faces
        .into_iter()
        .map(|f| {
            let c = centroid(&f);
            (f, c)
        })
        .collect();
    // (Each cell with the axis planes that bound it, for `label`.)
    let mut stack: Vec<(Faces, Hang, Bounds)> = vec![(faces, None, Vec::new())];
    while let Some((list, slot, bounds)) = stack.pop() {
        let link = match axis_split(list, options.leaf_faces) {
            Ok((plane, back, front)) => {
                let id = nodes.len() as u32;
                nodes.push(SolidNode {
                    plane,
                    front: SolidChild::Leaf(Region::Out),
                    back: SolidChild::Leaf(Region::Out),
                });
                let within = |side| [bounds.as_slice(), &[(plane, side)]].concat();
                stack.push((back, Some((id, false)), within(Side::Back)));
                stack.push((front, Some((id, true)), within(Side::Front)));
                SolidChild::Node(id)
            }
            Err(list) => {
                let list = list.into_iter().map(|(f, _)| f).collect();
                let in_cell = |path: &[(Plane, Side)], pieces: &[ConvexPolygon]| {
                    label(&[bounds.as_slice(), path].concat(), pieces)
                };
                graft(
                    &mut nodes,
                    BspSolid::from_boundary_labelled(list, &options.autopartition, &in_cell),
                )
            }
        };
        match slot {
            None => root = link,
            Some((parent, true)) => nodes[parent as usize].front = link,
            Some((parent, false)) => nodes[parent as usize].back = link,
        }
    }
    BspSolid::from_nodes(nodes, root).expect("the builder makes a tree")
}

/// The axis planes around a cell, each with the side the cell lies on.
type Bounds = Vec<(Plane, Side)>;

/// Where a subtree hangs: `None` for the root, else `(parent, is front
/// child)`.
type Hang = Option<(u32, bool)>;

/// The axis-aligned split of `list`, or the list back if it is small or no
/// good split exists.
fn axis_split(list: Faces, leaf_faces: usize) -> Result<AxisSplit, Faces> {
    if list.len() <= leaf_faces.max(1) {
        return Err(list);
    }
    let extent = |k: usize| {
        let (lo, hi) = list
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (_, c)| {
                (lo.min(c[k]), hi.max(c[k]))
            });
        hi - lo
    };
    let axis = (0..3)
        .max_by(|&a, &b| extent(a).total_cmp(&extent(b)))
        .expect("three axes");
    let mut coords: Vec<f64> = list.iter().map(|(_, c)| c[axis]).collect();
    let mid = coords.len() / 2;
    let (_, median, _) = coords.select_nth_unstable_by(mid, f64::total_cmp);
    let value = median.round().clamp(
        -f64::from(bsp_core::GRID_LIMIT),
        f64::from(bsp_core::GRID_LIMIT),
    ) as i32;
    let mut normal = [0_i64; 3];
    normal[axis] = 1;
    let mut point = [0_i32; 3];
    point[axis] = value;
    let Some(plane) = Plane::with_normal_through(
        normal,
        bsp_core::GridPoint {
            x: point[0],
            y: point[1],
            z: point[2],
        },
    ) else {
        return Err(list);
    };
    // Classify first (nothing is built), so that a rejected split gives the
    // list back untouched and an accepted one moves its faces.
    let (mut backs, mut fronts) = (0, 0);
    let mut sides = Vec::with_capacity(list.len());
    for (polygon, _) in &list {
        let side = polygon.classify(&plane);
        match side {
            PolygonSide::Back => backs += 1,
            PolygonSide::Front => fronts += 1,
            PolygonSide::Both => {
                backs += 1;
                fronts += 1;
            }
            PolygonSide::Coplanar(_) => return Err(list),
        }
        sides.push(side);
    }
    // Splits that barely divide would only add depth.
    if backs == 0 || fronts == 0 || backs.max(fronts) > list.len() * 7 / 8 {
        return Err(list);
    }
    let (mut back, mut front) = (Vec::with_capacity(backs), Vec::with_capacity(fronts));
    for ((polygon, c), side) in list.into_iter().zip(sides) {
        match side {
            PolygonSide::Back => back.push((polygon, c)),
            PolygonSide::Front => front.push((polygon, c)),
            _ => match polygon.split(&plane) {
                Split::Both(b, f) => {
                    back.push((b, c));
                    front.push((f, c));
                }
                _ => unreachable!("classify and split agree"),
            },
        }
    }
    Ok((plane, back, front))
}

/// Mean of a polygon's vertices.
fn centroid(polygon: &ConvexPolygon) -> [f64; 3] {
    let v = polygon.vertices_f64();
    let n = v.len() as f64;
    let s = v
        .iter()
        .fold([0.0; 3], |a, q| [a[0] + q[0], a[1] + q[1], a[2] + q[2]]);
    s.map(|c| c / n)
}

/// Faces (or fragments) with the centroids of their input faces.
type Faces = Vec<(ConvexPolygon, [f64; 3])>;

/// A splitting plane and the faces behind and in front of it.
type AxisSplit = (Plane, Faces, Faces);

/// Appends `sub`'s nodes to `nodes` and returns the link to its root.
fn graft(nodes: &mut Vec<SolidNode>, sub: BspSolid) -> SolidChild {
    let offset = nodes.len() as u32;
    let shift = |c: SolidChild| match c {
        SolidChild::Node(i) => SolidChild::Node(i + offset),
        leaf => leaf,
    };
    nodes.extend(sub.nodes().iter().map(|n| SolidNode {
        plane: n.plane,
        front: shift(n.front),
        back: shift(n.back),
    }));
    shift(sub.root())
}
