//! Shells: surfaces closed but for a hole (cups), whole or dented by the
//! grid, blocking as the body inside them ([`Body::shell`]).

use super::*;

/// The triangles of a random convex hull of points around `centre` (radii
/// `radii`), less one triangle or two that share an edge (the hole: flat,
/// or four corners bent), and with one vertex pushed in towards the centre
/// by `dent` of its distance when `dent > 0` (a surface the grid left
/// concave).
fn random_cup(rng: &mut Pcg64, centre: [f64; 3], radii: [f64; 3], dent: f64) -> Vec<ConvexPolygon> {
    let mut triangles = random_hull(rng, 6..14, centre, radii);
    if triangles.is_empty() {
        return Vec::new();
    }
    let hole = rng.random_range(0..triangles.len());
    let [a, b, c] = triangles.swap_remove(hole);
    if rng.random::<bool>() {
        // And the triangle across one of its edges.
        let edges = [(b, a), (c, b), (a, c)];
        if let Some(k) = triangles
            .iter()
            .position(|t| (0..3).any(|i| edges.contains(&(t[i], t[(i + 1) % 3]))))
        {
            triangles.swap_remove(k);
        }
    }
    if dent > 0.0 {
        let rim: Vec<GridPoint> = [a, b, c].to_vec();
        let corners: Vec<GridPoint> = triangles.iter().flatten().copied().collect();
        if let Some(&p) = corners.iter().find(|p| !rim.contains(p)) {
            let at = p.to_f64();
            let moved: [i64; 3] =
                std::array::from_fn(|k| (at[k] + dent * (centre[k] - at[k])).round() as i64);
            let q = g(moved[0], moved[1], moved[2]);
            for t in &mut triangles {
                for v in t.iter_mut() {
                    if *v == p {
                        *v = q;
                    }
                }
            }
        }
    }
    triangles
        .iter()
        .filter_map(|t| ConvexPolygon::from_grid_points(t, 0).ok())
        .collect()
}

/// The triangles of the convex hull of a random number (in `count`) of
/// grid points around `centre` on the ellipsoid with radii `radii`; none
/// when they span no volume.
fn random_hull(
    rng: &mut Pcg64,
    count: std::ops::Range<usize>,
    centre: [f64; 3],
    radii: [f64; 3],
) -> Vec<[GridPoint; 3]> {
    let points: Vec<GridPoint> = (0..rng.random_range(count))
        .map(|_| {
            let u = unit(rng);
            let c: [i64; 3] = std::array::from_fn(|k| (centre[k] + radii[k] * u[k]).round() as i64);
            g(c[0], c[1], c[2])
        })
        .collect();
    crate::groups::hull::convex_hull(&points)
        .map(|hull| hull.into_iter().map(|(t, _)| t).collect())
        .unwrap_or_default()
}

/// A random centre between the floor and the light, and radii around it.
fn random_place(rng: &mut Pcg64) -> ([f64; 3], [f64; 3]) {
    let centre = [
        rng.random_range(-1500.0..1500.0),
        rng.random_range(3000.0..7000.0),
        rng.random_range(-1500.0..1500.0),
    ];
    let radii: [f64; 3] = std::array::from_fn(|_| rng.random_range(300.0..2000.0));
    (centre, radii)
}

/// A random floor square (centre `x`, `z`, half-width) about the shadow
/// that the light high above casts of a body at `centre` with half-extents
/// `radii`, reaching out a fifth past it.
fn square_below(rng: &mut Pcg64, centre: [f64; 3], radii: [f64; 3]) -> (i64, i64, i64) {
    let t = 10_000.0 / (10_000.0 - centre[1]);
    (
        (centre[0] * t + rng.random_range(-1.2..1.2) * radii[0] * t).round() as i64,
        (centre[2] * t + rng.random_range(-1.2..1.2) * radii[2] * t).round() as i64,
        rng.random_range(5..100),
    )
}

