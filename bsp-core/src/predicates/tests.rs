//! Tests of the predicates against exact oracles.

use super::*;

/// The exact side through the homogeneous coordinates (the previous
/// implementation): an independent oracle for the Laplace expansion.
fn side_by_cofactors(planes: [&Plane; 3], q: &Plane) -> Side {
    let x = exact_homogeneous(planes[0], planes[1], planes[2]);
    let [a, b, c] = q.normal();
    let s = I256::from(a) * x[0]
        + I256::from(b) * x[1]
        + I256::from(c) * x[2]
        + I256::from(q.offset()) * x[3];
    Side::of_sign(s.signum128() * x[3].signum128())
}

#[test]
fn laplace_expansion_agrees_with_cofactors() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    let mut on = 0;
    for round in 0..4000 {
        // Full-range and small coordinates, and planes sharing points
        // so that zeros occur.
        let l = if round % 2 == 0 {
            crate::GRID_LIMIT
        } else {
            1000
        };
        let mut point = || {
            gp(
                rng.random_range(-l..=l),
                rng.random_range(-l..=l),
                rng.random_range(-l..=l),
            )
        };
        let shared = point();
        let pts: Vec<GridPoint> = (0..8).map(|_| point()).collect();
        let planes: Vec<Plane> = [
            (shared, pts[0], pts[1]),
            (pts[2], shared, pts[3]),
            (pts[4], pts[5], shared),
            (shared, pts[6], pts[7]),
        ]
        .iter()
        .filter_map(|&(a, b, c)| Plane::through(a, b, c))
        .collect();
        let [p1, p2, p3, q] = planes[..] else {
            continue;
        };
        if PointFilter::new(&p1, &p2, &p3).is_none() {
            continue;
        }
        for q in [
            q,
            q.flipped(),
            Plane::through(pts[0], pts[3], pts[6]).unwrap_or(q),
        ] {
            let expected = side_by_cofactors([&p1, &p2, &p3], &q);
            on += usize::from(expected == Side::On);
            assert_eq!(exact_side_of_implicit([&p1, &p2, &p3], &q), expected);
            assert_eq!(exact_side_of_implicit([&p2, &p1, &p3], &q), expected);
            assert_eq!(
                exact_side_of_implicit([&p3.flipped(), &p2, &p1], &q),
                expected
            );
            assert_eq!(lies_on_all([&p1, &p2, &p3], &[&q]), expected == Side::On);
            // Equality of two implicit points against the cofactors.
            if let (Ok(a), Ok(b)) = (
                ImplicitPoint::new(p1, p2, p3),
                ImplicitPoint::new(q, p2.flipped(), p1),
            ) {
                let oracle = [&q, &p2, &p1]
                    .iter()
                    .all(|r| side_by_cofactors([&p1, &p2, &p3], r) == Side::On);
                assert_eq!(a.same_point(&b), oracle);
                assert_eq!(b.same_point(&a), oracle);
            }
            assert_eq!(
                lies_on_all([&p2, &p3, &p1], &[&q, &p1, &q.flipped()]),
                expected == Side::On
            );
        }
    }
    assert!(on > 1000, "only {on} points on their plane");
}

#[test]
fn pencils_are_the_planes_through_both_points_of_a_line() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(12);
    let (mut inside, mut outside, mut parallel) = (0, 0, 0);
    for round in 0..4000 {
        // (Full range less the step below.)
        let l = if round % 2 == 0 {
            crate::GRID_LIMIT - 2
        } else {
            50
        };
        let mut point = || {
            gp(
                rng.random_range(-l..=l),
                rng.random_range(-l..=l),
                rng.random_range(-l..=l),
            )
        };
        // Two planes through the line pr, and a third through p and
        // either r (in the pencil) or another point (usually not).
        let (p, r) = (point(), point());
        let (x, y, z, w) = (point(), point(), point(), point());
        let (Some(a), Some(b)) = (Plane::through(p, r, x), Plane::through(y, p, r)) else {
            continue;
        };
        if a.is_coincident(&b) {
            continue;
        }
        // Or a plane through the line moved by a step, parallel to it
        // (usually not in the pencil, its normal orthogonal to the
        // line all the same).
        let step = |g: GridPoint, t: [i32; 3]| gp(g.x - t[0], g.y - t[1], g.z - t[2]);
        let t = [0; 3].map(|_| rng.random_range(-2..=2));
        let q = if round % 4 == 1 {
            Plane::through(step(p, t), step(r, t), z)
        } else {
            let third = if round % 3 == 0 { w } else { r };
            Plane::through(p, z, third)
        };
        let Some(q) = q else {
            continue;
        };
        // Oracle: q holds the line iff it holds both of its grid points.
        let expected = side_of_point(&q, p) == Side::On && side_of_point(&q, r) == Side::On;
        if round % 4 == 1 {
            parallel += usize::from(!expected);
        }
        if expected {
            inside += 1;
        } else {
            outside += 1;
        }
        for (a, b) in [(a, b), (b, a), (a.flipped(), b)] {
            assert_eq!(in_pencil(&a, &b, &q), expected);
            assert_eq!(in_pencil(&a, &b, &q.flipped()), expected);
            let pencil = Pencil::new(&a, &b).expect("a and b are not parallel");
            assert_eq!(pencil.holds(&q), expected);
            assert_eq!(pencil.holds(&q.flipped()), expected);
        }
    }
    assert!(
        inside > 1000 && outside > 1000 && parallel > 500,
        "{inside} in, {outside} out ({parallel} parallel)"
    );
}

