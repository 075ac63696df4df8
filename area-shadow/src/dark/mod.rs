//! Proofs that a region of a receiver sees none of an area light where no
//! single occluder hides all of it: the joint umbra of several occluders.
//!
//! The umbra of one convex occluder (or convex body) is bounded by planes;
//! that of several together is bounded by quadric (EEE) surfaces in
//! general, which no plane-bounded cell follows. Cells wholly inside such a
//! joint umbra are still penumbra for the volumes, yet see nothing.
//! [`sees_none`] proves it, exactly, or says it could not:
//!
//! - Every segment from a point of the region `K` to a point of the light
//!   `L` must meet some occluder. For one convex polygon `O` and fixed `k`,
//!   the points `l` whose segment `kl` crosses `O` form a convex set (the
//!   shadow cone of `O` seen from `k`), and the same holds with `k` and `l`
//!   swapped. So `O` blocks all of `K x L` as soon as it blocks the segments
//!   between their corners (`Occluder::pair_crossings`).
//! - Where no occluder blocks all of `K x L`, the light or the region is
//!   halved and each half proven on its own: the light into parallelograms
//!   of its plane's lattice of grid points ([`PlaneLattice`]: every corner
//!   stays a grid point, whatever the light's tilt), the region by axis-aligned
//!   grid planes (its corners are implicit points, as every cell's). Parts
//!   of the light a one-sided receiver has behind it need no occluder.
//!   Halving keeps every corner a corner of some part, so a corner pair
//!   that no blocker crosses ends the proof at once: it has failed.
//! - Before halving, where one blocker hides a run of the light piece's
//!   corners from all of the region, the piece is cut along the frontier
//!   of what that blocker hides (`frontier`): one side is hidden by it,
//!   the other left to the rest. Where two blockers' hidden parts overlap
//!   only thinly (beside a contact, or at a discontinuity the region's
//!   corners lie on), one such cut does what midpoint halving could only
//!   do many levels down.
//! - The halving stops at a depth and a node budget: a region next to the
//!   true (curved) boundary of the joint umbra is never proven, and stays
//!   penumbra. So is one that reaches where two occluders' hidden parts of
//!   the light meet with no overlap (a joint umbra that meets one
//!   occluder's umbra at the light's edge, say): no cut of the light then
//!   suits all of a part of it. Only what is proven is dark: the test is
//!   sound, not complete.
//! - Pieces of one object joined edge to edge that tile faces of their
//!   hull (a tent of triangles) block as one [`Body`] with the other hull
//!   faces open ([`sheet_bodies`]): where they meet, their hidden parts of
//!   the light join with no overlap, which no cut gets across. Pieces
//!   that share an edge block together across it (`hinge`), and pieces
//!   about a corner they share about it (`fan`), whatever their object.
//! - Where every corner of the region has a blocker that hides all of
//!   the light piece from it, but no one serves them all, the region is
//!   halved first.
//! - Each step looks only at the blockers in the [`Shaft`] between its
//!   parts of the region and of the light (a floating-point cull: a wrong
//!   one could only fail a proof).
//!
//! Every side decision is one of `bsp-core`'s exact predicates: a grid or
//! implicit point against a plane through three grid points.
//!
//! # Example
//!
//! ```
//! use area_shadow::AreaSource;
//! use area_shadow::dark::sees_none;
//! use bsp_core::{ConvexPolygon, GridPoint};
//!
//! let g = |x: i64, y: i64, z: i64| GridPoint::new(x, y, z).unwrap();
//! let rect = |x: [i64; 2], y: i64, z: [i64; 2]| {
//!     let c = [g(x[0], y, z[0]), g(x[1], y, z[0]), g(x[1], y, z[1]), g(x[0], y, z[1])];
//!     ConvexPolygon::from_grid_points(&c, 0).unwrap()
//! };
//! // A light over x, z in [0, 40] at height 100, facing down; two panels,
//! // one at height 60 to x = 25, one at height 30 from x = 22.
//! let light = AreaSource::from_grid_points(&[g(0, 100, 0), g(40, 100, 0), g(40, 100, 40), g(0, 100, 40)]).unwrap();
//! let high = rect([-200, 25], 60, [-200, 200]);
//! let low = rect([22, 200], 30, [-200, 200]);
//! // A bit of floor (facing up): x in [20, 22], z in [19, 21]. (From
//! // x = 19 down the floor sees the light between the panels.)
//! let c = [g(20, 0, 19), g(20, 0, 21), g(22, 0, 21), g(22, 0, 19)];
//! let floor = ConvexPolygon::from_grid_points(&c, 1).unwrap();
//! // The high panel hides the light's low x from it, the low one the
//! // rest: together, all of it.
//! assert!(sees_none(&floor, false, &light, &[&high, &low], &[]));
//! assert!(!sees_none(&floor, false, &light, &[&high], &[]));
//! assert!(!sees_none(&floor, false, &light, &[&low], &[]));
//! ```

