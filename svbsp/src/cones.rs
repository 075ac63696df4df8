//! Cones of a light: space cut by planes through the light into convex
//! regions that each hold few polygons, so that each region's shadows can
//! be computed on their own (and in parallel).
//!
//! A plane through a point light (for a directional light, a plane
//! parallel to its rays) contains every ray that touches it, so no ray
//! crosses it: nothing on one side can shadow anything on the other.
//! Cutting the scene by such planes leaves cones (prisms, for a directional
//! light) whose polygons interact only among themselves. The cuts are exact,
//! and every edge they make lies in a plane through the light, which is that
//! edge's own shadow plane, so a cut piece still casts exactly its share of
//! its polygon's shadow.
//!
//! The partition is a kd-tree over the light's directions: a cone with more
//! than `max_pieces` polygons is halved by the plane through the light, an
//! axis direction and the point halfway between the middle two centroids
//! of a sample of its polygons (ordered by their angle about that axis, or
//! for a directional light by their offset across it), trying the three
//! axes and keeping the plane that cuts fewest of the sample and splits it
//! most evenly. Each plane passes
//! through three grid points (the light, a grid point and its neighbour
//! along the axis; for a directional light, a grid point, its neighbour and
//! the point one light direction away), so the kernel's bounds hold.
//!
//! Every cut is logged in a [`CutForest`], so that the pieces of a polygon
//! that end up alike can be joined again into the polygon they came from.

use crate::LightSource;
use bsp_core::{ConvexPolygon, GridPoint, Plane, PolygonSide, Split};

/// Marks a forest node that was not cut.
const LEAF: u32 = u32::MAX;

/// Polygons of a cone sampled to choose its splitting plane.
const SAMPLE: usize = 32;

/// Cones are halved at most this many times on any path.
const MAX_DEPTH: u32 = 40;

/// The history of the cuts made to a list of polygons. Node `i` below the
/// number of roots is polygon `i` as given; cutting a node makes two new
/// nodes, its back part and then its front part, and the node keeps the
/// polygon it stood for. Children are numbered after their parent.
#[derive(Debug, Default)]
pub(crate) struct CutForest {
    /// Per node: its back child (the front child follows), or [`LEAF`].
    first_child: Vec<u32>,
    /// Per node: where its uncut polygon is in `uncut`, or [`LEAF`].
    uncut_at: Vec<u32>,
    uncut: Vec<Option<ConvexPolygon>>,
}

/// What the pieces under a forest node have in common.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Common<C> {
    /// All are alike: the node's polygon stands for them all.
    All(C),
    /// They differ.
    Mixed,
}

impl CutForest {
    /// A forest of `roots` uncut polygons.
    pub(crate) fn new(roots: usize) -> Self {
        Self {
            first_child: vec![LEAF; roots],
            uncut_at: vec![LEAF; roots],
            uncut: Vec::new(),
        }
    }

    /// Records that `node`, standing for `polygon`, was cut; returns its
    /// (back, front) children.
    pub(crate) fn cut(&mut self, node: u32, polygon: ConvexPolygon) -> (u32, u32) {
        let back = self.first_child.len() as u32;
        self.first_child[node as usize] = back;
        self.uncut_at[node as usize] = self.uncut.len() as u32;
        self.uncut.push(Some(polygon));
        self.first_child.extend([LEAF, LEAF]);
        self.uncut_at.extend([LEAF, LEAF]);
        (back, back + 1)
    }

    /// The number of nodes.
    pub(crate) fn len(&self) -> usize {
        self.first_child.len()
    }

    /// The children of `node`, if it was cut.
    pub(crate) fn children(&self, node: u32) -> Option<[u32; 2]> {
        match self.first_child[node as usize] {
            LEAF => None,
            b => Some([b, b + 1]),
        }
    }

    /// What every node's pieces have in common, given each uncut node's
    /// (a leaf's) own answer. Children come after their parents, so one
    /// pass from the end settles every node.
    pub(crate) fn common<C: Copy + PartialEq>(
        &self,
        leaf: impl Fn(u32) -> Common<C>,
    ) -> Vec<Common<C>> {
        let n = self.first_child.len();
        let mut common = vec![Common::Mixed; n];
        for node in (0..n).rev() {
            common[node] = match self.first_child[node] {
                LEAF => leaf(node as u32),
                b => match (common[b as usize], common[b as usize + 1]) {
                    (Common::All(x), Common::All(y)) if x == y => Common::All(x),
                    _ => Common::Mixed,
                },
            };
        }
        common
    }

