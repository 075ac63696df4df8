//! Generators of closed solids shared by the set-operation tests.

use bsp_core::{BspSolid, BuildOptions, ConvexPolygon, GridPoint, Plane, PointClass};
use rand::Rng;
use svbsp::{ConvexPolyhedron, SECTION_SOURCE, SetOp};

pub fn gp(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).expect("test point within the grid")
}

/// A solid given by its outward faces, and its tree.
#[derive(Debug, Clone)]
pub struct Solid {
    pub faces: Vec<ConvexPolygon>,
    pub tree: BspSolid,
}

impl Solid {
    pub fn from_faces(faces: Vec<ConvexPolygon>) -> Self {
        let tree = BspSolid::from_boundary(faces.clone(), &BuildOptions::default());
        tree.check_invariants().expect("a built tree is a tree");
        Self { faces, tree }
    }

    /// Volume from the faces (divergence theorem, `f64`).
    pub fn volume(&self) -> f64 {
        polygons_volume(&self.faces)
    }

    /// The complement, with flipped faces.
    pub fn complement(&self) -> Self {
        Self {
            faces: self.faces.iter().map(ConvexPolygon::flipped).collect(),
            tree: self.tree.complement(),
        }
    }
}

pub fn polygons_volume(polygons: &[ConvexPolygon]) -> f64 {
    let mut six = 0.0;
    for p in polygons {
        let v = p.vertices_f64();
        for i in 1..v.len() - 1 {
            let (a, b, c) = (v[0], v[i], v[i + 1]);
            six += a[0] * (b[1] * c[2] - b[2] * c[1])
                + a[1] * (b[2] * c[0] - b[0] * c[2])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
    }
    six / 6.0
}

/// The axis-aligned box `[lo, hi]`, six outward quads.
pub fn box_faces(lo: [i64; 3], hi: [i64; 3]) -> Vec<ConvexPolygon> {
    let c =
        |x: usize, y: usize, z: usize| gp([lo[0], hi[0]][x], [lo[1], hi[1]][y], [lo[2], hi[2]][z]);
    let quads = [
        [c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)],
        [c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)],
        [c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)],
        [c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)],
        [c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)],
        [c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)],
    ];
    quads
        .iter()
        .enumerate()
        .map(|(i, q)| ConvexPolygon::from_grid_points(q, i as u32).expect("box face"))
        .collect()
}

/// A random box with corners in `[-range, range]` and sides at least 1.
pub fn random_box(rng: &mut impl Rng, range: i64) -> Vec<ConvexPolygon> {
    let mut lo = [0; 3];
    let mut hi = [0; 3];
    for k in 0..3 {
        let a = rng.random_range(-range..range);
        let b = rng.random_range(a + 1..=range);
        (lo[k], hi[k]) = (a, b);
    }
    box_faces(lo, hi)
}

/// A random convex polyhedron: the cube of half-side `r` around `center`
/// cut by `cuts` random planes at distance about `0.8 r` from the centre.
/// Its faces have implicit vertices.
pub fn random_convex(
    rng: &mut impl Rng,
    center: [i64; 3],
    r: i64,
    cuts: usize,
) -> ConvexPolyhedron {
    let mut planes: Vec<Plane> = Vec::new();
    for axis in 0..3 {
        for s in [1_i64, -1] {
            let mut n = [0; 3];
            n[axis] = s;
            let mut p = center;
            p[axis] += s * r;
            planes.push(Plane::with_normal_through(n, gp(p[0], p[1], p[2])).unwrap());
        }
    }
    while planes.len() < 6 + cuts {
        let n: [i64; 3] = std::array::from_fn(|_| rng.random_range(-9_i64..=9));
        let len = ((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) as f64).sqrt();
        if len == 0.0 {
            continue;
        }
        let d = 0.8 * r as f64 / len;
        let p: [i64; 3] = std::array::from_fn(|k| center[k] + (n[k] as f64 * d).round() as i64);
        planes.push(Plane::with_normal_through(n, gp(p[0], p[1], p[2])).unwrap());
    }
    ConvexPolyhedron::from_planes(&planes).expect("the centre is inside")
}

