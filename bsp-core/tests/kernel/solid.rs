//! BSP solids: point classification against ray parity, polygon partition
//! against the same oracle, on random closed meshes.

use crate::common::{gp, orient, segment_crosses_triangle};
use bsp_core::{BspSolid, BuildOptions, Containment, ConvexPolygon, GridPoint, PointClass, Region};
use proptest::prelude::*;

/// A closed star-shaped mesh: the octahedron with each face cut in four,
/// every vertex pushed out along its direction to its own radius. Radial
/// moves keep each ray from the centre crossing exactly one face, so the
/// surface stays closed and embedded; it is not convex.
fn star_mesh(center: [i64; 3], radii: &[i64; 18]) -> Vec<[GridPoint; 3]> {
    // Directions: the 6 octahedron vertices and the 12 edge midpoints.
    let mut dirs: Vec<[i64; 3]> = Vec::new();
    for axis in 0..3 {
        for s in [1, -1] {
            let mut d = [0; 3];
            d[axis] = 2 * s;
            dirs.push(d);
        }
    }
    let index = |d: [i64; 3], dirs: &mut Vec<[i64; 3]>| {
        if let Some(i) = dirs.iter().position(|&e| e == d) {
            i
        } else {
            dirs.push(d);
            dirs.len() - 1
        }
    };
    let mut faces = Vec::new();
    for sx in [2, -2] {
        for sy in [2, -2] {
            for sz in [2, -2] {
                let (a, b, c) = ([sx, 0, 0], [0, sy, 0], [0, 0, sz]);
                let mid = |p: [i64; 3], q: [i64; 3]| {
                    [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2]
                };
                let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                for tri in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
                    faces.push(tri.map(|d| index(d, &mut dirs)));
                }
            }
        }
    }
    let point = |i: usize| {
        let d = dirs[i];
        let len = ((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) as f64).sqrt();
        let r = radii[i] as f64;
        gp(
            center[0] + (d[0] as f64 / len * r).round() as i64,
            center[1] + (d[1] as f64 / len * r).round() as i64,
            center[2] + (d[2] as f64 / len * r).round() as i64,
        )
    };
    faces
        .into_iter()
        .map(|[i, j, k]| {
            let (a, b, c) = (point(i), point(j), point(k));
            // Outward: counter-clockwise seen from outside the centre.
            let centre = [center[0] as f64, center[1] as f64, center[2] as f64];
            if orient(a.to_f64(), b.to_f64(), c.to_f64(), centre) > 0.0 {
                [a, b, c]
            } else {
                [a, c, b]
            }
        })
        .collect()
}

fn solid_of(mesh: &[[GridPoint; 3]]) -> BspSolid {
    let faces: Vec<ConvexPolygon> = mesh
        .iter()
        .enumerate()
        .map(|(i, t)| ConvexPolygon::from_grid_points(t, i as u32).expect("mesh triangle"))
        .collect();
    BspSolid::from_boundary(faces, &BuildOptions::default())
}

/// Ray-parity oracle, exact on `f64` input: `Some(inside)`, or `None` if the
/// ray grazes an edge or vertex (then the caller tries another ray).
fn parity(mesh: &[[GridPoint; 3]], p: [f64; 3], dir: [f64; 3]) -> Option<bool> {
    let far = [
        p[0] + dir[0] * 1e5,
        p[1] + dir[1] * 1e5,
        p[2] + dir[2] * 1e5,
    ];
    let mut crossings = 0;
    for t in mesh {
        let [a, b, c] = t.map(GridPoint::to_f64);
        let (s1, s2, s3) = (
            orient(p, far, a, b),
            orient(p, far, b, c),
            orient(p, far, c, a),
        );
        let (sp, sf) = (orient(a, b, c, p), orient(a, b, c, far));
        let straddles = (sp > 0.0) != (sf > 0.0) && sp != 0.0 && sf != 0.0;
        if straddles && (s1 == 0.0 || s2 == 0.0 || s3 == 0.0) {
            return None;
        }
        if segment_crosses_triangle(p, far, a, b, c) {
            crossings += 1;
        }
    }
    Some(crossings % 2 == 1)
}

fn inside_by_parity(mesh: &[[GridPoint; 3]], p: [f64; 3]) -> bool {
    let rays = [
        [0.31, 0.77, 0.55],
        [-0.61, 0.13, 0.78],
        [0.11, -0.93, 0.35],
        [0.71, 0.29, -0.64],
    ];
    rays.iter()
        .find_map(|&d| parity(mesh, p, d))
        .expect("some ray misses every edge")
}