use crate::AreaSource;
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, Plane, PlaneLattice, Split};
use smallvec::SmallVec;

mod body;
mod fan;
mod frontier;
mod hinge;
mod leak;
mod shaft;
mod sheet;
mod shell;
mod vector;
pub use body::Body;
pub use shaft::Shaft;
pub use sheet::sheet_bodies;
use shell::Clearance;
pub use shell::ShellSurface;

/// A point counts as dark for a light, in floating point, when it gets at
/// most this fraction of what all of the light would give there: rounding
/// leaves a point that sees nothing a trace of light (1e-18 of it, say).
/// (Only to choose which regions to try to prove dark.)
pub const DARK_FRACTION: f64 = 1e-9;

/// How many times the light and the region are halved, at most, along one
/// path of the proof.
const MAX_DEPTH: u32 = 10;

/// How many times in a row a proof halves the light, at most, when the
/// region could be halved too.
const LIGHT_RUN: u32 = 6;

/// Blockers few enough that a step of a proof keeps them all rather than
/// cull them by its shaft.
const FEW_BLOCKERS: usize = 4;

/// How many halvings one proof may make in all before it gives up.
const NODE_BUDGET: usize = 300;

/// Whether every point of `region` (a convex part of a receiver, its
/// support plane the receiver's front) sees none of `light` past
/// `occluders`; `false` when that could not be proven.
///
/// `two_sided`: the receiver takes light on both sides (else light behind
/// its plane never reaches it). Occluders whose corners are not all grid
/// points are left out (which can only make a proof fail).
pub fn sees_none(
    region: &ConvexPolygon,
    two_sided: bool,
    light: &AreaSource,
    occluders: &[&ConvexPolygon],
    bodies: &[&Body],
) -> bool {
    let occluders: Vec<Occluder> = occluders.iter().filter_map(|o| Occluder::new(o)).collect();
    if occluders.is_empty() && bodies.is_empty() {
        return false;
    }
    let light_corners: SmallVec<[GridPoint; 8]> = light.vertices().collect();
    let clearances = bodies
        .iter()
        .map(|b| b.clearance(region, &light_corners, light.support()))
        .collect();
    let hinges = hinge::hinges(&occluders);
    let prover = Prover {
        hinges_from: hinge::hinges_from(&hinges, occluders.len()),
        hinges,
        occluders,
        bodies,
        clearances,
        receiver: region.support(),
        two_sided,
        light,
        lattice: light
            .vertices()
            .next()
            .and_then(|on| PlaneLattice::of(light.support(), on)),
    };
    let whole = LightPiece {
        corners: light.vertices().collect(),
        rectangle: None,
    };
    let mut search = Search {
        budget: NODE_BUDGET,
        refuted: false,
        at_root: true,
    };
    let near = Near {
        occluders: (0..prover.occluders.len() as u32).collect(),
        bodies: (0..prover.bodies.len() as u32).collect(),
    };
    prover.prove(region, &whole, &near, MAX_DEPTH, 0, &mut search)
}

/// A convex occluder polygon by its grid corners (counter-clockwise about
/// its support plane's normal).
#[derive(Debug, Clone, PartialEq)]
struct Occluder {
    support: Plane,
    corners: SmallVec<[GridPoint; 8]>,
    /// The corners in floating point, for the shaft's cull.
    points: SmallVec<[[f64; 3]; 8]>,
}

