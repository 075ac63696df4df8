//! Tests of joint-umbra proofs: cases worked out by hand, and random
//! panels against segments sampled between the region and the light.

use super::*;
use crate::convex_groups;
use crate::test_shapes::cuboid;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

fn g(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).unwrap()
}

/// The square light `x, z` in `[lo, hi]` at height `y`, facing down.
fn light(lo: i64, hi: i64, y: i64) -> AreaSource {
    AreaSource::from_grid_points(&[g(lo, y, lo), g(hi, y, lo), g(hi, y, hi), g(lo, y, hi)]).unwrap()
}

/// The rectangle `x` in `x`, `z` in `z` at height `y`, facing down.
fn panel(x: [i64; 2], y: i64, z: [i64; 2]) -> ConvexPolygon {
    let corners = [
        g(x[0], y, z[0]),
        g(x[1], y, z[0]),
        g(x[1], y, z[1]),
        g(x[0], y, z[1]),
    ];
    ConvexPolygon::from_grid_points(&corners, 0).unwrap()
}

/// The floor square of half-width `r` around `(x, 0, z)`, facing up.
fn floor(x: i64, z: i64, r: i64) -> ConvexPolygon {
    let corners = [
        g(x - r, 0, z - r),
        g(x - r, 0, z + r),
        g(x + r, 0, z + r),
        g(x + r, 0, z - r),
    ];
    let square = ConvexPolygon::from_grid_points(&corners, 0).unwrap();
    assert!(square.support().normal()[1] > 0);
    square
}

/// Two panels at different heights that overlap seen from below: one
/// hides the light's low `x`, the other its high `x`, from the floor
/// around `x = 2000`; through the slanted gap between them the floor
/// around `x = 1500` sees some of it.
#[test]
fn two_panels_hide_a_light_neither_hides_alone() {
    let source = light(0, 4000, 10_000);
    let high = panel([-20_000, 2500], 6000, [-20_000, 20_000]);
    let low = panel([2200, 20_000], 3000, [-20_000, 20_000]);
    let both = [&high, &low];
    let dark = floor(2000, 2000, 20);
    assert!(sees_none(&dark, false, &source, &both, &[]));
    assert!(!sees_none(&dark, false, &source, &[&high], &[]));
    assert!(!sees_none(&dark, false, &source, &[&low], &[]));
    assert!(!sees_none(
        &floor(1500, 2000, 20),
        false,
        &source,
        &both,
        &[]
    ));
}

/// The two panels' joint umbra under a light tilted across the panels'
/// edges (its plane 4y = x + 40000): halved in its plane's lattice, the
/// light is hidden from the floor near `x = 2000` by the high panel up to
/// about `x = 2890`, by the low one from about `x = 2710`.
#[test]
fn two_panels_hide_a_tilted_light_neither_hides_alone() {
    let source = tilted_light(1000);
    let high = panel([-20_000, 2500], 6000, [-20_000, 20_000]);
    let low = panel([2200, 20_000], 3000, [-20_000, 20_000]);
    let dark = floor(2000, 2000, 20);
    assert!(sees_none(&dark, false, &source, &[&high, &low], &[]));
    assert!(!sees_none(&dark, false, &source, &[&high], &[]));
    assert!(!sees_none(&dark, false, &source, &[&low], &[]));
}

/// The light over `x, z` in `[0, 4000]`, rising by `rise` from `x = 0`
/// (at height 10000) to `x = 4000`, facing down.
fn tilted_light(rise: i64) -> AreaSource {
    let y = 10_000;
    AreaSource::from_grid_points(&[
        g(0, y, 0),
        g(4000, y + rise, 0),
        g(4000, y + rise, 4000),
        g(0, y, 4000),
    ])
    .unwrap()
}

