//! A convex body that casts one unit in place of its polygons
//! (`DmOptions::convex_bodies`): cells and irradiance against the oracles,
//! and against each polygon casting its own unit.

use crate::classes::check_against_area_shadow_with;
use crate::common::{
    TestScene, class_areas, closed_surface_flags, floor, light_class_areas, triangulated_cuboid,
    two_sided_flags,
};
use crate::illumination::check_vertices;
use dm_mesh::{DmOptions, DmScene, ObjectId, PieceId};
use proptest::prelude::*;
use std::collections::BTreeSet;
use svbsp::PieceFlags;

/// The units on `receiver` whose occluder is a piece of `object`.
fn units_of(scene: &DmScene, receiver: PieceId, object: ObjectId) -> BTreeSet<u32> {
    let dm = scene.receiver(receiver).unwrap();
    dm.cells()
        .flat_map(|(_, cell)| cell.entries().iter().map(|e| e.unit))
        .filter(|&u| {
            dm.unit_source(u)
                .is_some_and(|(o, _)| scene.piece_object(o) == Some(object))
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A box whose faces may be cut into triangles, may face in and may be
    /// two-sided, over a floor, below a light.
    #[test]
    fn a_convex_body_casts_one_unit(
        lo in prop::array::uniform3(-80_i64..40),
        size in prop::array::uniform3(6_i64..70),
        cuts in any::<u32>(),
        inward in any::<bool>(),
        two_sided in any::<bool>(),
        light in (-120_i64..60, -120_i64..60, 20_i64..100, 20_i64..100, 180_i64..260, -40_i64..40),
    ) {
        let lo = [lo[0], 40 + lo[1].rem_euclid(60), lo[2]];
        let hi = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
        let (x0, z0, w, d, h, tilt) = light;
        let mut faces = triangulated_cuboid(lo, hi, cuts);
        if inward {
            faces = faces.iter().map(|f| f.flipped()).collect();
        }
        // (A surface facing in is not a closed surface's outside.) A
        // two-sided face of the body sees light through the body from
        // behind when the light is on both sides of it.
        let flags = PieceFlags { closed_surface: !inward, two_sided, ..PieceFlags::default() };
        let t = TestScene {
            objects: vec![(vec![floor(500)], PieceFlags::default()), (faces, flags)],
            light: crate::common::light(x0, z0, w, d, h, tilt),
        };
        let below = t.objects[1].0.iter().all(|f| (0..f.len()).all(|k| {
            t.light.side_of_point(f.vertex_grid_point(k).unwrap()) == bsp_core::Side::Front
        }));
        prop_assume!(below);
        let (mut scene, ids, floor_piece) = t.build_over_floor()?;
        check_vertices(&t, &mut scene)?;
        check_against_area_shadow_with(&t, DmOptions::default())?;
        // Each polygon casting its own unit: the same classes.
        let per_polygon = DmOptions { convex_bodies: false, ..DmOptions::default() };
        let (faces_scene, faces_ids) = t.build_with(per_polygon);
        // One unit on the floor where the polygons put any.
        let faces_floor = faces_scene.object_pieces(faces_ids[0]).unwrap()[0];
        prop_assert_eq!(
            units_of(&scene, floor_piece, ids[1]).len(),
            usize::from(!units_of(&faces_scene, faces_floor, faces_ids[1]).is_empty())
        );
        for (k, (id, other)) in ids.iter().zip(&faces_ids).enumerate() {
            let (a, b) = (scene.object_pieces(*id).unwrap(), faces_scene.object_pieces(*other).unwrap());
            for (pa, pb) in a.iter().zip(b) {
                let (x, y) = (class_areas(&scene, *pa), class_areas(&faces_scene, *pb));
                let scale = scene.piece_polygon(*pa).unwrap().area();
                for c in 0..3 {
                    prop_assert!(
                        (x[c] - y[c]).abs() <= 1e-9 * scale,
                        "object {k} class {c}: one unit {} vs per polygon {}", x[c], y[c]
                    );
                }
            }
        }
    }
}

/// A two-sided box under a light on both sides of one of its faces, and a
/// square whose shadow cuts that face into cells: from behind, the face
/// sees the light's part on its back only through the box, so the box
/// hides it (its polygons the light enters by, not those facing the
/// vertex, which lies on the box).
#[test]
fn a_two_sided_face_of_a_body_sees_nothing_through_it() {
    use crate::common::{cuboid, gp};
    let square = bsp_core::ConvexPolygon::from_grid_points(
        &[
            gp(25, 90, 10),
            gp(35, 90, 10),
            gp(35, 90, 30),
            gp(25, 90, 30),
        ],
        0,
    )
    .unwrap();
    let t = TestScene {
        objects: vec![
            (vec![floor(500)], PieceFlags::default()),
            (cuboid([0, 40, 0], [40, 80, 40]), two_sided_flags()),
            (vec![square], PieceFlags::default()),
        ],
        light: crate::common::light(-50, -50, 100, 100, 200, 0),
    };
    let (mut scene, ids) = t.build();
    // The face at x = 40 has cells of the square's shadow, so vertices
    // inside it.
    let side = scene
        .object_pieces(ids[1])
        .unwrap()
        .iter()
        .copied()
        .find(|&p| {
            let polygon = scene.piece_polygon(p).unwrap();
            polygon.vertices_f64().iter().all(|v| v[0] == 40.0)
        })
        .unwrap();
    let dm = scene.receiver(side).unwrap();
    assert!(units_of(&scene, side, ids[2]).len() == 1 && dm.cells().count() > 2);
    check_vertices(&t, &mut scene).unwrap();
}

/// Per receiver and light, the lit, penumbra and umbra areas.
fn areas_per_light(scene: &DmScene, pieces: &[PieceId], lights: usize) -> Vec<[f64; 3]> {
    pieces
        .iter()
        .flat_map(|&piece| (0..lights).map(move |light| light_class_areas(scene, piece, light)))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Two lights, one of whose planes may cut the box (the box then casts
    /// one unit under the other light only): per light the same classes
    /// as each polygon casting its own unit, and the same irradiance
    /// where both meshes have a vertex.
    #[test]
    fn a_body_under_two_lights_agrees_with_its_polygons(
        lo in prop::array::uniform3(-60_i64..40),
        size in prop::array::uniform3(6_i64..60),
        cuts in any::<u32>(),
        high in (-120_i64..60, -120_i64..60, 20_i64..100, 20_i64..100, 180_i64..260),
        low in (-120_i64..60, -120_i64..60, 20_i64..100, 20_i64..100, 40_i64..120),
    ) {
        use dm_mesh::DmLight;
        let lo = [lo[0], 20 + lo[1].rem_euclid(40), lo[2]];
        let hi = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
        let objects = vec![
            (vec![floor(500)], PieceFlags::default()),
            (triangulated_cuboid(lo, hi, cuts), closed_surface_flags()),
        ];
        let lights: Vec<DmLight> = [high, low]
            .into_iter()
            .map(|(x, z, w, d, h)| DmLight::new(crate::common::light(x, z, w, d, h, 0), 1.0).unwrap())
            .collect();
        let build = |convex_bodies| {
            let options = DmOptions { convex_bodies, ..DmOptions::default() };
            let (mut scene, ids) = DmScene::build_with(lights.clone(), objects.clone(), options).unwrap();
            scene.check_invariants().unwrap();
            scene.illuminate();
            let pieces: Vec<PieceId> =
                ids.iter().flat_map(|id| scene.object_pieces(*id).unwrap().to_vec()).collect();
            (scene, pieces)
        };
        let ((one, pa), (each, pb)) = (build(true), build(false));
        let (a, b) = (areas_per_light(&one, &pa, 2), areas_per_light(&each, &pb, 2));
        for (k, (x, y)) in a.iter().zip(&b).enumerate() {
            let scale = one.piece_polygon(pa[k / 2]).unwrap().area();
            for c in 0..3 {
                prop_assert!(
                    (x[c] - y[c]).abs() <= 1e-9 * scale,
                    "receiver {} light {} class {c}: one unit {} vs per polygon {}", k / 2, k % 2, x[c], y[c]
                );
            }
        }
        for (&ra, &rb) in pa.iter().zip(&pb) {
            let (da, db) = (one.receiver(ra).unwrap(), each.receiver(rb).unwrap());
            let mut at = std::collections::HashMap::new();
            for (v, vertex) in db.mesh().vertices() {
                at.insert(vertex.position.to_f64().map(f64::to_bits), each.vertex_irradiance(rb, v).unwrap());
            }
            for (v, vertex) in da.mesh().vertices() {
                let p = vertex.position.to_f64();
                let got = one.vertex_irradiance(ra, v).unwrap();
                if let Some(&want) = at.get(&p.map(f64::to_bits)) {
                    prop_assert!(
                        (got - want).abs() <= 1e-9 * got.abs().max(want.abs()) + 1e-12,
                        "vertex {p:?}: one unit {got} vs per polygon {want}"
                    );
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// A closed box that meets the light: up through the light's plane, or
    /// with its top face in it, over some of the light. The light shines
    /// into it there, so its faces turned away from the light hide light
    /// too (the closed surface's shortcut, casting only the faces towards
    /// the light, would let that light through).
    #[test]
    fn a_closed_box_the_light_shines_into(
        lo in prop::array::uniform3(-60_i64..40),
        size in prop::array::uniform3(10_i64..60),
        top_in_plane in any::<bool>(),
        cuts in any::<u32>(),
    ) {
        let h = 200;
        let lo = [lo[0], h - 10 - lo[1].rem_euclid(40), lo[2]];
        let hi = [
            lo[0] + size[0],
            if top_in_plane { h } else { h + 1 + size[1] },
            lo[2] + size[2],
        ];
        let light = crate::common::light(-40, -40, 80, 80, h, 0);
        // The box meets the light's rectangle.
        prop_assume!(lo[0] < 40 && hi[0] > -40 && lo[2] < 40 && hi[2] > -40);
        let t = TestScene {
            objects: vec![
                (vec![floor(400)], PieceFlags::default()),
                (triangulated_cuboid(lo, hi, cuts), closed_surface_flags()),
            ],
            light,
        };
        let (mut scene, _) = t.build();
        scene.check_invariants().map_err(TestCaseError::fail)?;
        check_vertices(&t, &mut scene)?;
    }
}