/// A box around points (grid units), low and high corners.
type Bounds = [[f64; 3]; 2];

fn bounds(points: impl IntoIterator<Item = [f64; 3]>) -> Bounds {
    let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for p in points {
        for k in 0..3 {
            b[0][k] = b[0][k].min(p[k]);
            b[1][k] = b[1][k].max(p[k]);
        }
    }
    b
}

impl Occluder {
    fn new(polygon: &ConvexPolygon) -> Option<Self> {
        let corners = (0..polygon.len())
            .map(|i| polygon.vertex_grid_point(i))
            .collect::<Option<SmallVec<_>>>()?;
        Some(Self {
            support: *polygon.support(),
            points: corners.iter().map(|p: &GridPoint| p.to_f64()).collect(),
            corners,
        })
    }

    /// When the light and the region lie strictly on opposite sides of
    /// the polygon's plane, which corner pairs cross it (as
    /// [`Self::pair_crossings`]); `None` otherwise.
    fn candidate_pairs(&self, region: &ConvexPolygon, light: &[GridPoint]) -> Option<Pairs> {
        self.candidate_pairs_past(region, light, &[])
    }

    /// [`Self::candidate_pairs`], for the polygon with the edges `open`
    /// (each from that corner to the next) taken away: its plane's region
    /// inside the other edges.
    fn candidate_pairs_past(
        &self,
        region: &ConvexPolygon,
        light: &[GridPoint],
        open: &[usize],
    ) -> Option<Pairs> {
        let &first = light.first()?;
        let light_side = side_of_point(&self.support, first);
        if light_side == Side::On
            || light[1..]
                .iter()
                .any(|&l| side_of_point(&self.support, l) != light_side)
            || (0..region.len())
                .any(|i| region.vertex_side(i, &self.support) != light_side.flipped())
        {
            return None;
        }
        let all: SmallVec<[bool; 8]> = smallvec::smallvec![true; region.len()];
        // (Slices appended, not an iterator flattened: a proof's hot path.)
        let mut pairs = Pairs::new();
        for &l in light {
            pairs.extend_from_slice(&self.crossings_past(region, l, &all, open));
        }
        Some(pairs)
    }

    /// For each corner pair (light corner `j`, region corner `i`, at
    /// `j * region.len() + i`), whether its segment crosses this polygon
    /// (closed) strictly between its ends, or is `known` to cross some
    /// blocker (those are not looked at). When every pair crosses, every
    /// segment from `region` to `light` does (see the module's docs).
    fn pair_crossings(&self, region: &ConvexPolygon, light: &[GridPoint], known: &Pairs) -> Pairs {
        let nk = region.len();
        let mut region_sides: SmallVec<[Side; 8]> = SmallVec::from_elem(Side::On, nk);
        for (i, side) in region_sides.iter_mut().enumerate() {
            *side = region.vertex_side(i, &self.support);
        }
        let mut pairs = Pairs::new();
        for (j, &l) in light.iter().enumerate() {
            let known = &known[j * nk..(j + 1) * nk];
            let l_side = side_of_point(&self.support, l);
            let mut test: SmallVec<[bool; 8]> = SmallVec::from_elem(false, nk);
            for ((t, &k), &known) in test.iter_mut().zip(&region_sides).zip(known) {
                *t = !known && l_side != Side::On && k == l_side.flipped();
            }
            if test.contains(&true) {
                let mut crossed = self.crossings(region, l, &test);
                for (c, &k) in crossed.iter_mut().zip(known) {
                    *c |= k;
                }
                pairs.extend_from_slice(&crossed);
            } else {
                pairs.extend_from_slice(known);
            }
        }
        pairs
    }

    /// For each region corner `i` with `test[i]` (on the side of the plane
    /// strictly opposite that of `l`), whether the segment from it to `l`
    /// crosses the polygon there (false for the others).
    fn crossings(
        &self,
        region: &ConvexPolygon,
        l: GridPoint,
        test: &[bool],
    ) -> SmallVec<[bool; 8]> {
        self.crossings_past(region, l, test, &[])
    }

