//! A union of convex volumes kept as a BSP tree: the penumbra tree and the
//! umbra tree of one area light.
//!
//! Volumes go in by the general Thibault-Naylor union
//! ([`svbsp::union_in_place`]): penumbra volumes overlap, so the simplified
//! insertion of the 1989 paper would be wrong here. Polygons are filtered
//! down to their cells exactly; a polygon's point counts as inside only if
//! it is in the *interior* of the union. Points on a volume's boundary see
//! the light it would hide only along a set of measure zero, so they belong
//! with the outside: a fragment on its own occluder's plane is not shadowed
//! by that occluder, nor are fragments coplanar with it.

use bsp_core::{ConvexPolygon, GridPoint, Plane, Region, SolidChild, SolidNode, Split};
use svbsp::ConvexPolyhedron;

/// A union of convex volumes as a BSP tree (an arena of nodes).
#[derive(Debug, Clone)]
pub struct VolumeTree {
    nodes: Vec<SolidNode>,
    root: SolidChild,
}

impl Default for VolumeTree {
    fn default() -> Self {
        Self::new()
    }
}

/// A polygon filtered down a [`VolumeTree`].
#[derive(Debug, Clone, Default)]
pub struct Partition {
    /// Pieces in the interior of the union.
    pub inside: Vec<ConvexPolygon>,
    /// Pieces outside it or on its boundary.
    pub outside: Vec<ConvexPolygon>,
}

impl VolumeTree {
    /// The empty union.
    pub fn new() -> Self {
        Self {
            nodes: Vec::new(),
            root: SolidChild::Leaf(Region::Out),
        }
    }

    /// The empty union over a skeleton of axis-aligned planes that cut the
    /// box `lo..hi` into about `cells` boxes (halving the longest side
    /// each time). Volumes inserted later are split along these planes, so
    /// each keeps to the cells it meets and volumes far apart never cut
    /// each other's subtrees; without them, the planes of the first volumes
    /// run through the whole scene and split every later one.
    pub fn with_cells(lo: [i32; 3], hi: [i32; 3], cells: usize) -> Self {
        let mut tree = Self::new();
        tree.root = tree.cells(lo, hi, cells.max(1));
        tree
    }

    fn cells(&mut self, lo: [i32; 3], hi: [i32; 3], cells: usize) -> SolidChild {
        let axis = (0..3)
            .max_by_key(|&i| i64::from(hi[i]) - i64::from(lo[i]))
            .unwrap_or(0);
        let mid = ((i64::from(lo[axis]) + i64::from(hi[axis])) / 2) as i32;
        if cells < 2 || mid <= lo[axis] || mid >= hi[axis] {
            return SolidChild::Leaf(Region::Out);
        }
        let mut normal = [0_i64; 3];
        normal[axis] = 1;
        let mut through = lo;
        through[axis] = mid;
        let point = GridPoint {
            x: through[0],
            y: through[1],
            z: through[2],
        };
        let Some(plane) = Plane::with_normal_through(normal, point) else {
            return SolidChild::Leaf(Region::Out);
        };
        let index = self.nodes.len();
        self.nodes.push(SolidNode {
            plane,
            front: SolidChild::Leaf(Region::Out),
            back: SolidChild::Leaf(Region::Out),
        });
        let (mut back_hi, mut front_lo) = (hi, lo);
        back_hi[axis] = mid;
        front_lo[axis] = mid;
        let back = self.cells(lo, back_hi, cells / 2);
        let front = self.cells(front_lo, hi, cells - cells / 2);
        self.nodes[index].back = back;
        self.nodes[index].front = front;
        SolidChild::Node(index as u32)
    }

