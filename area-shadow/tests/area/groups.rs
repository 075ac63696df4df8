//! Convex bodies of several pieces: their umbra volume against the exact
//! occlusion oracle, and the umbra they add to a scene.

use crate::oracle::{Caster, blocked, gp, light_samples, samples};
use area_shadow::{
    AreaSource, Class, SceneLight, ShadowGroups, compute_shadows, compute_shadows_with_groups,
    convex_groups,
};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{BuildOptions, ConvexPolygon, GridPoint};
use proptest::prelude::*;
use svbsp::PieceFlags;

/// The faces of the box `lo..hi`, facing out (or in), each a quad or two
/// triangles cut along either diagonal (bits of `cuts`, two per face).
pub(crate) fn box_faces(lo: [i64; 3], hi: [i64; 3], cuts: u32, inward: bool) -> Vec<ConvexPolygon> {
    let c = |i: usize| {
        gp(
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        )
    };
    // Counter-clockwise seen from outside.
    let quads = [
        [0, 4, 6, 2], // x = lo
        [1, 3, 7, 5], // x = hi
        [0, 1, 5, 4], // y = lo
        [2, 6, 7, 3], // y = hi
        [0, 2, 3, 1], // z = lo
        [4, 5, 7, 6], // z = hi
    ];
    let mut out = Vec::new();
    for (f, q) in quads.iter().enumerate() {
        let mut q: Vec<GridPoint> = q.iter().map(|&i| c(i)).collect();
        if inward {
            q.reverse();
        }
        let parts: Vec<Vec<GridPoint>> = match (cuts >> (2 * f)) & 3 {
            0 | 3 => vec![q],
            1 => vec![vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]],
            _ => vec![vec![q[1], q[2], q[3]], vec![q[1], q[3], q[0]]],
        };
        out.extend(
            parts
                .into_iter()
                .map(|p| ConvexPolygon::from_grid_points(&p, 0).unwrap()),
        );
    }
    out
}

/// A tetrahedron's faces, facing out, if the points span one.
fn tetrahedron(p: [[i64; 3]; 4]) -> Option<Vec<ConvexPolygon>> {
    let g: Vec<GridPoint> = p.iter().map(|c| gp(c[0], c[1], c[2])).collect();
    let faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
    let plane = bsp_core::Plane::through(g[0], g[1], g[2])?;
    let flip = match side_of_point(&plane, g[3]) {
        Side::On => return None,
        Side::Front => true,
        Side::Back => false,
    };
    faces
        .iter()
        .map(|f| {
            let mut pts = vec![g[f[0]], g[f[1]], g[f[2]]];
            if flip {
                pts.reverse();
            }
            ConvexPolygon::from_grid_points(&pts, 0).ok()
        })
        .collect()
}

/// A parallelogram light at height `h` over `[x0, x0 + w] x [z0, z0 + d]`,
/// rising by `tilt` along x, emitting downwards.
fn light(x0: i64, z0: i64, w: i64, d: i64, h: i64, tilt: i64) -> AreaSource {
    let pts = [
        gp(x0, h, z0),
        gp(x0 + w, h + tilt, z0),
        gp(x0 + w, h + tilt, z0 + d),
        gp(x0, h, z0 + d),
    ];
    let polygon = ConvexPolygon::from_grid_points(&pts, 0).unwrap();
    if polygon.support().normal()[1] < 0 {
        AreaSource::new(polygon).unwrap()
    } else {
        AreaSource::new(polygon.flipped()).unwrap()
    }
}

fn body() -> impl Strategy<Value = Vec<ConvexPolygon>> {
    prop_oneof![
        (
            prop::array::uniform3(-60_i64..40),
            prop::array::uniform3(4_i64..50),
            any::<u32>(),
            any::<bool>(),
        )
            .prop_map(|(lo, size, cuts, inward)| {
                let lo = [lo[0], lo[1] + 100, lo[2]];
                let hi = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
                box_faces(lo, hi, cuts, inward)
            }),
        prop::array::uniform4(prop::array::uniform3(-50_i64..50))
            .prop_filter_map("flat", |p| tetrahedron(p.map(|c| [c[0], c[1] + 120, c[2]]))),
    ]
}

pub(crate) fn light_strategy() -> impl Strategy<Value = AreaSource> {
    (
        -80_i64..40,
        -80_i64..40,
        4_i64..60,
        4_i64..60,
        200_i64..260,
        -30_i64..30,
    )
        .prop_map(|(x0, z0, w, d, h, tilt)| light(x0, z0, w, d, h, tilt))
}