/// A random level square (centre, half-width) well inside a body at
/// `centre` with half-extents `radii`.
fn square_inside(rng: &mut Pcg64, centre: [f64; 3], radii: [f64; 3]) -> ([i64; 3], i64) {
    let at: [i64; 3] = std::array::from_fn(|k| {
        (centre[k] + rng.random_range(-0.4..0.4) * radii[k]).round() as i64
    });
    (at, rng.random_range(5..50))
}

/// Round `round`'s random cup at a random place, dented every other
/// round: its place, dent and pieces, and the shell its groups close, if
/// any.
fn cup_of_round(rng: &mut Pcg64, round: usize) -> (CupPlace, Vec<ConvexPolygon>, Option<Body>) {
    let (centre, radii) = random_place(rng);
    let dent = if round.is_multiple_of(2) { 0.02 } else { 0.0 };
    let cup = random_cup(rng, centre, radii, dent);
    let shell = convex_groups(&cup, &vec![Some(0); cup.len()])
        .iter()
        .find_map(|group| group.shell());
    ((centre, radii, dent), cup, shell)
}

/// A random cup's centre, half-extents and dent.
type CupPlace = ([f64; 3], [f64; 3], f64);

fn unit(rng: &mut Pcg64) -> [f64; 3] {
    loop {
        let v: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let length = vector::norm(v);
        if (0.1..=1.0).contains(&length) {
            break v.map(|c| c / length);
        }
    }
}

/// Random cups, whole and dented, over random floor squares (seeded):
/// whatever is proven dark past a cup's shell alone is dark, every sampled
/// segment from the region to the light meeting one of the cup's
/// triangles; and the shells, dented ones included, do prove regions
/// dark.
#[test]
fn proven_dark_regions_under_random_cups_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(17);
    let source = light(-500, 500, 10_000);
    let (mut shells, mut proven, mut proven_dented) = (0, 0, 0);
    for round in 0..300 {
        let ((centre, radii, dent), cup, shell) = cup_of_round(&mut rng, round);
        let Some(shell) = shell else {
            continue;
        };
        assert!(!shell.is_closed(), "a shell's boundary is no occluder");
        shells += 1;
        for _ in 0..8 {
            let (cx, cz, r) = square_below(&mut rng, centre, radii);
            let region = floor(cx, cz, r);
            if !sees_none(&region, false, &source, &[], &[&shell]) {
                continue;
            }
            proven += 1;
            if dent > 0.0 {
                proven_dented += 1;
            }
            assert_segments_meet(&mut rng, (cx, cz, r), &cup);
        }
    }
    assert!(
        shells >= 150 && proven >= 100 && proven_dented >= 30,
        "{shells} shells, {proven} regions proven ({proven_dented} under dented cups)"
    );
}

/// A pyramid cup whose square hole is bent (two corners 200 higher than
/// the other two), closed by the two triangles over its higher diagonal:
/// a segment passing just under that ridge enters by one cap and leaves
/// by the other, meeting no side of the cup. The shell must not claim
/// it (its ends are on opposite sides of the caps' planes), but does
/// claim a light above the cup hidden from the floor under its apex.
#[test]
fn a_shell_lets_through_what_passes_in_and_out_by_its_caps() {
    let [a, b, c, d, apex] = [
        g(-1000, 0, -1000),
        g(1000, 200, -1000),
        g(1000, 0, 1000),
        g(-1000, 200, 1000),
        g(0, -2000, 0),
    ];
    let cup: Vec<ConvexPolygon> = [[a, b, apex], [b, c, apex], [c, d, apex], [d, a, apex]]
        .iter()
        .map(|t| ConvexPolygon::from_grid_points(t, 0).unwrap())
        .collect();
    let groups = convex_groups(&cup, &[Some(0); 4]);
    let shell = groups
        .iter()
        .find_map(|group| group.shell())
        .expect("the cup closes over its hole");
    // The segment through (0, 150, 0) along (1, 0, 1) meets no side.
    let (k, l) = ([-2000.0, 150.0, -2000.0], [2000.0, 150.0, 2000.0]);
    assert!(!cup.iter().any(|t| {
        let p = t.vertices_f64();
        segment_meets_triangle(k, l, [p[0], p[1], p[2]])
    }));
    let region = {
        let corners = [
            g(-2010, 150, -2010),
            g(-2010, 150, -1990),
            g(-1990, 150, -1990),
            g(-1990, 150, -2010),
        ];
        ConvexPolygon::from_grid_points(&corners, 0).unwrap()
    };
    let across = AreaSource::from_grid_points(&[
        g(2010, 140, 1990),
        g(2010, 160, 1990),
        g(1990, 160, 2010),
        g(1990, 140, 2010),
    ])
    .unwrap();
    assert!(!sees_none(&region, true, &across, &[], &[&shell]));
    // From above, the cup hides a small light from the floor under it.
    let above = light(-100, 100, 10_000);
    let under = {
        let corners = [
            g(-20, -3000, -20),
            g(-20, -3000, 20),
            g(20, -3000, 20),
            g(20, -3000, -20),
        ];
        ConvexPolygon::from_grid_points(&corners, 0).unwrap()
    };
    assert!(sees_none(&under, false, &above, &[], &[&shell]));
}