    /// Inner nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the union is empty (no volume inserted).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty() && self.root == SolidChild::Leaf(Region::Out)
    }

    /// The nodes, for inspection.
    pub fn nodes(&self) -> &[SolidNode] {
        &self.nodes
    }

    /// The root link.
    pub fn root(&self) -> SolidChild {
        self.root
    }

    /// Adds a volume to the union.
    pub fn insert(&mut self, volume: ConvexPolyhedron) {
        svbsp::union_in_place(&mut self.nodes, &mut self.root, volume);
    }

    /// Splits `polygon` into its pieces inside the union and outside it (or
    /// on its boundary), exactly.
    ///
    /// Where a plane cut the polygon but both halves came out on the same
    /// side of the union (the plane bounds a volume elsewhere in the cell),
    /// the cut is undone and the piece comes back whole: the filter's split
    /// tree is collapsed bottom-up wherever a split's two halves agree.
    /// Nothing is recomputed or rounded; the pieces are the split tree's.
    pub fn partition(&self, polygon: ConvexPolygon) -> Partition {
        let mut splits = SplitTree {
            slots: vec![Slot::Open],
        };
        self.filter(polygon, None, &mut splits);
        splits.collapse()
    }

    /// [`Self::partition`] for a polygon that receives on the side `facing`
    /// points to (its support, or its support flipped): a piece in a node's
    /// plane is taken for the points just off it on that side, which is
    /// what it sees light past. (Plain `partition` takes such a piece to be
    /// inside only when it is inside on both sides: in the union's interior.)
    pub fn partition_facing(&self, polygon: ConvexPolygon, facing: &Plane) -> Partition {
        let mut splits = SplitTree {
            slots: vec![Slot::Open],
        };
        self.filter(polygon, Some(facing), &mut splits);
        splits.collapse()
    }

    /// Whether all of `polygon` lies in the interior of the union; stops at
    /// the first piece outside.
    pub fn contains(&self, polygon: &ConvexPolygon) -> bool {
        struct AllInside(bool);
        impl FilterSink for AllInside {
            fn split(&mut self, _: usize, _: ConvexPolygon) -> (usize, usize) {
                (0, 0)
            }
            fn piece(&mut self, _: usize, _: ConvexPolygon, inside: bool) -> bool {
                self.0 &= inside;
                inside
            }
        }
        let mut all = AllInside(true);
        self.filter(polygon.clone(), None, &mut all);
        all.0
    }

    /// Filters `polygon` down the tree, telling `sink` of every cut and of
    /// each final piece with whether it is inside (the sink says whether to
    /// go on). The polygon is slot 0; each cut gives the slots of its
    /// halves.
    ///
    /// A piece in a node's plane lies on the boundary of both cells; it is
    /// inside only if it is inside on both sides, so it goes down the front
    /// first and what ends inside there goes down the back too. Below such
    /// a node, a node with the same plane (a volume hung there repeats it)
    /// has an empty cell on one side: the piece goes only to the side it is
    /// being tested on.
    ///
    /// With `facing`, a piece in a node's plane goes to the side `facing`
    /// points to instead.
    fn filter(&self, polygon: ConvexPolygon, facing: Option<&Plane>, sink: &mut impl FilterSink) {
        // (piece, its slot, subtree, coplanar nodes above it with the side
        // being tested: true while on the front).
        type Pending = Vec<(u32, bool)>;
        let mut stack: Vec<(ConvexPolygon, usize, SolidChild, Pending)> =
            vec![(polygon, 0, self.root, Vec::new())];
        while let Some((mut piece, mut slot, mut child, mut pending)) = stack.pop() {
            loop {
                let i = match child {
                    SolidChild::Leaf(Region::In) => {
                        // Inside on the front of a plane it lies in: now the
                        // back must agree; inside on both: the next one out.
                        let mut next = None;
                        while let Some(&(node, front)) = pending.last() {
                            if front {
                                pending.last_mut().expect("just read").1 = false;
                                next = Some(self.nodes[node as usize].back);
                                break;
                            }
                            pending.pop();
                        }
                        if let Some(back) = next {
                            child = back;
                            continue;
                        }
                        if !sink.piece(slot, piece, true) {
                            return;
                        }
                        break;
                    }
                    SolidChild::Leaf(Region::Out) => {
                        if !sink.piece(slot, piece, false) {
                            return;
                        }
                        break;
                    }
                    SolidChild::Node(i) => i,
                };
                let node = &self.nodes[i as usize];
                match piece.split(&node.plane) {
                    Split::Back => child = node.back,
                    Split::Front => child = node.front,
                    Split::Both(back, front) => {
                        let (back_slot, front_slot) = sink.split(slot, piece);
                        stack.push((back, back_slot, node.back, pending.clone()));
                        piece = front;
                        slot = front_slot;
                        child = node.front;
                    }
                    Split::Coplanar(_) if facing.is_some() => {
                        child = if facing == Some(&node.plane) {
                            node.front
                        } else {
                            node.back
                        };
                    }
                    Split::Coplanar(_) => {
                        let known = pending.iter().find_map(|&(above, front)| {
                            let plane = &self.nodes[above as usize].plane;
                            if *plane == node.plane {
                                Some(front)
                            } else if plane.is_opposite(&node.plane) {
                                Some(!front)
                            } else {
                                None
                            }
                        });
                        match known {
                            Some(true) => child = node.front,
                            Some(false) => child = node.back,
                            None => {
                                pending.push((i, true));
                                child = node.front;
                            }
                        }
                    }
                }
            }
        }
    }
}