/// Points strictly inside the convex body of `faces`: convex combinations
/// of its vertices with positive weights (a fixed pseudo-random sequence,
/// spread over the body).
fn inner_points(faces: &[ConvexPolygon]) -> Vec<[f64; 3]> {
    let mut vertices: Vec<[f64; 3]> = faces.iter().flat_map(|f| f.vertices_f64()).collect();
    vertices.sort_by(|a, b| a.partial_cmp(b).unwrap());
    vertices.dedup();
    let mut state = 0x9e37_79b9_u32;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        // Cubed, so that some points lie near each vertex.
        (0.01 + f64::from(state % 1000) / 1000.0).powi(3)
    };
    // First points along each segment between two vertices (the edges
    // among them), pulled a fiftieth of the way to the centre: a ray
    // through one reaches the part of the light that only a corner or an
    // edge hides (from a far point, the penumbra's light can be a thin
    // sliver past the silhouette).
    let n = vertices.len() as f64;
    let centre: [f64; 3] = std::array::from_fn(|a| vertices.iter().map(|v| v[a]).sum::<f64>() / n);
    let mut near_edges: Vec<[f64; 3]> = Vec::new();
    for (i, u) in vertices.iter().enumerate() {
        for w in &vertices[i..] {
            for k in 0..16 {
                let t = f64::from(k) / 16.0;
                near_edges.push(std::array::from_fn(|a| {
                    0.98 * (u[a] + t * (w[a] - u[a])) + 0.02 * centre[a]
                }));
            }
        }
    }
    near_edges
        .into_iter()
        .chain((0..2000).map(|_| {
            let weights: Vec<f64> = vertices.iter().map(|_| next()).collect();
            let total: f64 = weights.iter().sum();
            std::array::from_fn(|a| {
                vertices
                    .iter()
                    .zip(&weights)
                    .map(|(v, w)| v[a] * w)
                    .sum::<f64>()
                    / total
            })
        }))
        .collect()
}

/// Where the ray from `p` through `k` meets the light's polygon, beyond
/// `k`, if it meets it well inside (away from its edges).
fn ray_to_light(p: [f64; 3], k: [f64; 3], light: &AreaSource) -> Option<[f64; 3]> {
    let [a, b, c, d] = light.support().approx();
    let dir = [k[0] - p[0], k[1] - p[1], k[2] - p[2]];
    let along = a * dir[0] + b * dir[1] + c * dir[2];
    if along == 0.0 {
        return None;
    }
    let t = -(a * p[0] + b * p[1] + c * p[2] + d) / along;
    if t <= 1.0 {
        return None;
    }
    let x: [f64; 3] = std::array::from_fn(|i| p[i] + t * dir[i]);
    let corners: Vec<[f64; 3]> = light.vertices().map(GridPoint::to_f64).collect();
    let n = [a, b, c];
    let inside = (0..corners.len()).all(|i| {
        let (u, v) = (corners[i], corners[(i + 1) % corners.len()]);
        let e = [v[0] - u[0], v[1] - u[1], v[2] - u[2]];
        let w = [x[0] - u[0], x[1] - u[1], x[2] - u[2]];
        let cross = [
            e[1] * w[2] - e[2] * w[1],
            e[2] * w[0] - e[0] * w[2],
            e[0] * w[1] - e[1] * w[0],
        ];
        let length = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
        let norm = (a * a + b * b + c * c).sqrt();
        (cross[0] * n[0] + cross[1] * n[1] + cross[2] * n[2]) / (length * norm) > 0.5
    });
    inside.then_some(x)
}

/// Whether a vertex of `faces` lies on or behind the light's plane.
fn reaches_light_plane(faces: &[ConvexPolygon], light: &AreaSource) -> bool {
    faces.iter().any(|f| {
        (0..f.len())
            .any(|k| side_of_point(light.support(), f.vertex_grid_point(k).unwrap()) != Side::Front)
    })
}

/// What the oracle tests against: the faces as casters, the light's
/// corners, and points spread inside the light.
#[allow(clippy::type_complexity)] // (the three, named where used)
fn oracle(
    faces: &[ConvexPolygon],
    light: &AreaSource,
) -> (Vec<Caster>, Vec<[f64; 3]>, Vec<[f64; 3]>) {
    (
        faces.iter().map(Caster::new).collect(),
        light.vertices().map(GridPoint::to_f64).collect(),
        light_samples(light.polygon()),
    )
}

