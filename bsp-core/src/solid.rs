//! BSP solids (Thibault & Naylor 1987): trees whose leaves are inside or
//! outside a polyhedron.

use crate::autopartition::{self, BuildOptions, Link};
use crate::predicates::{Side, side_of_point};
use crate::{ConvexPolygon, Facing, GridPoint, Plane, Split};

/// What a leaf of a solid is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Region {
    /// Inside the solid.
    In,
    /// Outside the solid.
    Out,
}

/// A child of a solid's node: a node (by index) or a labelled leaf.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SolidChild {
    /// An inner node, by index into [`BspSolid::nodes`].
    Node(u32),
    /// A leaf cell, in or out.
    Leaf(Region),
}

/// An inner node of a solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SolidNode {
    /// The splitting plane.
    pub plane: Plane,
    /// The subtree in front of `plane`.
    pub front: SolidChild,
    /// The subtree behind `plane`.
    pub back: SolidChild,
}

/// Where a point lies relative to a solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PointClass {
    /// In the interior.
    In,
    /// In the exterior.
    Out,
    /// On the boundary.
    On,
}

/// Where a piece of a polygon lies relative to a solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Containment {
    /// Inside the solid, both sides.
    Inside,
    /// Outside the solid, both sides.
    Outside,
    /// On the boundary, the solid behind it: it faces out, like the solid's
    /// own boundary.
    BoundarySame,
    /// On the boundary, the solid in front of it: it faces in.
    BoundaryOpposite,
}

impl Containment {
    /// From the regions on the piece's front and back sides.
    pub fn from_sides(front: Region, back: Region) -> Self {
        match (front, back) {
            (Region::In, Region::In) => Containment::Inside,
            (Region::Out, Region::Out) => Containment::Outside,
            (Region::Out, Region::In) => Containment::BoundarySame,
            (Region::In, Region::Out) => Containment::BoundaryOpposite,
        }
    }
}

/// A polyhedral solid as a BSP tree with in / out leaves.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BspSolid {
    nodes: Vec<SolidNode>,
    root: SolidChild,
}

/// A node still to visit in [`BspSolid::from_boundary_labelled`]'s walk:
/// its number, the length of its path from the root, and the last step
/// of that path (the side of its parent's plane it lies on; none for the
/// root).
struct Visit {
    node: u32,
    depth: usize,
    step: Option<(Plane, Side)>,
}

/// Labels an empty region of [`BspSolid::from_boundary_labelled`] from
/// the planes that bound it, root first (each with the side the region
/// lies on; the last is the plane of the node above it), and the
/// boundary's pieces lying in that last plane there; `None` keeps the
/// last plane's label.
pub type LeafLabel<'a> = &'a dyn Fn(&[(Plane, Side)], &[ConvexPolygon]) -> Option<Region>;

impl BspSolid {
    /// The empty set.
    pub fn empty() -> Self {
        Self {
            nodes: Vec::new(),
            root: SolidChild::Leaf(Region::Out),
        }
    }

    /// All of space.
    pub fn full() -> Self {
        Self {
            nodes: Vec::new(),
            root: SolidChild::Leaf(Region::In),
        }
    }

    /// A solid from nodes and a root; `None` if a link points outside
    /// `nodes` or the links do not form a tree (a node reached twice, or a
    /// cycle).
    pub fn from_nodes(nodes: Vec<SolidNode>, root: SolidChild) -> Option<Self> {
        let mut seen = vec![false; nodes.len()];
        let mut stack = vec![root];
        while let Some(child) = stack.pop() {
            if let SolidChild::Node(i) = child {
                let seen_i = seen.get_mut(i as usize)?;
                if *seen_i {
                    return None;
                }
                *seen_i = true;
                let n = &nodes[i as usize];
                stack.push(n.front);
                stack.push(n.back);
            }
        }
        Some(Self { nodes, root })
    }

    /// The solid bounded by `boundary`, the faces of a closed polyhedron
    /// with outward normals (counter-clockwise seen from outside).
    ///
    /// An autopartition of the faces: an empty region behind the last plane
    /// is inside (just behind the splitting face), one in front is outside.
    /// The result is meaningful only if the faces close up.
    pub fn from_boundary(boundary: Vec<ConvexPolygon>, options: &BuildOptions) -> Self {
        Self::from_boundary_labelled(boundary, options, &|_, _| None)
    }

