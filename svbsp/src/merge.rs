//! Set operations on BSP solids by tree merging (Naylor, Amanatides &
//! Thibault, *Merging BSP Trees Yields Polyhedral Set Operations*,
//! SIGGRAPH 1990).
//!
//! `merge(A, B, op)` walks `A`; at each inner node of `A` it partitions the
//! part of `B` in the node's cell by the node's *sub-hyperplane* (its plane
//! restricted to its cell) into the parts behind and in front, and recurses
//! on both sides; where `A` (or `B`) reaches a leaf, the operation's truth
//! table picks the leaf or the other tree. Cells are convex polyhedra closed
//! by the bounding box `[-2^24, 2^24]^3` ([`ConvexPolyhedron`]), so results
//! are exact for every grid point; what lies outside the box is not
//! represented.
//!
//! Partitioning a tree `T` by a plane `H` with sub-hyperplane `s_H` (the
//! paper's `partition_tree`) looks, at each node `v` with plane `H_v` and
//! sub-hyperplane `s_v`, at how `s_H` lies against `H_v`:
//!
//! - `H_v` is `H` (same orientation or opposite): `v`'s children are the
//!   two halves, swapped if opposite;
//! - `s_H` is cut by `H_v`: so is `s_v` by `H` (both pass through the
//!   cell's interior); `v` splits into a node behind `H` and one in front
//!   (each with its part of `s_v`), and both children are partitioned with
//!   their parts of `s_H`;
//! - `s_H` lies on one side of `H_v`: the child on that side is partitioned
//!   by `s_H`; the child on the other side does not meet `H`, and which
//!   side of `H` it lies on is the side of `s_v` (its face on `H_v`), so it
//!   stays whole under a copy of `v` on that side of `H`.
//!
//! `B` is annotated with its sub-hyperplanes up front (partitioning needs
//! them wherever it goes); `A` is walked with its cells, so that its
//! sub-hyperplanes are computed only where `B` still has structure.
//!
//! Every decision is an exact kernel predicate. All traversals use explicit
//! stacks (trees can be thousands of nodes deep); `B`'s subtrees are moved,
//! never copied, and a final pass drops nodes whose children are the same
//! leaf.

use crate::polyhedron::{CellParts, ConvexPolyhedron};
use bsp_core::{BspSolid, ConvexPolygon, Plane, PolygonSide, Region, SolidChild, SolidNode, Split};

/// A Boolean set operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SetOp {
    /// `A ∪ B`.
    Union,
    /// `A ∩ B`.
    Intersection,
    /// `A \ B`.
    Difference,
}

impl SetOp {
    /// The operation on membership: whether a point in `A` (or not) and in
    /// `B` (or not) is in the result.
    pub fn apply(self, in_a: bool, in_b: bool) -> bool {
        match self {
            SetOp::Union => in_a || in_b,
            SetOp::Intersection => in_a && in_b,
            SetOp::Difference => in_a && !in_b,
        }
    }
}

/// A node of a tree under merging: its plane, its sub-hyperplane (the plane
/// restricted to the node's cell, oriented like the plane; `None` in nodes
/// of the result that will not be partitioned again) and its children, as
/// links into the same arena.
#[derive(Debug, Clone)]
pub(crate) struct WorkNode {
    pub plane: Plane,
    pub section: Option<ConvexPolygon>,
    pub front: SolidChild,
    pub back: SolidChild,
}

/// Where a result link goes: into a node of the arena, or into one of a
/// fixed number of result registers.
#[derive(Debug, Clone, Copy)]
enum Slot {
    Register(usize),
    Front(u32),
    Back(u32),
}

fn set(arena: &mut [WorkNode], registers: &mut [SolidChild], slot: Slot, link: SolidChild) {
    match slot {
        Slot::Register(r) => registers[r] = link,
        Slot::Front(i) => arena[i as usize].front = link,
        Slot::Back(i) => arena[i as usize].back = link,
    }
}