fn all_hidden(p: [f64; 3], targets: &[[f64; 3]], casters: &[Caster]) -> bool {
    // No receiver: `own` is a plane none of the body's faces lie in.
    let own =
        ConvexPolygon::from_grid_points(&[gp(0, -9, 0), gp(1, -9, 0), gp(0, -9, -1)], 0).unwrap();
    targets.iter().all(|x| blocked(p, *x, casters, &own))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Strictly inside a body's umbra volume no point of the light is
    /// seen; strictly outside it some light vertex is (the umbra of a
    /// convex body is where it hides every light vertex).
    #[test]
    fn a_bodys_umbra_is_where_it_hides_every_light_vertex(
        faces in body(),
        light in light_strategy(),
        points in prop::collection::vec(prop::array::uniform3(-150_i64..150), 200),
    ) {
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        prop_assert_eq!(groups.len(), 1);
        prop_assert_eq!(groups[0].pieces.len(), faces.len());
        let Some(planes) = groups[0].umbra_planes(&light) else {
            // Only when the body reaches the light's plane.
            prop_assert!(reaches_light_plane(&faces, &light));
            return Ok(());
        };
        let (casters, corners, inside_light) = oracle(&faces, &light);
        for c in points {
            let p = gp(c[0], c[1] + 40, c[2]);
            let on_a_face = faces.iter().any(|f| side_of_point(f.support(), p) == Side::On);
            let sides: Vec<Side> = planes.iter().map(|q| side_of_point(q, p)).collect();
            if on_a_face || sides.contains(&Side::On) {
                continue;
            }
            let q = p.to_f64();
            if sides.iter().all(|s| *s == Side::Back) {
                prop_assert!(all_hidden(q, &corners, &casters), "{q:?} in the umbra sees a light vertex");
                prop_assert!(all_hidden(q, &inside_light, &casters), "{q:?} in the umbra sees the light");
            } else {
                prop_assert!(!all_hidden(q, &corners, &casters), "{q:?} outside the umbra sees no light vertex");
            }
        }
    }

    /// A body's penumbra volume is where it hides some of the light:
    /// strictly outside, every sampled point of the light and every light
    /// vertex is seen (exactly: from there a plane separates the body from
    /// the light); well inside (16 grid units from every plane), the ray
    /// from the point through some point of the body goes on to the light,
    /// and the oracle finds that light point hidden.
    /// A point strictly inside the umbra volume is never outside it.
    #[test]
    fn a_bodys_penumbra_is_where_it_hides_some_of_the_light(
        faces in body(),
        light in light_strategy(),
        points in prop::collection::vec(prop::array::uniform3(-150_i64..150), 200),
    ) {
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        prop_assert_eq!(groups.len(), 1);
        let Some(planes) = groups[0].penumbra_planes(&light) else {
            // Only when the body reaches the light's plane (boxes and
            // tetrahedra on the grid are exactly convex).
            prop_assert!(reaches_light_plane(&faces, &light));
            return Ok(());
        };
        let (casters, corners, inside_light) = oracle(&faces, &light);
        let depth = |q: [f64; 3]| {
            planes
                .iter()
                .map(|plane| {
                    let [a, b, c, d] = plane.approx();
                    -(a * q[0] + b * q[1] + c * q[2] + d) / (a * a + b * b + c * c).sqrt()
                })
                .fold(f64::INFINITY, f64::min)
        };
        let own =
            ConvexPolygon::from_grid_points(&[gp(0, -9, 0), gp(1, -9, 0), gp(0, -9, -1)], 0).unwrap();
        let hidden = |q: [f64; 3], x: &[f64; 3]| blocked(q, *x, &casters, &own);
        let umbra = groups[0].umbra_planes(&light).unwrap_or_default();
        let body_points = inner_points(&faces);
        // The light is a parallelogram: corner 0 plus combinations of the
        // edges to corners 1 and 3.
        let fine_light: Vec<[f64; 3]> = (0..128 * 128)
            .map(|k| {
                let (s, t) = ((f64::from(k / 128) + 0.5) / 128.0, (f64::from(k % 128) + 0.5) / 128.0);
                std::array::from_fn(|a| {
                    corners[0][a] + s * (corners[1][a] - corners[0][a]) + t * (corners[3][a] - corners[0][a])
                })
            })
            .collect();
        for c in points {
            let p = gp(c[0], c[1] + 40, c[2]);
            if faces.iter().any(|f| side_of_point(f.support(), p) == Side::On) {
                continue;
            }
            let q = p.to_f64();
            let outside = planes.iter().any(|plane| side_of_point(plane, p) == Side::Front);
            if !umbra.is_empty() && umbra.iter().all(|plane| side_of_point(plane, p) == Side::Back) {
                prop_assert!(!outside, "{q:?} in the umbra is outside the penumbra");
            }
            if outside {
                prop_assert!(
                    !corners.iter().chain(&inside_light).any(|x| hidden(q, x)),
                    "{q:?} outside the penumbra has some of the light hidden"
                );
            } else if depth(q) > 16.0 {
                // A witness: a sampled point of the light hidden, or a
                // point of the body whose ray from `q` goes on to the light
                // (sampling the light alone misses the thin band a sliver
                // of a body hides; sampling the body alone, a small light),
                // or, failing those, a point of a 128 x 128 grid over the
                // light (a far body's image can overlap only a thin band
                // along the light's edge, between two rows of the samples).
                let witness = inside_light.iter().copied().find(|x| hidden(q, x)).or_else(|| {
                    body_points
                        .iter()
                        .filter_map(|k| ray_to_light(q, *k, &light))
                        .find(|x| hidden(q, x))
                }).or_else(|| fine_light.iter().copied().find(|x| hidden(q, x)));
                prop_assert!(witness.is_some(), "{q:?} deep in the penumbra sees all of the light");
            }
        }
    }

    /// One convex body over a floor, below the light's plane: umbra
    /// fragments see none of the light, and penumbra fragments see some
    /// light vertex (where one body hides the light, the classes are exact
    /// both ways; a body reaching the light's plane keeps its pieces'
    /// umbrae).
    #[test]
    fn a_body_over_a_floor_has_exact_classes(faces in body(), light in light_strategy()) {
        prop_assume!(faces.iter().all(|f| (0..f.len()).all(|k| {
            side_of_point(light.support(), f.vertex_grid_point(k).unwrap()) == Side::Front
        })));
        let mut pieces = vec![ConvexPolygon::from_grid_points(
            &[gp(-400, 0, 400), gp(400, 0, 400), gp(400, 0, -400), gp(-400, 0, -400)],
            0,
        ).unwrap()];
        pieces.extend(faces);
        let pieces: Vec<ConvexPolygon> = pieces.into_iter().enumerate().map(|(k, p)| p.with_source(k as u32)).collect();
        let flags = vec![PieceFlags::default(); pieces.len()];
        let out = compute_shadows(&pieces, &flags, &[SceneLight::Area(light.clone())], &BuildOptions::default()).unwrap();
        floor_classes_are_exact(&out.fragments, &pieces, &light)?;
    }
}