/// `dot_sign` against 256-bit products, at the bounds it is stated
/// for: random vectors, and exact zeros (a normal in the span of the two
/// whose cross product is the other vector) moved by one unit.
#[test]
fn dot_sign_is_exact() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(31);
    let limit = (1_i64 << 51) - 1;
    let mut zeros = 0;
    for round in 0..20_000 {
        let mut normal = || [0; 3].map(|_| rng.random_range(-limit..=limit));
        let (a, b) = (normal(), normal());
        let wide = |v: [i64; 3]| v.map(i128::from);
        let (a, b) = (wide(a), wide(b));
        let v = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let u = match round % 3 {
            // alpha a + beta b: u . v = 0.
            0 => [0, 1, 2].map(|k| a[k] - b[k]),
            1 => [0, 1, 2].map(|k| a[k] + 2 * b[k]),
            _ => wide(normal()),
        };
        let u = if round % 6 == 3 {
            [u[0] + 1, u[1], u[2]]
        } else {
            u
        };
        let oracle = (0..3).fold(I256::ZERO, |acc, k| {
            acc + I256::from(u[k]) * I256::from(v[k])
        });
        let expected = Side::of_sign(oracle.signum128());
        zeros += usize::from(expected == Side::On);
        assert_eq!(dot_sign(u, v), expected, "{u:?} . {v:?}");
    }
    assert!(zeros > 1000, "{zeros} exact zeros");
}

#[test]
fn explicit_points() {
    let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    // Counter-clockwise seen from +z: a point below is in front.
    assert_eq!(orient3d_f64(a, b, c, [0.3, 0.3, -1e-300]), Side::Front);
    assert_eq!(orient3d_f64(a, b, c, [0.3, 0.3, 1e-300]), Side::Back);
    assert_eq!(orient3d_f64(a, b, c, [0.1, 0.2, 0.0]), Side::On);
}

fn gp(x: i32, y: i32, z: i32) -> GridPoint {
    GridPoint { x, y, z }
}

fn axis_plane(axis: usize, value: i32) -> Plane {
    // x_axis = value, normal along +axis.
    let mut n = [0_i64; 3];
    n[axis] = 1;
    let mut p = [0; 3];
    p[axis] = value;
    Plane::with_normal_through(n, gp(p[0], p[1], p[2])).unwrap()
}

#[test]
fn homogeneous_coordinates_solve_the_three_planes() {
    let p = ImplicitPoint::new(axis_plane(0, 5), axis_plane(1, -3), axis_plane(2, 7)).unwrap();
    assert_eq!(p.to_f64(), [5.0, -3.0, 7.0]);
    assert_eq!(p.side(&axis_plane(0, 4)), Side::Front);
    assert_eq!(p.side(&axis_plane(0, 6)), Side::Back);
    assert_eq!(p.side(&axis_plane(0, 5)), Side::On);
    // The orientation of the defining planes does not change the point.
    let q = ImplicitPoint::new(
        axis_plane(1, -3).flipped(),
        axis_plane(0, 5),
        axis_plane(2, 7).flipped(),
    )
    .unwrap();
    assert!(p.same_point(&q));
    assert_eq!(q.side(&axis_plane(0, 4)), Side::Front);
}

#[test]
fn parallel_planes_do_not_meet() {
    let r = ImplicitPoint::new(axis_plane(0, 5), axis_plane(0, 6), axis_plane(2, 7));
    assert_eq!(r, Err(Error::NoIntersection));
}

