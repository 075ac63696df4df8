//! The scene BSP: an autopartition of the scene's convex polygons, built
//! once and traversed front-to-back from every light.

use crate::autopartition::{self, BuildOptions, Link};
use crate::predicates::{Side, side_of_direction, side_of_point};
use crate::{ConvexPolygon, GridPoint, Plane};

/// A child of a scene BSP node: another node, or a leaf cell (a convex
/// region that no polygon crosses), numbered `0..leaf_count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SceneChild {
    /// An inner node, by index.
    Node(u32),
    /// A leaf cell, by index.
    Leaf(u32),
}

/// An inner node: its plane, the range of [`SceneBsp::polygons`] that lie in
/// it, and its two children.
#[derive(Debug, Clone)]
pub struct SceneNode {
    /// The splitting plane (the support plane of one of its polygons).
    pub plane: Plane,
    /// Indices into [`SceneBsp::polygons`] of the polygons in `plane`.
    pub polygons: std::ops::Range<u32>,
    /// The subtree in front of `plane`.
    pub front: SceneChild,
    /// The subtree behind `plane`.
    pub back: SceneChild,
}

/// Where a viewer stands: at a grid point, or infinitely far away.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Viewpoint {
    /// A point viewer (a point light, a sub-light's centroid, an eye).
    Point(GridPoint),
    /// A viewer at infinity in this direction from the scene (a directional
    /// light that travels along `-direction`).
    Direction([i32; 3]),
}

impl Viewpoint {
    /// Which side of `plane` the viewer is on, exactly.
    #[inline]
    pub fn side(&self, plane: &Plane) -> Side {
        match *self {
            Viewpoint::Point(p) => side_of_point(plane, p),
            Viewpoint::Direction(d) => side_of_direction(plane, d),
        }
    }
}

/// Where a point lies in the scene BSP.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// Strictly inside a leaf cell.
    Leaf(u32),
    /// On the plane of this node, within the node's region.
    OnPlane(u32),
}

/// An autopartition BSP tree of convex polygons.
///
/// Nodes live in an arena and are visited with explicit stacks, so an
/// unbalanced tree cannot overflow the call stack. The polygons are the
/// input's, split where a node's plane cuts them; each keeps its `source`.
#[derive(Debug, Clone)]
pub struct SceneBsp {
    nodes: Vec<SceneNode>,
    polygons: Vec<ConvexPolygon>,
    root: SceneChild,
    leaf_count: u32,
}

impl SceneBsp {
    /// Builds the tree over `polygons` (see [`BuildOptions`]).
    pub fn build(polygons: Vec<ConvexPolygon>, options: &BuildOptions) -> Self {
        Self::from_built(autopartition::build(polygons, options, false))
    }

    /// [`build`](Self::build), also giving back, whole, every input polygon
    /// that a node's plane cut, with its index in the input, in index
    /// order. A caller that finds all the pieces of a polygon alike can
    /// then use the polygon itself instead of its pieces, without copying
    /// every polygon beforehand.
    pub fn build_keeping_cut(
        polygons: Vec<ConvexPolygon>,
        options: &BuildOptions,
    ) -> (Self, Vec<(u32, ConvexPolygon)>) {
        let mut built = autopartition::build(polygons, options, true);
        let cut = std::mem::take(&mut built.cut)
            .into_iter()
            .enumerate()
            .filter_map(|(i, p)| Some((i as u32, p?)))
            .collect();
        (Self::from_built(built), cut)
    }

    fn from_built(built: autopartition::Built) -> Self {
        let mut leaf_count = 0_u32;
        let mut link = |l: Link| match l {
            Link::Node(i) => SceneChild::Node(i),
            Link::EmptyFront | Link::EmptyBack => {
                leaf_count += 1;
                SceneChild::Leaf(leaf_count - 1)
            }
        };
        let root = link(built.root);
        let mut nodes = Vec::with_capacity(built.nodes.len());
        let mut all = Vec::new();
        for node in built.nodes {
            let start = all.len() as u32;
            all.extend(node.polygons);
            nodes.push(SceneNode {
                plane: node.plane,
                polygons: start..all.len() as u32,
                front: link(node.front),
                back: link(node.back),
            });
        }
        Self {
            nodes,
            polygons: all,
            root,
            leaf_count,
        }
    }

    /// The root: a node, or the single leaf of an empty scene.
    pub fn root(&self) -> SceneChild {
        self.root
    }