/// Copies `solid` into `arena` with the sub-hyperplane of each node in the
/// bounding box. A node whose plane misses its cell's interior (possible
/// only outside the box, or for a redundant node) is replaced by the child
/// on the cell's side. Returns the root link.
pub(crate) fn annotate(solid: &BspSolid, arena: &mut Vec<WorkNode>) -> SolidChild {
    let mut registers = [SolidChild::Leaf(Region::Out)];
    let mut stack = vec![(
        solid.root(),
        ConvexPolyhedron::bounding_box(),
        Slot::Register(0),
    )];
    while let Some((mut child, mut cell, mut slot)) = stack.pop() {
        loop {
            let i = match child {
                SolidChild::Leaf(_) => {
                    set(arena, &mut registers, slot, child);
                    break;
                }
                SolidChild::Node(i) => i,
            };
            let node = &solid.nodes()[i as usize];
            match cell.into_split(&node.plane) {
                CellParts::Back(whole) => (child, cell) = (node.back, whole),
                CellParts::Front(whole) => (child, cell) = (node.front, whole),
                CellParts::Both {
                    back,
                    front,
                    section,
                } => {
                    let id = arena.len() as u32;
                    arena.push(WorkNode {
                        plane: node.plane,
                        section: Some(section),
                        front: SolidChild::Leaf(Region::Out),
                        back: SolidChild::Leaf(Region::Out),
                    });
                    set(arena, &mut registers, slot, SolidChild::Node(id));
                    stack.push((node.back, back, Slot::Back(id)));
                    (child, cell, slot) = (node.front, front, Slot::Front(id));
                }
            }
        }
    }
    registers[0]
}

/// Partitions the subtree `tree` (its nodes carrying sub-hyperplanes in
/// their cells) by `plane`, whose part in the subtree's cell is `section`:
/// returns `(part behind, part in front)`. Consumes the subtree: its nodes
/// are reused, and new nodes are appended for nodes the plane cuts.
pub(crate) fn partition(
    arena: &mut Vec<WorkNode>,
    tree: SolidChild,
    plane: &Plane,
    section: ConvexPolygon,
) -> (SolidChild, SolidChild) {
    let mut registers = [SolidChild::Leaf(Region::Out); 2];
    let mut stack = vec![(tree, section, Slot::Register(0), Slot::Register(1))];
    while let Some((mut t, mut s, mut to_back, mut to_front)) = stack.pop() {
        loop {
            let i = match t {
                SolidChild::Leaf(_) => {
                    set(arena, &mut registers, to_back, t);
                    set(arena, &mut registers, to_front, t);
                    break;
                }
                SolidChild::Node(i) => i,
            };
            let node = &arena[i as usize];
            let (v_plane, v_front, v_back) = (node.plane, node.front, node.back);
            if v_plane == *plane {
                set(arena, &mut registers, to_back, v_back);
                set(arena, &mut registers, to_front, v_front);
                break;
            }
            if v_plane.is_opposite(plane) {
                set(arena, &mut registers, to_back, v_front);
                set(arena, &mut registers, to_front, v_back);
                break;
            }
            match s.split(&v_plane) {
                Split::Both(s_back, s_front) => {
                    // `s_H` crosses the cell's interior on both sides of
                    // `H_v`, so `H` crosses `s_v`.
                    let Split::Both(v_section_back, v_section_front) =
                        section_of(arena, i).split(plane)
                    else {
                        unreachable!("sub-hyperplanes that cross each other cut each other");
                    };
                    arena[i as usize].section = Some(v_section_back);
                    let j = arena.len() as u32;
                    arena.push(WorkNode {
                        plane: v_plane,
                        section: Some(v_section_front),
                        front: SolidChild::Leaf(Region::Out),
                        back: SolidChild::Leaf(Region::Out),
                    });
                    set(arena, &mut registers, to_back, SolidChild::Node(i));
                    set(arena, &mut registers, to_front, SolidChild::Node(j));
                    stack.push((v_back, s_back, Slot::Back(i), Slot::Back(j)));
                    (t, s, to_back, to_front) = (v_front, s_front, Slot::Front(i), Slot::Front(j));
                }
                Split::Front => {
                    // `s_H` is in front of `H_v`: `v.back` does not meet `H`
                    // and lies on the side of `H` where `s_v` is.
                    if section_behind(section_of(arena, i), plane) {
                        set(arena, &mut registers, to_back, SolidChild::Node(i));
                        to_back = Slot::Front(i);
                    } else {
                        set(arena, &mut registers, to_front, SolidChild::Node(i));
                        to_front = Slot::Front(i);
                    }
                    t = v_front;
                }
                Split::Back => {
                    if section_behind(section_of(arena, i), plane) {
                        set(arena, &mut registers, to_back, SolidChild::Node(i));
                        to_back = Slot::Back(i);
                    } else {
                        set(arena, &mut registers, to_front, SolidChild::Node(i));
                        to_front = Slot::Back(i);
                    }
                    t = v_back;
                }
                Split::Coplanar(_) => unreachable!("coincident planes are handled above"),
            }
        }
    }
    (registers[0], registers[1])
}

