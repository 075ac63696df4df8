//! Cutting a light piece along the frontier of what one blocker hides.
//!
//! Where two blockers hide the light only together, halving at midpoints
//! must shrink the pieces below the overlap of their hidden parts before
//! any piece is hidden by one of them: many levels when the overlap is
//! thin, as beside a contact or a discontinuity the region's corners lie
//! on. But the part of the light a convex blocker hides from all of a
//! convex region is convex (the segments from a point that cross a convex
//! polygon, or enter a convex body, form a convex set, and the region's
//! corners stand for it). So when a blocker hides a run of the piece's
//! corners from all of the region and not the others, the last grid
//! points it hides along the two edges leaving that run (found by
//! bisection) bound a chord inside what it hides: the side with the run
//! is hidden by that blocker, and one cut leaves the rest to the others.
//!
//! The bisection only guides the cut: each side is proven as any piece is,
//! so the cut is sound whatever it finds.

use super::{BlockerRef, LightPiece, Pairs, Prover};
use bsp_core::{ConvexPolygon, GridPoint};
use smallvec::SmallVec;

impl Prover<'_> {
    /// The piece cut along the frontier of what one of the `candidates`
    /// (blockers with their crossed corner pairs) hides: the side it hides
    /// first. `None` when no blocker hides one run of the piece's corners
    /// from every region corner and misses the rest, or the cut would
    /// leave a side with no area.
    pub(super) fn cut_at_frontier(
        &self,
        region: &ConvexPolygon,
        light: &LightPiece,
        candidates: &[(BlockerRef, Pairs)],
    ) -> Option<[LightPiece; 2]> {
        let lattice = self.lattice?;
        let corners = &light.corners;
        let (nk, nl) = (region.len(), corners.len());
        // The blocker that hides the most corners from all of the region,
        // as one run.
        let (blocker, first, last) = candidates
            .iter()
            .filter_map(|(blocker, pairs)| {
                let hides: SmallVec<[bool; 8]> = (0..nl)
                    .map(|j| pairs[j * nk..(j + 1) * nk].iter().all(|&c| c))
                    .collect();
                let (first, last) = one_run(&hides)?;
                Some((*blocker, first, last, hides.iter().filter(|&&h| h).count()))
            })
            .max_by_key(|&(.., count)| count)
            .map(|(blocker, first, last, _)| (blocker, first, last))?;
        // Whether the blocker hides a point from all of the region (a
        // body's side of the region worked out once for the bisections).
        let body_test = match blocker {
            BlockerRef::Body(k) => {
                Some(self.bodies[k as usize].point_test(region, self.clearances[k as usize]))
            }
            BlockerRef::Occluder(_) | BlockerRef::Hinge(_) | BlockerRef::Fan => None,
        };
        let hides = |p: GridPoint| match &body_test {
            Some(test) => test(p),
            None => self
                .candidate_pairs(blocker, region, &[p])
                .is_some_and(|pairs| !pairs.contains(&false)),
        };
        // The last hidden grid point from `from` (hidden) towards `to`
        // (not): the hidden points of the edge are one interval from
        // `from`, as what the blocker hides is convex.
        let frontier = |from: GridPoint, to: GridPoint| -> Option<GridPoint> {
            let (a, b) = (lattice.coords(from), lattice.coords(to));
            let delta = [b[0] - a[0], b[1] - a[1]];
            let steps = gcd(delta[0].unsigned_abs(), delta[1].unsigned_abs()) as i64;
            if steps == 0 {
                return None;
            }
            let step = [delta[0] / steps, delta[1] / steps];
            let at = |t: i64| lattice.point([a[0] + t * step[0], a[1] + t * step[1]]);
            let (mut hidden, mut seen) = (0, steps);
            while seen - hidden > 1 {
                let mid = hidden + (seen - hidden) / 2;
                if hides(at(mid)?) {
                    hidden = mid;
                } else {
                    seen = mid;
                }
            }
            at(hidden)
        };
        let next = |j: usize| (j + 1) % nl;
        let before = |j: usize| (j + nl - 1) % nl;
        let p = frontier(corners[last], corners[next(last)])?;
        let q = frontier(corners[first], corners[before(first)])?;
        // The hidden side: the run from `first` to `last`, then p and q;
        // the rest: p, the corners after the run up to the one before it,
        // then q.
        let mut hidden: SmallVec<[GridPoint; 8]> = SmallVec::new();
        let mut j = first;
        loop {
            hidden.push(corners[j]);
            if j == last {
                break;
            }
            j = next(j);
        }
        hidden.extend([p, q]);
        let mut rest: SmallVec<[GridPoint; 8]> = smallvec::smallvec![p];
        let mut j = next(last);
        while j != first {
            rest.push(corners[j]);
            j = next(j);
        }
        rest.push(q);
        let side = |points: SmallVec<[GridPoint; 8]>| -> Option<LightPiece> {
            let corners = distinct(points);
            // Three corners not on one line: the side has area.
            ConvexPolygon::from_grid_points(&corners, 0).ok()?;
            Some(LightPiece {
                corners,
                rectangle: None,
            })
        };
        Some([side(hidden)?, side(rest)?])
    }
}

/// The first and last index of the one cyclic run of `true` in `marks`,
/// if the marks hold exactly one such run and some `false`.
fn one_run(marks: &[bool]) -> Option<(usize, usize)> {
    let n = marks.len();
    let starts: SmallVec<[usize; 8]> = (0..n)
        .filter(|&j| marks[j] && !marks[(j + n - 1) % n])
        .collect();
    let &[first] = starts.as_slice() else {
        return None;
    };
    let mut last = first;
    while marks[(last + 1) % n] {
        last = (last + 1) % n;
    }
    Some((first, last))
}

/// The points with repeats in a row (cyclically) dropped.
fn distinct(points: SmallVec<[GridPoint; 8]>) -> SmallVec<[GridPoint; 8]> {
    let mut out: SmallVec<[GridPoint; 8]> = SmallVec::new();
    for p in points {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::one_run;

    #[test]
    fn runs_are_found_cyclically() {
        assert_eq!(one_run(&[true, true, false, false]), Some((0, 1)));
        assert_eq!(one_run(&[true, false, false, true]), Some((3, 0)));
        assert_eq!(one_run(&[false, true, false, true]), None);
        assert_eq!(one_run(&[true, true, true]), None);
        assert_eq!(one_run(&[false, false]), None);
    }
}