/// Every floor fragment (source 0; `pieces[0]` is the floor, the others
/// cast shadows) against the exact segment oracle at its sample points:
/// umbra sees none of the light, penumbra some light vertex or sample,
/// lit all of them (behind the light's plane nothing arrives; the floor
/// faces every light point).
pub(crate) fn floor_classes_are_exact(
    fragments: &[svbsp::Fragment],
    pieces: &[ConvexPolygon],
    light: &AreaSource,
) -> Result<(), TestCaseError> {
    let casters: Vec<Caster> = pieces[1..].iter().map(Caster::new).collect();
    let corners: Vec<[f64; 3]> = light.vertices().map(GridPoint::to_f64).collect();
    let inside_light = light_samples(light.polygon());
    let [a, b, c, d] = light.support().approx();
    for f in fragments.iter().filter(|f| f.polygon.source() == 0) {
        let class = Class::of(f, 0);
        for q in samples(&f.polygon) {
            let reached = a * q[0] + b * q[1] + c * q[2] + d > 0.0;
            let seen = |x: &[f64; 3]| reached && !blocked(q, *x, &casters, &pieces[0]);
            let sees = |targets: &[[f64; 3]]| targets.iter().any(seen);
            match class {
                Class::Umbra => prop_assert!(
                    !sees(&inside_light) && !sees(&corners),
                    "umbra at {q:?} sees the light"
                ),
                Class::Penumbra => prop_assert!(
                    sees(&corners) || sees(&inside_light),
                    "penumbra at {q:?} sees none of the light"
                ),
                Class::Lit => prop_assert!(
                    corners.iter().chain(&inside_light).all(seen),
                    "lit at {q:?} misses some of the light"
                ),
            }
        }
    }
    Ok(())
}

