//! A bounding-volume hierarchy of occluder outlines, to find the occluders
//! that may lie between a point and an area light.
//!
//! A polygon hides part of the light from `p` only if it meets the convex
//! hull of `p` and the light: a pyramid with the light as its base. The
//! search walks a tree of axis-aligned boxes and drops every box and polygon
//! that a face of the pyramid, or the box of the pyramid, separates from it;
//! a polygon whose plane leaves the whole pyramid on one side goes too.
//!
//! The tests are `f64` with a margin towards "keep": a spurious candidate
//! only costs a clipping that removes nothing, a missed one would be wrong.
//! Unlike a scene BSP, whose node planes run through the whole scene, the
//! boxes are local, so a thin pyramid in a large scene meets few of them.

use crate::area_light::AreaLight;
use crate::vec3::{Vec3, add, area_normal, cross, dot, norm, scale, sub};

/// Polygons per leaf.
const LEAF_SIZE: usize = 4;

/// Occluder outlines in a bounding-volume hierarchy.
#[derive(Debug, Clone, Default)]
pub struct OccluderIndex {
    outlines: Vec<Vec<Vec3>>,
    /// Per outline: its plane `[a, b, c, d]` (unnormalised) or `None` for a
    /// degenerate outline, which is never dropped by its plane.
    planes: Vec<Option<[f64; 4]>>,
    boxes: Vec<Aabb>,
    nodes: Vec<Node>,
    /// Outline indices, each leaf a run of them.
    order: Vec<u32>,
}

#[derive(Debug, Clone, Copy)]
struct Aabb {
    lo: Vec3,
    hi: Vec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    fn grow(&mut self, other: &Aabb) {
        for i in 0..3 {
            self.lo[i] = self.lo[i].min(other.lo[i]);
            self.hi[i] = self.hi[i].max(other.hi[i]);
        }
    }

    fn of(points: &[Vec3]) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.grow(&Aabb { lo: *p, hi: *p });
        }
        b
    }

    fn overlaps(&self, other: &Aabb) -> bool {
        (0..3).all(|i| self.lo[i] <= other.hi[i] && other.lo[i] <= self.hi[i])
    }

    fn centre(&self, axis: usize) -> f64 {
        0.5 * (self.lo[axis] + self.hi[axis])
    }
}

#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: Aabb,
    /// Leaf: `order[start..start + len]`; inner node (`len == 0`): children
    /// `start` and `start + 1`.
    start: u32,
    len: u32,
}

/// The pyramid of a query: its box, grown by the margin, and its face
/// planes with outward normals.
struct Hull {
    points: Vec<Vec3>,
    bounds: Aabb,
    faces: Vec<[f64; 4]>,
    /// A length far above the rounding of the coordinates involved.
    margin: f64,
}

impl OccluderIndex {
    /// Indexes `outlines` (polygons, any orientation); query results are
    /// indices into it.
    pub fn new(outlines: Vec<Vec<Vec3>>) -> Self {
        let planes = outlines.iter().map(|o| plane_of(o)).collect();
        let boxes: Vec<Aabb> = outlines.iter().map(|o| Aabb::of(o)).collect();
        let mut index = OccluderIndex {
            outlines,
            planes,
            boxes,
            nodes: Vec::new(),
            order: Vec::new(),
        };
        index.order = (0..index.outlines.len() as u32).collect();
        if !index.order.is_empty() {
            index.nodes.push(Node {
                bounds: Aabb::EMPTY,
                start: 0,
                len: 0,
            });
            index.build(0, 0, index.order.len());
        }
        index
    }

    /// The outlines, as given.
    pub fn outlines(&self) -> &[Vec<Vec3>] {
        &self.outlines
    }

