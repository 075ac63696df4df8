//! Target `merge`: two random solids combined by a random set operation,
//! checked pointwise.
//!
//! [`MergeCase::arbitrary`] decodes two solids, each a union of a few
//! axis-aligned boxes with small coordinates (so faces are often coplanar,
//! boxes touch along faces, edges and corners), a set operation and query
//! points. [`check_merge`] merges the trees with Naylor-Amanatides-Thibault
//! merging and checks the result's invariants and, at every query point off
//! both operands' boundaries, that it classifies the point as the Boolean
//! of the operands does.

use arbitrary::{Arbitrary, Unstructured};
use bsp_core::{BspSolid, BuildOptions, ConvexPolygon, GridPoint, PointClass};
use svbsp::{SetOp, merge};

/// One decoded input of the `merge` target; its `Debug` output is Rust code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MergeCase {
    /// Boxes of the first solid, `(lo, hi)` corners.
    pub a: Vec<([i64; 3], [i64; 3])>,
    /// Boxes of the second solid.
    pub b: Vec<([i64; 3], [i64; 3])>,
    /// 0: union, 1: intersection, 2: difference.
    pub op: u8,
    /// Query points.
    pub points: Vec<[i64; 3]>,
}

fn small_box(u: &mut Unstructured<'_>) -> arbitrary::Result<([i64; 3], [i64; 3])> {
    let mut lo = [0_i64; 3];
    let mut hi = [0_i64; 3];
    for k in 0..3 {
        lo[k] = i64::from(u.int_in_range(-6_i8..=5)?);
        hi[k] = lo[k] + i64::from(u.int_in_range(1_i8..=6)?);
    }
    Ok((lo, hi))
}

impl<'a> Arbitrary<'a> for MergeCase {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        let na = u.int_in_range(1_usize..=3)?;
        let nb = u.int_in_range(1_usize..=3)?;
        let a = (0..na).map(|_| small_box(u)).collect::<Result<_, _>>()?;
        let b = (0..nb).map(|_| small_box(u)).collect::<Result<_, _>>()?;
        let op = u.int_in_range(0_u8..=2)?;
        let np = u.int_in_range(1_usize..=24)?;
        let points = (0..np)
            .map(|_| Ok([0, 1, 2].map(|_| u.int_in_range(-8_i8..=13).map(i64::from).unwrap_or(0))))
            .collect::<arbitrary::Result<_>>()?;
        Ok(Self { a, b, op, points })
    }
}

/// Decodes fuzzer bytes.
pub fn decode(data: &[u8]) -> Option<MergeCase> {
    MergeCase::arbitrary_take_rest(Unstructured::new(data)).ok()
}

/// The body of the `merge` fuzz target.
pub fn run(data: &[u8]) {
    let Some(case) = decode(data) else { return };
    if let Err(problem) = check_merge(&case) {
        panic!("merge invariant violated: {problem}\n{case:?}");
    }
}

fn gp(p: [i64; 3]) -> GridPoint {
    GridPoint::new(p[0], p[1], p[2]).expect("small coordinates")
}

/// The six outward faces of a box.
fn box_faces(lo: [i64; 3], hi: [i64; 3]) -> Vec<ConvexPolygon> {
    let c = |x: bool, y: bool, z: bool| {
        gp([
            if x { hi[0] } else { lo[0] },
            if y { hi[1] } else { lo[1] },
            if z { hi[2] } else { lo[2] },
        ])
    };
    let (f, t) = (false, true);
    [
        [c(f, f, f), c(f, t, f), c(t, t, f), c(t, f, f)],
        [c(f, f, t), c(t, f, t), c(t, t, t), c(f, t, t)],
        [c(f, f, f), c(t, f, f), c(t, f, t), c(f, f, t)],
        [c(f, t, f), c(f, t, t), c(t, t, t), c(t, t, f)],
        [c(f, f, f), c(f, f, t), c(f, t, t), c(f, t, f)],
        [c(t, f, f), c(t, t, f), c(t, t, t), c(t, f, t)],
    ]
    .iter()
    .map(|q| ConvexPolygon::from_grid_points(q, 0).expect("a box face"))
    .collect()
}