    /// [`Self::from_boundary`], each empty region labelled by `label` where
    /// it answers ([`LeafLabel`]). The last plane's side is right for a
    /// surface that bounds a solid; for one that folds or crosses itself
    /// (faces snapped to a grid), a winding number in the region is.
    pub fn from_boundary_labelled(
        boundary: Vec<ConvexPolygon>,
        options: &BuildOptions,
        label: LeafLabel<'_>,
    ) -> Self {
        // Leaves are labelled by the side of the last face plane: every
        // splitter must be a face.
        let options = BuildOptions {
            axis_planes: false,
            ..*options
        };
        let built = autopartition::build(boundary, &options, false);
        let leaf = |front: bool| SolidChild::Leaf(if front { Region::Out } else { Region::In });
        let link = |l: Link| match l {
            Link::Node(i) => SolidChild::Node(i),
            Link::EmptyFront => leaf(true),
            Link::EmptyBack => leaf(false),
        };
        let mut nodes: Vec<SolidNode> = built
            .nodes
            .iter()
            .map(|n| SolidNode {
                plane: n.plane,
                front: link(n.front),
                back: link(n.back),
            })
            .collect();
        // Each empty region asked about with the planes that bound it: a
        // walk down the tree, the path to each node kept.
        let mut path: Vec<(Plane, Side)> = Vec::new();
        let mut stack: Vec<Visit> = match built.root {
            Link::Node(node) => vec![Visit {
                node,
                depth: 0,
                step: None,
            }],
            _ => Vec::new(),
        };
        while let Some(Visit {
            node: i,
            depth,
            step,
        }) = stack.pop()
        {
            path.truncate(depth.saturating_sub(1));
            path.extend(step);
            let n = &built.nodes[i as usize];
            for (child, side) in [(n.front, Side::Front), (n.back, Side::Back)] {
                match child {
                    Link::Node(c) => stack.push(Visit {
                        node: c,
                        depth: depth + 1,
                        step: Some((n.plane, side)),
                    }),
                    Link::EmptyFront | Link::EmptyBack => {
                        path.push((n.plane, side));
                        let labelled = label(&path, &n.polygons);
                        path.pop();
                        if let Some(region) = labelled {
                            let slot = &mut nodes[i as usize];
                            *(if side == Side::Front {
                                &mut slot.front
                            } else {
                                &mut slot.back
                            }) = SolidChild::Leaf(region);
                        }
                    }
                }
            }
        }
        Self {
            root: link(built.root),
            nodes,
        }
    }

    /// The root.
    pub fn root(&self) -> SolidChild {
        self.root
    }

    /// The inner nodes.
    pub fn nodes(&self) -> &[SolidNode] {
        &self.nodes
    }

    /// The complement: every leaf flipped.
    pub fn complement(&self) -> Self {
        let flip = |c: SolidChild| match c {
            SolidChild::Leaf(Region::In) => SolidChild::Leaf(Region::Out),
            SolidChild::Leaf(Region::Out) => SolidChild::Leaf(Region::In),
            node => node,
        };
        Self {
            root: flip(self.root),
            nodes: self
                .nodes
                .iter()
                .map(|n| SolidNode {
                    plane: n.plane,
                    front: flip(n.front),
                    back: flip(n.back),
                })
                .collect(),
        }
    }

    /// Classifies a grid point exactly: a point on a node's plane is looked
    /// up on both sides; it is on the boundary when the leaves around it
    /// disagree.
    pub fn classify_point(&self, p: GridPoint) -> PointClass {
        let (mut inside, mut outside) = (false, false);
        let mut stack = vec![self.root];
        while let Some(child) = stack.pop() {
            match child {
                SolidChild::Leaf(Region::In) => inside = true,
                SolidChild::Leaf(Region::Out) => outside = true,
                SolidChild::Node(i) => {
                    let node = &self.nodes[i as usize];
                    match side_of_point(&node.plane, p) {
                        Side::Front => stack.push(node.front),
                        Side::Back => stack.push(node.back),
                        Side::On => {
                            stack.push(node.front);
                            stack.push(node.back);
                        }
                    }
                }
            }
            if inside && outside {
                return PointClass::On;
            }
        }
        if inside {
            PointClass::In
        } else {
            PointClass::Out
        }
    }

    /// Partitions a convex polygon into its pieces inside, outside and on
    /// the boundary of the solid, exactly. The pieces tile the polygon.
    ///
    /// A piece that reaches a node's plane lying in it is filtered down the
    /// subtree on its front side and then, piece by piece, down the subtree
    /// on its back side: the two answers say what lies on either side of it.
    pub fn partition_polygon(&self, polygon: &ConvexPolygon) -> Vec<(ConvexPolygon, Containment)> {
        self.partition(polygon, |c| c, false)
    }

    /// [`partition_polygon`](Self::partition_polygon) with each piece
    /// labelled by `key`, and the cuts that separate nothing `key` tells
    /// apart undone: wherever all the pieces a node and the nodes below it
    /// cut from a part of the polygon have one key, that part comes back
    /// whole. The pieces still tile the polygon, exactly; a tree's planes
    /// that cross the polygon away from anything the caller distinguishes
    /// (another face's plane, a balancing split) leave no seam in it.
    pub fn partition_polygon_by<K: Copy + Eq>(
        &self,
        polygon: &ConvexPolygon,
        key: impl Fn(Containment) -> K,
    ) -> Vec<(ConvexPolygon, K)> {
        self.partition(polygon, key, true)
    }