/// The sub-hyperplane of a node of an annotated tree.
fn section_of(arena: &[WorkNode], i: u32) -> &ConvexPolygon {
    arena[i as usize]
        .section
        .as_ref()
        .expect("nodes under partition carry their sub-hyperplanes")
}

/// Whether a sub-hyperplane that `plane` does not cut lies behind it.
fn section_behind(section: &ConvexPolygon, plane: &Plane) -> bool {
    match section.classify(plane) {
        PolygonSide::Back => true,
        PolygonSide::Front => false,
        other => unreachable!("a sub-hyperplane off the plane's section is {other:?}"),
    }
}

/// `A op B` as a new solid, exact within the bounding box.
///
/// ```
/// use bsp_core::{BspSolid, GridPoint, Plane};
/// use svbsp::{SetOp, merge};
///
/// let g = |x, y, z| GridPoint { x, y, z };
/// // Half-spaces x < 0 and y < 0 as one-node solids.
/// let half = |p: Plane| {
///     BspSolid::from_nodes(
///         vec![bsp_core::SolidNode {
///             plane: p,
///             front: bsp_core::SolidChild::Leaf(bsp_core::Region::Out),
///             back: bsp_core::SolidChild::Leaf(bsp_core::Region::In),
///         }],
///         bsp_core::SolidChild::Node(0),
///     )
///     .unwrap()
/// };
/// let a = half(Plane::with_normal_through([1, 0, 0], g(0, 0, 0)).unwrap());
/// let b = half(Plane::with_normal_through([0, 1, 0], g(0, 0, 0)).unwrap());
/// let both = merge(&a, &b, SetOp::Intersection);
/// assert_eq!(both.classify_point(g(-1, -1, 5)), bsp_core::PointClass::In);
/// assert_eq!(both.classify_point(g(-1, 1, 5)), bsp_core::PointClass::Out);
/// ```
pub fn merge(a: &BspSolid, b: &BspSolid, op: SetOp) -> BspSolid {
    // A \ B = A ∩ complement(B): the complement only flips leaves.
    let (b, op) = match op {
        SetOp::Difference => (b.complement(), SetOp::Intersection),
        _ => (b.clone(), op),
    };
    let mut arena: Vec<WorkNode> = Vec::with_capacity(2 * (a.nodes().len() + b.nodes().len()));
    let root_b = annotate(&b, &mut arena);
    let root = merge_into(&mut arena, a, root_b, op);
    compact(&arena, root)
}

