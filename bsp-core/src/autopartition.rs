//! Autopartition: a BSP tree whose splitting planes are the polygons' own
//! support planes (and, where they cannot balance the tree, axis-aligned
//! planes). Shared by [`SceneBsp`](crate::SceneBsp) and
//! [`BspSolid`](crate::BspSolid), which differ only in what their leaves mean.

use crate::{ConvexPolygon, GRID_LIMIT, GridPoint, Plane, PolygonSide, Split};

/// How the autopartition chooses its splitting planes.
///
/// At each node a few candidate polygons, spread evenly over the node's
/// list, are scored against an evenly spread sample of the list:
/// `split_weight * (polygons cut) + |front - back|`. The lowest score wins
/// (the earliest candidate on ties, so builds are deterministic). Sampling
/// bounds the cost per node, so large inputs build in `O(n log n)`-like time.
///
/// The faces of a convex object all lie behind each other's planes, so an
/// autopartition of them is a chain as deep as the object has faces, and
/// building it costs `O(n^2)`. With `axis_planes`, an axis-aligned plane
/// through the sample's median is scored too and wins where it balances
/// better. A list of at most 48 polygons first tries its candidates for
/// one that cuts nothing and leaves one side empty, and takes it at once:
/// small convex patches then cost two passes per node (the light's cones
/// of closed surfaces are such lists).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BuildOptions {
    /// Candidate splitters scored per node (at least 1).
    pub candidates: usize,
    /// Polygons each candidate is scored against.
    pub sample: usize,
    /// Cost of one cut polygon relative to one polygon of imbalance.
    pub split_weight: u32,
    /// Whether an axis-aligned plane (holding no polygon) may split a node.
    /// BSP solids built from a boundary need every splitter to be a face
    /// (their leaves are labelled by the side of the last one) and ignore
    /// this.
    pub axis_planes: bool,
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self {
            candidates: 8,
            sample: 24,
            split_weight: 6,
            axis_planes: true,
        }
    }
}

/// Lists up to this long first look for a candidate that cuts nothing and
/// leaves one side empty (see `choose_splitter`).
const SMALL_LIST: usize = 48;

/// A child link while building: another node, or an empty region on the
/// front or back side of its parent's plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Link {
    Node(u32),
    EmptyFront,
    EmptyBack,
}

/// A node of the tree under construction, with the polygons that lie in its
/// plane.
#[derive(Debug)]
pub(crate) struct BuiltNode {
    pub plane: Plane,
    pub polygons: Vec<ConvexPolygon>,
    pub front: Link,
    pub back: Link,
}

/// The built tree: nodes in creation order (parents before children, front
/// subtrees numbered before back subtrees) and the root link.
pub(crate) struct Built {
    pub nodes: Vec<BuiltNode>,
    pub root: Link,
    /// With `keep_cut`: entry `i` holds input polygon `i` as it was given,
    /// if some plane cut it (empty otherwise).
    pub cut: Vec<Option<ConvexPolygon>>,
}

/// Where a subtree built from a work item hangs.
#[derive(Clone, Copy)]
enum Slot {
    Root,
    Front(u32),
    Back(u32),
}

/// Builds the autopartition with an explicit stack (no recursion, so an
/// unbalanced tree cannot overflow the call stack). An empty input gives a
/// root that is an empty front region.
///
/// Polygons stay in one arena and work lists hold their indices, so a level
/// of the tree moves four bytes per polygon, not the polygon. A split puts
/// its back part in the cut polygon's slot, so the arena ends at the number
/// of fragments. With `keep_cut`, an input polygon is moved aside, whole,
/// when it is first cut (its slot then holds its back part).
pub(crate) fn build(polygons: Vec<ConvexPolygon>, options: &BuildOptions, keep_cut: bool) -> Built {
    let inputs = polygons.len();
    let mut cut: Vec<Option<ConvexPolygon>> = Vec::new();
    if keep_cut {
        cut.resize_with(inputs, || None);
    }
    let mut arena = polygons;
    let mut nodes: Vec<BuiltNode> = Vec::new();
    let mut node_members: Vec<Vec<u32>> = Vec::new();
    let mut root = Link::EmptyFront;
    let all: Vec<u32> = (0..arena.len() as u32).collect();
    let mut stack: Vec<(Slot, Vec<u32>)> = vec![(Slot::Root, all)];
    while let Some((slot, list)) = stack.pop() {
        let link = if list.is_empty() {
            match slot {
                Slot::Root | Slot::Front(_) => Link::EmptyFront,
                Slot::Back(_) => Link::EmptyBack,
            }
        } else {
            let plane = choose_splitter(&arena, &list, options);
            // Sized for the worst case: growing them was a tenth of the
            // allocator's work.
            let (mut coplanar, mut front, mut back) = (
                Vec::new(),
                Vec::with_capacity(list.len()),
                Vec::with_capacity(list.len()),
            );
            for index in list {
                match arena[index as usize].split(&plane) {
                    Split::Back => back.push(index),
                    Split::Front => front.push(index),
                    Split::Both(b, f) => {
                        let i = index as usize;
                        if keep_cut && i < inputs && cut[i].is_none() {
                            cut[i] = Some(std::mem::replace(&mut arena[i], b));
                        } else {
                            arena[i] = b;
                        }
                        back.push(index);
                        front.push(arena.len() as u32);
                        arena.push(f);
                    }
                    Split::Coplanar(_) => coplanar.push(index),
                }
            }
            let id = nodes.len() as u32;
            nodes.push(BuiltNode {
                plane,
                polygons: Vec::new(),
                front: Link::EmptyFront,
                back: Link::EmptyBack,
            });
            node_members.push(coplanar);
            // Popped last-in first-out: the front subtree is built first.
            stack.push((Slot::Back(id), back));
            stack.push((Slot::Front(id), front));
            Link::Node(id)
        };
        match slot {
            Slot::Root => root = link,
            Slot::Front(parent) => nodes[parent as usize].front = link,
            Slot::Back(parent) => nodes[parent as usize].back = link,
        }
    }
    // Every arena slot belongs to exactly one node: move the polygons out.
    let mut slots: Vec<Option<ConvexPolygon>> = arena.into_iter().map(Some).collect();
    for (node, members) in nodes.iter_mut().zip(node_members) {
        node.polygons = members
            .into_iter()
            .map(|i| {
                slots[i as usize]
                    .take()
                    .expect("each fragment sits at one node")
            })
            .collect();
    }
    Built { nodes, root, cut }
}