/// The faces of a bounded convex polyhedron, sources renumbered.
pub fn convex_faces(polyhedron: &ConvexPolyhedron) -> Vec<ConvexPolygon> {
    assert!(
        polyhedron
            .facets()
            .iter()
            .all(|f| f.source() != SECTION_SOURCE)
    );
    polyhedron
        .facets()
        .iter()
        .enumerate()
        .map(|(i, f)| f.clone().with_source(i as u32))
        .collect()
}

/// A closed star-shaped mesh: the octahedron with each face cut into
/// `m * m` triangles, every vertex pushed out along its direction to its own
/// radius (a function of the direction, so shared vertices agree). Radial
/// moves keep each ray from the centre crossing exactly one face.
pub fn star_mesh(center: [i64; 3], m: i64, radius: impl Fn([f64; 3]) -> f64) -> Vec<ConvexPolygon> {
    let point = |d: [i64; 3]| {
        let len = ((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) as f64).sqrt();
        let u = d.map(|c| c as f64 / len);
        let r = radius(u);
        gp(
            center[0] + (u[0] * r).round() as i64,
            center[1] + (u[1] * r).round() as i64,
            center[2] + (u[2] * r).round() as i64,
        )
    };
    let mut faces = Vec::new();
    for sx in [1_i64, -1] {
        for sy in [1_i64, -1] {
            for sz in [1_i64, -1] {
                // Barycentric lattice i + j + k = m on the octant's face.
                let at = |i: i64, j: i64| point([sx * i, sy * j, sz * (m - i - j)]);
                for i in 0..m {
                    for j in 0..m - i {
                        let mut tris = vec![[at(i, j), at(i + 1, j), at(i, j + 1)]];
                        if i + j + 1 < m {
                            tris.push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                        }
                        for t in tris {
                            // Outward: the centre behind the face.
                            let Ok(f) = ConvexPolygon::from_grid_points(&t, faces.len() as u32)
                            else {
                                panic!("degenerate star triangle {t:?}");
                            };
                            let c = gp(center[0], center[1], center[2]);
                            let f = if bsp_core::predicates::side_of_point(f.support(), c)
                                == bsp_core::predicates::Side::Front
                            {
                                f.flipped()
                            } else {
                                f
                            };
                            faces.push(f);
                        }
                    }
                }
            }
        }
    }
    faces
}

/// A random star-shaped mesh of `8 m^2` triangles with radii in
/// `[r_min, r_max]`, smooth in the direction.
pub fn random_star(
    rng: &mut impl Rng,
    center: [i64; 3],
    m: i64,
    r_min: f64,
    r_max: f64,
) -> Vec<ConvexPolygon> {
    let k: [f64; 3] = std::array::from_fn(|_| rng.random_range(1.0..4.0));
    let phase: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.0..6.3));
    star_mesh(center, m, move |u| {
        let s = ((k[0] * u[0] + phase[0]).sin()
            + (k[1] * u[1] + phase[1]).sin()
            + (k[2] * u[2] + phase[2]).sin())
            / 3.0;
        r_min + (r_max - r_min) * 0.5 * (1.0 + s)
    })
}

/// Whether `result` agrees with `op` applied to `a` and `b` at `points`
/// off both boundaries; returns the number of points compared.
pub fn check_pointwise(
    result: &BspSolid,
    a: &BspSolid,
    b: &BspSolid,
    op: SetOp,
    points: impl IntoIterator<Item = GridPoint>,
) -> usize {
    let mut compared = 0;
    for p in points {
        let (ca, cb) = (a.classify_point(p), b.classify_point(p));
        if ca == PointClass::On || cb == PointClass::On {
            continue;
        }
        let want = op.apply(ca == PointClass::In, cb == PointClass::In);
        let got = result.classify_point(p);
        let expected = if want {
            PointClass::In
        } else {
            PointClass::Out
        };
        assert_eq!(got, expected, "{op:?} at {p:?}");
        compared += 1;
    }
    compared
}

pub fn random_points(rng: &mut impl Rng, n: usize, range: i64) -> Vec<GridPoint> {
    (0..n)
        .map(|_| {
            gp(
                rng.random_range(-range..=range),
                rng.random_range(-range..=range),
                rng.random_range(-range..=range),
            )
        })
        .collect()
}

pub const OPS: [SetOp; 3] = [SetOp::Union, SetOp::Intersection, SetOp::Difference];