/// Merges `a` with the annotated tree `root_b` in `arena` by `Union` or
/// `Intersection`; returns the root of the result in `arena`.
///
/// `a` is walked with its cells (split on the way down), so that its
/// sub-hyperplanes are computed only where `b` has structure left to
/// partition; where `b` is a leaf, `a`'s subtree is copied as it is.
fn merge_into(
    arena: &mut Vec<WorkNode>,
    a: &BspSolid,
    root_b: SolidChild,
    op: SetOp,
) -> SolidChild {
    debug_assert!(op != SetOp::Difference);
    let mut registers = [SolidChild::Leaf(Region::Out)];
    let mut stack = vec![(
        Slot::Register(0),
        a.root(),
        ConvexPolyhedron::bounding_box(),
        root_b,
    )];
    while let Some((slot, mut ta, mut cell, tb)) = stack.pop() {
        let link = loop {
            break match (ta, tb, op) {
                (SolidChild::Leaf(Region::In), _, SetOp::Union)
                | (_, SolidChild::Leaf(Region::In), SetOp::Union) => SolidChild::Leaf(Region::In),
                (SolidChild::Leaf(Region::Out), _, SetOp::Union) => tb,
                (_, SolidChild::Leaf(Region::Out), SetOp::Union) => copy_subtree(arena, a, ta),
                (SolidChild::Leaf(Region::Out), _, _) | (_, SolidChild::Leaf(Region::Out), _) => {
                    SolidChild::Leaf(Region::Out)
                }
                (SolidChild::Leaf(Region::In), _, _) => tb,
                (_, SolidChild::Leaf(Region::In), _) => copy_subtree(arena, a, ta),
                (SolidChild::Node(i), _, _) => {
                    let node = a.nodes()[i as usize];
                    match cell.into_split(&node.plane) {
                        // The plane misses the cell: only one child matters.
                        CellParts::Back(whole) => {
                            (ta, cell) = (node.back, whole);
                            continue;
                        }
                        CellParts::Front(whole) => {
                            (ta, cell) = (node.front, whole);
                            continue;
                        }
                        CellParts::Both {
                            back,
                            front,
                            section,
                        } => {
                            let (b_back, b_front) = partition(arena, tb, &node.plane, section);
                            let id = arena.len() as u32;
                            arena.push(WorkNode {
                                plane: node.plane,
                                section: None,
                                front: SolidChild::Leaf(Region::Out),
                                back: SolidChild::Leaf(Region::Out),
                            });
                            stack.push((Slot::Back(id), node.back, back, b_back));
                            stack.push((Slot::Front(id), node.front, front, b_front));
                            SolidChild::Node(id)
                        }
                    }
                }
            };
        };
        set(arena, &mut registers, slot, link);
    }
    registers[0]
}

/// Copies the subtree of `solid` under `root` into `arena` (without
/// sub-hyperplanes: it is final) and returns its link.
fn copy_subtree(arena: &mut Vec<WorkNode>, solid: &BspSolid, root: SolidChild) -> SolidChild {
    let mut registers = [SolidChild::Leaf(Region::Out)];
    let mut stack = vec![(root, Slot::Register(0))];
    while let Some((child, slot)) = stack.pop() {
        let link = match child {
            SolidChild::Leaf(_) => child,
            SolidChild::Node(i) => {
                let node = &solid.nodes()[i as usize];
                let id = arena.len() as u32;
                arena.push(WorkNode {
                    plane: node.plane,
                    section: None,
                    front: SolidChild::Leaf(Region::Out),
                    back: SolidChild::Leaf(Region::Out),
                });
                stack.push((node.back, Slot::Back(id)));
                stack.push((node.front, Slot::Front(id)));
                SolidChild::Node(id)
            }
        };
        set(arena, &mut registers, slot, link);
    }
    registers[0]
}