/// A slab and a panel: the light the panel leaves the floor near
/// `x = 3000` goes through the slab (in by its bottom or its side, out by
/// its top). The slab as one closed body proves it, as its faces do.
#[test]
fn a_closed_body_blocks_what_its_faces_do() {
    let source = light(0, 4000, 10_000);
    let slab = cuboid([-20_000, 5000, -20_000], [2500, 7000, 20_000]);
    let groups = convex_groups(&slab, &vec![Some(0); slab.len()]);
    let [group] = &groups[..] else {
        panic!("the slab is one group")
    };
    let Some(crate::Blocker::Body(body)) = group.blocker(&slab) else {
        panic!("the slab is a body")
    };
    assert!(body.is_closed());
    let low = panel([2700, 20_000], 3000, [-20_000, 20_000]);
    let region = floor(3000, 2000, 20);
    let mut faces: Vec<&ConvexPolygon> = slab.iter().collect();
    faces.push(&low);
    assert!(sees_none(&region, false, &source, &faces, &[]));
    assert!(sees_none(&region, false, &source, &[&low], &[&body]));
    // Without the panel, the light's high `x` reaches the region.
    assert!(!sees_none(&region, false, &source, &[], &[&body]));
    assert!(!sees_none(&region, false, &source, &[&low], &[]));
}

/// A quad bent along its diagonal (two triangles in a valley) hides a
/// small light from the floor under the diagonal: each ray crosses one
/// triangle or the other, changing over along the diagonal's shadow, so no
/// triangle alone hides a part of the light from a part of the floor
/// around it. As one body (closed by its other two triangles, which face
/// away from the floor) it does, and so do the triangles as a hinge along
/// the diagonal (the light seen along it within the valley's angle).
#[test]
fn a_bent_quad_hides_light_as_one_body() {
    let source = light(-200, 200, 10_000);
    let [a, b, c, d] = [
        g(-2000, 5000, -2000),
        g(2000, 5500, -2000),
        g(2000, 5000, 2000),
        g(-2000, 5500, 2000),
    ];
    let triangles = vec![
        ConvexPolygon::from_grid_points(&[a, b, c], 0).unwrap(),
        ConvexPolygon::from_grid_points(&[a, c, d], 0).unwrap(),
    ];
    let groups = convex_groups(&triangles, &[Some(0), Some(0)]);
    let [group] = &groups[..] else {
        panic!("the bent quad is one group")
    };
    let Some(crate::Blocker::Body(body)) = group.blocker(&triangles) else {
        panic!("the bent quad is a body")
    };
    assert!(!body.is_closed());
    let region = floor(0, 0, 20);
    let faces: Vec<&ConvexPolygon> = triangles.iter().collect();
    assert!(sees_none(&region, false, &source, &faces, &[]));
    assert!(sees_none(&region, false, &source, &[], &[&body]));
    // Each triangle alone hides only part of it.
    for face in &faces {
        assert!(!sees_none(&region, false, &source, &[*face], &[]));
    }
}

/// A wall in `x = 0` facing `+x` under a light across its plane: a
/// one-sided wall takes only the part of the light in front, and a panel
/// hides that part; two-sided, the part behind reaches it too.
#[test]
fn a_light_across_a_one_sided_receiver_counts_in_front_only() {
    let source = light(-2000, 2000, 10_000);
    let corners = [
        g(0, 100, 100),
        g(0, 100, 140),
        g(0, 140, 140),
        g(0, 140, 100),
    ];
    let mut wall = ConvexPolygon::from_grid_points(&corners, 0).unwrap();
    if wall.support().normal()[0] < 0 {
        wall = wall.flipped();
    }
    let roof = panel([0, 20_000], 5000, [-20_000, 20_000]);
    assert!(sees_none(&wall, false, &source, &[&roof], &[]));
    assert!(!sees_none(&wall, true, &source, &[&roof], &[]));
}

/// Whether the segment from `k` to `l` crosses the horizontal rectangle
/// `(x, y, z)`, `None` when it passes within `margin` of its border (too
/// close to tell in floating point).
fn crosses(
    k: [f64; 3],
    l: [f64; 3],
    (x, y, z): ([f64; 2], f64, [f64; 2]),
    margin: f64,
) -> Option<bool> {
    if (k[1] - y) * (l[1] - y) > 0.0 || k[1] == l[1] {
        return Some(false);
    }
    let t = (y - k[1]) / (l[1] - k[1]);
    let at = [k[0] + t * (l[0] - k[0]), k[2] + t * (l[2] - k[2])];
    let inside = |v: f64, [lo, hi]: [f64; 2]| (v - lo).min(hi - v);
    let depth = inside(at[0], x).min(inside(at[1], z));
    if depth.abs() <= margin {
        None
    } else {
        Some(depth > 0.0)
    }
}

