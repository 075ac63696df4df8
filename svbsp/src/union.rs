//! Union of a BSP solid with a convex polyhedron by insertion (Thibault &
//! Naylor, *Set Operations on Polyhedra Using Binary Space Partitioning
//! Trees*, SIGGRAPH 1987), in its general form.
//!
//! The polyhedron `P` is filtered down the tree as a volume: at each node it
//! is split exactly into the parts behind and in front of the node's plane
//! ([`ConvexPolyhedron::split`]), each part carrying the faces of `P` that
//! still bound it. A part that reaches an `In` leaf changes nothing; a part
//! that reaches an `Out` leaf replaces the leaf with a chain of the planes
//! of `P` that still bound that part, `In` behind the last. A cell that lies
//! wholly inside `P` receives a part with no face of `P` left and simply
//! becomes `In`.
//!
//! Filtering the volume rather than the faces is what makes this the
//! general union: the simplified insertion of Chin & Feiner (1989) filters
//! only the faces and hangs the whole volume at every leaf a face reaches,
//! which is exact only when the new volume overlaps no `In` region and no
//! leaf cell lies inside it. Penumbra volumes overlap, so the area-light
//! trees need this version.
//!
//! The tree keeps every existing node; inserted chains are appended to the
//! arena. The traversal uses an explicit stack.

use crate::polyhedron::{CellParts, ConvexPolyhedron};
use bsp_core::{BspSolid, Region, SolidChild, SolidNode};

/// `solid ∪ polyhedron`.
///
/// ```
/// use bsp_core::{BspSolid, GridPoint, Plane, PointClass};
/// use svbsp::{ConvexPolyhedron, union_with_convex};
///
/// let g = |x, y, z| GridPoint { x, y, z };
/// // The cube [-1, 1]^3 from its six planes.
/// let planes: Vec<Plane> = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
///     .map(|n: [i64; 3]| Plane::with_normal_through(n, g(n[0] as i32, n[1] as i32, n[2] as i32)).unwrap())
///     .to_vec();
/// let cube = ConvexPolyhedron::from_planes(&planes).unwrap();
/// let solid = union_with_convex(&BspSolid::empty(), &cube);
/// assert_eq!(solid.classify_point(g(0, 0, 0)), PointClass::In);
/// assert_eq!(solid.classify_point(g(1, 0, 0)), PointClass::On);
/// assert_eq!(solid.classify_point(g(2, 0, 0)), PointClass::Out);
/// ```
pub fn union_with_convex(solid: &BspSolid, polyhedron: &ConvexPolyhedron) -> BspSolid {
    let mut nodes: Vec<SolidNode> = solid.nodes().to_vec();
    let mut root = solid.root();
    union_in_place(&mut nodes, &mut root, polyhedron.clone());
    BspSolid::from_nodes(nodes, root).expect("insertion keeps a tree")
}

/// [`union_with_convex`] on a tree held as an arena (`nodes`, `root`),
/// changed in place: no node is copied, so a tree grown by many insertions
/// (the penumbra and umbra trees of an area light) costs only the nodes
/// each insertion visits and appends.
///
/// ```
/// use bsp_core::{GridPoint, Plane, Region, SolidChild};
/// use svbsp::{ConvexPolyhedron, union_in_place};
///
/// let g = |x, y, z| GridPoint { x, y, z };
/// let planes: Vec<Plane> = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
///     .map(|n: [i64; 3]| Plane::with_normal_through(n, g(n[0] as i32, n[1] as i32, n[2] as i32)).unwrap())
///     .to_vec();
/// let (mut nodes, mut root) = (Vec::new(), SolidChild::Leaf(Region::Out));
/// union_in_place(&mut nodes, &mut root, ConvexPolyhedron::from_planes(&planes).unwrap());
/// assert_eq!(nodes.len(), 6);
/// ```
pub fn union_in_place(
    nodes: &mut Vec<SolidNode>,
    root: &mut SolidChild,
    polyhedron: ConvexPolyhedron,
) {
    // (subtree, part of P in its cell, where the subtree hangs: None for
    // the root, else (parent, is front child)).
    let mut stack = vec![(*root, polyhedron, None::<(u32, bool)>)];
    while let Some((mut child, mut part, mut slot)) = stack.pop() {
        loop {
            let i = match child {
                SolidChild::Leaf(Region::In) => break,
                SolidChild::Leaf(Region::Out) => {
                    let link = hang_chain(nodes, &part);
                    match slot {
                        None => *root = link,
                        Some((parent, true)) => nodes[parent as usize].front = link,
                        Some((parent, false)) => nodes[parent as usize].back = link,
                    }
                    break;
                }
                SolidChild::Node(i) => i,
            };
            let node = nodes[i as usize];
            match part.into_split(&node.plane) {
                CellParts::Back(whole) => {
                    (child, part, slot) = (node.back, whole, Some((i, false)))
                }
                CellParts::Front(whole) => {
                    (child, part, slot) = (node.front, whole, Some((i, true)))
                }
                CellParts::Both { back, front, .. } => {
                    stack.push((node.back, back, Some((i, false))));
                    (child, part, slot) = (node.front, front, Some((i, true)));
                }
            }
        }
    }
}

/// Appends the chain of `part`'s remaining input planes (outside in front of
/// each, `In` behind the last) and returns its link.
fn hang_chain(nodes: &mut Vec<SolidNode>, part: &ConvexPolyhedron) -> SolidChild {
    let planes = part.input_planes();
    if planes.is_empty() {
        return SolidChild::Leaf(Region::In);
    }
    let first = nodes.len() as u32;
    let count = planes.len() as u32;
    for (k, plane) in planes.into_iter().enumerate() {
        let k = k as u32;
        nodes.push(SolidNode {
            plane,
            front: SolidChild::Leaf(Region::Out),
            back: if k + 1 == count {
                SolidChild::Leaf(Region::In)
            } else {
                SolidChild::Node(first + k + 1)
            },
        });
    }
    SolidChild::Node(first)
}