    /// [`Self::crossings`] with the edges `open` taken away.
    fn crossings_past(
        &self,
        region: &ConvexPolygon,
        l: GridPoint,
        test: &[bool],
        open: &[usize],
    ) -> SmallVec<[bool; 8]> {
        // The segment k-l crosses the plane at x. For an edge a-b, the plane
        // H through a, b, l meets the support in the edge's line, and x lies
        // between k and l with l on H: x is on the polygon's side of the
        // line exactly when k is on the side of H of the polygon's inside.
        // With the corners counter-clockwise about the support's normal,
        // that side is the one opposite the side of the support that l is
        // on (the sign of the triple product (b - a) x (inside - a) . (l -
        // a)), the same for every edge.
        let outer = side_of_point(&self.support, l);
        let mut inside: SmallVec<[bool; 8]> = SmallVec::from_slice(test);
        if outer == Side::On {
            inside.fill(false);
            return inside;
        }
        let m = self.corners.len();
        for e in 0..m {
            if !inside.contains(&true) {
                break;
            }
            if open.contains(&e) {
                continue;
            }
            let (a, b) = (self.corners[e], self.corners[(e + 1) % m]);
            let Some(h) = Plane::through_unreduced(a, b, l) else {
                inside.fill(false);
                break;
            };
            for (i, keep) in inside.iter_mut().enumerate() {
                *keep = *keep && region.vertex_side(i, &h) != outer;
            }
        }
        inside
    }
}

/// One flag per pair of a light corner and a region corner.
type Pairs = SmallVec<[bool; 32]>;

/// A part of the light: the light itself, a parallelogram of its plane's
/// lattice, or a side of a cut along a blocker's frontier
/// ([`frontier`]); a convex polygon with grid points at its corners,
/// covering part of the light (and maybe some of the plane beyond it).
struct LightPiece {
    corners: SmallVec<[GridPoint; 8]>,
    /// The parallelogram's low and high lattice coordinates; `None` for
    /// the light itself and the sides of frontier cuts.
    rectangle: Option<[[i64; 2]; 2]>,
}

/// A blocker of a proof: one of the prover's occluders or bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum BlockerRef {
    Occluder(u32),
    Body(u32),
    /// Two occluders that share an edge, as one ([`hinge`]).
    Hinge(u32),
    /// Occluders about a corner they share, as one ([`fan`]; made by a
    /// step of a proof for its light piece, and not asked again).
    Fan,
}

struct Prover<'a> {
    occluders: Vec<Occluder>,
    /// The pairs of occluders that share an edge.
    hinges: Vec<hinge::Hinge>,
    /// Per occluder, the hinges it is the first of (ascending).
    hinges_from: Vec<SmallVec<[u32; 4]>>,
    bodies: &'a [&'a Body],
    /// Per body: whether it is clear of the receiver's and the light's
    /// planes ([`Body::clearance`]).
    clearances: Vec<Clearance>,
    receiver: &'a Plane,
    two_sided: bool,
    light: &'a AreaSource,
    lattice: Option<PlaneLattice>,
}

/// The blockers a node of a proof looks at: indices into the prover's
/// occluders and bodies.
#[derive(Clone)]
struct Near {
    occluders: SmallVec<[u32; 16]>,
    bodies: SmallVec<[u32; 16]>,
}

impl Near {
    /// The occluders, then the bodies.
    fn blockers(&self) -> impl Iterator<Item = BlockerRef> + '_ {
        let occluders = self.occluders.iter().map(|&k| BlockerRef::Occluder(k));
        occluders.chain(self.bodies.iter().map(|&k| BlockerRef::Body(k)))
    }
}

/// The state of one proof: how many halvings it may still make, and whether
/// it is refuted (a corner of a part of the region sees a point of the
/// light past every blocker).
struct Search {
    budget: usize,
    refuted: bool,
    /// Whether the next step is the first.
    at_root: bool,
}