/// Whether `p` lies on a face of the mesh (exactly, grid points only).
fn on_surface(mesh: &[[GridPoint; 3]], p: GridPoint) -> bool {
    let q = p.to_f64();
    mesh.iter().any(|t| {
        let [a, b, c] = t.map(GridPoint::to_f64);
        if orient(a, b, c, q) != 0.0 {
            return false;
        }
        // In the triangle: the same side of each edge, seen along the normal.
        let n = [a[0] + 1.0e3, a[1] + 1.7e3, a[2] + 2.9e3];
        let (s1, s2, s3) = (orient(a, b, n, q), orient(b, c, n, q), orient(c, a, n, q));
        (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0)
    })
}

fn radii() -> impl Strategy<Value = [i64; 18]> {
    prop::array::uniform18(200_i64..1000)
}

/// Three corners of a triangle through and around a star mesh.
fn triangle() -> impl Strategy<Value = Vec<[i64; 3]>> {
    prop::collection::vec(prop::array::uniform3(-1200_i64..1200), 3)
}

/// The star mesh of `radii`, its solid, and the triangle of `corners`
/// (`None` when they are in line).
fn star_and_triangle(
    radii: &[i64; 18],
    corners: &[[i64; 3]],
) -> Option<(Vec<[GridPoint; 3]>, BspSolid, ConvexPolygon)> {
    let mesh = star_mesh([0, 0, 0], radii);
    let solid = solid_of(&mesh);
    let points: Vec<GridPoint> = corners.iter().map(|p| gp(p[0], p[1], p[2])).collect();
    let polygon = ConvexPolygon::from_grid_points(&points, 0).ok()?;
    Some((mesh, solid, polygon))
}