/// Whether `occluders` are proven to hide all of `source` from `region`
/// (one-sided, facing up), and if so, whether no one of them alone is (a
/// joint umbra).
fn proven_dark(
    region: &ConvexPolygon,
    source: &AreaSource,
    occluders: &[&ConvexPolygon],
) -> Option<bool> {
    if !sees_none(region, false, source, occluders, &[]) {
        return None;
    }
    Some(
        occluders
            .iter()
            .all(|o| !sees_none(region, false, source, &[*o], &[])),
    )
}

/// Random panels over random floor squares (seeded), under a level light
/// and a tilted one: whatever is proven dark is dark, every sampled
/// segment from the region to the light crossing a panel (or passing too
/// close to a border to tell); and the proofs do find joint umbrae
/// (regions no one panel hides).
#[test]
fn proven_dark_regions_see_no_light() {
    for rise in [0, 1300] {
        proven_dark_regions_see_no_light_under(rise);
    }
}

/// [`proven_dark_regions_see_no_light`] under the light over `x, z` in
/// `[-500, 500]` rising by `rise` from height 10000 at `x = -500`.
fn proven_dark_regions_see_no_light_under(rise: i64) {
    let mut rng = Pcg64::seed_from_u64(8);
    let y = 10_000;
    let source = AreaSource::from_grid_points(&[
        g(-500, y, -500),
        g(500, y + rise, -500),
        g(500, y + rise, 500),
        g(-500, y, 500),
    ])
    .unwrap();
    let (mut proven, mut joint) = (0, 0);
    for _ in 0..1000 {
        let panels: Vec<([i64; 2], i64, [i64; 2])> = (0..rng.random_range(3..8))
            .map(|_| {
                let (x, z) = (rng.random_range(-2500..1500), rng.random_range(-2500..1500));
                let (w, d) = (rng.random_range(300..2500), rng.random_range(300..2500));
                ([x, x + w], rng.random_range(2000..8000), [z, z + d])
            })
            .collect();
        let polygons: Vec<ConvexPolygon> = panels.iter().map(|&(x, y, z)| panel(x, y, z)).collect();
        let refs: Vec<&ConvexPolygon> = polygons.iter().collect();
        let (cx, cz, r) = (
            rng.random_range(-1000..1000),
            rng.random_range(-1000..1000),
            rng.random_range(5..100),
        );
        let region = floor(cx, cz, r);
        let Some(jointly) = proven_dark(&region, &source, &refs) else {
            continue;
        };
        proven += 1;
        joint += usize::from(jointly);
        let rects: Vec<([f64; 2], f64, [f64; 2])> = panels
            .iter()
            .map(|&(x, y, z)| (x.map(|v| v as f64), y as f64, z.map(|v| v as f64)))
            .collect();
        for _ in 0..256 {
            let (k, l) = segment_to_light(&mut rng, (cx, cz, r), rise);
            assert!(
                rects
                    .iter()
                    .any(|&rect| crosses(k, l, rect, 1e-6) != Some(false)),
                "segment {k:?} -> {l:?} passes every panel of {panels:?}"
            );
        }
    }
    assert!(
        proven >= 50 && joint >= 8,
        "rise {rise}: proven {proven}, joint {joint}"
    );
}

/// A random segment from the floor square of half-width `r` around
/// `(cx, 0, cz)` to the light `x, z` in `[-500, 500]` at height 10 000,
/// rising by `rise` along `x`.
fn segment_to_light(
    rng: &mut Pcg64,
    (cx, cz, r): (i64, i64, i64),
    rise: i64,
) -> ([f64; 3], [f64; 3]) {
    let k = [
        (cx - r) as f64 + rng.random::<f64>() * 2.0 * r as f64,
        0.0,
        (cz - r) as f64 + rng.random::<f64>() * 2.0 * r as f64,
    ];
    let s = rng.random::<f64>();
    let l = [
        -500.0 + s * 1000.0,
        10_000.0 + s * rise as f64,
        -500.0 + rng.random::<f64>() * 1000.0,
    ];
    (k, l)
}