/// A UV sphere of `rings` x `segments` quads, each cut into two
/// triangles, its vertices rounded to the grid: the quads' two triangles
/// meet at slight valleys or ridges, so the surface is only nearly convex.
fn rounded_sphere(centre: [f64; 3], radius: f64, rings: u32, segments: u32) -> Vec<ConvexPolygon> {
    let at = |i: u32, j: u32| {
        let (t, f) = (
            std::f64::consts::PI * f64::from(i) / f64::from(rings),
            2.0 * std::f64::consts::PI * f64::from(j % segments) / f64::from(segments),
        );
        gp(
            (centre[0] + radius * t.sin() * f.cos()).round() as i64,
            (centre[1] + radius * t.cos()).round() as i64,
            (centre[2] + radius * t.sin() * f.sin()).round() as i64,
        )
    };
    let mut out = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            // Outwards: counter-clockwise seen from outside.
            for t in [[a, b, c], [a, c, d]] {
                if let Ok(p) = ConvexPolygon::from_grid_points(&t, 0) {
                    out.push(p);
                }
            }
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// A sphere rounded to the grid is convex only nearly; it still forms a
    /// body (a hull of its vertices moved in a little), and where that
    /// body's umbra is no point of the light is seen past the sphere's own
    /// triangles.
    #[test]
    fn a_rounded_sphere_hides_the_light_from_its_bodys_umbra(
        centre in prop::array::uniform3(-30.0_f64..30.0),
        radius in 20.0_f64..70.0,
        rings in 4_u32..9,
        segments in 5_u32..13,
        light in light_strategy(),
        points in prop::collection::vec(prop::array::uniform3(-150_i64..150), 200),
    ) {
        let faces = rounded_sphere([centre[0], centre[1] + 110.0, centre[2]], radius, rings, segments);
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        prop_assert_eq!(groups.len(), 1);
        prop_assert_eq!(groups[0].pieces.len(), faces.len());
        let Some(planes) = groups[0].umbra_planes(&light) else {
            return Ok(());
        };
        let (casters, corners, inside_light) = oracle(&faces, &light);
        // The body fills most of the sphere: its centre is in the umbra.
        let middle = gp(centre[0].round() as i64, centre[1].round() as i64 + 110, centre[2].round() as i64);
        prop_assert!(planes.iter().all(|q| side_of_point(q, middle) == Side::Back));
        for c in points {
            let p = gp(c[0], c[1] + 40, c[2]);
            if faces.iter().any(|f| side_of_point(f.support(), p) == Side::On) {
                continue;
            }
            if planes.iter().all(|q| side_of_point(q, p) == Side::Back) {
                let q = p.to_f64();
                prop_assert!(all_hidden(q, &corners, &casters), "{q:?} in the umbra sees a light vertex");
                prop_assert!(all_hidden(q, &inside_light, &casters), "{q:?} in the umbra sees the light");
            }
        }
    }
}

/// The floor's area in `class` for a box over it under a light.
fn floor_area(faces: Vec<ConvexPolygon>, light: &AreaSource, groups: bool, class: Class) -> f64 {
    let mut pieces = vec![
        ConvexPolygon::from_grid_points(
            &[
                gp(-400, 0, 400),
                gp(400, 0, 400),
                gp(400, 0, -400),
                gp(-400, 0, -400),
            ],
            0,
        )
        .unwrap(),
    ];
    pieces.extend(faces);
    let flags = vec![PieceFlags::default(); pieces.len()];
    let groups = if groups {
        ShadowGroups::connected(&pieces, &flags)
    } else {
        ShadowGroups::default()
    };
    let lights = [SceneLight::Area(light.clone())];
    let out =
        compute_shadows_with_groups(&pieces, &flags, &groups, &lights, &BuildOptions::default())
            .unwrap();
    out.fragments
        .iter()
        .filter(|f| f.polygon.source() == 0 && Class::of(f, 0) == class)
        .map(|f| f.polygon.area())
        .sum()
}