    /// The inner nodes.
    pub fn nodes(&self) -> &[SceneNode] {
        &self.nodes
    }

    /// All polygons (fragments of the input), grouped by node.
    pub fn polygons(&self) -> &[ConvexPolygon] {
        &self.polygons
    }

    /// The polygons (as [`polygons`](Self::polygons) orders them), without
    /// copying them; the tree is consumed.
    pub fn into_polygons(self) -> Vec<ConvexPolygon> {
        self.polygons
    }

    /// The polygons lying in node `node`'s plane.
    pub fn node_polygons(&self, node: u32) -> &[ConvexPolygon] {
        let r = &self.nodes[node as usize].polygons;
        &self.polygons[r.start as usize..r.end as usize]
    }

    /// Number of leaf cells.
    pub fn leaf_count(&self) -> u32 {
        self.leaf_count
    }

    /// Length of the longest root-to-leaf path, in nodes.
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(self.root, 0_usize)];
        while let Some((child, d)) = stack.pop() {
            match child {
                SceneChild::Leaf(_) => deepest = deepest.max(d),
                SceneChild::Node(i) => {
                    let n = &self.nodes[i as usize];
                    stack.push((n.front, d + 1));
                    stack.push((n.back, d + 1));
                }
            }
        }
        deepest
    }

    /// The polygons in front-to-back order from `view`: no polygon is
    /// hidden, even partly, by one that comes after it. Yields each
    /// polygon's index into [`polygons`](Self::polygons) with the polygon.
    pub fn front_to_back(&self, view: Viewpoint) -> Traversal<'_> {
        Traversal::new(self, view, Order::FrontToBack)
    }

    /// The polygons in back-to-front (painter's) order from `view`.
    pub fn back_to_front(&self, view: Viewpoint) -> Traversal<'_> {
        Traversal::new(self, view, Order::BackToFront)
    }

    /// Locates a grid point: the leaf cell containing it, or the first node
    /// on whose plane it lies.
    pub fn locate(&self, p: GridPoint) -> Location {
        let mut child = self.root;
        loop {
            match child {
                SceneChild::Leaf(l) => return Location::Leaf(l),
                SceneChild::Node(i) => {
                    let node = &self.nodes[i as usize];
                    child = match side_of_point(&node.plane, p) {
                        Side::Front => node.front,
                        Side::Back => node.back,
                        Side::On => return Location::OnPlane(i),
                    };
                }
            }
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Order {
    FrontToBack,
    BackToFront,
}

#[derive(Debug, Clone, Copy)]
enum Task {
    Visit(SceneChild),
    Emit(u32),
}

/// Iterator over a [`SceneBsp`]'s polygons in visibility order.
#[derive(Debug, Clone)]
pub struct Traversal<'a> {
    bsp: &'a SceneBsp,
    view: Viewpoint,
    order: Order,
    stack: Vec<Task>,
    current: std::ops::Range<u32>,
}

impl<'a> Traversal<'a> {
    fn new(bsp: &'a SceneBsp, view: Viewpoint, order: Order) -> Self {
        Self {
            bsp,
            view,
            order,
            stack: vec![Task::Visit(bsp.root)],
            current: 0..0,
        }
    }
}

impl<'a> Iterator for Traversal<'a> {
    type Item = (u32, &'a ConvexPolygon);

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(i) = self.current.next() {
                return Some((i, &self.bsp.polygons[i as usize]));
            }
            match self.stack.pop()? {
                Task::Emit(node) => self.current = self.bsp.nodes[node as usize].polygons.clone(),
                Task::Visit(SceneChild::Leaf(_)) => {}
                Task::Visit(SceneChild::Node(i)) => {
                    let node = &self.bsp.nodes[i as usize];
                    // The viewer's side comes first front-to-back; a viewer on
                    // the plane sees its polygons edge-on, so either order is
                    // right.
                    let (near, far) = match self.view.side(&node.plane) {
                        Side::Front | Side::On => (node.front, node.back),
                        Side::Back => (node.back, node.front),
                    };
                    let (first, last) = match self.order {
                        Order::FrontToBack => (near, far),
                        Order::BackToFront => (far, near),
                    };
                    self.stack.push(Task::Visit(last));
                    self.stack.push(Task::Emit(i));
                    self.stack.push(Task::Visit(first));
                }
            }
        }
    }
}
