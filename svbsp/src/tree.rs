//! The Shadow Volume BSP tree of one light (Chin & Feiner 1989).
//!
//! Inner nodes hold shadow planes (through the light) and caps (the plane
//! of an occluder, light in front); leaves are lit or in shadow. Polygons
//! are filtered down in front-to-back order from the light; each lit piece
//! of an occluder then replaces its leaf with its own shadow volume.

use crate::LightSource;
use bsp_core::predicates::Side;
use bsp_core::{ConvexPolygon, Plane, Split};
use smallvec::SmallVec;

/// A child link: an inner node, or a leaf.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VolumeChild {
    /// An inner node, by index.
    Node(u32),
    /// A region the light reaches.
    Lit,
    /// A region in shadow.
    Shadow,
}

/// An inner node of the tree.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VolumeNode {
    /// A shadow plane (the volume behind it) or a cap (light in front).
    pub plane: Plane,
    /// The side away from the volume.
    pub front: VolumeChild,
    /// The side towards the volume.
    pub back: VolumeChild,
    /// The parent node, for the planes above a leaf.
    parent: Option<u32>,
}

/// Where a lit piece arrived: the link to replace with its volume.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    /// The root (the tree is a single lit leaf).
    Root,
    /// The front child of a node.
    Front(u32),
    /// The back child of a node.
    Back(u32),
}

/// The pieces of a filtered polygon.
#[derive(Debug, Clone, Default)]
pub struct Filtered {
    /// Pieces the light reaches, with the leaf each arrived at.
    pub lit: Vec<(ConvexPolygon, Slot)>,
    /// Pieces in shadow.
    pub shadowed: Vec<ConvexPolygon>,
    /// Pieces waiting to go down a subtree, kept with the lists so that
    /// filtering polygon after polygon allocates nothing once warm.
    stack: Vec<(VolumeChild, Slot, ConvexPolygon)>,
}

impl Filtered {
    fn clear(&mut self) {
        self.lit.clear();
        self.shadowed.clear();
        self.stack.clear();
    }
}

/// The result of [`ShadowVolumeTree::filter_ref`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Filtering {
    /// No plane cut the polygon: it reached this lit leaf whole.
    Lit(Slot),
    /// No plane cut the polygon: it reached a shadowed leaf whole.
    Shadowed,
    /// Some plane cut it: its pieces (which may still all lie on one side)
    /// are in the lists passed in.
    Pieces,
}

/// A Shadow Volume BSP tree for one light.
#[derive(Debug, Clone)]
pub struct ShadowVolumeTree {
    light: LightSource,
    nodes: Vec<VolumeNode>,
    root: VolumeChild,
}

impl ShadowVolumeTree {
    /// An empty tree: everything is lit.
    pub fn new(light: LightSource) -> Self {
        Self {
            light,
            nodes: Vec::new(),
            root: VolumeChild::Lit,
        }
    }

    /// An empty tree with room for `nodes` nodes.
    pub fn with_capacity(light: LightSource, nodes: usize) -> Self {
        Self {
            light,
            nodes: Vec::with_capacity(nodes),
            root: VolumeChild::Lit,
        }
    }

    /// The light.
    pub fn light(&self) -> LightSource {
        self.light
    }

    /// The inner nodes.
    pub fn nodes(&self) -> &[VolumeNode] {
        &self.nodes
    }

    /// The root.
    pub fn root(&self) -> VolumeChild {
        self.root
    }

    /// Splits `polygon` into the pieces the light reaches and those in
    /// shadow, exactly. A piece lying in a cap's plane is not behind it and
    /// goes to the light's side.
    pub fn filter(&self, polygon: ConvexPolygon) -> Filtered {
        let mut out = Filtered::default();
        out.stack.push((self.root, Slot::Root, polygon));
        self.filter_pieces(&mut out);
        out
    }

    /// [`filter`](Self::filter) without taking the polygon: a polygon that
    /// no plane cuts (the common case) is not copied, and its leaf is
    /// returned instead of its pieces. Otherwise the pieces replace what
    /// `pieces` held (its buffers are reused).
    pub fn filter_ref(&self, polygon: &ConvexPolygon, pieces: &mut Filtered) -> Filtering {
        let (mut child, mut slot) = (self.root, Slot::Root);
        loop {
            let i = match child {
                VolumeChild::Lit => return Filtering::Lit(slot),
                VolumeChild::Shadow => return Filtering::Shadowed,
                VolumeChild::Node(i) => i,
            };
            let node = &self.nodes[i as usize];
            let go_front = match polygon.split(&node.plane) {
                Split::Front => true,
                Split::Back => false,
                Split::Both(back, front) => {
                    pieces.clear();
                    // Popped front first, as `filter` does.
                    pieces.stack.push((node.back, Slot::Back(i), back));
                    pieces.stack.push((node.front, Slot::Front(i), front));
                    self.filter_pieces(pieces);
                    return Filtering::Pieces;
                }
                // In a cap's plane: not behind it, so on the light's side.
                Split::Coplanar(_) => self.light.side(&node.plane) != Side::Back,
            };
            (child, slot) = if go_front {
                (node.front, Slot::Front(i))
            } else {
                (node.back, Slot::Back(i))
            };
        }
    }