/// What [`VolumeTree::filter`] reports to.
trait FilterSink {
    /// The piece at `slot` was cut in two; the slots of its back and front
    /// halves.
    fn split(&mut self, slot: usize, whole: ConvexPolygon) -> (usize, usize);
    /// A final piece at `slot`; returns whether to go on.
    fn piece(&mut self, slot: usize, piece: ConvexPolygon, inside: bool) -> bool;
}

/// A slot of a [`SplitTree`].
#[derive(Debug)]
enum Slot {
    /// Not reported yet.
    Open,
    /// A final piece, inside the union or not.
    Piece(ConvexPolygon, bool),
    /// A piece cut in two; its back half is at the given slot, its front
    /// half at the next.
    Cut(ConvexPolygon, usize),
}

/// The cuts a polygon went through on its way down a tree.
#[derive(Debug)]
struct SplitTree {
    slots: Vec<Slot>,
}

impl FilterSink for SplitTree {
    fn split(&mut self, slot: usize, whole: ConvexPolygon) -> (usize, usize) {
        let back = self.slots.len();
        self.slots.push(Slot::Open);
        self.slots.push(Slot::Open);
        self.slots[slot] = Slot::Cut(whole, back);
        (back, back + 1)
    }

    fn piece(&mut self, slot: usize, piece: ConvexPolygon, inside: bool) -> bool {
        self.slots[slot] = Slot::Piece(piece, inside);
        true
    }
}

impl SplitTree {
    /// The largest pieces of the tree whose parts all lie on one side.
    fn collapse(mut self) -> Partition {
        // A cut's halves come after it, so one backward pass finds, for
        // every slot, whether all of it lies on one side.
        let mut uniform: Vec<Option<bool>> = vec![None; self.slots.len()];
        for i in (0..self.slots.len()).rev() {
            uniform[i] = match self.slots[i] {
                Slot::Open => None,
                Slot::Piece(_, inside) => Some(inside),
                Slot::Cut(_, back) if uniform[back] == uniform[back + 1] => uniform[back],
                Slot::Cut(..) => None,
            };
        }
        let mut out = Partition::default();
        let mut stack = vec![0];
        while let Some(i) = stack.pop() {
            match (
                std::mem::replace(&mut self.slots[i], Slot::Open),
                uniform[i],
            ) {
                (Slot::Piece(piece, _) | Slot::Cut(piece, _), Some(inside)) => {
                    if inside {
                        out.inside.push(piece);
                    } else {
                        out.outside.push(piece);
                    }
                }
                (Slot::Cut(_, back), None) => stack.extend([back + 1, back]),
                (Slot::Open, _) | (Slot::Piece(..), None) => {
                    debug_assert!(false, "every slot is reported");
                }
            }
        }
        out
    }
}