impl Prover<'_> {
    /// Whether every segment from `region` to `light` crosses a blocker,
    /// of those `near` (indices into the occluders and the bodies) that
    /// reach into the shaft between them.
    fn prove(
        &self,
        region: &ConvexPolygon,
        light: &LightPiece,
        near: &Near,
        depth: u32,
        light_run: u32,
        search: &mut Search,
    ) -> bool {
        if search.refuted {
            return false;
        }
        if self.needs_no_occluder(light) {
            return true;
        }
        // Parts of the region and of the light are parts of their parent's:
        // each keeps fewer blockers. (With a few left, culling costs more
        // than it saves.)
        let near = if near.occluders.len() + near.bodies.len() <= FEW_BLOCKERS {
            near.clone()
        } else {
            let light_points: SmallVec<[[f64; 3]; 8]> =
                light.corners.iter().map(|p| p.to_f64()).collect();
            let shaft = Shaft::new(&region.vertices_f64(), &light_points);
            Near {
                occluders: near
                    .occluders
                    .iter()
                    .copied()
                    .filter(|&k| !shaft.misses(&self.occluders[k as usize].points))
                    .collect(),
                bodies: near
                    .bodies
                    .iter()
                    .copied()
                    .filter(|&k| !shaft.misses_box(&self.bodies[k as usize].bounds))
                    .collect(),
            }
        };
        // The blockers that may hide all of the light from all of the
        // region (strictly between them, or a body they may enter), each
        // with the corner pairs it crosses: one that crosses them all hides
        // it all, and the others guide the halving.
        let mut candidates: Vec<(BlockerRef, Pairs)> = Vec::new();
        for blocker in near.blockers() {
            let Some(pairs) = self.candidate_pairs(blocker, region, &light.corners) else {
                continue;
            };
            if !pairs.contains(&false) {
                return true;
            }
            candidates.push((blocker, pairs));
        }
        // Hinges of two occluders between the region and the light that
        // each cross some corner pair. (One that crosses none adds no
        // proof: where a hinge crosses every pair and one of its occluders
        // none, every pair passes the seam on the other's side, and so
        // does every segment, the side being bilinear: the other crosses
        // them all alone.)
        let crossing: SmallVec<[u32; 16]> = candidates
            .iter()
            .filter_map(|(blocker, pairs)| match blocker {
                BlockerRef::Occluder(k) if pairs.contains(&true) => Some(*k),
                _ => None,
            })
            .collect();
        if crossing.len() >= 2 {
            // The occluders among the candidates, and the hinges between
            // them in order.
            let mut pieces: SmallVec<[u32; 16]> = candidates
                .iter()
                .filter_map(|(blocker, _)| match blocker {
                    BlockerRef::Occluder(k) => Some(*k),
                    _ => None,
                })
                .collect();
            pieces.sort_unstable();
            let among: SmallVec<[u32; 16]> = pieces
                .iter()
                .flat_map(|&k| &self.hinges_from[k as usize])
                .copied()
                .filter(|&h| {
                    let other = self.hinges[h as usize].occluders[1].0;
                    pieces.binary_search(&other).is_ok()
                })
                .collect();
            for &k in &among {
                let hinge = &self.hinges[k as usize];
                if !hinge.occluders.iter().all(|(o, _)| crossing.contains(o)) {
                    continue;
                }
                let blocker = BlockerRef::Hinge(k);
                let Some(pairs) = self.candidate_pairs(blocker, region, &light.corners) else {
                    continue;
                };
                if !pairs.contains(&false) {
                    return true;
                }
                candidates.push((blocker, pairs));
            }
            // Fans of occluders about a corner they share: the pieces of a
            // bent face or a tent, where the light's parts meet at a point.
            let joints = among.iter().map(|&h| &self.hinges[h as usize]);
            let fans = fan::fan_pairs(&self.occluders, joints, &crossing, region, &light.corners);
            for pairs in fans {
                if !pairs.contains(&false) {
                    return true;
                }
                candidates.push((BlockerRef::Fan, pairs));
            }
        }
        // No one blocker hides it all: before halving, once, look for what
        // dooms the proof (a sampled segment that clearly passes every
        // blocker, a corner pair none crosses).
        if std::mem::take(&mut search.at_root)
            && (self.leaks(region) || self.refuted(region, light, &near, &candidates))
        {
            search.refuted = true;
            return false;
        }
        if depth == 0 || search.budget == 0 {
            return false;
        }
        search.budget -= 1;
        // Where one blocker hides the light's corners on one side from all
        // of the region, cut the light along the edge of what it hides:
        // that side is proven at once, the other left to the rest.
        if let Some([hidden, rest]) = self.cut_at_frontier(region, light, &candidates) {
            return self.prove(region, &hidden, &near, depth - 1, light_run + 1, search)
                && self.prove(region, &rest, &near, depth - 1, light_run + 1, search);
        }
        // Where a blocker hides the light from some corner pairs and not
        // others, cut between them: the pieces on each side then have one
        // blocker more or less to care about. Else alternate: a joint
        // umbra is most often one occluder hiding one part of the light and
        // another the rest, each over all of the region.
        let pairs: Vec<Pairs> = candidates.into_iter().map(|(_, pairs)| pairs).collect();
        let (light_side, region_axis, seam_axis) = self.guide(region, light, &pairs);
        // Where each corner of the region has a blocker that hides all of
        // the light piece from it, but no one blocker serves all corners,
        // the region is cut between them: each part nearer its own. After
        // a run of light cuts, the region once, across the seam between
        // two blockers' parts of the light where one moves across it: no
        // cut of the light then suits all of the region.
        let nk = region.len();
        let each_corner_covered = (0..nk).all(|i| {
            pairs
                .iter()
                .any(|m| (0..light.corners.len()).all(|j| m[j * nk + i]))
        });
        let (light_first, region_axis) = if region_axis.is_some() && each_corner_covered {
            (false, region_axis)
        } else if light_side.is_some() && light_run >= LIGHT_RUN {
            (false, region_axis.or(seam_axis))
        } else {
            (
                light_side.is_some() || (region_axis.is_none() && depth.is_multiple_of(2)),
                region_axis,
            )
        };
        for split_light in [light_first, !light_first] {
            if split_light {
                if let Some([a, b]) = self.halve_light(light, light_side) {
                    return self.prove(region, &a, &near, depth - 1, light_run + 1, search)
                        && self.prove(region, &b, &near, depth - 1, light_run + 1, search);
                }
            } else if let Some((a, b)) = halve_region(region, region_axis) {
                return self.prove(&a, light, &near, depth - 1, 0, search)
                    && self.prove(&b, light, &near, depth - 1, 0, search);
            }
        }
        false
    }

    /// The corner pairs `blocker` crosses when it may hide all of the
    /// light piece with corners `light` from `region` (see
    /// [`Occluder::candidate_pairs`], [`Body::candidate_pairs`]).
    fn candidate_pairs(
        &self,
        blocker: BlockerRef,
        region: &ConvexPolygon,
        light: &[GridPoint],
    ) -> Option<Pairs> {
        match blocker {
            BlockerRef::Occluder(k) => self.occluders[k as usize].candidate_pairs(region, light),
            BlockerRef::Hinge(k) => {
                self.hinges[k as usize].candidate_pairs(&self.occluders, region, light)
            }
            BlockerRef::Body(k) => {
                self.bodies[k as usize].candidate_pairs(region, light, self.clearances[k as usize])
            }
            BlockerRef::Fan => None,
        }
    }

    /// Whether a sampled segment from inside the region to the light
    /// clearly passes every blocker ([`leak::sees_light`]): then no proof
    /// can succeed.
    fn leaks(&self, region: &ConvexPolygon) -> bool {
        let light_points: Vec<[f64; 3]> = self.light.vertices().map(|p| p.to_f64()).collect();
        let receiver_normal =
            (!self.two_sided).then(|| region.support().normal().map(|c| c as f64));
        let outlines = self.occluders.iter().map(|o| &o.points[..]).chain(
            self.bodies
                .iter()
                .flat_map(|b| b.surface.iter().map(|o| &o.points[..])),
        );
        leak::sees_light(
            &region.vertices_f64(),
            &light_points,
            receiver_normal,
            outlines,
        )
    }

    /// Whether a corner pair no blocker `near` crosses refutes the proof:
    /// it stays a corner pair of some part however the region and the
    /// light are halved, and no part with it is ever proven. The pairs the
    /// `candidates` cross are known; each other blocker is asked only for
    /// those no blocker before it crosses.
    fn refuted(
        &self,
        region: &ConvexPolygon,
        light: &LightPiece,
        near: &Near,
        candidates: &[(BlockerRef, Pairs)],
    ) -> bool {
        let mut crossed: Pairs = smallvec::smallvec![false; region.len() * light.corners.len()];
        for (_, pairs) in candidates {
            for (c, &p) in crossed.iter_mut().zip(pairs) {
                *c |= p;
            }
        }
        for blocker in near.blockers() {
            if !crossed.contains(&false) {
                return false;
            }
            crossed = match blocker {
                BlockerRef::Occluder(k) => {
                    self.occluders[k as usize].pair_crossings(region, &light.corners, &crossed)
                }
                BlockerRef::Body(k) => self.bodies[k as usize].pair_crossings(
                    region,
                    &light.corners,
                    &crossed,
                    self.clearances[k as usize],
                ),
                // (A segment a hinge blocks crosses one of its occluders,
                // asked on their own.)
                BlockerRef::Hinge(_) | BlockerRef::Fan => crossed,
            };
        }
        self.pair_sees_past_all(region.len(), light, &crossed)
    }

    /// Whether a pair of a region corner and a light corner that is a
    /// point of the light shining on the receiver is crossed by no blocker.
    fn pair_sees_past_all(
        &self,
        region_corners: usize,
        light: &LightPiece,
        crossed: &Pairs,
    ) -> bool {
        light.corners.iter().enumerate().any(|(j, &l)| {
            let shines = self.two_sided || side_of_point(self.receiver, l) == Side::Front;
            let on_light = self
                .light
                .polygon()
                .edges()
                .all(|edge| side_of_point(edge, l) != Side::Front);
            shines
                && on_light
                && crossed[j * region_corners..(j + 1) * region_corners].contains(&false)
        })
    }

    /// Where a blocker (its corner pairs `candidates`) turns from hiding
    /// the light to not: the light piece's side (0 or 1, in its lattice)
    /// across which it hides all the region from some corners and not
    /// others; the region's axis across which it hides all the light from
    /// some region corners and not others; and the region's axis across
    /// which it hides one light corner from some region corners and not
    /// others (where a seam between two blockers' parts of the light
    /// crosses the region).
    fn guide(
        &self,
        region: &ConvexPolygon,
        light: &LightPiece,
        candidates: &[Pairs],
    ) -> (Option<usize>, Option<usize>, Option<usize>) {
        let (nk, nl) = (region.len(), light.corners.len());
        let (mut light_side, mut region_axis, mut seam_axis) = (None, None, None);
        for m in candidates {
            if light_side.is_none() {
                let by_light: SmallVec<[bool; 8]> =
                    (0..nl).map(|j| (0..nk).all(|i| m[j * nk + i])).collect();
                light_side = self.lattice.and_then(|lattice| {
                    let coords = light
                        .corners
                        .iter()
                        .map(|&p| lattice.coords(p).map(|c| c as f64));
                    separating_axis(coords, &by_light)
                });
            }
            if region_axis.is_none() {
                let by_region: SmallVec<[bool; 8]> =
                    (0..nk).map(|i| (0..nl).all(|j| m[j * nk + i])).collect();
                region_axis = separating_axis(region.vertices_f64(), &by_region);
            }
            if seam_axis.is_none() {
                seam_axis = (0..nl)
                    .find_map(|j| separating_axis(region.vertices_f64(), &m[j * nk..(j + 1) * nk]));
            }
        }
        (light_side, region_axis, seam_axis)
    }

    /// Whether no light of the piece reaches the receiver: it lies behind a
    /// one-sided receiver, or outside the light (a covering piece's part
    /// beyond one of its edges; the light's own corners are all on or
    /// inside every edge, and some inside).
    fn needs_no_occluder(&self, light: &LightPiece) -> bool {
        let behind = |p: &GridPoint| side_of_point(self.receiver, *p) != Side::Front;
        if !self.two_sided && light.corners.iter().all(behind) {
            return true;
        }
        self.light.polygon().edges().any(|edge| {
            light
                .corners
                .iter()
                .all(|&p| side_of_point(edge, p) != Side::Back)
        })
    }

    /// The piece's bounding lattice parallelogram halved across its
    /// longer side (in lattice steps), or `None` (a light whose lattice
    /// is out of range, or a parallelogram one step wide).
    fn halve_light(&self, light: &LightPiece, side: Option<usize>) -> Option<[LightPiece; 2]> {
        let lattice = self.lattice?;
        let [lo, hi] = light.rectangle.unwrap_or_else(|| {
            let coords: SmallVec<[[i64; 2]; 8]> =
                light.corners.iter().map(|&p| lattice.coords(p)).collect();
            let along = |k: usize| coords.iter().map(move |c| c[k]);
            [
                [along(0).min().unwrap_or(0), along(1).min().unwrap_or(0)],
                [along(0).max().unwrap_or(0), along(1).max().unwrap_or(0)],
            ]
        });
        // A receiver whose plane meets the light's in a lattice line
        // across the piece cuts it there first: each side then has its own
        // occluders (or none, behind a one-sided receiver).
        let across = lattice
            .line_of(self.receiver)
            .filter(|&(side, at)| lo[side] < at && at < hi[side]);
        let (side, mid) = match across {
            Some(cut) => cut,
            None => {
                let longer = if hi[0] - lo[0] >= hi[1] - lo[1] { 0 } else { 1 };
                let side = side.unwrap_or(longer);
                if hi[side] - lo[side] < 2 {
                    return None;
                }
                (side, lo[side] + (hi[side] - lo[side]) / 2)
            }
        };
        let (mut low_hi, mut high_lo) = (hi, lo);
        low_hi[side] = mid;
        high_lo[side] = mid;
        Some([
            Self::parallelogram(&lattice, [lo, low_hi])?,
            Self::parallelogram(&lattice, [high_lo, hi])?,
        ])
    }

    fn parallelogram(lattice: &PlaneLattice, [lo, hi]: [[i64; 2]; 2]) -> Option<LightPiece> {
        Some(LightPiece {
            corners: [
                lattice.point([lo[0], lo[1]])?,
                lattice.point([hi[0], lo[1]])?,
                lattice.point([hi[0], hi[1]])?,
                lattice.point([lo[0], hi[1]])?,
            ]
            .into_iter()
            .collect(),
            rectangle: Some([lo, hi]),
        })
    }
}

