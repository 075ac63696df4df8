//! Occluders around a corner they share, blocking as one: a fan.
//!
//! A [`Hinge`] proves two occluders that share an edge dark together
//! wherever the segments from the region to the light cross both planes
//! inside their other edges. Where several pieces meet at a corner `v` (a
//! tent's apex, the corner of a fold whose quads the grid cut into
//! triangles) the region's corner may see the light's corner exactly past
//! `v`: the light's parts the pieces hide then meet at one point, with no
//! room to cut between them, and no pair of pieces hides the light near
//! it. Together they do, by an angle about `v`.
//!
//! Fix a light point `l`. The planes through `l` and `v` turn about the
//! line `lv`; each half-plane `H_t` bounded by that line (`t` an angle)
//! meets the plane of a piece `P` through `v` in one ray from `v` (the
//! line does not lie in `P`'s plane when `l` does not), and a line of
//! `P`'s plane through `v` in the two rays of a pair of opposite
//! half-planes. So the corner of `P` at `v` is seen as an arc `T_P` of
//! angles, between those of its two edges at `v`, shorter than a half
//! turn. A segment from `k` to `l` lies in `H_t(k)`, so it meets `P`'s plane
//! (if it crosses it at all) at `v` or on the ray of angle `t(k)`: inside
//! `P` exactly when `t(k)` is in `T_P` and the point is inside `P`'s edges
//! away from `v`.
//!
//! Let the pieces around `v` follow one another `P_1 .. P_n`, each sharing
//! an edge at `v` with the next (a hinge), and let each hinge fold apart
//! for `l` (the two pieces strictly on opposite sides of the plane through
//! the shared edge and `l`): then the arcs `T_1 .. T_n` follow one another
//! turning one way, from the angle of `P_1`'s other edge at `v` (0, say) to
//! that of `P_n`'s (`T`). Let `P'` be `P`'s plane inside its edges but some
//! of its edges at `v`: both, for every piece but the ends; at the ends,
//! the shared one. A segment from `k` that crosses every `P'` crosses a
//! piece when `t(k)` lies in the arcs' span:
//!
//! - a closed fan (`P_n` shares an edge with `P_1` too, and each piece
//!   drops both its edges at `v`): the arcs go all the way round, every
//!   angle is in one;
//! - an open fan where each end keeps its other edge at `v`: crossing
//!   `P_1'` puts `t(k)` in the half turn `[0, π]` on `P_1`'s side of that
//!   edge, crossing `P_n'` in `[T - π, T]`, and together in `[0, T]`;
//! - an open fan where only `P_1` keeps it, when `T` is at least a half
//!   turn: `t(k)` in `[0, π]`, within `[0, T]` (and likewise with `P_n`).
//!   `T` is at least a half turn when `P_n`'s other edge at `v` is not on
//!   `P_1`'s side of the plane through `P_1`'s other edge and `l`.
//!
//! Each condition on `l` (folding apart, the half turn) holds for the
//! whole light piece when it holds for its corners (a half-space or a
//! convex angle of `l`), and each `P'` is convex, so the corner pairs
//! tell (the module's docs). The last kind proves what the others cannot
//! where a fold's two pieces span more than a half turn about a corner.

use super::hinge::Hinge;
use super::{Occluder, Pairs};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, Plane};
use smallvec::SmallVec;

/// A fan's pieces (indices into the prover's occluders), each with the
/// edges its `P'` leaves out.
type Fan = SmallVec<[(u32, SmallVec<[usize; 2]>); 8]>;

/// A piece's hinges about a corner: each hinge (its position) with the
/// piece's edge there.
type Links = SmallVec<[(usize, usize); 2]>;

/// For each fan about a corner of occluders joined by those of `hinges`
/// that fold apart for the light piece with corners `light` (the hinges
/// between the occluders that may hide the light piece from the region),
/// two of them or more among `crossing` (those that cross some corner
/// pair), the corner pairs that cross every piece's `P'` (see the
/// module's docs): every such pair crosses a piece. Corners by their
/// order, fans by their first piece; fans whose pieces do not all have the
/// region and the light strictly on opposite sides of their planes are
/// left out.
pub(super) fn fan_pairs<'h>(
    occluders: &[Occluder],
    hinges: impl Iterator<Item = &'h Hinge>,
    crossing: &[u32],
    region: &ConvexPolygon,
    light: &[GridPoint],
) -> Vec<Pairs> {
    let joints: SmallVec<[&Hinge; 16]> = hinges.filter(|h| h.folds_apart(light)).collect();
    if joints.is_empty() {
        return Vec::new();
    }
    let mut by_corner: SmallVec<[(GridPoint, usize); 32]> = joints
        .iter()
        .enumerate()
        .flat_map(|(j, h)| h.axis.map(|p| (p, j)))
        .collect();
    by_corner.sort_unstable();
    let mut out = Vec::new();
    for at in by_corner.chunk_by(|a, b| a.0 == b.0) {
        let v = at[0].0;
        let about: SmallVec<[&Hinge; 8]> = at.iter().map(|&(_, j)| joints[j]).collect();
        for fan in fans(occluders, &about, v, light) {
            // (A fan with one piece crossing some pair adds no proof: the
            // pairs all pass within that piece's corner, and so does every
            // segment, which that piece alone then crosses.)
            if fan.iter().filter(|(k, _)| crossing.contains(k)).count() < 2 {
                continue;
            }
            let mut all: Option<Pairs> = None;
            for (k, open) in &fan {
                let Some(crossed) =
                    occluders[*k as usize].candidate_pairs_past(region, light, open)
                else {
                    all = None;
                    break;
                };
                all = Some(match all {
                    None => crossed,
                    Some(mut all) => {
                        for (x, &y) in all.iter_mut().zip(&crossed) {
                            *x &= y;
                        }
                        all
                    }
                });
            }
            out.extend(all);
        }
    }
    out
}

