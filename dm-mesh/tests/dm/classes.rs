//! DM cells against truth: the exact occlusion oracle at interior points,
//! and area-shadow's independent classification (penumbra and umbra trees
//! of the whole scene) area for area.

use crate::common::{
    TestScene, bumpy_bodies, class_areas, closed_surface_flags, cuboid, facing_boxes, floor,
    ring_bodies, scene, scene_with, triangulated_cuboid, two_sided_flags,
};
use crate::oracle::{hidden, interior_samples};
use area_shadow::{Class, SceneLight, ShadowGroups, compute_shadows_with_groups};
use bsp_core::BuildOptions;
use dm_mesh::{CellClass, DmOptions, OverlapKind};
use proptest::prelude::*;
use svbsp::PieceFlags;

fn check_against_area_shadow(t: &TestScene) -> Result<(), TestCaseError> {
    check_against_area_shadow_with(t, DmOptions::default())
}

pub fn check_against_area_shadow_with(
    t: &TestScene,
    options: DmOptions,
) -> Result<(), TestCaseError> {
    let (scene, ids) = t.build_with(options);
    scene.check_invariants().map_err(TestCaseError::fail)?;
    let polygons = t.polygons();
    let flags: Vec<PieceFlags> = t
        .objects
        .iter()
        .flat_map(|(ps, f)| std::iter::repeat_n(*f, ps.len()))
        .collect();
    let numbered: Vec<_> = polygons
        .iter()
        .enumerate()
        .map(|(k, p)| p.clone().with_source(k as u32))
        .collect();
    // Bodies form per object in both pipelines (and join across objects
    // where they touch), as `umbra shadow` and `umbra dm` group them.
    let objects: Vec<u32> = t
        .objects
        .iter()
        .enumerate()
        .flat_map(|(o, (ps, _))| std::iter::repeat_n(o as u32, ps.len()))
        .collect();
    let groups = ShadowGroups::of_objects(&numbered, &flags, &objects);
    let light = SceneLight::Area(t.light.clone());
    let out = compute_shadows_with_groups(
        &numbered,
        &flags,
        &groups,
        &[light],
        &BuildOptions::default(),
    )
    .unwrap();
    let mut truth = vec![[0.0; 3]; polygons.len()];
    for f in &out.fragments {
        let k = match Class::of(f, 0) {
            Class::Lit => 0,
            Class::Penumbra => 1,
            Class::Umbra => 2,
        };
        truth[f.polygon.source() as usize][k] += f.polygon.area();
    }
    let pieces: Vec<_> = ids
        .iter()
        .flat_map(|id| scene.object_pieces(*id).unwrap().to_vec())
        .collect();
    for (k, piece) in pieces.iter().enumerate() {
        let dm = scene.receiver(*piece).unwrap();
        dm.check_invariants().map_err(TestCaseError::fail)?;
        let got = class_areas(&scene, *piece);
        let scale = polygons[k].area();
        for c in 0..3 {
            prop_assert!(
                (got[c] - truth[k][c]).abs() <= 1e-9 * scale,
                "piece {k} class {c}: dm {} vs area-shadow {}",
                got[c],
                truth[k][c]
            );
        }
    }
    Ok(())
}

