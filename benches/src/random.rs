//! Deterministic random inputs for the kernel benchmarks: grid points,
//! planes, implicit-point queries, convex quads and triangle soups.
//!
//! Every generator takes a seed (or a seeded [`Pcg64`]) so that benchmark
//! runs are comparable and a surprising figure can be reproduced.

use bsp_core::predicates::PointFilter;
use bsp_core::{ConvexPolygon, GRID_LIMIT, GridPoint, Plane};
use rand::{Rng, SeedableRng};
pub use rand_pcg::Pcg64;

/// A seeded generator.
pub fn rng(seed: u64) -> Pcg64 {
    Pcg64::seed_from_u64(seed)
}

/// A grid point uniform in the cube `±(2^bits - 1)` (`bits <= 24`).
pub fn grid_point(rng: &mut Pcg64, bits: u32) -> GridPoint {
    let l = (1_i32 << bits.min(24)) - 1;
    GridPoint {
        x: rng.random_range(-l..=l),
        y: rng.random_range(-l..=l),
        z: rng.random_range(-l..=l),
    }
}

/// A grid point uniform over the whole grid (`±(2^24 - 1)`).
pub fn full_grid_point(rng: &mut Pcg64) -> GridPoint {
    grid_point(rng, 24)
}

/// A plane through three random grid points of the whole grid: the largest
/// coefficients the kernel meets.
pub fn plane(rng: &mut Pcg64) -> Plane {
    loop {
        if let Some(p) = Plane::through(
            full_grid_point(rng),
            full_grid_point(rng),
            full_grid_point(rng),
        ) {
            return p;
        }
    }
}

/// One implicit-point query: the point `planes[0] ∩ planes[1] ∩ planes[2]`
/// (with its filter data) against the plane `q`.
#[derive(Debug, Clone, Copy)]
pub struct ImplicitQuery {
    /// The three planes defining the point.
    pub planes: [Plane; 3],
    /// The point's filter data.
    pub filter: PointFilter,
    /// The plane to classify against.
    pub q: Plane,
}

impl ImplicitQuery {
    /// The planes as the predicates take them.
    pub fn plane_refs(&self) -> [&Plane; 3] {
        [&self.planes[0], &self.planes[1], &self.planes[2]]
    }
}

/// `n` queries with every plane through three random grid points: the
/// filter's typical input (it decides all but a tiny fraction).
pub fn random_implicit_queries(n: usize, seed: u64) -> Vec<ImplicitQuery> {
    let mut rng = rng(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let planes = [plane(&mut rng), plane(&mut rng), plane(&mut rng)];
        let Some(filter) = PointFilter::new(&planes[0], &planes[1], &planes[2]) else {
            continue;
        };
        out.push(ImplicitQuery {
            planes,
            filter,
            q: plane(&mut rng),
        });
    }
    out
}

/// `n` queries the filter cannot decide: the implicit point is a grid point
/// `g` (three planes through `g`) and `q` passes through `g` too, so the
/// exact answer is `On` while the floating-point value is only known to be
/// near zero. No plane of a query coincides with `q`, so the exact path
/// evaluates the full 4x4 determinant.
pub fn degenerate_implicit_queries(n: usize, seed: u64) -> Vec<ImplicitQuery> {
    let mut rng = rng(seed);
    let mut out = Vec::with_capacity(n);
    // Keep g and its neighbours inside the grid.
    let reach = 1_i32 << 20;
    while out.len() < n {
        let g = grid_point(&mut rng, 23);
        let through_g = |rng: &mut Pcg64| loop {
            let mut near = || GridPoint {
                x: g.x + rng.random_range(-reach..=reach),
                y: g.y + rng.random_range(-reach..=reach),
                z: g.z + rng.random_range(-reach..=reach),
            };
            if let Some(p) = Plane::through(g, near(), near()) {
                return p;
            }
        };
        let planes = [
            through_g(&mut rng),
            through_g(&mut rng),
            through_g(&mut rng),
        ];
        let q = through_g(&mut rng);
        if planes.iter().any(|p| p.is_coincident(&q)) {
            continue;
        }
        let Some(filter) = PointFilter::new(&planes[0], &planes[1], &planes[2]) else {
            continue;
        };
        out.push(ImplicitQuery { planes, filter, q });
    }
    out
}