    /// Takes the polygon a cut node stood for (`None` for a leaf, or once
    /// taken).
    pub(crate) fn take_uncut(&mut self, node: u32) -> Option<ConvexPolygon> {
        match self.uncut_at[node as usize] {
            LEAF => None,
            at => self.uncut[at as usize].take(),
        }
    }
}

/// Polygons cut into cones of a light.
#[derive(Debug)]
pub(crate) struct Cones {
    /// The pieces, by slot (taken out by [`Cones::take_cones`]).
    pieces: Vec<Option<ConvexPolygon>>,
    /// The forest node of each slot.
    pub(crate) node_of: Vec<u32>,
    /// The slots of each cone, cones in a fixed order.
    cones: Vec<Vec<u32>>,
    /// How the input polygons were cut.
    pub(crate) forest: CutForest,
}

impl Cones {
    /// The number of cones.
    pub(crate) fn len(&self) -> usize {
        self.cones.len()
    }

    /// The cones' pieces with their slots, in cone order; the pieces are
    /// moved out.
    pub(crate) fn take_cones(&mut self) -> Vec<Vec<(u32, ConvexPolygon)>> {
        let cones = std::mem::take(&mut self.cones);
        let cones = cones
            .into_iter()
            .map(|slots| {
                slots
                    .into_iter()
                    .map(|s| {
                        let piece = self.pieces[s as usize]
                            .take()
                            .expect("each slot lies in one cone");
                        (s, piece)
                    })
                    .collect()
            })
            .collect();
        // Every slot is empty now: give its memory back at once.
        self.pieces = Vec::new();
        cones
    }
}

/// Cuts `polygons` into cones of `light` holding at most `max_pieces`
/// pieces each (where a sample of them can be separated). No polygon may
/// lie in a plane through the light (such a polygon is edge-on to it and
/// takes no part in its shadows); one that does is kept on a front side.
pub(crate) fn partition(
    light: LightSource,
    polygons: Vec<ConvexPolygon>,
    max_pieces: usize,
) -> Cones {
    let roots = polygons.len();
    let mut pieces = polygons;
    let mut node_of: Vec<u32> = (0..roots as u32).collect();
    let mut forest = CutForest::new(roots);
    let mut cones = Vec::new();
    let mut stack = vec![((0..roots as u32).collect::<Vec<u32>>(), 0_u32)];
    while let Some((list, depth)) = stack.pop() {
        if list.len() <= max_pieces.max(1) || depth >= MAX_DEPTH {
            cones.push(list);
            continue;
        }
        let Some(plane) = splitter(light, &pieces, &list) else {
            cones.push(list);
            continue;
        };
        let mut back = Vec::with_capacity(list.len());
        let mut front = Vec::with_capacity(list.len());
        for s in list {
            let i = s as usize;
            match pieces[i].split(&plane) {
                Split::Back => back.push(s),
                Split::Front | Split::Coplanar(_) => front.push(s),
                Split::Both(b, f) => {
                    let whole = std::mem::replace(&mut pieces[i], b);
                    let (nb, nf) = forest.cut(node_of[i], whole);
                    node_of[i] = nb;
                    back.push(s);
                    front.push(pieces.len() as u32);
                    pieces.push(f);
                    node_of.push(nf);
                }
            }
        }
        // Front popped first: cones come in the order of a depth-first
        // walk, the same on every run.
        stack.push((back, depth + 1));
        stack.push((front, depth + 1));
    }
    Cones {
        pieces: pieces.into_iter().map(Some).collect(),
        node_of,
        cones,
        forest,
    }
}