/// The plane that splits `list` best: a candidate polygon's support plane,
/// or an axis-aligned plane through the sample's median.
fn choose_splitter(arena: &[ConvexPolygon], list: &[u32], options: &BuildOptions) -> Plane {
    let n = list.len();
    let first = *arena[list[0] as usize].support();
    if n <= 2 {
        return first;
    }
    let candidates = options.candidates.clamp(1, n);
    let sample = options.sample.clamp(1, n);
    let try_axis = options.axis_planes && n >= 16;
    if candidates == 1 && !try_axis {
        // A lone candidate wins whatever its score.
        return first;
    }
    if n <= SMALL_LIST && candidates > 1 {
        // A small list: a candidate that cuts nothing and leaves one side
        // empty is taken at once. It makes no fragment, and the depth it
        // adds is bounded by the list; the faces of a convex patch (a
        // light's cone of a closed surface) then cost two passes per node
        // instead of a scoring of every candidate and an axis plane that
        // would cut them. A polygon that spoils a candidate (crossing it,
        // or on the other side from an earlier one) is tried next: it is
        // often the one that all the others lie on one side of (a floor
        // under a patch). A caller asking for one candidate keeps it.
        let mut next = list[0];
        for _ in 0..candidates {
            let plane = *arena[next as usize].support();
            match one_side_or_witness(arena, list, &plane) {
                None => return plane,
                Some(witness) => next = witness,
            }
        }
    }
    // The score of a plane, or `None` as soon as it cannot beat `bound`:
    // the cuts only grow, and the imbalance can shrink by at most one per
    // polygon still to classify. The choice is the same as with full
    // scores.
    let score = |plane: &Plane, bound: u64| {
        let (mut front, mut back, mut cut) = (0_i64, 0_i64, 0_u64);
        let weight = u64::from(options.split_weight);
        for s in 0..sample {
            match arena[list[s * n / sample] as usize].classify(plane) {
                PolygonSide::Front => front += 1,
                PolygonSide::Back => back += 1,
                PolygonSide::Both => cut += 1,
                PolygonSide::Coplanar(_) => {}
            }
            let left = (sample - 1 - s) as u64;
            let imbalance = (front - back).unsigned_abs();
            if cut * weight + imbalance.saturating_sub(left) >= bound {
                return None;
            }
        }
        Some((
            cut * weight + (front - back).unsigned_abs(),
            front,
            back,
            cut,
        ))
    };
    let mut best = (u64::MAX, first);
    for c in 0..candidates {
        let plane = *arena[list[c * n / candidates] as usize].support();
        if let Some((s, ..)) = score(&plane, best.0) {
            // `score` gives a value only below the bound.
            best = (s, plane);
        }
    }
    if try_axis && let Some(plane) = median_axis_plane(arena, list, sample) {
        // It must separate the sample (so each side shrinks) and cut
        // few, and beat every face on the same score.
        if let Some((s, front, back, cut)) = score(&plane, best.0)
            && front > 0
            && back > 0
            && 2 * cut < sample as u64
        {
            best = (s, plane);
        }
    }
    best.1
}

/// `None` if no polygon of `list` crosses `plane` and none lies strictly on
/// one of its sides; otherwise the first polygon found crossing it or lying
/// on the side opposite an earlier one.
fn one_side_or_witness(arena: &[ConvexPolygon], list: &[u32], plane: &Plane) -> Option<u32> {
    let (mut front, mut back) = (false, false);
    for &i in list {
        match arena[i as usize].classify(plane) {
            PolygonSide::Front => front = true,
            PolygonSide::Back => back = true,
            PolygonSide::Both => return Some(i),
            PolygonSide::Coplanar(_) => {}
        }
        if front && back {
            return Some(i);
        }
    }
    None
}

/// The plane perpendicular to the axis along which the sample's first
/// vertices spread most, through their median (a grid coordinate).
fn median_axis_plane(arena: &[ConvexPolygon], list: &[u32], sample: usize) -> Option<Plane> {
    let n = list.len();
    let points: Vec<[f64; 3]> = (0..sample)
        .map(|s| arena[list[s * n / sample] as usize].vertex_f64(0))
        .collect();
    let spread = |a: usize| {
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[a]), hi.max(p[a]))
            });
        hi - lo
    };
    let axis = (0..3).max_by(|&a, &b| spread(a).total_cmp(&spread(b)))?;
    let mut values: Vec<f64> = points.iter().map(|p| p[axis]).collect();
    values.sort_by(f64::total_cmp);
    let median = values[values.len() / 2]
        .round()
        .clamp(-f64::from(GRID_LIMIT), f64::from(GRID_LIMIT)) as i64;
    let mut at = [0_i64; 3];
    at[axis] = median;
    let mut normal = [0_i64; 3];
    normal[axis] = 1;
    Plane::with_normal_through(normal, GridPoint::new(at[0], at[1], at[2]).ok()?)
}