    /// Filters the pieces on `out.stack` (each with the subtree it enters)
    /// to their leaves.
    fn filter_pieces(&self, out: &mut Filtered) {
        // A piece walks down in place; only the back part of a cut waits on
        // the stack (moving polygons is the dominant cost otherwise).
        while let Some((mut child, mut slot, mut piece)) = out.stack.pop() {
            loop {
                let i = match child {
                    VolumeChild::Lit => {
                        out.lit.push((piece, slot));
                        break;
                    }
                    VolumeChild::Shadow => {
                        out.shadowed.push(piece);
                        break;
                    }
                    VolumeChild::Node(i) => i,
                };
                let node = &self.nodes[i as usize];
                let go_front = match piece.split(&node.plane) {
                    Split::Front => true,
                    Split::Back => false,
                    Split::Both(back, front) => {
                        out.stack.push((node.back, Slot::Back(i), back));
                        piece = front;
                        true
                    }
                    // In a cap's plane: not behind it, so on the light's side.
                    Split::Coplanar(_) => self.light.side(&node.plane) != Side::Back,
                };
                (child, slot) = if go_front {
                    (node.front, Slot::Front(i))
                } else {
                    (node.back, Slot::Back(i))
                };
            }
        }
    }

    /// Replaces the lit leaf at `slot` with the shadow volume of the region
    /// bounded by `shadow_planes` (each oriented with the occluder behind
    /// it) and capped by `cap` (oriented with the light in front). Planes
    /// that already bound the leaf's region (equal to a plane above it, as
    /// for an edge made by an SVBSP split) are left out: their lit side
    /// would be empty; this is also what spares a second plane for an edge
    /// shared by two lit faces of one surface (the 1989 paper's silhouette
    /// optimisation). Returns the numbers of nodes added and planes left out.
    pub fn insert_volume(
        &mut self,
        slot: Slot,
        shadow_planes: &[Plane],
        cap: Plane,
    ) -> (usize, usize) {
        // One walk up the tree marks the planes that already bound the leaf;
        // a plane and its flip share |a|, which rejects most ancestors with
        // one comparison.
        let mut bounded: SmallVec<[bool; 8]> = SmallVec::from_elem(false, shadow_planes.len());
        let keys: SmallVec<[u64; 8]> = shadow_planes
            .iter()
            .map(|p| p.normal()[0].unsigned_abs())
            .collect();
        let leaf_parent = match slot {
            Slot::Root => None,
            Slot::Front(i) | Slot::Back(i) => Some(i),
        };
        let mut at = leaf_parent;
        while let Some(i) = at {
            let node = &self.nodes[i as usize];
            let key = node.plane.normal()[0].unsigned_abs();
            for ((b, p), &k) in bounded.iter_mut().zip(shadow_planes).zip(&keys) {
                *b = *b || (k == key && node.plane.is_coincident(p));
            }
            at = node.parent;
        }
        let skipped = bounded.iter().filter(|&&b| b).count();
        let count = shadow_planes.len() - skipped + 1;
        let chain = shadow_planes
            .iter()
            .zip(&bounded)
            .filter(|(_, b)| !**b)
            .map(|(p, _)| *p)
            .chain(std::iter::once(cap));
        let first = self.nodes.len() as u32;
        let mut parent = leaf_parent;
        self.nodes.reserve(count);
        for (k, plane) in chain.enumerate() {
            let id = first + k as u32;
            let back = if k + 1 == count {
                VolumeChild::Shadow
            } else {
                VolumeChild::Node(id + 1)
            };
            self.nodes.push(VolumeNode {
                plane,
                front: VolumeChild::Lit,
                back,
                parent,
            });
            parent = Some(id);
        }
        let link = VolumeChild::Node(first);
        match slot {
            Slot::Root => self.root = link,
            Slot::Front(i) => self.nodes[i as usize].front = link,
            Slot::Back(i) => self.nodes[i as usize].back = link,
        }
        (count, skipped)
    }
}