/// The union of boxes, by merging box solids one at a time.
fn union_of(boxes: &[([i64; 3], [i64; 3])]) -> BspSolid {
    boxes.iter().fold(BspSolid::empty(), |acc, &(lo, hi)| {
        merge(
            &acc,
            &BspSolid::from_boundary(box_faces(lo, hi), &BuildOptions::default()),
            SetOp::Union,
        )
    })
}

/// Whether a point is in the union of boxes: `Some(inside)`, or `None` on
/// a box's boundary (where the union's boundary may or may not be).
fn in_boxes(boxes: &[([i64; 3], [i64; 3])], p: [i64; 3]) -> Option<bool> {
    let mut on_boundary = false;
    for (lo, hi) in boxes {
        let inside = (0..3).all(|k| lo[k] < p[k] && p[k] < hi[k]);
        if inside {
            return Some(true);
        }
        on_boundary |= (0..3).all(|k| lo[k] <= p[k] && p[k] <= hi[k]);
    }
    if on_boundary { None } else { Some(false) }
}

/// Merges and checks; `Err` describes the first violated invariant.
pub fn check_merge(case: &MergeCase) -> Result<(), String> {
    let op = match case.op {
        0 => SetOp::Union,
        1 => SetOp::Intersection,
        _ => SetOp::Difference,
    };
    let a = union_of(&case.a);
    let b = union_of(&case.b);
    let result = merge(&a, &b, op);
    for solid in [&a, &b, &result] {
        solid.check_invariants()?;
    }
    for &p in &case.points {
        // Independent truth: the boxes themselves.
        let (Some(in_a), Some(in_b)) = (in_boxes(&case.a, p), in_boxes(&case.b, p)) else {
            continue;
        };
        let expected = op.apply(in_a, in_b);
        let got = result.classify_point(gp(p));
        let want = if expected {
            PointClass::In
        } else {
            PointClass::Out
        };
        // A point off both operands' boundaries is off the result's too.
        if got != want {
            return Err(format!(
                "point {p:?}: {got:?}, expected {want:?} (in A: {in_a}, in B: {in_b})"
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::pseudo_random_bytes as bytes;

    #[test]
    fn seed_corpus_replays() {
        let files = crate::corpus_files("merge").expect("corpus/merge is readable");
        assert!(files.len() >= 8, "only {} seed files", files.len());
        for (name, data) in files {
            let case = decode(&data).expect("decodes");
            if let Err(problem) = check_merge(&case) {
                panic!("corpus/merge/{name}: {problem}\n{case:?}");
            }
        }
    }

    #[test]
    fn pseudo_random_inputs_pass() {
        for seed in 0..1_500 {
            let data = bytes(seed, 40 + (seed % 61) as usize);
            let case = decode(&data).expect("decodes");
            if let Err(problem) = check_merge(&case) {
                panic!("seed {seed}: {problem}\n{case:?}");
            }
        }
    }

    #[test]
    fn touching_boxes() {
        // Two boxes sharing a face, and a third touching along an edge.
        let case = MergeCase {
            a: vec![([0, 0, 0], [2, 2, 2]), ([2, 0, 0], [4, 2, 2])],
            b: vec![([4, 2, 0], [6, 4, 2])],
            op: 0,
            points: vec![[1, 1, 1], [3, 1, 1], [5, 3, 1], [3, 3, 1], [2, 1, 1]],
        };
        check_merge(&case).unwrap();
    }

    /// Writes the seed corpus (run by hand when the decoder changes).
    #[test]
    #[ignore = "rewrites corpus/merge; run by hand"]
    fn regenerate_seed_corpus() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/merge");
        std::fs::create_dir_all(&dir).unwrap();
        for seed in 0..12_u64 {
            std::fs::write(
                dir.join(format!("seed-{seed:02}")),
                bytes(1000 + seed, 48 + 7 * seed as usize),
            )
            .unwrap();
        }
    }
}