/// Two narrow panels overlapping in plan (neither has an umbra): from the
/// floor strip x in [0, 250] the high one hides the light's low x, the low
/// one its high x, with the seam between them moving across the strip as
/// x does. No one cut of the light suits the whole strip; halving the
/// light and the strip in turn proves it (halving only the light, as long
/// as a blocker told where, did not).
#[test]
fn a_seam_moving_across_the_region_needs_both_halved() {
    let source = light(-500, 500, 4000);
    let low = panel([-450, 50], 2000, [-1500, 1500]);
    let high = panel([-50, 450], 2300, [-1500, 1500]);
    for (x0, x1) in [(-250, 0), (0, 250), (0, 125), (125, 250)] {
        let c = [g(x0, 0, -125), g(x0, 0, 125), g(x1, 0, 125), g(x1, 0, -125)];
        let region = ConvexPolygon::from_grid_points(&c, 0).unwrap();
        assert!(
            sees_none(&region, false, &source, &[&low, &high], &[]),
            "{x0}..{x1}"
        );
        assert!(!sees_none(&region, false, &source, &[&low], &[]));
        assert!(!sees_none(&region, false, &source, &[&high], &[]));
    }
}

/// Two boxes standing on the floor that run into each other (turned, as
/// `rotate_deg` leaves them), under a light that neither hides alone from
/// the floor in the notch between them. The region's corner `(-423091,
/// -1460769)` sits next to where one box's hidden part of the light starts
/// as the other's ends: halving at midpoints had to shrink the light below
/// that thin overlap and gave up; cut along the first box's frontier, one
/// cut leaves the rest to the second. Sampled segments agree it is dark.
#[test]
fn boxes_running_into_each_other_hide_the_light_from_their_notch() {
    let quad = |c: [[i64; 3]; 4]| {
        ConvexPolygon::from_grid_points(&c.map(|[x, y, z]| g(x, y, z)), 0).unwrap()
    };
    // A box on the floor: its corners at the floor in counter-clockwise
    // order seen from above, and its height.
    let upright = |base: [[i64; 2]; 4], h: i64| -> Vec<ConvexPolygon> {
        let at = |[x, z]: [i64; 2], y: i64| [x, y, z];
        let mut faces = vec![
            quad(base.map(|c| at(c, h))),
            quad([base[3], base[2], base[1], base[0]].map(|c| at(c, 0))),
        ];
        for i in 0..4 {
            let (a, b) = (base[i], base[(i + 1) % 4]);
            faces.push(quad([at(a, 0), at(b, 0), at(b, h), at(a, h)]));
        }
        faces
    };
    let first = upright(
        [
            [-99184, -1173868],
            [404620, -833032],
            [733580, -1319284],
            [229772, -1660120],
        ],
        3_286_000,
    );
    let second = upright(
        [
            [-339812, -728368],
            [645196, -273212],
            [836552, -687336],
            [-148456, -1142488],
        ],
        2_134_000,
    );
    let body = |faces: &[ConvexPolygon]| {
        let groups = convex_groups(faces, &vec![Some(0); faces.len()]);
        let [group] = &groups[..] else {
            panic!("a box is one group")
        };
        let Some(crate::Blocker::Body(body)) = group.blocker(faces) else {
            panic!("a box is a body")
        };
        body
    };
    let (a, b) = (body(&first), body(&second));
    let y = 15_800_000;
    let source = AreaSource::from_grid_points(&[
        g(4_000_000, y, 2_000_000),
        g(8_000_000, y, 2_000_000),
        g(8_000_000, y, 6_000_000),
        g(4_000_000, y, 6_000_000),
    ])
    .unwrap();
    let corners = [
        g(-282_049, 0, -1_395_596),
        g(-423_091, 0, -1_460_769),
        g(-282_049, 0, -1_335_841),
    ];
    let region = ConvexPolygon::from_grid_points(&corners, 0).unwrap();
    assert!(region.support().normal()[1] > 0, "the floor faces up");
    assert!(sees_none(&region, false, &source, &[], &[&a, &b]));
    assert!(!sees_none(&region, false, &source, &[], &[&a]));
    assert!(!sees_none(&region, false, &source, &[], &[&b]));

    // Sampled segments from the region to the light all enter a box.
    let planes = |faces: &[ConvexPolygon]| -> Vec<([f64; 3], f64)> {
        faces
            .iter()
            .map(|f| {
                let [a, b, c, d] = f.support().approx();
                let length = (a * a + b * b + c * c).sqrt();
                ([a / length, b / length, c / length], d / length)
            })
            .collect()
    };
    let boxes = [planes(&first), planes(&second)];
    // How deep the segment k-l runs inside a box (parameter length).
    let inside = |faces: &[([f64; 3], f64)], k: [f64; 3], l: [f64; 3]| {
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        for (n, d) in faces {
            let (at_k, at_l) = (vector::dot(*n, k) + d, vector::dot(*n, l) + d);
            if at_k == at_l {
                if at_k > 0.0 {
                    return 0.0;
                }
                continue;
            }
            let t = at_k / (at_k - at_l);
            if at_k > at_l {
                lo = lo.max(t);
            } else {
                hi = hi.min(t);
            }
        }
        hi - lo
    };
    let mut rng = Pcg64::seed_from_u64(3);
    let points = region.vertices_f64();
    for _ in 0..4000 {
        let (s, t) = (rng.random::<f64>(), rng.random::<f64>());
        let (s, t) = if s + t > 1.0 {
            (1.0 - s, 1.0 - t)
        } else {
            (s, t)
        };
        let k: [f64; 3] = std::array::from_fn(|i| {
            points[0][i] + s * (points[1][i] - points[0][i]) + t * (points[2][i] - points[0][i])
        });
        let l = [
            4e6 + rng.random::<f64>() * 4e6,
            y as f64,
            2e6 + rng.random::<f64>() * 4e6,
        ];
        assert!(
            boxes.iter().any(|faces| inside(faces, k, l) > 1e-9),
            "segment {k:?} -> {l:?} passes both boxes"
        );
    }
}