#[test]
fn a_triangulated_box_casts_the_umbra_of_the_box() {
    let light = light(-20, -20, 40, 40, 300, 0);
    let (lo, hi) = ([-60, 80, -60], [60, 120, 60]);
    let quads = floor_area(box_faces(lo, hi, 0, false), &light, true, Class::Umbra);
    let quads_alone = floor_area(box_faces(lo, hi, 0, false), &light, false, Class::Umbra);
    let triangles = floor_area(box_faces(lo, hi, 0x555, false), &light, true, Class::Umbra);
    let alone = floor_area(box_faces(lo, hi, 0x555, false), &light, false, Class::Umbra);
    // From every light vertex the box's shadow on the floor is its top's
    // (the light is above the box), so the box's umbra is the top face's,
    // whether the top is one piece or its two triangles hide it together.
    assert!(quads > 0.0);
    assert!(
        (quads - quads_alone).abs() <= 1e-9 * quads,
        "{quads} vs {quads_alone}"
    );
    assert!(
        (quads - triangles).abs() <= 1e-9 * quads,
        "{quads} vs {triangles}"
    );
    // No one triangle hides the light from most of it.
    assert!(
        alone < 0.9 * triangles,
        "the triangles alone: {alone}, together {triangles}"
    );
}

#[test]
fn two_triangles_of_a_quad_form_one_flat_group() {
    let (a, b, c, d) = (gp(0, 10, 0), gp(10, 10, 0), gp(10, 10, -10), gp(0, 10, -10));
    let t = |p: &[GridPoint]| ConvexPolygon::from_grid_points(p, 0).unwrap();
    let pieces = [t(&[a, b, c]), t(&[a, c, d])];
    let groups = convex_groups(&pieces, &[Some(0), Some(0)]);
    assert_eq!(groups.len(), 1);
    assert!(groups[0].is_flat());
    // In different objects they form none.
    assert!(convex_groups(&pieces, &[Some(0), Some(1)]).is_empty());
    // Nor when one casts no shadow.
    assert!(convex_groups(&pieces, &[Some(0), None]).is_empty());
    // An L of three squares is no convex polygon.
    let e = gp(20, 10, 0);
    let f = gp(20, 10, -10);
    let g = gp(0, 10, -20);
    let h = gp(10, 10, -20);
    let l_shape = [t(&[a, b, c, d]), t(&[b, e, f, c]), t(&[d, c, h, g])];
    assert!(convex_groups(&l_shape, &[Some(0); 3]).is_empty());
    // A row of two squares is.
    let row = [t(&[a, b, c, d]), t(&[b, e, f, c])];
    assert_eq!(convex_groups(&row, &[Some(0); 2]).len(), 1);
}

#[test]
fn bodies_two_faces_short_or_shared_form_no_group() {
    let (lo, hi) = ([0, 100, 0], [10, 110, 10]);
    // One face short (or half a face, a triangle), a box is a group
    // (closed by that face); two faces short, none.
    let mut half = box_faces(lo, hi, 0x555, false);
    half.pop();
    assert_eq!(convex_groups(&half, &vec![Some(0); half.len()]).len(), 1);
    let mut open = box_faces(lo, hi, 0, false);
    open.pop();
    assert_eq!(convex_groups(&open, &vec![Some(0); open.len()]).len(), 1);
    open.pop();
    assert!(convex_groups(&open, &vec![Some(0); open.len()]).is_empty());
    // Two boxes stacked face to face: the shared square's edges are
    // matched twice, so neither closed surface is found (no claim is made).
    let mut two = box_faces([0, 100, 0], [10, 110, 10], 0, false);
    two.extend(box_faces([0, 110, 0], [10, 120, 10], 0, false));
    assert!(convex_groups(&two, &vec![Some(0); two.len()]).is_empty());
    // In objects of their own, each is its body.
    let objects: Vec<Option<u32>> = (0..12).map(|k| Some(k / 6)).collect();
    assert_eq!(convex_groups(&two, &objects).len(), 2);
    // A box facing in is a group all the same.
    let inward = box_faces(lo, hi, 0, true);
    assert_eq!(convex_groups(&inward, &[Some(0); 6]).len(), 1);
}