    /// The partition, with each split's two sides joined again when `join`
    /// is set and all their pieces' keys agree.
    fn partition<K: Copy + Eq>(
        &self,
        polygon: &ConvexPolygon,
        key: impl Fn(Containment) -> K,
        join: bool,
    ) -> Vec<(ConvexPolygon, K)> {
        let mut out = Vec::new();
        let mut continuations: Vec<Continuation> = Vec::new();
        let mut stack = vec![Step::Descend(self.root, polygon.clone(), None)];
        while let Some(step) = stack.pop() {
            let (child, piece, cont) = match step {
                Step::Descend(child, piece, cont) => (child, piece, cont),
                Step::Join { start, whole } => {
                    // Depth first: everything cut from `whole` has gone to
                    // `out[start..]`, and nothing else has.
                    let first = out.get(start).map(|&(_, k)| k);
                    if let Some(k) = first.filter(|&k| out[start..].iter().all(|&(_, j)| j == k)) {
                        out.truncate(start);
                        out.push((whole, k));
                    }
                    continue;
                }
            };
            match child {
                SolidChild::Leaf(region) => {
                    let sides = (region, region);
                    if let Some((piece, class)) =
                        self.resolve(piece, sides, cont, &mut continuations, &mut stack)
                    {
                        out.push((piece, key(class)));
                    }
                }
                SolidChild::Node(i) => {
                    let node = &self.nodes[i as usize];
                    match piece.split(&node.plane) {
                        Split::Front => stack.push(Step::Descend(node.front, piece, cont)),
                        Split::Back => stack.push(Step::Descend(node.back, piece, cont)),
                        Split::Both(back, front) => {
                            if join {
                                let start = out.len();
                                stack.push(Step::Join {
                                    start,
                                    whole: piece,
                                });
                            }
                            stack.push(Step::Descend(node.back, back, cont));
                            stack.push(Step::Descend(node.front, front, cont));
                        }
                        Split::Coplanar(facing) => {
                            // The piece's front side looks into `first`.
                            let (first, second) = match facing {
                                Facing::Same => (node.front, node.back),
                                Facing::Opposite => (node.back, node.front),
                            };
                            continuations.push(Continuation::First {
                                second,
                                parent: cont,
                            });
                            let k = continuations.len() as u32 - 1;
                            stack.push(Step::Descend(first, piece, Some(k)));
                        }
                    }
                }
            }
        }
        out
    }

    /// A piece reached a leaf (or finished a coplanar descent) with the
    /// regions `(front side, back side)`; pass them up the continuations.
    /// Returns the piece with its containment once every continuation is
    /// answered, or `None` when it goes on down another subtree.
    fn resolve(
        &self,
        piece: ConvexPolygon,
        mut sides: (Region, Region),
        mut cont: Option<u32>,
        continuations: &mut Vec<Continuation>,
        stack: &mut Vec<Step>,
    ) -> Option<(ConvexPolygon, Containment)> {
        loop {
            let Some(k) = cont else {
                return Some((piece, Containment::from_sides(sides.0, sides.1)));
            };
            match continuations[k as usize] {
                Continuation::First { second, parent } => {
                    continuations.push(Continuation::Second {
                        front_side: sides.0,
                        parent,
                    });
                    let next = continuations.len() as u32 - 1;
                    stack.push(Step::Descend(second, piece, Some(next)));
                    return None;
                }
                Continuation::Second { front_side, parent } => {
                    sides = (front_side, sides.1);
                    cont = parent;
                }
            }
        }
    }

    /// Checks that links form a tree over all nodes.
    pub fn check_invariants(&self) -> Result<(), String> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack = vec![self.root];
        while let Some(child) = stack.pop() {
            if let SolidChild::Node(i) = child {
                let Some(s) = seen.get_mut(i as usize) else {
                    return Err(format!("link to missing node {i}"));
                };
                if *s {
                    return Err(format!("node {i} reached twice"));
                }
                *s = true;
                let n = &self.nodes[i as usize];
                stack.push(n.front);
                stack.push(n.back);
            }
        }
        match seen.iter().position(|s| !s) {
            Some(i) => Err(format!("node {i} is unreachable")),
            None => Ok(()),
        }
    }
}

/// Work of [`BspSolid::partition`]: a piece to filter down a subtree, or
/// the two sides of a split to join again if their pieces agree.
enum Step {
    Descend(SolidChild, ConvexPolygon, Option<u32>),
    Join { start: usize, whole: ConvexPolygon },
}

/// What to do with a piece of a coplanar polygon when its descent ends.
#[derive(Debug, Clone, Copy)]
enum Continuation {
    /// The front-side descent is under way; the back side is next.
    First {
        second: SolidChild,
        parent: Option<u32>,
    },
    /// The back-side descent is under way; the front side gave this.
    Second {
        front_side: Region,
        parent: Option<u32>,
    },
}