/// A tent of three triangles around an apex (an open sheet of one object)
/// hides a light from the floor under the seam between two of them: each
/// triangle hides part of the light, the parts joining along the seam's
/// image with no overlap, so no proof taking them one by one gets across;
/// as a sheet (the hull of the three, its base and back open) it does, and
/// so do the triangles as hinges along their seams. Sampled segments
/// agree.
#[test]
fn a_tent_of_triangles_hides_the_light_as_one_sheet() {
    let apex = g(0, 1400, 0);
    let base = [
        g(700, 800, 0),
        g(350, 800, -606),
        g(-350, 800, -606),
        g(-700, 800, 0),
    ];
    let tent: Vec<ConvexPolygon> = (0..3)
        .map(|i| ConvexPolygon::from_grid_points(&[base[i], base[i + 1], apex], 0).unwrap())
        .collect();
    let sheets = sheet_bodies(&tent, &[Some(0); 3]);
    let [(members, sheet)] = &sheets[..] else {
        panic!("the tent is one sheet: {} found", sheets.len())
    };
    assert_eq!(members, &[0, 1, 2]);
    assert!(!sheet.is_closed());
    // Another object's triangle joins no sheet.
    assert!(sheet_bodies(&tent, &[Some(0), Some(1), None]).is_empty());
    // A sheet folded up, down and up again is no face of its hull in the
    // valley: no body.
    let p = |i: i64, z: i64| g(1000 * i, 500 * (i % 2), z);
    let zigzag: Vec<ConvexPolygon> = (0..3)
        .flat_map(|i| {
            [
                [p(i, 0), p(i + 1, 0), p(i, 1000)],
                [p(i, 1000), p(i + 1, 0), p(i + 1, 1000)],
            ]
        })
        .map(|t| ConvexPolygon::from_grid_points(&t, 0).unwrap())
        .collect();
    assert!(sheet_bodies(&zigzag, &[Some(0); 6]).is_empty());
    assert_eq!(
        sheet_bodies(&zigzag[..4], &[Some(0); 4]).len(),
        1,
        "up and down is a roof"
    );

    let y = 3000;
    let source = AreaSource::from_grid_points(&[
        g(-100, y, -500),
        g(100, y, -500),
        g(100, y, -300),
        g(-100, y, -300),
    ])
    .unwrap();
    let region = floor(276, -247, 20);
    let triangles: Vec<&ConvexPolygon> = tent.iter().collect();
    assert!(sees_none(&region, false, &source, &[], &[sheet]));
    assert!(sees_none(&region, false, &source, &triangles, &[]));
    for triangle in &triangles {
        assert!(!sees_none(&region, false, &source, &[*triangle], &[]));
    }

    let mut rng = Pcg64::seed_from_u64(5);
    let light = ([-100.0, 100.0], [-500.0, -300.0], y as f64);
    assert_segments_to_meet(&mut rng, (276, 0, -247, 20), light, 4000, &tent);
}

