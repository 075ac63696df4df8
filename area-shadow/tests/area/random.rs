//! Random scenes against the exact occlusion oracle: fragments partition
//! their pieces, and every class agrees with what a sample point sees.

use crate::oracle::{Caster, blocked, gp, light_samples, samples};
use area_shadow::{AreaSource, Class, SceneLight, SourceSide, compute_shadows};
use bsp_core::{BuildOptions, ConvexPolygon, GridPoint};
use proptest::prelude::*;
use svbsp::PieceFlags;

fn floor(half: i64) -> ConvexPolygon {
    ConvexPolygon::from_grid_points(
        &[
            gp(-half, 0, half),
            gp(half, 0, half),
            gp(half, 0, -half),
            gp(-half, 0, -half),
        ],
        0,
    )
    .unwrap()
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

fn scene() -> impl Strategy<Value = (Vec<ConvexPolygon>, AreaSource)> {
    (
        prop::collection::vec(
            (
                prop::array::uniform3(-200_i64..200),
                prop::collection::vec(prop::array::uniform3(-60_i64..60), 3),
            ),
            1..7,
        ),
        (
            -120_i64..60,
            -120_i64..60,
            20_i64..100,
            20_i64..100,
            180_i64..260,
            -40_i64..40,
        ),
    )
        .prop_map(|(tris, (x0, z0, w, d, h, tilt))| {
            let mut pieces = vec![floor(500)];
            for (c, corners) in tris {
                let pts: Vec<GridPoint> = corners
                    .iter()
                    .map(|o| {
                        // One triangle in three lies in a common plane y = 100.
                        let y = if c[1] % 3 == 0 {
                            100
                        } else {
                            120 + c[1] / 2 + o[1]
                        };
                        gp(c[0] + o[0], y, c[2] + o[2])
                    })
                    .collect();
                if let Ok(t) = ConvexPolygon::from_grid_points(&pts, 0) {
                    pieces.push(t);
                }
            }
            (pieces, light(x0, z0, w, d, h, tilt))
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(160))]

    #[test]
    fn classes_agree_with_the_occlusion_oracle((pieces, light) in scene()) {
        // Triangles are open, two-sided receivers here so that both of
        // their sides are checked.
        let flags: Vec<PieceFlags> = (0..pieces.len())
            .map(|k| PieceFlags { two_sided: k > 0, ..PieceFlags::default() })
            .collect();
        let out = compute_shadows(&pieces, &flags, &[SceneLight::Area(light.clone())], &BuildOptions::default()).unwrap();
        // Fragments partition their pieces.
        let mut area = vec![0.0; pieces.len()];
        for f in &out.fragments {
            f.polygon.check_invariants().unwrap();
            prop_assert!(f.polygon.support() == pieces[f.polygon.source() as usize].support());
            area[f.polygon.source() as usize] += f.polygon.area();
        }
        for (k, p) in pieces.iter().enumerate() {
            prop_assert!((area[k] - p.area()).abs() <= 1e-9 * p.area(), "piece {k}: {} vs {}", area[k], p.area());
        }
        let casters: Vec<Caster> = pieces.iter().map(Caster::new).collect();
        let lights = light_samples(light.polygon());
        let mut unconfirmed = Vec::new();
        for f in &out.fragments {
            let own = &pieces[f.polygon.source() as usize];
            let class = Class::of(f, 0);
            for q in samples(&f.polygon) {
                // Behind the light's plane, or on the wrong side of a one-
                // sided receiver, nothing arrives.
                let visible: Vec<bool> = lights
                    .iter()
                    .map(|x| {
                        in_front_of_light(&light, q)
                            && faces(own, flags[f.polygon.source() as usize].two_sided, q, *x)
                            && !blocked(q, *x, &casters, own)
                    })
                    .collect();
                let any = visible.iter().any(|v| *v);
                let all = visible.iter().all(|v| *v);
                match class {
                    Class::Lit => prop_assert!(all, "lit fragment of piece {} sees only part of the light at {q:?}", f.polygon.source()),
                    Class::Umbra => prop_assert!(!any, "umbra fragment of piece {} sees the light at {q:?}", f.polygon.source()),
                    Class::Penumbra => {
                        if all {
                            unconfirmed.push((q, f.polygon.source()));
                        }
                    }
                }
                if any && !all {
                    prop_assert_eq!(class, Class::Penumbra);
                }
            }
        }
        // A penumbra point whose samples all see the light must still have
        // part of it hidden: the visible part from `illum` (independent
        // f64 clipping) says how much.
        let corners: Vec<[f64; 3]> = light.vertices().map(GridPoint::to_f64).collect();
        let illum_light = illum::AreaLight::new(&corners, 1.0).unwrap();
        let mut visible = illum::VisiblePart::new();
        for (q, k) in unconfirmed {
            let own = &pieces[k as usize];
            let whole_light_in_front = match light.side_of(own.support()) {
                SourceSide::Front => true,
                // Two-sided, a receiver takes each part of a light its plane
                // cuts on its own side: all of the light.
                SourceSide::Back | SourceSide::Both => flags[k as usize].two_sided,
                SourceSide::In => false,
            };
            if !whole_light_in_front {
                continue; // part of the light is behind the receiver: penumbra at best
            }
            let occluders: Vec<Vec<[f64; 3]>> = casters
                .iter()
                .filter(|c| !c.polygon.support().is_coincident(own.support()))
                .map(|c| c.outline.clone())
                .collect();
            visible.compute(&illum_light, &occluders, q);
            let fraction = visible.area() / illum_light.area();
            prop_assert!(fraction < 1.0 - 1e-12, "penumbra point {q:?} of piece {k} sees {fraction} of the light");
        }
    }
}

fn in_front_of_light(light: &AreaSource, q: [f64; 3]) -> bool {
    let [a, b, c, d] = light.support().approx();
    a * q[0] + b * q[1] + c * q[2] + d > 0.0
}

/// Whether light from `x` arrives on a receiving side of `own` at `q`
/// (two-sided: on either side, grazing included).
fn faces(own: &ConvexPolygon, two_sided: bool, q: [f64; 3], x: [f64; 3]) -> bool {
    let [a, b, c, d] = own.support().approx();
    let side = a * x[0] + b * x[1] + c * x[2] + d;
    let _ = q;
    side > 0.0 || two_sided
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A union does not depend on the order its volumes went in: the area
    /// of every piece inside it is the same for the input order and its
    /// reverse, and over a skeleton of cells (coplanar occluders repeat
    /// planes along a path; a piece in such a plane must still be
    /// classified by its true cells).
    #[test]
    fn union_is_independent_of_insertion_order((pieces, light) in scene(), cells in 2_usize..40) {
        let volumes: Vec<_> = pieces
            .iter()
            .flat_map(|p| area_shadow::cast_volumes(p, &light).penumbra)
            .collect();
        let mut forward = area_shadow::VolumeTree::new();
        let mut backward = area_shadow::VolumeTree::new();
        for v in &volumes {
            forward.insert(v.clone());
        }
        for v in volumes.iter().rev() {
            backward.insert(v.clone());
        }
        // Over a skeleton of axis-aligned cells around the pieces, the
        // union is the same set too.
        let (mut lo, mut hi) = ([i32::MAX; 3], [i32::MIN; 3]);
        for p in &pieces {
            for q in (0..p.len()).filter_map(|i| p.vertex_grid_point(i)) {
                for (i, c) in [q.x, q.y, q.z].into_iter().enumerate() {
                    lo[i] = lo[i].min(c);
                    hi[i] = hi[i].max(c);
                }
            }
        }
        let mut celled = area_shadow::VolumeTree::with_cells(lo, hi, cells);
        for v in &volumes {
            celled.insert(v.clone());
        }
        for (k, p) in pieces.iter().enumerate() {
            let a: f64 = forward.partition(p.clone()).inside.iter().map(ConvexPolygon::area).sum();
            let b: f64 = backward.partition(p.clone()).inside.iter().map(ConvexPolygon::area).sum();
            let c: f64 = celled.partition(p.clone()).inside.iter().map(ConvexPolygon::area).sum();
            prop_assert!((a - b).abs() <= 1e-9 * p.area(), "piece {k}: {a} vs {b}");
            prop_assert!((a - c).abs() <= 1e-9 * p.area(), "piece {k}: {a} vs {c} over {cells} cells");
        }
    }
}