/// The square of half-width `r` around `(x, y, z)`, facing up.
fn level_square(x: i64, y: i64, z: i64, r: i64) -> ConvexPolygon {
    let corners = [
        g(x - r, y, z - r),
        g(x - r, y, z + r),
        g(x + r, y, z + r),
        g(x + r, y, z - r),
    ];
    ConvexPolygon::from_grid_points(&corners, 0).unwrap()
}

/// Random cups, whole and dented, with random level squares inside them
/// (seeded): whatever is proven dark past a cup's shell alone is dark,
/// every sampled segment from the square to the light meeting one of the
/// cup's triangles; and squares in cups whose hole looks away from the
/// light are proven dark.
#[test]
fn proven_dark_regions_inside_random_cups_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(23);
    let source = light(-500, 500, 10_000);
    let (mut tried, mut proven) = (0, 0);
    for round in 0..300 {
        let ((centre, radii, _), cup, shell) = cup_of_round(&mut rng, round);
        let Some(shell) = shell else {
            continue;
        };
        for _ in 0..8 {
            let (at, r) = square_inside(&mut rng, centre, radii);
            tried += 1;
            let region = level_square(at[0], at[1], at[2], r);
            if !sees_none(&region, false, &source, &[], &[&shell]) {
                continue;
            }
            proven += 1;
            assert_square_segments_meet(&mut rng, (at[0], at[1], at[2], r), &cup);
        }
    }
    assert!(
        tried >= 2000 && proven >= 300,
        "{tried} regions tried, {proven} proven"
    );
}

/// A box open at the top, one wall cut along its diagonal, under a light
/// low on that wall's side: the far wall's inside, low down, sees none of
/// it (every segment crosses the cut wall, one triangle or the other);
/// high up, it sees the light over the cut wall. The shell alone shows
/// both from inside (no segment to the light meets the cap low down);
/// sampled segments check the first.
#[test]
fn a_shell_hides_the_light_from_its_inside() {
    let mut cup = cuboid([-1000, 4000, -1000], [1000, 6000, 1000]);
    cup.remove(3);
    // The wall in x = -1000 (now at 3), as two triangles.
    let wall: Vec<GridPoint> = (0..4)
        .map(|i| cup[3].vertex_grid_point(i).unwrap())
        .collect();
    let halves = [[wall[0], wall[1], wall[2]], [wall[0], wall[2], wall[3]]]
        .map(|t| ConvexPolygon::from_grid_points(&t, 0).unwrap());
    cup.splice(3..4, halves);
    let shell = convex_groups(&cup, &vec![Some(0); cup.len()])
        .iter()
        .find_map(|group| group.shell())
        .expect("the cup closes over its hole");
    let source = AreaSource::from_grid_points(&[
        g(-20_000, 7000, -1000),
        g(-20_000, 7000, 1000),
        g(-18_000, 7400, 1000),
        g(-18_000, 7400, -1000),
    ])
    .unwrap();
    // On the far wall, facing in (-x).
    let on_wall = |y: i64| {
        let corners = [
            g(1000, y, 100),
            g(1000, y + 200, 100),
            g(1000, y + 200, -100),
            g(1000, y, -100),
        ];
        ConvexPolygon::from_grid_points(&corners, 0).unwrap()
    };
    assert!(sees_none(&on_wall(4100), false, &source, &[], &[&shell]));
    assert!(!sees_none(&on_wall(5790), false, &source, &[], &[&shell]));
    let triangles: Vec<[[f64; 3]; 3]> = cup
        .iter()
        .flat_map(|p| {
            let c = p.vertices_f64();
            (1..c.len() - 1).map(move |i| [c[0], c[i], c[i + 1]])
        })
        .collect();
    let mut rng = Pcg64::seed_from_u64(29);
    for _ in 0..4000 {
        let k = [
            1000.0,
            4100.0 + 200.0 * rng.random::<f64>(),
            -100.0 + 200.0 * rng.random::<f64>(),
        ];
        let (u, v) = (rng.random::<f64>(), rng.random::<f64>());
        let l = [
            -20_000.0 + 2000.0 * u,
            5000.0 + 400.0 * u,
            -1000.0 + 2000.0 * v,
        ];
        assert!(
            triangles.iter().any(|&t| segment_meets_triangle(k, l, t)),
            "segment {k:?} -> {l:?} passes the cup"
        );
    }
}