#[test]
fn filter_and_exact_agree_on_random_planes() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
    let l = crate::GRID_LIMIT - 1;
    let mut point = || {
        gp(
            rng.random_range(-l..=l),
            rng.random_range(-l..=l),
            rng.random_range(-l..=l),
        )
    };
    let mut decided = 0;
    for _ in 0..2000 {
        let planes: Vec<Plane> = (0..4)
            .filter_map(|_| Plane::through(point(), point(), point()))
            .collect();
        let [p1, p2, p3, q] = planes[..] else {
            continue;
        };
        let Some(f) = PointFilter::new(&p1, &p2, &p3) else {
            continue;
        };
        let exact = exact_side_of_implicit([&p1, &p2, &p3], &q);
        if let Some(side) = f.side(&q) {
            assert_eq!(side, exact);
            decided += 1;
        }
    }
    assert!(decided > 1900, "filter decided only {decided}");
}

#[test]
fn exact_path_decides_what_the_filter_cannot() {
    // A point on q that is not one of its defining planes: the filter
    // cannot certify a zero, the exact path must.
    let o = |x: i32, y: i32, z: i32| gp(x + 100_003, y - 200_017, z + 300_007);
    let a = Plane::through(o(0, 0, 0), o(1000, 3, 7), o(5, 1000, 11)).unwrap();
    let b = Plane::through(o(0, 0, 0), o(-7, 13, 1000), o(1000, 5, -3)).unwrap();
    let c = Plane::through(o(0, 0, 0), o(17, 1000, -5), o(-3, 2, 999)).unwrap();
    let q = Plane::through(o(0, 0, 0), o(123, 456, 789), o(-50, 900, 13)).unwrap();
    let f = PointFilter::new(&a, &b, &c).unwrap();
    assert_eq!(f.side(&q), None);
    let before = exact_fallbacks();
    assert_eq!(side_of_implicit(&f, [&a, &b, &c], &q), Side::On);
    assert!(exact_fallbacks() > before);
    // A plane one unit off the point: the filter may or may not decide,
    // and both answers agree.
    let q1 = Plane::through(o(1, 0, 0), o(124, 456, 789), o(-49, 900, 13)).unwrap();
    let exact = exact_side_of_implicit([&a, &b, &c], &q1);
    assert_ne!(exact, Side::On);
    assert_eq!(side_of_implicit(&f, [&a, &b, &c], &q1), exact);
}

#[test]
fn near_degenerate_points_are_decided_exactly() {
    // Two planes nearly parallel at the grid's extent: the intersection is
    // ill-conditioned, yet its sides are exact and consistent with the
    // grid points that it coincides with.
    let l = crate::GRID_LIMIT - 1;
    let a = Plane::through(gp(-l, 0, -l), gp(l, 1, -l), gp(-l, 0, l)).unwrap();
    let b = Plane::through(gp(-l, 0, -l), gp(l, 2, -l), gp(-l, 0, l)).unwrap();
    let c = axis_plane(0, -l);
    let p = ImplicitPoint::new(a, b, c);
    // a and b share the line through (-l,0,-l) and (-l,0,l), which lies
    // in c: no single point.
    assert!(p.is_err());
    let c2 = axis_plane(2, 12345);
    let p = ImplicitPoint::new(a, b, c2).unwrap();
    let on = Plane::through(gp(-l, 0, 12345), gp(-l, 0, 0), gp(0, 99, 12345)).unwrap();
    assert_eq!(p.side(&on), Side::On);
    let f = p.to_f64();
    assert!((f[0] + f64::from(l)).abs() < 1e-6 && f[1].abs() < 1e-6);
}

#[test]
fn grid_point_and_direction_sides_are_exact() {
    let l = crate::GRID_LIMIT;
    let p = Plane::through(gp(-l, -l, -l), gp(l, -l + 1, -l), gp(-l, l, l - 1)).unwrap();
    assert_eq!(side_of_point(&p, gp(-l, -l, -l)), Side::On);
    assert_eq!(side_of_point(&p, gp(l, -l + 1, -l)), Side::On);
    let n = p.normal();
    let dir = [
        n[0].signum() as i32,
        n[1].signum() as i32,
        n[2].signum() as i32,
    ];
    assert_eq!(side_of_direction(&p, dir), Side::Front);
    assert_eq!(side_of_direction(&p, dir.map(|c| -c)), Side::Back);
}