    /// Builds node `node` over `order[start..end]`: split at the median of
    /// the boxes' centres along the widest axis. Recursion depth is the
    /// tree's height, about `log2(n / LEAF_SIZE)`.
    fn build(&mut self, node: usize, start: usize, end: usize) {
        let mut bounds = Aabb::EMPTY;
        let mut centres = Aabb::EMPTY;
        for &k in &self.order[start..end] {
            let b = self.boxes[k as usize];
            bounds.grow(&b);
            let c = [b.centre(0), b.centre(1), b.centre(2)];
            centres.grow(&Aabb { lo: c, hi: c });
        }
        self.nodes[node].bounds = bounds;
        if end - start <= LEAF_SIZE {
            self.nodes[node].start = start as u32;
            self.nodes[node].len = (end - start) as u32;
            return;
        }
        let axis = (0..3)
            .max_by(|&a, &b| {
                (centres.hi[a] - centres.lo[a]).total_cmp(&(centres.hi[b] - centres.lo[b]))
            })
            .unwrap_or(0);
        let mid = start + (end - start) / 2;
        let boxes = &self.boxes;
        // Ties broken by index, so the tree does not depend on sort details.
        self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
            boxes[a as usize]
                .centre(axis)
                .total_cmp(&boxes[b as usize].centre(axis))
                .then(a.cmp(&b))
        });
        let first = self.nodes.len();
        let leaf = Node {
            bounds: Aabb::EMPTY,
            start: 0,
            len: 0,
        };
        self.nodes.extend([leaf, leaf]);
        self.nodes[node].start = first as u32;
        self.nodes[node].len = 0;
        self.build(first, start, mid);
        self.build(first + 1, mid, end);
    }

    /// Indices of the outlines that may lie between `p` and `light`, in
    /// increasing order, appended to `out` (cleared first).
    pub fn candidates_between(&self, p: Vec3, light: &AreaLight, out: &mut Vec<u32>) {
        out.clear();
        if self.nodes.is_empty() {
            return;
        }
        let hull = Hull::new(p, light);
        let mut stack = vec![0_usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if !hull.may_meet_box(&node.bounds) {
                continue;
            }
            if node.len == 0 {
                stack.push(node.start as usize);
                stack.push(node.start as usize + 1);
                continue;
            }
            let run = &self.order[node.start as usize..(node.start + node.len) as usize];
            out.extend(run.iter().copied().filter(|&k| {
                let k = k as usize;
                hull.may_meet_box(&self.boxes[k])
                    && hull.may_meet_points(&self.outlines[k])
                    && self.planes[k].is_none_or(|plane| hull.straddles(plane))
            }));
        }
        out.sort_unstable();
    }
}

impl Hull {
    fn new(p: Vec3, light: &AreaLight) -> Hull {
        let base = light.vertices();
        let mut points = Vec::with_capacity(base.len() + 1);
        points.push(p);
        points.extend_from_slice(base);
        let bounds = Aabb::of(&points);
        let size = (0..3)
            .map(|i| bounds.hi[i].abs().max(bounds.lo[i].abs()))
            .fold(1.0, f64::max);
        let margin = 1e-9 * size;
        let bounds = Aabb {
            lo: bounds.lo.map(|x| x - margin),
            hi: bounds.hi.map(|x| x + margin),
        };
        // Faces: the light's plane and one plane through `p` and each light
        // edge, each turned away from a point inside the pyramid. A face
        // too thin to give a plane (p on the light's plane, say) is skipped:
        // fewer faces only keep more.
        let inside = scale(points.iter().fold([0.0; 3], |s, q| add(s, *q)), {
            1.0 / points.len() as f64
        });
        let mut faces = Vec::with_capacity(base.len() + 1);
        let mut push_face = |a: Vec3, b: Vec3, c: Vec3| {
            let n = cross(sub(b, a), sub(c, a));
            let d = -dot(n, a);
            let (n, d) = if dot(n, inside) + d > 0.0 {
                (scale(n, -1.0), -d)
            } else {
                (n, d)
            };
            let length = norm(n);
            if length > 0.0 && dot(n, inside) + d < -margin * length {
                faces.push([n[0] / length, n[1] / length, n[2] / length, d / length]);
            }
        };
        push_face(base[0], base[1], base[2]);
        for k in 0..base.len() {
            push_face(p, base[k], base[(k + 1) % base.len()]);
        }
        Hull {
            points,
            bounds,
            faces,
            margin,
        }
    }

    /// Whether the box may meet the pyramid: it overlaps the pyramid's box
    /// and no face has the whole box outside it.
    fn may_meet_box(&self, b: &Aabb) -> bool {
        self.bounds.overlaps(b)
            && self.faces.iter().all(|f| {
                // The box corner furthest inside this face.
                let corner: Vec3 =
                    std::array::from_fn(|i| if f[i] > 0.0 { b.lo[i] } else { b.hi[i] });
                dot([f[0], f[1], f[2]], corner) + f[3] <= self.margin
            })
    }

    /// Whether no face has all of `points` outside it.
    fn may_meet_points(&self, points: &[Vec3]) -> bool {
        self.faces.iter().all(|f| {
            points
                .iter()
                .any(|q| dot([f[0], f[1], f[2]], *q) + f[3] <= self.margin)
        })
    }

    /// Whether the plane does not leave the whole pyramid strictly on one
    /// side.
    fn straddles(&self, plane: [f64; 4]) -> bool {
        let n = [plane[0], plane[1], plane[2]];
        let margin = self.margin * dot(n, n).sqrt();
        let (mut front, mut back) = (false, false);
        for q in &self.points {
            let value = dot(n, *q) + plane[3];
            front |= value >= -margin;
            back |= value <= margin;
        }
        front && back
    }
}

/// The plane of an outline, or `None` if it has no area.
fn plane_of(outline: &[Vec3]) -> Option<[f64; 4]> {
    let n = area_normal(outline);
    let length = norm(n);
    if length == 0.0 || !length.is_finite() {
        return None;
    }
    let n = scale(n, 1.0 / length);
    let centre = scale(
        outline.iter().fold([0.0; 3], |s, q| add(s, *q)),
        1.0 / outline.len() as f64,
    );
    Some([n[0], n[1], n[2], -dot(n, centre)])
}