/// Cells against the exact occlusion oracle. With `one_body` (the only
/// occluder is one convex body) where the light is all hidden is exactly
/// the body's umbra, so a penumbra cell must also see some of the light.
fn check_against_oracle(t: &TestScene, one_body: bool) -> Result<(), TestCaseError> {
    let (scene, _) = t.build();
    let casters: Vec<_> = t
        .objects
        .iter()
        .filter(|(_, f)| f.casts_shadows)
        .flat_map(|(ps, _)| ps.clone())
        .collect();
    let lights = interior_samples(t.light.polygon(), 8);
    let [la, lb, lc, ld] = t.light.support().approx();
    for (_, dm) in scene.receivers() {
        let own = dm.polygon().clone();
        let [a, b, c, d] = own.support().approx();
        for (f, cell) in dm.cells() {
            let class = dm.class(cell, 0);
            let polygon = dm.mesh().face_polygon(f, 0).unwrap();
            let centre = polygon.centroid();
            let mut points = vec![centre];
            for v in polygon.vertices_f64() {
                points.push(std::array::from_fn(|k| 0.75 * v[k] + 0.25 * centre[k]));
            }
            // Penumbra needs one interior witness with part of the light
            // hidden (the class is the cell's; a cell that is really lit has
            // none, and a cell only partly right shows in the exact areas
            // compared with area-shadow). In a cell smaller than a
            // millionth of a grid cell (a sliver where the penumbra's
            // boundary meets the receiver's) the hidden part is below
            // f64's resolution: the oracle cannot tell there.
            let mut witness =
                class != CellClass::Penumbra || !full_reach(t, &own) || polygon.area() < 1e-6;
            let mut lit_witness =
                !one_body || class != CellClass::Penumbra || polygon.area() < 1e-6;
            let mut closest = 0.0_f64;
            for p in points {
                let seen: Vec<bool> = lights
                    .iter()
                    .map(|x| {
                        let in_front = la * p[0] + lb * p[1] + lc * p[2] + ld > 0.0;
                        let side = a * x[0] + b * x[1] + c * x[2] + d;
                        // Two-sided: from either side, grazing included.
                        let faces = side > 0.0 || two_sided(t, &own);
                        in_front && faces && !hidden(p, *x, &casters, &own)
                    })
                    .collect();
                let (any, all) = (seen.iter().any(|s| *s), seen.iter().all(|s| *s));
                match class {
                    CellClass::Lit => {
                        prop_assert!(all, "lit cell sees only part of the light at {p:?}")
                    }
                    CellClass::Umbra => prop_assert!(!any, "umbra cell sees the light at {p:?}"),
                    CellClass::Penumbra if all => {
                        // The samples miss a thin hidden sliver: the
                        // visible part of the light (illum's independent
                        // f64 clipping past every caster) may still lack
                        // some area.
                        let fraction = visible_fraction(t, &casters, &own, p);
                        witness |= fraction < 1.0 - 1e-12;
                        closest = closest.max(1.0 - fraction);
                    }
                    CellClass::Penumbra => witness = true,
                }
                if class == CellClass::Penumbra && !lit_witness {
                    // A sliver seen past the body's edge may fall between
                    // the samples: illum's visible part says.
                    lit_witness = any || visible_fraction(t, &casters, &own, p) > 1e-12;
                }
            }
            prop_assert!(
                lit_witness,
                "a penumbra cell of one body sees none of the light"
            );
            prop_assert!(
                witness,
                "no point of a penumbra cell has light hidden (at most {closest})"
            );
        }
    }
    Ok(())
}

fn visible_fraction(
    t: &TestScene,
    casters: &[bsp_core::ConvexPolygon],
    own: &bsp_core::ConvexPolygon,
    p: [f64; 3],
) -> f64 {
    let corners: Vec<[f64; 3]> = t.light.vertices().map(|g| g.to_f64()).collect();
    let light = illum::AreaLight::new(&corners, 1.0).unwrap();
    let occluders: Vec<Vec<[f64; 3]>> = casters
        .iter()
        .filter(|c| !c.support().is_coincident(own.support()))
        .map(|c| c.vertices_f64())
        .collect();
    let mut part = illum::VisiblePart::new();
    part.compute(&light, &occluders, p);
    part.area() / light.area()
}

fn two_sided(t: &TestScene, own: &bsp_core::ConvexPolygon) -> bool {
    t.objects
        .iter()
        .any(|(ps, f)| f.two_sided && ps.iter().any(|p| p == own))
}