/// The plane through the light that best halves a sample of `list` (fewest
/// cuts, then best balance, over the three axes), or `None` if none
/// separates it.
fn splitter(light: LightSource, pieces: &[ConvexPolygon], list: &[u32]) -> Option<Plane> {
    let n = list.len();
    let size = SAMPLE.min(n);
    let sample: Vec<(u32, [f64; 3])> = (0..size)
        .map(|s| {
            let slot = list[s * n / size];
            (slot, vertex_mean(&pieces[slot as usize]))
        })
        .collect();
    let mut best: Option<(u64, Plane)> = None;
    for axis in 0..3 {
        let Some(mut keyed) = order_about(light, &sample, axis) else {
            continue;
        };
        keyed.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        // Between the two middle centroids, so as not to cut the median
        // polygon through its middle.
        let m = size / 2;
        let (p, q) = (sample[keyed[m - 1].1].1, sample[keyed[m].1].1);
        let Some(plane) = plane_about(light, axis, [0, 1, 2].map(|a| (p[a] + q[a]) / 2.0)) else {
            continue;
        };
        let (mut front, mut back, mut cut) = (0_i64, 0_i64, 0_u64);
        for &(slot, _) in &sample {
            match pieces[slot as usize].classify(&plane) {
                PolygonSide::Front | PolygonSide::Coplanar(_) => front += 1,
                PolygonSide::Back => back += 1,
                PolygonSide::Both => cut += 1,
            }
        }
        // Each side must get a polygon of the sample the other does not.
        if front == 0 || back == 0 {
            continue;
        }
        let score = 2 * cut + (front - back).unsigned_abs();
        if best.is_none_or(|(s, _)| score < s) {
            best = Some((score, plane));
        }
    }
    best.map(|(_, plane)| plane)
}

/// Keys that order the sample's centroids about `axis` (with their
/// indices): for a point light, the tangent of each one's angle from the
/// sample's mean direction about the axis through the light (no
/// trigonometry, and the order is the angles' within a quarter turn either
/// side); for a directional light, the offset across the planes that hold
/// its rays and the axis. `None` if a directional light runs along the
/// axis.
fn order_about(
    light: LightSource,
    sample: &[(u32, [f64; 3])],
    axis: usize,
) -> Option<Vec<(f64, usize)>> {
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    match light {
        LightSource::Point(l) => {
            let l = l.to_f64();
            let v: Vec<[f64; 2]> = sample
                .iter()
                .map(|(_, c)| [c[a] - l[a], c[b] - l[b]])
                .collect();
            let mean = v.iter().fold([0.0, 0.0], |m, v| {
                let len = v[0].hypot(v[1]);
                if len > 0.0 {
                    [m[0] + v[0] / len, m[1] + v[1] / len]
                } else {
                    m
                }
            });
            Some(
                v.iter()
                    .enumerate()
                    .map(|(i, v)| {
                        let cross = mean[0] * v[1] - mean[1] * v[0];
                        let dot = mean[0] * v[0] + mean[1] * v[1];
                        let key = if dot > 0.0 {
                            cross / dot
                        } else if cross < 0.0 {
                            f64::MIN
                        } else {
                            f64::MAX
                        };
                        (key, i)
                    })
                    .collect(),
            )
        }
        LightSource::Directional(d) => {
            let n = across(d, axis)?;
            Some(
                sample
                    .iter()
                    .enumerate()
                    .map(|(i, (_, c))| (n[0] * c[0] + n[1] * c[1] + n[2] * c[2], i))
                    .collect(),
            )
        }
    }
}

/// The normal `d x e_axis` of the planes that hold a directional light's
/// rays and the axis, if they are not parallel.
fn across(d: [i32; 3], axis: usize) -> Option<[f64; 3]> {
    let d = d.map(f64::from);
    let mut e = [0.0; 3];
    e[axis] = 1.0;
    let n = [
        d[1] * e[2] - d[2] * e[1],
        d[2] * e[0] - d[0] * e[2],
        d[0] * e[1] - d[1] * e[0],
    ];
    (n != [0.0; 3]).then_some(n)
}