/// The triangles of a random convex hull of points around `centre`
/// (radii `radii`), less two that share no corner: a surface with two
/// holes (a tube, roughly). Empty when no two such triangles are found.
fn random_tube(rng: &mut Pcg64, centre: [f64; 3], radii: [f64; 3]) -> Vec<ConvexPolygon> {
    let mut triangles = random_hull(rng, 8..16, centre, radii);
    if triangles.is_empty() {
        return Vec::new();
    }
    let first = triangles.swap_remove(rng.random_range(0..triangles.len()));
    let Some(second) = triangles
        .iter()
        .position(|t| t.iter().all(|p| !first.contains(p)))
    else {
        return Vec::new();
    };
    triangles.swap_remove(second);
    triangles
        .iter()
        .filter_map(|t| ConvexPolygon::from_grid_points(t, 0).ok())
        .collect()
}

/// Random surfaces with two holes over random floor squares and with
/// random level squares inside them (seeded): whatever is proven dark
/// past their shells alone is dark, every sampled segment from the
/// region to the light meeting one of their triangles; and the shells
/// prove regions dark, outside and inside.
#[test]
fn proven_dark_regions_by_random_tubes_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(31);
    let source = light(-500, 500, 10_000);
    let (mut shells, mut below, mut inside) = (0, 0, 0);
    for _ in 0..300 {
        let (centre, radii) = random_place(&mut rng);
        let tube = random_tube(&mut rng, centre, radii);
        let inputs: Vec<u32> = (0..tube.len() as u32).collect();
        let found = crate::holed_shells(&tube, &vec![Some(0); tube.len()], &inputs);
        let [(members, shell)] = &found[..] else {
            continue;
        };
        assert_eq!(members.len(), tube.len());
        shells += 1;
        for _ in 0..8 {
            let (cx, cz, r) = square_below(&mut rng, centre, radii);
            if sees_none(&floor(cx, cz, r), false, &source, &[], &[shell]) {
                below += 1;
                assert_segments_meet(&mut rng, (cx, cz, r), &tube);
            }
            let (at, r) = square_inside(&mut rng, centre, radii);
            let region = level_square(at[0], at[1], at[2], r);
            if sees_none(&region, false, &source, &[], &[shell]) {
                inside += 1;
                assert_square_segments_meet(&mut rng, (at[0], at[1], at[2], r), &tube);
            }
        }
    }
    assert!(
        shells >= 150 && below >= 50 && inside >= 500,
        "{shells} shells, {below} regions below proven, {inside} inside"
    );
}