/// `n` (plane, grid point) pairs over the whole grid.
pub fn grid_point_queries(n: usize, seed: u64) -> Vec<(Plane, GridPoint)> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| (plane(&mut rng), full_grid_point(&mut rng)))
        .collect()
}

/// A strictly convex quad in a random plane, with a grid point strictly
/// inside it (its centre).
///
/// The quad is the kite `(-a1, 0), (0, -b1), (a2, 0), (0, b2)` in the
/// coordinates `c + s u + t v` of two random integer vectors `u`, `v`, so it
/// is exactly planar and convex; `c` is inside. Its extent is about
/// `2^size_bits` grid units.
pub fn quad(rng: &mut Pcg64, size_bits: u32) -> (ConvexPolygon, GridPoint) {
    let size_bits = size_bits.clamp(4, 22);
    loop {
        let c = grid_point(rng, 22);
        let vector = |rng: &mut Pcg64| -> [i64; 3] {
            std::array::from_fn(|_| rng.random_range(-16_i64..=16))
        };
        let (u, v) = (vector(rng), vector(rng));
        let reach = 1_i64 << (size_bits - 4);
        let mut k = || rng.random_range(reach / 2..=reach);
        let uv = [(-k(), 0), (0, -k()), (k(), 0), (0, k())];
        let corners: Option<Vec<GridPoint>> = uv
            .iter()
            .map(|&(s, t)| {
                GridPoint::new(
                    i64::from(c.x) + s * u[0] + t * v[0],
                    i64::from(c.y) + s * u[1] + t * v[1],
                    i64::from(c.z) + s * u[2] + t * v[2],
                )
                .ok()
            })
            .collect();
        let Some(corners) = corners else { continue };
        if let Ok(q) = ConvexPolygon::from_grid_points(&corners, 0) {
            return (q, c);
        }
    }
}

/// A random plane through the grid point `inside` of a polygon: it cuts
/// the polygon in two (unless it is the polygon's own plane, which the
/// generator avoids).
pub fn plane_through(rng: &mut Pcg64, inside: GridPoint, polygon: &ConvexPolygon) -> Plane {
    loop {
        let p = Plane::through(inside, full_grid_point(rng), full_grid_point(rng));
        if let Some(p) = p.filter(|p| !p.is_coincident(polygon.support())) {
            return p;
        }
    }
}

/// `n` pairs of a random convex quad (extent about `2^20`) and a random
/// plane through its centre, which cuts it.
pub fn quad_cuts(n: usize, seed: u64) -> Vec<(ConvexPolygon, Plane)> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| {
            let (q, c) = quad(&mut rng, 20);
            let p = plane_through(&mut rng, c, &q);
            (q, p)
        })
        .collect()
}

/// A soup of `n` random small triangles in the box `±2^box_bits`: each
/// triangle's corners lie within `2^size_bits` of a random centre.
/// Degenerate triangles are redrawn; sources number the triangles.
pub fn triangle_soup(n: usize, box_bits: u32, size_bits: u32, seed: u64) -> Vec<ConvexPolygon> {
    let mut rng = rng(seed);
    let box_bits = box_bits.min(23);
    let reach = 1_i32 << size_bits.min(box_bits);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let c = grid_point(&mut rng, box_bits);
        let mut corner = || {
            GridPoint::new(
                i64::from(c.x) + i64::from(rng.random_range(-reach..=reach)),
                i64::from(c.y) + i64::from(rng.random_range(-reach..=reach)),
                i64::from(c.z) + i64::from(rng.random_range(-reach..=reach)),
            )
            .expect("within the grid")
        };
        let (a, b, d) = (corner(), corner(), corner());
        if let Ok(t) = ConvexPolygon::from_grid_points(&[a, b, d], out.len() as u32) {
            out.push(t);
        }
    }
    out
}

/// Largest grid coordinate, for callers that build their own points.
pub const LIMIT: i32 = GRID_LIMIT - 1;