/// Whether the whole light is on a receiving side of `own` (otherwise an
/// unoccluded cell is penumbra).
fn full_reach(t: &TestScene, own: &bsp_core::ConvexPolygon) -> bool {
    use area_shadow::SourceSide;
    match t.light.side_of(own.support()) {
        SourceSide::Front => true,
        // Two-sided, a receiver takes each part of a light its plane cuts
        // on its own side: all of the light.
        SourceSide::Back | SourceSide::Both => two_sided(t, own),
        SourceSide::In => false,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn cells_agree_with_area_shadow(t in scene()) {
        check_against_area_shadow(&t)?;
    }

    #[test]
    fn cells_agree_with_the_occlusion_oracle(t in scene()) {
        check_against_oracle(&t, false)?;
    }

    /// A box whose faces may be cut into triangles: its umbra is the
    /// body's, not just what one face hides alone.
    #[test]
    fn one_body_has_exact_cells(
        lo in prop::array::uniform3(-80_i64..40),
        size in prop::array::uniform3(6_i64..70),
        cuts in any::<u32>(),
        light in (-120_i64..60, -120_i64..60, 20_i64..100, 20_i64..100, 180_i64..260, -40_i64..40),
    ) {
        let lo = [lo[0], 40 + lo[1].rem_euclid(60), lo[2]];
        let hi = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
        let (x0, z0, w, d, h, tilt) = light;
        let t = TestScene {
            objects: vec![
                (vec![floor(500)], PieceFlags::default()),
                (triangulated_cuboid(lo, hi, cuts), closed_surface_flags()),
            ],
            light: crate::common::light(x0, z0, w, d, h, tilt),
        };
        // Below the light's plane (one reaching it keeps its faces' umbrae).
        let below = t.objects[1].0.iter().all(|f| (0..f.len()).all(|k| {
            t.light.side_of_point(f.vertex_grid_point(k).unwrap()) == bsp_core::Side::Front
        }));
        prop_assume!(below);
        check_against_oracle(&t, true)?;
        check_against_area_shadow(&t)?;
    }

    /// A box and the floor in one object said to have closed parts: the
    /// box is one, whose faces turned away from the light cast nothing, as
    /// when it is an object of its own; the cells are the same, and agree
    /// with the oracle.
    #[test]
    fn a_closed_part_of_an_object_casts_as_a_closed_object(
        lo in prop::array::uniform3(-80_i64..40),
        size in prop::array::uniform3(6_i64..70),
        cuts in any::<u32>(),
        light in (-120_i64..60, -120_i64..60, 20_i64..100, 20_i64..100, 180_i64..260, -40_i64..40),
    ) {
        let lo = [lo[0], 40 + lo[1].rem_euclid(60), lo[2]];
        let hi = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
        let (x0, z0, w, d, h, tilt) = light;
        let light = crate::common::light(x0, z0, w, d, h, tilt);
        let boxed = triangulated_cuboid(lo, hi, cuts);
        let mut together = vec![floor(500)];
        together.extend(boxed.iter().cloned());
        let one = TestScene {
            objects: vec![(together, closed_surface_flags())],
            light: light.clone(),
        };
        let two = TestScene {
            objects: vec![
                (vec![floor(500)], PieceFlags::default()),
                (boxed, closed_surface_flags()),
            ],
            light,
        };
        let ((a, a_ids), (b, b_ids)) = (one.build(), two.build());
        let a_pieces = a.object_pieces(a_ids[0]).unwrap();
        let b_pieces: Vec<_> = b_ids.iter().flat_map(|&id| b.object_pieces(id).unwrap().iter().copied()).collect();
        prop_assert_eq!(a_pieces.len(), b_pieces.len());
        for (&pa, &pb) in a_pieces.iter().zip(&b_pieces) {
            let (ra, rb) = (a.receiver(pa).unwrap(), b.receiver(pb).unwrap());
            prop_assert_eq!(ra.cell_count(), rb.cell_count());
            prop_assert_eq!(ra.node_count(), rb.node_count());
            let (ca, cb) = (class_areas(&a, pa), class_areas(&b, pb));
            for (x, y) in ca.iter().zip(&cb) {
                prop_assert!((x - y).abs() <= 1e-9 * (1.0 + x.abs()), "{:?} {:?}", ca, cb);
            }
        }
        check_against_oracle(&one, false)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Many objects: the floor's tree starts tiled.
    #[test]
    fn tiled_cells_agree_with_the_occlusion_oracle(t in scene_with(9..14)) {
        check_against_oracle(&t, false)?;
    }

    /// The shadow overlap cube finds every pair that matters too.
    #[test]
    fn cube_pairs_agree_with_area_shadow(t in scene_with(3..12)) {
        let options = DmOptions { overlap: OverlapKind::Cube, ..DmOptions::default() };
        check_against_area_shadow_with(&t, options)?;
    }

    /// Faces in contact between two boxes under a light across their
    /// plane: two-sided, each side's part of the light is hidden by the
    /// box on that side.
    #[test]
    fn boxes_face_to_face_agree_with_area_shadow_and_the_oracle(t in facing_boxes()) {
        for overlap in [OverlapKind::Grid, OverlapKind::Cube] {
            check_against_area_shadow_with(&t, DmOptions { overlap, ..DmOptions::default() })?;
        }
        check_against_oracle(&t, false)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]

    /// Bumpy bodies far from convex: the umbra of their kernels' cores
    /// is where area-shadow puts it, and the cells' classes hold against
    /// the oracle.
    #[test]
    fn bumpy_bodies_agree_with_area_shadow_and_the_oracle(t in bumpy_bodies()) {
        check_against_area_shadow(&t)?;
        check_against_oracle(&t, false)?;
    }

    /// A ring (no kernel) beside a bumpy body: the umbrae of the ring's
    /// cores are where area-shadow puts them, and the cells' classes hold
    /// against the oracle.
    #[test]
    fn rings_agree_with_area_shadow_and_the_oracle(t in ring_bodies()) {
        check_against_area_shadow(&t)?;
        check_against_oracle(&t, false)?;
    }
}

/// Two two-sided boxes of two objects face to face in `x = 30` (the first
/// one's face inside the second's), the light across that plane: the
/// faces in contact see the part of the light at `x < 30` only through
/// the first box and the rest only through the second, so they are umbra
/// though neither box hides all of the light from them; with the second
/// box gone the first one's face is penumbra.
#[test]
fn two_sided_boxes_face_to_face_hide_the_light_together() {
    let t = TestScene {
        objects: vec![
            (vec![floor(500)], PieceFlags::default()),
            (cuboid([0, 40, 0], [30, 70, 20]), two_sided_flags()),
            (cuboid([30, 40, -10], [60, 80, 30]), two_sided_flags()),
        ],
        light: crate::common::light(10, -10, 40, 40, 200, 0),
    };
    for overlap in [OverlapKind::Grid, OverlapKind::Cube] {
        let options = DmOptions {
            overlap,
            ..DmOptions::default()
        };
        let (mut scene, ids) = t.build_with(options);
        scene.check_invariants().unwrap();
        // Faces 3 and 2 of the boxes: `x = 30` (30 x 20, and 40 x 40).
        let first = scene.object_pieces(ids[1]).unwrap()[3];
        let second = scene.object_pieces(ids[2]).unwrap()[2];
        assert_eq!(class_areas(&scene, first), [0.0, 0.0, 600.0], "{overlap:?}");
        let [lit, penumbra, umbra] = class_areas(&scene, second);
        assert_eq!(lit, 0.0);
        assert!((umbra - 600.0).abs() < 1e-9, "{overlap:?}: umbra {umbra}");
        assert!((penumbra - 1000.0).abs() < 1e-9, "{overlap:?}: {penumbra}");
        check_against_area_shadow_with(&t, options).unwrap();
        scene.remove_object(ids[2]).unwrap();
        scene.check_invariants().unwrap();
        assert_eq!(class_areas(&scene, first), [0.0, 600.0, 0.0], "{overlap:?}");
    }
    check_against_oracle(&t, false).unwrap();
}

/// Two boxes side by side, touching over a 1 x 1 square, under a light
/// across their contact plane (found by `cube_pairs_agree_with_area_shadow`):
/// the first box's face there is covered by the second, so it sees none of
/// the light, in both pipelines.
#[test]
fn a_face_against_a_box_is_in_its_umbra() {
    let t = TestScene {
        objects: vec![
            (vec![floor(500)], PieceFlags::default()),
            (
                cuboid([-20, 30, -92], [14, 70, -82]),
                closed_surface_flags(),
            ),
            (cuboid([14, 69, -83], [24, 79, -73]), closed_surface_flags()),
        ],
        light: crate::common::light(0, 0, 20, 20, 180, 0),
    };
    for overlap in [OverlapKind::Grid, OverlapKind::Cube] {
        let (scene, ids) = t.build_with(DmOptions {
            overlap,
            ..DmOptions::default()
        });
        scene.check_invariants().unwrap();
        // The first box's face x = 14, facing the second box.
        let face = scene.object_pieces(ids[1]).unwrap()[3];
        let [lit, penumbra, umbra] = class_areas(&scene, face);
        assert_eq!(lit, 0.0);
        assert!((umbra - 1.0).abs() < 1e-9, "{overlap:?}: umbra {umbra}");
        assert!(
            (penumbra - 399.0).abs() < 1e-9,
            "{overlap:?}: penumbra {penumbra}"
        );
        check_against_area_shadow_with(
            &t,
            DmOptions {
                overlap,
                ..DmOptions::default()
            },
        )
        .unwrap();
    }
}

/// A two-sided triangle through a box, under a light on both of its sides
/// (found by `cells_agree_with_area_shadow` with 400 cases): where it is
/// inside the box it sees none of the light, in both pipelines.
#[test]
fn a_two_sided_triangle_through_a_box_is_dark_inside_it() {
    use crate::common::gp;
    let triangle = bsp_core::ConvexPolygon::from_grid_points(
        &[gp(-44, 48, 118), gp(-55, 106, 54), gp(-13, 94, 90)],
        0,
    )
    .unwrap();
    let t = TestScene {
        objects: vec![
            (vec![floor(500)], PieceFlags::default()),
            (vec![triangle], two_sided_flags()),
            (cuboid([-40, 39, 78], [-30, 78, 91]), closed_surface_flags()),
        ],
        light: crate::common::light(-41, 0, 22, 20, 180, 0),
    };
    assert_eq!(
        t.light.side_of(t.objects[1].0[0].support()),
        area_shadow::SourceSide::Both
    );
    for overlap in [OverlapKind::Grid, OverlapKind::Cube] {
        check_against_area_shadow_with(
            &t,
            DmOptions {
                overlap,
                ..DmOptions::default()
            },
        )
        .unwrap();
    }
    check_against_oracle(&t, false).unwrap();
}