/// A light held in a closed box (strictly inside it, or in its top face's
/// plane facing into it): every point outside sees none of it, and the
/// box's inside, two-sided, receives it.
#[test]
fn a_box_that_holds_the_light_in_darkens_everything_outside() {
    let floor = ConvexPolygon::from_grid_points(
        &[
            gp(-200, 0, -200),
            gp(-200, 0, 200),
            gp(200, 0, 200),
            gp(200, 0, -200),
        ],
        0,
    )
    .unwrap();
    for (height, cuts, inward) in [(80, 0, false), (100, 0, false), (100, 0x3f, true)] {
        // The box [-20, 20] x [60, 100] x [-20, 20], its faces cut or not,
        // facing out or in; the light facing down at `height`: inside it,
        // or in its top face's plane.
        let top = height;
        let light = light(-10, -10, 20, 20, height, 0);
        let faces = box_faces([-20, 60, -20], [20, 100, 20], cuts, inward);
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        assert_eq!(groups.len(), 1);
        let parts = groups[0].enclosing_umbra(&light);
        assert!(!parts.is_empty(), "light at {top}");
        let mut pieces = vec![floor.clone()];
        pieces.extend(faces.iter().cloned());
        let pieces: Vec<ConvexPolygon> = pieces
            .into_iter()
            .enumerate()
            .map(|(k, p)| p.with_source(k as u32))
            .collect();
        let two_sided = PieceFlags {
            two_sided: true,
            ..PieceFlags::default()
        };
        let mut flags = vec![two_sided; pieces.len()];
        flags[0] = PieceFlags::default();
        let objects: Vec<u32> = (0..pieces.len()).map(|k| u32::from(k > 0)).collect();
        let groups = ShadowGroups::of_objects(&pieces, &flags, &objects);
        let out = compute_shadows_with_groups(
            &pieces,
            &flags,
            &groups,
            &[SceneLight::Area(light.clone())],
            &BuildOptions::default(),
        )
        .unwrap();
        let area = |source: u32, class: Class| -> f64 {
            out.fragments
                .iter()
                .filter(|f| f.polygon.source() == source && Class::of(f, 0) == class)
                .map(|f| f.polygon.area())
                .sum()
        };
        assert!(
            (area(0, Class::Umbra) - floor.area()).abs() < 1e-9,
            "light at {top}"
        );
        // The bottom face, lit from inside on its two-sided back.
        let bottom = 1 + faces
            .iter()
            .position(|f| (0..f.len()).all(|k| f.vertex_grid_point(k).unwrap().y == 60))
            .unwrap() as u32;
        assert!(area(bottom, Class::Umbra) < 1e-9, "light at {top}");
    }
    // Facing out of the top face, the light is not held in.
    let out = light(-10, -10, 20, 20, 100, 0);
    let flipped = AreaSource::new(out.polygon().flipped()).unwrap();
    let faces = box_faces([-20, 60, -20], [20, 100, 20], 0, false);
    let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
    assert!(groups[0].enclosing_umbra(&flipped).is_empty());
    // Nor is one partly outside the box.
    let wide = light(-30, -10, 60, 20, 80, 0);
    assert!(groups[0].enclosing_umbra(&wide).is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A box one face short (its other faces whole or cut into triangles,
    /// facing out or in) hides from every point outside it what the closed
    /// box does: strictly inside an umbra part no point of the light is
    /// seen past its faces; outside every part and outside the box some
    /// light vertex is.
    #[test]
    fn an_open_box_hides_what_the_closed_one_does_from_outside(
        lo in prop::array::uniform3(-80_i64..40),
        size in prop::array::uniform3(6_i64..60),
        cuts in any::<u32>(),
        missing in 0_usize..6,
        inward in any::<bool>(),
        light in light_strategy(),
        points in prop::collection::vec(prop::array::uniform3(-150_i64..150), 200),
    ) {
        let lo = [lo[0], 40 + lo[1].rem_euclid(60), lo[2]];
        let hi = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
        // The missing face whole; the pieces before it, one or two a face.
        let cuts = cuts & !(3 << (2 * missing));
        let pieces_of = |f: usize| if matches!((cuts >> (2 * f)) & 3, 1 | 2) { 2 } else { 1 };
        let at: usize = (0..missing).map(pieces_of).sum();
        let mut faces = box_faces(lo, hi, cuts, inward);
        faces.remove(at);
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        prop_assert_eq!(groups.len(), 1);
        prop_assert!(groups[0].umbra_planes(&light).is_none());
        prop_assert!(groups[0].penumbra_planes(&light).is_none());
        let parts = groups[0].umbra_parts(&light);
        if parts.is_empty() {
            // Only when the box reaches the light's plane.
            prop_assert!(reaches_light_plane(&faces, &light));
            return Ok(());
        }
        let (casters, corners, inside_light) = oracle(&faces, &light);
        for c in points {
            let p = gp(c[0], c[1] + 40, c[2]);
            let on_a_plane = faces.iter().any(|f| side_of_point(f.support(), p) == Side::On)
                || parts.iter().flatten().any(|q| side_of_point(q, p) == Side::On);
            if on_a_plane {
                continue;
            }
            let q = p.to_f64();
            let inside_box = (0..3).all(|a| (lo[a] as f64) < q[a] && q[a] < hi[a] as f64);
            let in_part = parts
                .iter()
                .any(|part| part.iter().all(|plane| side_of_point(plane, p) == Side::Back));
            prop_assert!(!(inside_box && in_part), "{q:?} inside the box in an umbra part");
            if in_part {
                prop_assert!(all_hidden(q, &inside_light, &casters), "{q:?} in the umbra sees the light");
            } else if !inside_box {
                prop_assert!(!all_hidden(q, &corners, &casters), "{q:?} outside the umbra sees no light vertex");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A quad whose fourth corner the grid moved off the plane of the
    /// other three, given as two triangles (along either diagonal): a
    /// group, closed by the other diagonal's triangles into a thin
    /// tetrahedron, whose umbra parts hold exactly the points the two
    /// triangles hide all of the light from (outside them).
    #[test]
    fn a_bent_quad_hides_the_light_where_its_triangles_do_together(
        corner in prop::array::uniform3(-60_i64..20),
        u in (10_i64..80, -8_i64..8, -20_i64..20),
        v in (-20_i64..20, -8_i64..8, 10_i64..80),
        bend in prop_oneof![Just(-2_i64), Just(-1), Just(1), Just(2)],
        other_diagonal in any::<bool>(),
        light in light_strategy(),
        points in prop::collection::vec(prop::array::uniform3(-150_i64..150), 200),
    ) {
        let c = [corner[0], 100 + corner[1] / 4, corner[2]];
        let (u, v) = ([u.0, u.1, u.2], [v.0, v.1, v.2]);
        // A bent quad: the bend must take the fourth corner off the plane
        // of the other three, whose normal u x v then needs a y part
        // (else the four lie in one upright plane, the quad is flat and
        // folds over, and the triangles overlap: no body).
        prop_assume!(u[2] * v[0] - u[0] * v[2] != 0);
        let p = |s: i64, t: i64, dy: i64| gp(c[0] + s * u[0] + t * v[0], c[1] + s * u[1] + t * v[1] + dy, c[2] + s * u[2] + t * v[2]);
        let (a, b, d, e) = (p(0, 0, 0), p(1, 0, 0), p(1, 1, bend), p(0, 1, 0));
        let triangle = |x: GridPoint, y: GridPoint, z: GridPoint| ConvexPolygon::from_grid_points(&[x, y, z], 0).ok();
        let pieces = if other_diagonal {
            [triangle(a, b, d), triangle(a, d, e)]
        } else {
            [triangle(a, b, e), triangle(b, d, e)]
        };
        let [Some(t1), Some(t2)] = pieces else {
            return Ok(());
        };
        let faces = vec![t1, t2];
        // Not in one plane: no flat group.
        prop_assume!(faces[0].support() != faces[1].support());
        let groups = convex_groups(&faces, &[Some(0), Some(0)]);
        prop_assert_eq!(groups.len(), 1);
        let parts = groups[0].umbra_parts(&light);
        let (casters, corners, inside_light) = oracle(&faces, &light);
        let tetrahedron = [a, b, d, e];
        for c in points {
            let q = gp(c[0], c[1] - 60, c[2]);
            let on_a_plane = parts.iter().flatten().any(|plane| side_of_point(plane, q) == Side::On)
                || faces.iter().any(|f| side_of_point(f.support(), q) == Side::On);
            // Inside the thin tetrahedron the parts claim nothing.
            let inside = (0..4).all(|k| {
                let [x, y, z] = [0, 1, 2].map(|i| tetrahedron[(k + 1 + i) % 4]);
                let plane = bsp_core::Plane::through(x, y, z).unwrap();
                let side = side_of_point(&plane, q);
                side == Side::On || side == side_of_point(&plane, tetrahedron[k])
            });
            if on_a_plane || inside {
                continue;
            }
            let x = q.to_f64();
            let in_part = parts
                .iter()
                .any(|part| part.iter().all(|plane| side_of_point(plane, q) == Side::Back));
            if in_part {
                prop_assert!(all_hidden(x, &inside_light, &casters), "{x:?} in the umbra sees the light");
            } else if !parts.is_empty() {
                prop_assert!(!all_hidden(x, &corners, &casters), "{x:?} outside the umbra sees no light vertex");
            }
        }
    }
}