/// Each piece is sound and inside the mesh exactly when it says so (a
/// random triangle has no piece on the boundary).
fn pieces_agree_with_parity(
    mesh: &[[GridPoint; 3]],
    pieces: &[(ConvexPolygon, Containment)],
) -> Result<(), TestCaseError> {
    for (piece, class) in pieces {
        piece.check_invariants().map_err(TestCaseError::fail)?;
        let inside = inside_by_parity(mesh, piece.centroid());
        match class {
            Containment::Inside => prop_assert!(inside),
            Containment::Outside => prop_assert!(!inside),
            _ => prop_assert!(false, "a random triangle is not on the boundary"),
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn points_classify_like_ray_parity(
        radii in radii(),
        points in prop::collection::vec(prop::array::uniform3(-1100_i64..1100), 40),
    ) {
        let mesh = star_mesh([0, 0, 0], &radii);
        let solid = solid_of(&mesh);
        solid.check_invariants().map_err(TestCaseError::fail)?;
        for p in points {
            let g = gp(p[0], p[1], p[2]);
            let class = solid.classify_point(g);
            if on_surface(&mesh, g) {
                prop_assert_eq!(class, PointClass::On);
            } else {
                let expected = if inside_by_parity(&mesh, g.to_f64()) { PointClass::In } else { PointClass::Out };
                prop_assert_eq!(class, expected, "point {:?}", g);
            }
        }
        // The complement flips every answer off the boundary.
        let complement = solid.complement();
        prop_assert_eq!(complement.classify_point(gp(0, 0, 0)), PointClass::Out);
    }

    #[test]
    fn polygon_partition_agrees_with_parity(radii in radii(), corners in triangle()) {
        let Some((mesh, solid, polygon)) = star_and_triangle(&radii, &corners) else {
            return Ok(());
        };
        let pieces = solid.partition_polygon(&polygon);
        let total: f64 = pieces.iter().map(|(p, _)| p.area()).sum();
        prop_assert!((total - polygon.area()).abs() <= 1e-9 * polygon.area());
        pieces_agree_with_parity(&mesh, &pieces)?;
    }

    /// Keyed, the partition has the same regions in no more pieces, fewer
    /// still for a coarser key, and the polygon whole for one key.
    #[test]
    fn a_keyed_partition_joins_what_its_key_does_not_tell_apart(
        radii in radii(),
        corners in triangle(),
    ) {
        let Some((mesh, solid, polygon)) = star_and_triangle(&radii, &corners) else {
            return Ok(());
        };
        let plain = solid.partition_polygon(&polygon);
        let keyed = solid.partition_polygon_by(&polygon, |c| c);
        prop_assert!(keyed.len() <= plain.len());
        let area = |pieces: &[(ConvexPolygon, Containment)], class: Containment| -> f64 {
            pieces.iter().filter(|(_, c)| *c == class).map(|(p, _)| p.area()).sum()
        };
        for class in [Containment::Inside, Containment::Outside] {
            let (a, b) = (area(&plain, class), area(&keyed, class));
            prop_assert!((a - b).abs() <= 1e-9 * polygon.area(), "{:?}: {} != {}", class, a, b);
        }
        pieces_agree_with_parity(&mesh, &keyed)?;
        let inside_or_not = solid.partition_polygon_by(&polygon, |c| c == Containment::Inside);
        prop_assert!(inside_or_not.len() <= keyed.len());
        let whole = solid.partition_polygon_by(&polygon, |_| ());
        prop_assert_eq!(whole.len(), 1);
        prop_assert_eq!(&whole[0].0, &polygon);
    }
}

#[test]
fn boundary_pieces_know_which_way_they_face() {
    // An axis-aligned cube [0, 8]^3, faces outward, split into triangles.
    let c = |x, y, z| gp(x, y, z);
    let quads = [
        [c(0, 0, 0), c(0, 8, 0), c(8, 8, 0), c(8, 0, 0)], // z = 0, normal -z
        [c(0, 0, 8), c(8, 0, 8), c(8, 8, 8), c(0, 8, 8)], // z = 8, +z
        [c(0, 0, 0), c(8, 0, 0), c(8, 0, 8), c(0, 0, 8)], // y = 0, -y
        [c(0, 8, 0), c(0, 8, 8), c(8, 8, 8), c(8, 8, 0)], // y = 8, +y
        [c(0, 0, 0), c(0, 0, 8), c(0, 8, 8), c(0, 8, 0)], // x = 0, -x
        [c(8, 0, 0), c(8, 8, 0), c(8, 8, 8), c(8, 0, 8)], // x = 8, +x
    ];
    let faces: Vec<ConvexPolygon> = quads
        .iter()
        .enumerate()
        .map(|(i, q)| ConvexPolygon::from_grid_points(q, i as u32).unwrap())
        .collect();
    let cube = BspSolid::from_boundary(faces, &BuildOptions::default());
    assert_eq!(cube.classify_point(c(4, 4, 4)), PointClass::In);
    assert_eq!(cube.classify_point(c(4, 4, 8)), PointClass::On);
    assert_eq!(cube.classify_point(c(8, 8, 8)), PointClass::On);
    assert_eq!(cube.classify_point(c(4, 4, 9)), PointClass::Out);

    // A square in z = 8 overhanging the top face: on the boundary where it
    // overlaps, outside elsewhere; facing as its normal says.
    let square =
        ConvexPolygon::from_grid_points(&[c(4, 4, 8), c(12, 4, 8), c(12, 12, 8), c(4, 12, 8)], 0)
            .unwrap();
    for (polygon, expected) in [
        (square.clone(), Containment::BoundarySame),
        (square.flipped(), Containment::BoundaryOpposite),
    ] {
        let pieces = cube.partition_polygon(&polygon);
        let area = |want: Containment| {
            pieces
                .iter()
                .filter(|(_, c)| *c == want)
                .map(|(p, _)| p.area())
                .sum::<f64>()
        };
        assert_eq!(area(expected), 16.0);
        assert_eq!(area(Containment::Outside), 48.0);
        assert_eq!(area(Containment::Inside), 0.0);
    }
    // A square through the middle: inside where it crosses the cube.
    let middle =
        ConvexPolygon::from_grid_points(&[c(-4, -4, 4), c(4, -4, 4), c(4, 4, 4), c(-4, 4, 4)], 0)
            .unwrap();
    let pieces = cube.partition_polygon(&middle);
    let inside: f64 = pieces
        .iter()
        .filter(|(_, c)| *c == Containment::Inside)
        .map(|(p, _)| p.area())
        .sum();
    assert_eq!(inside, 16.0);
    assert_eq!(BspSolid::full().classify_point(c(0, 0, 0)), PointClass::In);
    assert_eq!(BspSolid::empty().complement(), BspSolid::full());
    assert!(matches!(cube.root(), bsp_core::SolidChild::Node(_)));
    let _ = Region::In;
}