/// A small parallelogram of `piece`'s plane around its centre, facing the
/// other way (into a cup whose pieces face out): cut by planes across
/// the two axes the plane's normal leans on least, `1/8` of the piece's
/// extent along each from its centre.
fn inside_of(piece: &ConvexPolygon) -> Option<ConvexPolygon> {
    let support = piece.support().flipped();
    let normal = support.normal();
    let mut axes = [0, 1, 2];
    axes.sort_by_key(|&a| normal[a].unsigned_abs());
    let corners = piece.vertices_f64();
    let centre = piece.centroid();
    let mut edges = Vec::new();
    for &axis in &axes[..2] {
        let (lo, hi) = corners
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                (lo.min(c[axis]), hi.max(c[axis]))
            });
        let half = ((hi - lo) / 8.0).round().max(1.0) as i64;
        for (sign, at) in [
            (1, centre[axis].round() as i64 + half),
            (-1, centre[axis].round() as i64 - half),
        ] {
            let mut n = [0_i64; 3];
            n[axis] = sign;
            let mut p = [0_i64; 3];
            p[axis] = at;
            edges.push(Plane::with_normal_through(n, g(p[0], p[1], p[2]))?);
        }
    }
    // A cycle: +a, +b, -a, -b, or the other way round.
    let cycle = [edges[0], edges[2], edges[1], edges[3]];
    ConvexPolygon::from_planes(support, &cycle, 0)
        .or_else(|_| {
            let back: Vec<Plane> = cycle.iter().rev().copied().collect();
            ConvexPolygon::from_planes(support, &back, 0)
        })
        .ok()
}

/// Random cups, whole and dented, with small regions of their own pieces
/// that face in, towards some of the light, or take light on both sides
/// (seeded): whatever is proven dark past a cup's shell alone is dark,
/// every sampled segment from the region to the light it takes meeting
/// another of the cup's triangles; and walls of dented cups are proven
/// too.
#[test]
fn proven_dark_walls_of_random_cups_see_no_light() {
    let mut rng = Pcg64::seed_from_u64(37);
    let source = light(-500, 500, 10_000);
    let (mut tried, mut proven, mut proven_dented) = (0, 0, 0);
    for round in 0..300 {
        let ((_, _, dent), cup, shell) = cup_of_round(&mut rng, round);
        let Some(shell) = shell else {
            continue;
        };
        for (k, piece) in cup.iter().enumerate() {
            let Some(region) = inside_of(piece) else {
                continue;
            };
            // Half the walls take light on both sides; the others only
            // walls whose inside faces some of the light.
            let two_sided = k % 2 == 0;
            if !two_sided
                && source
                    .vertices()
                    .all(|l| side_of_point(region.support(), l) != Side::Front)
            {
                continue;
            }
            tried += 1;
            if !sees_none(&region, two_sided, &source, &[], &[&shell]) {
                continue;
            }
            proven += 1;
            if dent > 0.0 {
                proven_dented += 1;
            }
            let others: Vec<[[f64; 3]; 3]> = cup
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != k)
                .map(|(_, t)| {
                    let c = t.vertices_f64();
                    [c[0], c[1], c[2]]
                })
                .collect();
            let corners = region.vertices_f64();
            let facing = region.support().unit_normal_f64();
            for _ in 0..64 {
                let w: Vec<f64> = corners.iter().map(|_| rng.random::<f64>()).collect();
                let total: f64 = w.iter().sum();
                let p: [f64; 3] = std::array::from_fn(|a| {
                    corners.iter().zip(&w).map(|(c, w)| c[a] * w).sum::<f64>() / total
                });
                let l = [
                    -500.0 + 1000.0 * rng.random::<f64>(),
                    10_000.0,
                    -500.0 + 1000.0 * rng.random::<f64>(),
                ];
                // A one-sided region takes light on its front only.
                if !two_sided && vector::dot(facing, vector::sub(l, p)) <= 0.0 {
                    continue;
                }
                assert!(
                    others.iter().any(|&t| segment_meets_triangle(p, l, t)),
                    "segment {p:?} -> {l:?} passes the cup {cup:?}"
                );
            }
        }
    }
    assert!(
        tried >= 2000 && proven >= 400 && proven_dented >= 200,
        "{tried} walls tried, {proven} proven ({proven_dented} of dented cups)"
    );
}

