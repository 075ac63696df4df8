//! A floating-point look for light that gets through, before a proof:
//! segments from points inside the region to points of the light that
//! clearly miss every blocker. One such segment means the proof would fail
//! (a proof shows every segment blocked by these very blockers), so it is
//! not tried; the exact proof decides all the rest. A segment that comes
//! near a blocker counts as blocked: rounding can only let a proof run.

use super::vector::{cross, dot, norm, sub};

/// Unit normal and offset of a plane, and a polygon's corners.
struct Outline<'a> {
    normal: [f64; 3],
    offset: f64,
    corners: &'a [[f64; 3]],
}

/// Whether some segment from a point inside the polygon `region` (its
/// centre, and halfway from it to each corner) to a point of the light
/// (its corners, centre, edge midpoints, and halfway from its centre to
/// each corner) that shines on the region misses all of `blockers`
/// (convex polygons) by a margin. `receiver_normal`: the region's front,
/// for a one-sided receiver (light from behind it does not count).
pub(super) fn sees_light<'a>(
    region: &[[f64; 3]],
    light: &[[f64; 3]],
    receiver_normal: Option<[f64; 3]>,
    blockers: impl Iterator<Item = &'a [[f64; 3]]>,
) -> bool {
    let extent = region
        .iter()
        .chain(light)
        .flat_map(|p| p.iter().map(|c| c.abs()))
        .fold(1.0, f64::max);
    let margin = 1e-7 * extent;
    let outlines: Vec<Outline<'_>> = blockers.filter_map(outline).collect();
    let region_points = inner_points(region, false);
    let region_centre = centre(region);
    let light_points: Vec<[f64; 3]> = inner_points(light, true)
        .into_iter()
        .filter(|&l| {
            receiver_normal.is_none_or(|n| dot(n, sub(l, region_centre)) > margin * norm(n))
        })
        .collect();
    region_points.iter().any(|&k| {
        light_points
            .iter()
            .any(|&l| outlines.iter().all(|o| misses(o, k, l, margin)))
    })
}

/// The centre of the points, the points halfway from it to each, and (if
/// `rim`) the points themselves and their edges' midpoints.
fn inner_points(points: &[[f64; 3]], rim: bool) -> Vec<[f64; 3]> {
    let c = centre(points);
    let mut out = vec![c];
    out.extend(points.iter().map(|&p| mid(p, c)));
    if rim {
        out.extend_from_slice(points);
        out.extend((0..points.len()).map(|i| mid(points[i], points[(i + 1) % points.len()])));
    }
    out
}

fn outline(corners: &[[f64; 3]]) -> Option<Outline<'_>> {
    // Newell's normal: the polygons are planar up to rounding.
    let mut n = [0.0; 3];
    for (i, &p) in corners.iter().enumerate() {
        let q = corners[(i + 1) % corners.len()];
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    let length = norm(n);
    if corners.len() < 3 || length == 0.0 {
        return None;
    }
    let normal = n.map(|x| x / length);
    Some(Outline {
        normal,
        offset: -dot(normal, centre(corners)),
        corners,
    })
}

/// Whether the segment `k`-`l` passes the polygon by more than `margin`
/// (a polygon with no plane is never passed).
fn misses(o: &Outline<'_>, k: [f64; 3], l: [f64; 3], margin: f64) -> bool {
    let (dk, dl) = (dot(o.normal, k) + o.offset, dot(o.normal, l) + o.offset);
    if (dk > margin && dl > margin) || (dk < -margin && dl < -margin) {
        return true;
    }
    if (dk - dl).abs() <= margin {
        return false;
    }
    let t = dk / (dk - dl);
    let x: [f64; 3] = std::array::from_fn(|i| k[i] + t * (l[i] - k[i]));
    // Outside some edge by the margin: the normal is the corners' own,
    // so the inside is on the left of each edge about it.
    let n = o.corners.len();
    (0..n).any(|i| {
        let (a, b) = (o.corners[i], o.corners[(i + 1) % n]);
        let edge = sub(b, a);
        let length = norm(edge);
        length > 0.0 && dot(cross(edge, sub(x, a)), o.normal) < -margin * length
    })
}

fn centre(points: &[[f64; 3]]) -> [f64; 3] {
    let n = points.len().max(1) as f64;
    std::array::from_fn(|k| points.iter().map(|p| p[k]).sum::<f64>() / n)
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| 0.5 * (a[k] + b[k]))
}

#[cfg(test)]
mod tests {
    use super::sees_light;

    const FLOOR: [[f64; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
    ];
    const LIGHT: [[f64; 3]; 4] = [
        [0.0, 10.0, 0.0],
        [1.0, 10.0, 0.0],
        [1.0, 10.0, 1.0],
        [0.0, 10.0, 1.0],
    ];

    fn panel(x: [f64; 2], z: [f64; 2]) -> [[f64; 3]; 4] {
        [
            [x[0], 5.0, z[0]],
            [x[1], 5.0, z[0]],
            [x[1], 5.0, z[1]],
            [x[0], 5.0, z[1]],
        ]
    }

    #[test]
    fn light_through_a_gap_is_seen_and_a_cover_hides_it() {
        let up = Some([0.0, 1.0, 0.0]);
        let cover = panel([-1.0, 2.0], [-1.0, 2.0]);
        assert!(!sees_light(&FLOOR, &LIGHT, up, [&cover[..]].into_iter()));
        // Two halves with a slot between them at x in [0.45, 0.55].
        let (left, right) = (
            panel([-1.0, 0.45], [-1.0, 2.0]),
            panel([0.55, 2.0], [-1.0, 2.0]),
        );
        assert!(sees_light(
            &FLOOR,
            &LIGHT,
            up,
            [&left[..], &right[..]].into_iter()
        ));
        // Touching halves: the seam's segments come near both, so count
        // as blocked.
        let (left, right) = (
            panel([-1.0, 0.5], [-1.0, 2.0]),
            panel([0.5, 2.0], [-1.0, 2.0]),
        );
        assert!(!sees_light(
            &FLOOR,
            &LIGHT,
            up,
            [&left[..], &right[..]].into_iter()
        ));
        // No blocker: seen; a light behind a one-sided receiver: not.
        assert!(sees_light(&FLOOR, &LIGHT, up, std::iter::empty()));
        assert!(!sees_light(
            &FLOOR,
            &LIGHT,
            Some([0.0, -1.0, 0.0]),
            std::iter::empty()
        ));
    }
}