/// Whether the segment `k`-`l` meets the triangle (Möller-Trumbore, with
/// its border counted in).
fn segment_meets_triangle(k: [f64; 3], l: [f64; 3], [a, b, c]: [[f64; 3]; 3]) -> bool {
    let sub = vector::sub;
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let (d, e1, e2) = (sub(l, k), sub(b, a), sub(c, a));
    let p = cross(d, e2);
    let det = vector::dot(e1, p);
    if det == 0.0 {
        return false;
    }
    let s = sub(k, a);
    let u = vector::dot(s, p) / det;
    let q = cross(s, e1);
    let v = vector::dot(d, q) / det;
    let t = vector::dot(e2, q) / det;
    (-1e-9..=1.0 + 1e-9).contains(&u)
        && v >= -1e-9
        && u + v <= 1.0 + 1e-9
        && (0.0..=1.0).contains(&t)
}

/// Checks that 256 random segments from the floor square of half-width
/// `r` around `(cx, 0, cz)` to the light `x, z` in `[-500, 500]` at
/// height 10 000 meet one of `triangles`.
fn assert_segments_meet(
    rng: &mut Pcg64,
    (cx, cz, r): (i64, i64, i64),
    triangles: &[ConvexPolygon],
) {
    assert_square_segments_meet(rng, (cx, 0, cz, r), triangles);
}

/// Checks that 256 random segments from the level square of half-width
/// `r` around `(x, y, z)` to the light `x, z` in `[-500, 500]` at height
/// 10 000 meet one of `triangles`.
fn assert_square_segments_meet(
    rng: &mut Pcg64,
    square: (i64, i64, i64, i64),
    triangles: &[ConvexPolygon],
) {
    let light = ([-500.0, 500.0], [-500.0, 500.0], 10_000.0);
    assert_segments_to_meet(rng, square, light, 256, triangles);
}

/// Checks that `count` random segments from the level square of
/// half-width `r` around `(x, y, z)` to the level rectangle `light` (its
/// `x` and `z` ranges, its height) meet one of `polygons` (each fanned
/// into triangles).
fn assert_segments_to_meet(
    rng: &mut Pcg64,
    (x, y, z, r): (i64, i64, i64, i64),
    (lx, lz, ly): ([f64; 2], [f64; 2], f64),
    count: usize,
    polygons: &[ConvexPolygon],
) {
    for _ in 0..count {
        let k = [
            (x - r) as f64 + rng.random::<f64>() * 2.0 * r as f64,
            y as f64,
            (z - r) as f64 + rng.random::<f64>() * 2.0 * r as f64,
        ];
        let l = [
            lx[0] + (lx[1] - lx[0]) * rng.random::<f64>(),
            ly,
            lz[0] + (lz[1] - lz[0]) * rng.random::<f64>(),
        ];
        let through = polygons.iter().any(|p| {
            let c = p.vertices_f64();
            (1..c.len() - 1).any(|i| segment_meets_triangle(k, l, [c[0], c[i], c[i + 1]]))
        });
        assert!(through, "segment {k:?} -> {l:?} passes {polygons:?}");
    }
}