/// A hexagonal tube along `z` (walls as triangles), one corner of an end
/// pushed out a little along `z` so that end's hexagon is bent: no planar cap closes
/// it, a fan of triangles does. The tube is one shell with two holes,
/// and from the floor under it the light above (within the tube's length,
/// behind both ends) is hidden.
#[test]
fn a_tube_with_a_bent_end_is_closed_by_a_fan() {
    let ring = |z: i64, lift: i64| -> Vec<GridPoint> {
        (0..6)
            .map(|i| {
                let angle = std::f64::consts::PI / 3.0 * f64::from(i);
                let (x, y) = (1000.0 * angle.cos(), 5000.0 + 1000.0 * angle.sin());
                g(
                    x.round() as i64,
                    y.round() as i64,
                    z + if i == 0 { lift } else { 0 },
                )
            })
            .collect()
    };
    let (near, far) = (ring(-1000, 0), ring(1000, 7));
    let mut tube = Vec::new();
    for i in 0..6 {
        let j = (i + 1) % 6;
        // Facing out of the tube.
        for t in [[near[i], near[j], far[j]], [near[i], far[j], far[i]]] {
            tube.push(ConvexPolygon::from_grid_points(&t, 0).unwrap());
        }
    }
    let mid = [0.0, 5000.0, 0.0];
    for t in &tube {
        let out = vector::dot(
            t.support().unit_normal_f64(),
            vector::sub(t.centroid(), mid),
        );
        assert!(out > 0.0, "the walls face out");
    }
    let inputs: Vec<u32> = (0..tube.len() as u32).collect();
    let found = crate::holed_shells(&tube, &vec![Some(0); tube.len()], &inputs);
    let [(members, shell)] = &found[..] else {
        panic!("one shell: {} found", found.len())
    };
    assert_eq!(members.len(), 12);
    let source = light(-500, 500, 10_000);
    assert!(sees_none(&floor(0, 0, 50), false, &source, &[], &[shell]));
    let mut rng = Pcg64::seed_from_u64(41);
    assert_segments_meet(&mut rng, (0, 0, 50), &tube);
}

/// A box open at the top with a lid over part of it, one of the lid's
/// corners a grid step off the wall top it should meet (as the grid
/// leaves a turned lid): the pieces make no surface with one hole, and no
/// group. Less the lid they are a cup, a shell; from the floor beside it,
/// a light on the other side is hidden, each ray entering by the bottom
/// or by the near wall.
#[test]
fn a_cup_with_a_lid_off_its_walls_is_a_shell_without_it() {
    let mut pieces = cuboid([-1000, 4000, -1000], [1000, 6000, 1000]);
    pieces.remove(3);
    let [a, b, c, d] = [
        g(-1000, 6000, -1000),
        g(-1000, 6000, 1000),
        g(137, 6001, 1000),
        g(137, 6000, -1000),
    ];
    for t in [[a, b, c], [a, c, d]] {
        pieces.push(ConvexPolygon::from_grid_points(&t, 0).unwrap());
    }
    assert!(pieces[5].support().normal()[1] > 0, "the lid faces out");
    let owners = vec![Some(0); pieces.len()];
    assert!(
        convex_groups(&pieces, &owners)
            .iter()
            .all(|g| g.shell().is_none()),
        "no group closes the lidded cup"
    );
    let inputs: Vec<u32> = vec![0, 1, 2, 3, 4, 5, 5];
    let found = crate::holed_shells(&pieces, &owners, &inputs);
    let [(members, shell)] = &found[..] else {
        panic!("one shell: {} found", found.len())
    };
    assert_eq!(members, &[0, 1, 2, 3, 4], "the cup without its lid");
    let source = AreaSource::from_grid_points(&[
        g(-3000, 10_000, -500),
        g(-1000, 10_000, -500),
        g(-1000, 10_000, 500),
        g(-3000, 10_000, 500),
    ])
    .unwrap();
    let region = floor(2500, 0, 20);
    assert!(sees_none(&region, false, &source, &[], &[shell]));
    let mut rng = Pcg64::seed_from_u64(43);
    let light = ([-3000.0, -1000.0], [-500.0, 500.0], 10_000.0);
    assert_segments_to_meet(&mut rng, (2500, 0, 0, 20), light, 4000, &pieces[..5]);
}