/// The axis along which the points marked `true` lie all on one side of
/// those marked `false` (the widest such gap), if some do.
fn separating_axis<const N: usize>(
    points: impl IntoIterator<Item = [f64; N]>,
    marks: &[bool],
) -> Option<usize> {
    if !marks.contains(&true) || !marks.contains(&false) {
        return None;
    }
    let points: SmallVec<[[f64; N]; 8]> = points.into_iter().collect();
    let range = |axis: usize, mark: bool| {
        let values = points
            .iter()
            .zip(marks)
            .filter(|(_, m)| **m == mark)
            .map(|(p, _)| p[axis]);
        values.fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], v| {
            [lo.min(v), hi.max(v)]
        })
    };
    (0..N)
        .filter_map(|axis| {
            let (a, b) = (range(axis, true), range(axis, false));
            let gap = (a[0] - b[1]).max(b[0] - a[1]);
            (gap > 0.0).then_some((axis, gap))
        })
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .map(|(axis, _)| axis)
}

/// The region cut in two by the grid plane across the middle of its extent
/// along `axis` (by default its longest), or `None` when no such plane cuts
/// it.
fn halve_region(
    region: &ConvexPolygon,
    axis: Option<usize>,
) -> Option<(ConvexPolygon, ConvexPolygon)> {
    let corners = region.vertices_f64();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for c in &corners {
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    let axis =
        axis.or_else(|| (0..3).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))))?;
    let mid = ((lo[axis] + hi[axis]) / 2.0).round();
    if !(mid > lo[axis] && mid < hi[axis]) {
        return None;
    }
    let mut normal = [0_i64; 3];
    normal[axis] = 1;
    let mut at = [0_i64; 3];
    at[axis] = mid as i64;
    let plane = Plane::with_normal_through(normal, GridPoint::new(at[0], at[1], at[2]).ok()?)?;
    match region.split(&plane) {
        Split::Both(back, front) => Some((back, front)),
        _ => None,
    }
}
#[cfg(test)]
mod tests;