/// The tree under `root` as a [`BspSolid`], dropping every node whose two
/// children end up the same leaf (bottom-up, so chains of them collapse).
pub(crate) fn compact(arena: &[WorkNode], root: SolidChild) -> BspSolid {
    // Pre-order over the reachable nodes; reversed, children come first.
    let mut order: Vec<u32> = Vec::new();
    let mut stack = vec![root];
    while let Some(child) = stack.pop() {
        if let SolidChild::Node(i) = child {
            order.push(i);
            let node = &arena[i as usize];
            stack.push(node.back);
            stack.push(node.front);
        }
    }
    // What each reachable node simplifies to: itself, or a leaf.
    let mut simplified: Vec<SolidChild> = vec![SolidChild::Leaf(Region::Out); arena.len()];
    let resolve = |c: SolidChild, simplified: &[SolidChild]| match c {
        SolidChild::Node(j) => simplified[j as usize],
        leaf => leaf,
    };
    for &i in order.iter().rev() {
        let node = &arena[i as usize];
        let (front, back) = (
            resolve(node.front, &simplified),
            resolve(node.back, &simplified),
        );
        simplified[i as usize] = match (front, back) {
            (SolidChild::Leaf(f), SolidChild::Leaf(b)) if f == b => SolidChild::Leaf(f),
            _ => SolidChild::Node(i),
        };
    }
    // Renumber the kept nodes in pre-order.
    let mut new_index: Vec<u32> = vec![u32::MAX; arena.len()];
    let mut nodes: Vec<SolidNode> = Vec::new();
    for &i in &order {
        if simplified[i as usize] == SolidChild::Node(i) {
            new_index[i as usize] = nodes.len() as u32;
            nodes.push(SolidNode {
                plane: arena[i as usize].plane,
                front: SolidChild::Leaf(Region::Out),
                back: SolidChild::Leaf(Region::Out),
            });
        }
    }
    let relink = |c: SolidChild| match resolve(c, &simplified) {
        SolidChild::Node(j) => SolidChild::Node(new_index[j as usize]),
        leaf => leaf,
    };
    for &i in &order {
        let k = new_index[i as usize];
        if k != u32::MAX {
            let node = &arena[i as usize];
            nodes[k as usize].front = relink(node.front);
            nodes[k as usize].back = relink(node.back);
        }
    }
    BspSolid::from_nodes(nodes, relink(root)).expect("a compacted tree is a tree")
}

#[cfg(test)]
mod tests {
    use super::*;
    use bsp_core::{GridPoint, PointClass};

    fn gp(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    /// The axis-aligned box `[lo, hi]` as a chain of six planes.
    fn box_solid(lo: [i32; 3], hi: [i32; 3]) -> BspSolid {
        let mut nodes = Vec::new();
        for axis in 0..3 {
            for (sign, v) in [(1_i64, hi[axis]), (-1, lo[axis])] {
                let mut n = [0; 3];
                n[axis] = sign;
                let mut p = [0; 3];
                p[axis] = v;
                let plane = Plane::with_normal_through(n, gp(p[0], p[1], p[2])).unwrap();
                let id = nodes.len() as u32;
                nodes.push(SolidNode {
                    plane,
                    front: SolidChild::Leaf(Region::Out),
                    back: SolidChild::Node(id + 1),
                });
            }
        }
        nodes.last_mut().unwrap().back = SolidChild::Leaf(Region::In);
        BspSolid::from_nodes(nodes, SolidChild::Node(0)).unwrap()
    }

    #[test]
    fn boxes_combine_pointwise() {
        let a = box_solid([0, 0, 0], [4, 4, 4]);
        let b = box_solid([2, 2, 2], [6, 6, 4]);
        for op in [SetOp::Union, SetOp::Intersection, SetOp::Difference] {
            let r = merge(&a, &b, op);
            r.check_invariants().unwrap();
            for x in -1..8 {
                for y in -1..8 {
                    for z in -1..6 {
                        let p = gp(x, y, z);
                        let (ca, cb) = (a.classify_point(p), b.classify_point(p));
                        if ca == PointClass::On || cb == PointClass::On {
                            continue;
                        }
                        let want = op.apply(ca == PointClass::In, cb == PointClass::In);
                        let got = r.classify_point(p);
                        assert_eq!(got == PointClass::In, want, "{op:?} at {p:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_with_itself_and_its_complement() {
        let a = box_solid([0, 0, 0], [4, 4, 4]);
        assert_eq!(merge(&a, &a.complement(), SetOp::Union), BspSolid::full());
        assert_eq!(
            merge(&a, &a.complement(), SetOp::Intersection),
            BspSolid::empty()
        );
        assert_eq!(merge(&a, &a, SetOp::Difference), BspSolid::empty());
        let same = merge(&a, &a, SetOp::Union);
        assert_eq!(same.classify_point(gp(1, 1, 1)), PointClass::In);
        assert_eq!(same.nodes().len(), 6);
    }
}