/// The fans about `v` that the hinges `about` (each with `v` on its
/// shared edge) make, each in the kinds the light piece `light` allows:
/// closed fans of three or more pieces; open fans of three or more with
/// both ends keeping their other edge at `v`; and open fans of two or
/// more with one end keeping it, where the span is at least a half turn.
/// (A fan of two keeping both is the hinge itself.) None where a piece
/// has more than two hinges about `v` (an edge shared three ways).
fn fans(occluders: &[Occluder], about: &[&Hinge], v: GridPoint, light: &[GridPoint]) -> Vec<Fan> {
    // Each piece's hinges about `v`: (hinge, its edge there).
    let mut links: SmallVec<[(u32, Links); 8]> = SmallVec::new();
    for (h, hinge) in about.iter().enumerate() {
        for &(k, edge) in &hinge.occluders {
            match links.iter_mut().find(|(o, _)| *o == k) {
                Some((_, l)) => l.push((h, edge)),
                None => links.push((k, smallvec::smallvec![(h, edge)])),
            }
        }
    }
    // (An edge shared three ways, or a piece with more than two edges at
    // `v`: no fan.)
    if links
        .iter()
        .any(|(_, l)| l.len() > 2 || (l.len() == 2 && l[0].1 == l[1].1))
    {
        return Vec::new();
    }
    links.sort_unstable_by_key(|(k, _)| *k);
    let links_of = |k: u32| &links[links.iter().position(|(o, _)| *o == k).unwrap_or(0)].1;
    let mut seen: SmallVec<[u32; 8]> = SmallVec::new();
    let mut out = Vec::new();
    // Open fans from their lower end, then closed ones from their lowest
    // piece.
    let ends = links.iter().filter(|(_, l)| l.len() == 1).map(|(k, _)| *k);
    let rest: SmallVec<[u32; 8]> = links.iter().map(|(k, _)| *k).collect();
    for (start, closed) in ends
        .map(|k| (k, false))
        .chain(rest.into_iter().map(|k| (k, true)))
    {
        if seen.contains(&start) {
            continue;
        }
        // Walk from `start`: each piece with its edges at `v` that are
        // hinges of the walk.
        let mut walk: Fan = SmallVec::new();
        let (mut k, mut came) = (start, None::<usize>);
        loop {
            seen.push(k);
            let next = links_of(k).iter().find(|(h, _)| Some(*h) != came).copied();
            let mut edges: SmallVec<[usize; 2]> = links_of(k)
                .iter()
                .filter(|(h, _)| Some(*h) == came || Some(*h) == next.map(|n| n.0))
                .map(|&(_, e)| e)
                .collect();
            edges.dedup();
            walk.push((k, edges));
            let Some((h, _)) = next else { break };
            let [(a, _), (b, _)] = about[h].occluders;
            let other = if a == k { b } else { a };
            if other == start {
                // Round: the start's edge on the closing hinge.
                if let Some(&(_, e)) = links_of(start).iter().find(|(g, _)| *g == h) {
                    walk[0].1.push(e);
                }
                break;
            }
            if seen.contains(&other) {
                // (A piece reached again other than the start: no fan.)
                walk.clear();
                break;
            }
            (k, came) = (other, Some(h));
        }
        let n = walk.len();
        if closed {
            if n >= 3 {
                out.push(walk);
            }
            continue;
        }
        if n < 2 {
            continue;
        }
        // The ends' other edges at `v`: (index, far corner), and the far
        // corner of each end's hinge (on its side of the other edge).
        let outer = |k: u32, hinge_edge: usize| -> Option<(usize, GridPoint, GridPoint)> {
            let corners = &occluders[k as usize].corners;
            let m = corners.len();
            let i = corners.iter().position(|&c| c == v)?;
            let (before, after) = ((i + m - 1) % m, i);
            if hinge_edge != before && hinge_edge != after {
                return None;
            }
            let far = |e: usize| {
                if e == before {
                    corners[before]
                } else {
                    corners[(i + 1) % m]
                }
            };
            let other = if hinge_edge == before { after } else { before };
            Some((other, far(other), far(hinge_edge)))
        };
        let (first, last) = (&walk[0], &walk[n - 1]);
        let (Some(head), Some(tail)) = (outer(first.0, first.1[0]), outer(last.0, last.1[0]))
        else {
            continue;
        };
        if n >= 3 {
            out.push(walk.clone());
        }
        // One end keeps its other edge, the other drops it too.
        for (keep, drop, at_end) in [(head, tail, n - 1), (tail, head, 0)] {
            if spans_half_turn(v, keep, drop.1, light) {
                let mut fan = walk.clone();
                fan[at_end].1.push(drop.0);
                out.push(fan);
            }
        }
    }
    out
}

/// Whether, for every light corner `l`, the far corner `beyond` of the
/// other end's edge is not on the side of the plane through `v`, the
/// kept edge's far corner and `l` where the kept end lies (shown by
/// `keep`'s far hinge corner): the fan spans at least a half turn about
/// `v` seen from `l`.
fn spans_half_turn(
    v: GridPoint,
    (_, kept_far, inside): (usize, GridPoint, GridPoint),
    beyond: GridPoint,
    light: &[GridPoint],
) -> bool {
    light.iter().all(|&l| {
        Plane::through_unreduced(v, kept_far, l).is_some_and(|plane| {
            let side = side_of_point(&plane, inside);
            side != Side::On && side_of_point(&plane, beyond) != side
        })
    })
}