/// Random sheets (the faces of a random convex hull that face one random
/// way, as triangles of one object) over random floor squares (seeded):
/// whatever is proven dark past a sheet's body is dark, every sampled
/// segment from the region to the light meeting one of its triangles; and
/// the sheets do prove regions dark.
#[test]
fn proven_dark_regions_under_random_sheets_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(11);
    let source = light(-500, 500, 10_000);
    let unit = |rng: &mut Pcg64| loop {
        let v: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let length = vector::norm(v);
        if (0.1..=1.0).contains(&length) {
            break v.map(|c| c / length);
        }
    };
    let (mut sheets_seen, mut proven) = (0, 0);
    for _ in 0..400 {
        let centre = [
            rng.random_range(-1500.0..1500.0),
            rng.random_range(3000.0..7000.0),
            rng.random_range(-1500.0..1500.0),
        ];
        let radii: [f64; 3] = std::array::from_fn(|_| rng.random_range(300.0..2000.0));
        let points: Vec<GridPoint> = (0..rng.random_range(5..12))
            .map(|_| {
                let u = unit(&mut rng);
                let c: [i64; 3] =
                    std::array::from_fn(|k| (centre[k] + radii[k] * u[k]).round() as i64);
                g(c[0], c[1], c[2])
            })
            .collect();
        let Some(hull) = crate::groups::hull::convex_hull(&points) else {
            continue;
        };
        // Half the sheets face up, towards the light (the rest any way).
        let mut towards = unit(&mut rng);
        if rng.random::<bool>() {
            towards[1] = towards[1].abs();
        }
        let triangles: Vec<ConvexPolygon> = hull
            .iter()
            .filter(|(_, plane)| vector::dot(plane.unit_normal_f64(), towards) > 0.0)
            .filter_map(|(t, _)| ConvexPolygon::from_grid_points(t, 0).ok())
            .collect();
        let owners = vec![Some(0); triangles.len()];
        for (_, body) in sheet_bodies(&triangles, &owners) {
            sheets_seen += 1;
            // Around the sheet's shadow: its centre seen from the light's.
            let t = 10_000.0 / (10_000.0 - centre[1]);
            let shadow = [centre[0] * t, centre[2] * t];
            for _ in 0..8 {
                let (cx, cz, r) = (
                    (shadow[0] + rng.random_range(-1.2..1.2) * radii[0] * t).round() as i64,
                    (shadow[1] + rng.random_range(-1.2..1.2) * radii[2] * t).round() as i64,
                    rng.random_range(5..100),
                );
                let region = floor(cx, cz, r);
                if !sees_none(&region, false, &source, &[], &[&body]) {
                    continue;
                }
                proven += 1;
                assert_segments_meet(&mut rng, (cx, cz, r), &triangles);
            }
        }
    }
    assert!(
        sheets_seen >= 300 && proven >= 40,
        "{sheets_seen} sheets, {proven} regions proven"
    );
}

mod fan;
mod hinge;
mod shell;

/// A box whose bottom is cut in two strips: their corners fall mid-edge
/// on the faces beside them (T-junctions), so no edge-matched closed
/// surface (and no convex group) is there, but the pieces tile the faces
/// of their hull: one closed body. From the floor under the box, each
/// ray to a light wider than the box crosses one strip or the other,
/// changing over along the seam's shadow, which no proof taking the
/// pieces one by one gets across; as a body they hide all of it, and so
/// do the pieces with the strips as a (flat) hinge along their seam.
#[test]
fn a_box_with_a_face_cut_in_strips_blocks_as_one_body() {
    let mut faces = cuboid([-1000, 4000, -1000], [1000, 6000, 1000]);
    let g32 = |x, y, z| GridPoint { x, y, z };
    let strip = |x0: i32, x1: i32| {
        let corners = [
            g32(x0, 4000, -1000),
            g32(x1, 4000, -1000),
            g32(x1, 4000, 1000),
            g32(x0, 4000, 1000),
        ];
        ConvexPolygon::from_grid_points(&corners, 0).unwrap()
    };
    faces.splice(2..3, [strip(-1000, 137), strip(137, 1000)]);
    let owners = vec![Some(0); faces.len()];
    assert!(
        convex_groups(&faces, &owners).is_empty(),
        "no convex group across the T-junctions"
    );
    let bodies = sheet_bodies(&faces, &owners);
    let [(members, body)] = &bodies[..] else {
        panic!("one body: {} found", bodies.len())
    };
    assert_eq!(members.len(), 7);
    assert!(body.is_closed());
    let source = light(-2000, 2000, 10_000);
    let pieces: Vec<&ConvexPolygon> = faces.iter().collect();
    let under = floor(0, 0, 100);
    assert!(sees_none(&under, false, &source, &[], &[body]));
    assert!(sees_none(&under, false, &source, &pieces, &[]));
    // Beyond the umbra (|x| <= 333 under the bottom), the light's far
    // side passes the box.
    assert!(!sees_none(
        &floor(600, 0, 100),
        false,
        &source,
        &[],
        &[body]
    ));
    // A strip short of the face leaves a slit: no body.
    faces[3] = strip(140, 1000);
    assert!(sheet_bodies(&faces, &owners).is_empty());
}