/// The plane through the light that holds the direction of `axis` and
/// passes through `at` snapped to the grid: through the light, that grid
/// point and its neighbour along the axis. `None` if they are collinear.
fn plane_about(light: LightSource, axis: usize, at: [f64; 3]) -> Option<Plane> {
    let g = GridPoint::new(
        at[0].round() as i64,
        at[1].round() as i64,
        at[2].round() as i64,
    )
    .ok()?;
    let mut h = g.to_i64();
    h[axis] += if h[axis] < i64::from(bsp_core::GRID_LIMIT) {
        1
    } else {
        -1
    };
    let next = GridPoint::new(h[0], h[1], h[2]).ok()?;
    light.shadow_plane(g, next)
}

/// The mean of a polygon's vertices (inside it: it is convex).
fn vertex_mean(p: &ConvexPolygon) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for k in 0..p.len() {
        let v = p.vertex_f64(k);
        for a in 0..3 {
            sum[a] += v[a];
        }
    }
    sum.map(|s| s / p.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use bsp_core::predicates::Side;

    fn g(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint::new(x, y, z).unwrap()
    }

    /// A row of small squares under a light, and a floor under them all.
    fn scene() -> Vec<ConvexPolygon> {
        let mut out = vec![
            ConvexPolygon::from_grid_points(
                &[
                    g(-100, 0, 100),
                    g(100, 0, 100),
                    g(100, 0, -100),
                    g(-100, 0, -100),
                ],
                0,
            )
            .unwrap(),
        ];
        for i in 0..30_i64 {
            let x = -90 + 6 * i;
            let z = (i * 37 % 50) - 25;
            out.push(
                ConvexPolygon::from_grid_points(
                    &[
                        g(x, 10, z + 2),
                        g(x + 2, 10, z + 2),
                        g(x + 2, 10, z),
                        g(x, 10, z),
                    ],
                    out.len() as u32,
                )
                .unwrap(),
            );
        }
        out
    }

    fn check(light: LightSource) {
        let polygons = scene();
        let areas: Vec<f64> = polygons.iter().map(ConvexPolygon::area).collect();
        let mut cones = partition(light, polygons, 4);
        assert!(cones.len() > 4, "{} cones", cones.len());
        let mut area = vec![0.0; areas.len()];
        let all = cones.take_cones();
        for cone in &all {
            // No cone is cut again by another cone's pieces' planes: each
            // piece lies within the cone (checked through the forest: every
            // slot is a leaf).
            for (slot, piece) in cone {
                piece.check_invariants().unwrap();
                area[piece.source() as usize] += piece.area();
                assert!(
                    cones
                        .forest
                        .children(cones.node_of[*slot as usize])
                        .is_none()
                );
            }
        }
        for (got, want) in area.iter().zip(&areas) {
            assert!((got - want).abs() <= 1e-9 * want, "{got} vs {want}");
        }
        // The floor was cut; joining every piece gives it back whole.
        let common = cones.forest.common(|_| Common::All(()));
        assert_eq!(common[0], Common::All(()));
        assert!(cones.forest.children(0).is_some());
        let whole = cones.forest.take_uncut(0).unwrap();
        assert!((whole.area() - areas[0]).abs() < 1e-9);
        // Every cut lies in a plane through the light: each piece's new
        // edges contain it.
        for cone in &all {
            for (_, piece) in cone {
                let original = &scene()[piece.source() as usize];
                for edge in piece.edges() {
                    if !original.edges().any(|e| e == edge) {
                        assert_eq!(light.side(edge), Side::On);
                    }
                }
            }
        }
    }

    #[test]
    fn point_light_cones_partition_and_log_their_cuts() {
        check(LightSource::Point(g(3, 50, -7)));
    }

    #[test]
    fn directional_light_prisms_partition_and_log_their_cuts() {
        check(LightSource::Directional([1, -4, 2]));
    }

    #[test]
    fn mixed_leaves_keep_their_parents_mixed() {
        let cones = partition(LightSource::Point(g(3, 50, -7)), scene(), 4);
        // Only the floor's first piece differs.
        let mut odd = 0;
        while let Some([back, _]) = cones.forest.children(odd) {
            odd = back;
        }
        assert_ne!(odd, 0, "the floor was cut");
        let common = cones.forest.common(|n| {
            if n == odd {
                Common::All(1)
            } else {
                Common::All(0)
            }
        });
        assert_eq!(common[0], Common::Mixed);
        assert_eq!(common[1], Common::All(0));
    }
}
