//! Merging the pieces a tree cut a fragment into back together where they
//! have the same class.
//!
//! Filtering a polygon down a BSP tree cuts it by every plane of every cell
//! it crosses, even where the class is the same on both sides (the plane
//! bounds a volume elsewhere in the cell). Two pieces of one class that
//! share a whole edge and whose union is convex become one again: fewer
//! fragments, fewer vertices to illuminate. Every test is exact.

use crate::Class;
use crate::conform::MeshPoint;
use bsp_core::ConvexPolygon;
use bsp_core::predicates::Side;

/// `a ∪ b` when they share a whole edge and their union is convex.
pub fn merge_pair(a: &ConvexPolygon, b: &ConvexPolygon) -> Option<ConvexPolygon> {
    let (n, m) = (a.len(), b.len());
    let (k, l) = (0..n).find_map(|k| {
        let l = (0..m).find(|&l| b.edge(l).is_opposite(a.edge(k)))?;
        Some((k, l))
    })?;
    // The same segment: a's edge k runs p -> q, b's edge l runs q -> p.
    if !MeshPoint::vertex(a, k).same_point(&MeshPoint::vertex(b, (l + 1) % m))
        || !MeshPoint::vertex(a, (k + 1) % n).same_point(&MeshPoint::vertex(b, l))
    {
        return None;
    }
    // Convex union: each lies behind the other's remaining edges.
    let behind = |p: &ConvexPolygon, q: &ConvexPolygon, skip: usize| {
        (0..p.len())
            .filter(|&e| e != skip)
            .all(|e| (0..q.len()).all(|v| q.vertex_side(v, p.edge(e)) != Side::Front))
    };
    if !behind(a, b, k) || !behind(b, a, l) {
        return None;
    }
    // a's edges after k round to before k, then b's after l round to before
    // l; an edge of b on the same line as its neighbour of a is dropped.
    let mut edges: Vec<_> = (1..n).map(|i| *a.edge((k + i) % n)).collect();
    let a_first = *a.edge((k + 1) % n);
    let a_last = *a.edge((k + n - 1) % n);
    let (b_first, b_last) = ((l + 1) % m, (l + m - 1) % m);
    // The far vertex of a's last edge and of a's first edge.
    let before_p = MeshPoint::vertex(a, (k + n - 1) % n);
    let after_q = MeshPoint::vertex(a, (k + 2) % n);
    for i in 1..m {
        let e = (l + i) % m;
        let plane = *b.edge(e);
        if e == b_first && (plane == a_last || before_p.side(&plane) == Side::On) {
            continue;
        }
        if e == b_last && (plane == a_first || after_q.side(&plane) == Side::On) {
            continue;
        }
        edges.push(plane);
    }
    ConvexPolygon::from_planes(*a.support(), &edges, a.source()).ok()
}

/// The key of an edge plane's line: its normal and offset, signed so that
/// both orientations agree.
type LineKey = ([i64; 3], i128);

/// A plane's line key, the same for both orientations.
fn plane_key(p: &bsp_core::Plane) -> LineKey {
    let n = p.normal();
    let first = n.iter().copied().find(|&c| c != 0).unwrap_or(0);
    if first < 0 {
        (n.map(|c| -c), -p.offset())
    } else {
        (n, p.offset())
    }
}

/// Where edge `e` of `p` lies along its line, in `f64`: its midpoint's
/// coordinate on the axis the line runs most along. Two pieces that share
/// a whole edge give the same value up to rounding.
fn edge_position(p: &ConvexPolygon, e: usize) -> f64 {
    let (a, b) = (p.vertex_f64(e), p.vertex_f64((e + 1) % p.len()));
    let axis = (0..3)
        .max_by(|&i, &j| (a[i] - b[i]).abs().total_cmp(&(a[j] - b[j]).abs()))
        .unwrap_or(0);
    0.5 * (a[axis] + b[axis])
}

/// Merges same-class neighbours among `pieces` (the pieces of one polygon)
/// until no two can merge.
///
/// The pieces' edges are grouped by their line and kept sorted along it;
/// each piece, and each union as it is made, is tried once against the
/// edges at the same place on its edges' lines (the `f64` position only
/// chooses which pairs [`merge_pair`] tests exactly, with a margin far above
/// rounding). A piece that merges is replaced by the union, whose edges go
/// into the lines in turn, so the work is `n log n` in all rather than a
/// quadratic search or a pass over every piece per round.
pub fn merge_same_class(pieces: Vec<(ConvexPolygon, Class)>) -> Vec<(ConvexPolygon, Class)> {
    if pieces.len() < 2 {
        return pieces;
    }
    let mut pieces: Vec<Option<(ConvexPolygon, Class)>> = pieces.into_iter().map(Some).collect();
    // Every line's edges: (position along it, piece), sorted. A merged
    // piece's entries stay behind and are skipped.
    let mut keys: Vec<(LineKey, f64, usize)> = Vec::new();
    for (i, (p, _)) in pieces.iter().flatten().enumerate() {
        for (e, plane) in p.edges().enumerate() {
            keys.push((plane_key(plane), edge_position(p, e), i));
        }
    }
    keys.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut lines: Vec<(LineKey, Vec<(f64, usize)>)> = Vec::new();
    for (key, t, i) in keys {
        match lines.last_mut() {
            Some((last, list)) if *last == key => list.push((t, i)),
            _ => lines.push((key, vec![(t, i)])),
        }
    }
    let line_of = |lines: &[(LineKey, Vec<(f64, usize)>)], key: &LineKey| {
        lines.binary_search_by(|(k, _)| k.cmp(key)).ok()
    };
    let mut queue: std::collections::VecDeque<usize> = (0..pieces.len()).collect();
    'pieces: while let Some(i) = queue.pop_front() {
        let Some((a, class)) = &pieces[i] else {
            continue;
        };
        for (e, plane) in a.edges().enumerate() {
            let line = line_of(&lines, &plane_key(plane)).expect("every edge's line is listed");
            let t = edge_position(a, e);
            let margin = 1e-7 * t.abs().max(1.0);
            let list = &lines[line].1;
            let from = list.partition_point(|(u, _)| *u < t - margin);
            for &(_, j) in list[from..].iter().take_while(|(u, _)| *u <= t + margin) {
                if j == i {
                    continue;
                }
                let Some((b, other)) = &pieces[j] else {
                    continue;
                };
                if other != class {
                    continue;
                }
                if let Some(union) = merge_pair(a, b) {
                    let (class, k) = (*class, pieces.len());
                    for (e, plane) in union.edges().enumerate() {
                        let key = plane_key(plane);
                        let t = edge_position(&union, e);
                        // A union's edges are its pieces' edges: the
                        // line is listed.
                        let line = line_of(&lines, &key).expect("every edge's line is listed");
                        let list = &mut lines[line].1;
                        let at = list.partition_point(|(u, _)| *u <= t);
                        list.insert(at, (t, k));
                    }
                    pieces[i] = None;
                    pieces[j] = None;
                    pieces.push(Some((union, class)));
                    queue.push_back(k);
                    continue 'pieces;
                }
            }
        }
    }
    pieces.into_iter().flatten().collect()
}
