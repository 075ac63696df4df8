//! Incremental updates against from-scratch builds: after random moves,
//! removals and additions every receiver has the same lit, penumbra and
//! umbra areas as a build of the final scene, the same class at random
//! points, and the same irradiance at vertices both meshes have; the trees
//! keep their invariants after every operation.

use crate::common::{
    CellPrint, Object, TestScene, bumpy_bodies, class_areas, concavity, cuboid, facing_boxes,
    floor, light, light_class_areas, plate_over_boxes, receiver_print, ring_bodies, scene,
    scene_with,
};
use crate::oracle::interior_samples;
use area_shadow::AreaSource;
use bsp_core::ConvexPolygon;
use dm_mesh::{CellClass, Deletion, DmLight, DmOptions, DmScene, ObjectId, OverlapKind, PieceId};
use proptest::prelude::*;
use std::collections::{BTreeMap, BTreeSet};
use svbsp::PieceFlags;

#[derive(Debug, Clone)]
enum Op {
    Move(usize, [i64; 3]),
    Remove(usize),
    ReAdd(usize),
}

fn ops() -> impl Strategy<Value = Vec<Op>> {
    prop::collection::vec(
        prop_oneof![
            3 => (1_usize..8, prop::array::uniform3(-40_i64..40)).prop_map(|(k, d)| Op::Move(k, d)),
            1 => (1_usize..8).prop_map(Op::Remove),
            1 => (1_usize..8).prop_map(Op::ReAdd),
        ],
        1..6,
    )
}

/// The scene's objects as they are now (`None`: removed).
struct Model {
    objects: Vec<Option<(Object, ObjectId)>>,
    removed: Vec<Option<Object>>,
}

fn check_all(scene: &DmScene) -> Result<(), TestCaseError> {
    scene.check_invariants().map_err(TestCaseError::fail)
}

fn apply(scene: &mut DmScene, model: &mut Model, op: &Op) -> Result<(), TestCaseError> {
    let since = scene.revision();
    let before: BTreeMap<PieceId, Vec<CellPrint>> = scene
        .receivers()
        .map(|(piece, _)| (piece, receiver_print(scene, piece)))
        .collect();
    let applied = apply_op(scene, model, op)?;
    check_all(scene)?;
    // Every receiver the op changed (new ones included) is listed as
    // changed; every other one holds what it held, bit for bit.
    prop_assert_eq!(scene.revision() > since, applied);
    let listed: BTreeSet<PieceId> = scene.receivers_changed_since(since).collect();
    for &piece in &listed {
        prop_assert!(
            scene.receiver(piece).is_some(),
            "{piece:?} listed, but gone"
        );
    }
    for (piece, _) in scene.receivers() {
        if !listed.contains(&piece) {
            prop_assert!(
                before.get(&piece) == Some(&receiver_print(scene, piece)),
                "{piece:?} changed, but not listed"
            );
        }
    }
    Ok(())
}

/// Applies `op` to the scene and the model; whether it changed anything
/// (an object to move or remove was there, one to add back had been
/// removed).
fn apply_op(scene: &mut DmScene, model: &mut Model, op: &Op) -> Result<bool, TestCaseError> {
    let n = model.objects.len();
    match *op {
        Op::Move(k, d) => {
            let k = 1 + (k - 1) % (n - 1);
            if let Some(((polys, flags), id)) = model.objects[k].clone() {
                let moved: Vec<ConvexPolygon> =
                    polys.iter().map(|p| p.translated(d).unwrap()).collect();
                scene.translate_object(id, d).unwrap();
                model.objects[k] = Some(((moved, flags), id));
                return Ok(true);
            }
        }
        Op::Remove(k) => {
            let k = 1 + (k - 1) % (n - 1);
            if let Some((object, id)) = model.objects[k].take() {
                scene.remove_object(id).unwrap();
                let revision = scene.revision();
                prop_assert!(scene.remove_object(id).is_err());
                prop_assert_eq!(scene.revision(), revision, "a refused change is none");
                model.removed[k] = Some(object);
                return Ok(true);
            }
        }
        Op::ReAdd(k) => {
            let k = 1 + (k - 1) % (n - 1);
            if let Some(object) = model.removed[k].take() {
                let id = scene.add_object(object.0.clone(), object.1).unwrap();
                model.objects[k] = Some((object, id));
                return Ok(true);
            }
        }
    }
    Ok(false)
}

/// Receivers of the live objects, in model order, piece by piece.
fn pieces(scene: &DmScene, ids: &[ObjectId]) -> Vec<PieceId> {
    ids.iter()
        .flat_map(|id| scene.object_pieces(*id).unwrap().to_vec())
        .collect()
}

fn compare(
    a: &mut DmScene,
    ids_a: &[ObjectId],
    b: &mut DmScene,
    ids_b: &[ObjectId],
) -> Result<(), TestCaseError> {
    a.illuminate();
    b.illuminate();
    let (pa, pb) = (pieces(a, ids_a), pieces(b, ids_b));
    prop_assert_eq!(pa.len(), pb.len());
    for (&ra, &rb) in pa.iter().zip(&pb) {
        let (da, db) = (a.receiver(ra).unwrap(), b.receiver(rb).unwrap());
        prop_assert!(da.polygon() == db.polygon());
        let scale = da.polygon().area();
        let lights = a.lights().len();
        for light in 0..lights {
            let (xa, xb) = (
                light_class_areas(a, ra, light),
                light_class_areas(b, rb, light),
            );
            for c in 0..3 {
                prop_assert!(
                    (xa[c] - xb[c]).abs() <= 1e-9 * scale,
                    "light {light} class {c}: {} vs {}",
                    xa[c],
                    xb[c]
                );
            }
        }
        // Class of sample points of each cell of one, located exactly in
        // the other (by the cell planes, at points strictly inside).
        for (f, cell) in da.cells() {
            let polygon = da.mesh().face_polygon(f, 0).unwrap();
            let classes: Vec<CellClass> = (0..lights).map(|l| da.class(cell, l)).collect();
            for (g, other) in db.cells() {
                let q = db.mesh().face_polygon(g, 0).unwrap();
                // Overlap with area: clip one by the other's edge planes.
                let mut piece = Some(polygon.clone());
                for e in q.edges() {
                    piece = piece.and_then(|p| match p.split(e) {
                        bsp_core::Split::Back => Some(p),
                        bsp_core::Split::Both(back, _) => Some(back),
                        _ => None,
                    });
                }
                if piece.is_some() {
                    for (light, &class) in classes.iter().enumerate() {
                        prop_assert_eq!(
                            class,
                            db.class(other, light),
                            "cells overlap with different classes of light {}",
                            light
                        );
                    }
                }
            }
        }
        // Irradiance where both have a vertex.
        let mut at: BTreeMap<[u64; 3], f64> = BTreeMap::new();
        for (f, _) in db.cells() {
            for v in db.mesh().face_vertices(f) {
                let p = db.mesh().vertex(v).unwrap().position.to_f64();
                at.insert(p.map(f64::to_bits), b.vertex_irradiance(rb, v).unwrap());
            }
        }
        for (f, _) in da.cells() {
            for v in da.mesh().face_vertices(f) {
                let position = da.mesh().vertex(v).unwrap().position;
                let p = position.to_f64();
                if let Some(eb) = at.get(&p.map(f64::to_bits)) {
                    let ea = a.vertex_irradiance(ra, v).unwrap();
                    prop_assert!(
                        (ea - eb).abs() <= 1e-9 * ea.abs().max(eb.abs()) + 1e-15,
                        "{p:?}: {ea} vs {eb}"
                    );
                }
            }
        }
    }
    Ok(())
}

fn run(t: &TestScene, ops: &[Op]) -> Result<(), TestCaseError> {
    run_with(t, ops, DmOptions::default())
}

fn run_with(t: &TestScene, ops: &[Op], options: DmOptions) -> Result<(), TestCaseError> {
    run_movable(t, ops, options, &[])
}

/// [`run_with`], the objects at `movable` declared movable at the build.
fn run_movable(
    t: &TestScene,
    ops: &[Op],
    options: DmOptions,
    movable: &[usize],
) -> Result<(), TestCaseError> {
    run_under(std::slice::from_ref(&t.light), t, ops, options, movable)
}

/// [`run_movable`] under `sources` (the scene's own light ignored).
fn run_under(
    sources: &[AreaSource],
    t: &TestScene,
    ops: &[Op],
    options: DmOptions,
    movable: &[usize],
) -> Result<(), TestCaseError> {
    let lights = || -> Vec<DmLight> {
        sources
            .iter()
            .map(|s| DmLight::new(s.clone(), 1.0).unwrap())
            .collect()
    };
    let (mut scene, ids) =
        DmScene::build_movable(lights(), t.objects.clone(), movable, options).unwrap();
    scene.illuminate();
    check_all(&scene)?;
    let mut model = Model {
        objects: t.objects.iter().cloned().zip(ids).map(Some).collect(),
        removed: vec![None; t.objects.len()],
    };
    if model.objects.len() < 2 {
        return Ok(());
    }
    for op in ops {
        apply(&mut scene, &mut model, op)?;
    }
    let live: Vec<(Object, ObjectId)> = model.objects.iter().flatten().cloned().collect();
    let (mut fresh, fresh_ids) =
        DmScene::build(lights(), live.iter().map(|(o, _)| o.clone()).collect()).unwrap();
    let ids: Vec<ObjectId> = live.iter().map(|(_, id)| *id).collect();
    compare(&mut scene, &ids, &mut fresh, &fresh_ids)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn updates_agree_with_a_rebuild(t in scene(), ops in ops()) {
        run(&t, &ops)?;
    }

    /// Removing an object and adding it back gives the regions it had.
    #[test]
    fn remove_then_re_add_restores_the_regions(t in scene(), k in 1_usize..8) {
        let (mut scene, ids) = t.build();
        if ids.len() < 2 {
            return Ok(());
        }
        let k = 1 + (k - 1) % (ids.len() - 1);
        let before: Vec<[f64; 3]> = pieces(&scene, &ids).iter().map(|p| class_areas(&scene, *p)).collect();
        scene.remove_object(ids[k]).unwrap();
        check_all(&scene)?;
        let again = scene.add_object(t.objects[k].0.clone(), t.objects[k].1).unwrap();
        check_all(&scene)?;
        let mut order = ids.clone();
        order[k] = again;
        let after: Vec<[f64; 3]> = pieces(&scene, &order).iter().map(|p| class_areas(&scene, *p)).collect();
        for (x, y) in before.iter().zip(&after) {
            for c in 0..3 {
                prop_assert!((x[c] - y[c]).abs() <= 1e-9 * (x[0] + x[1] + x[2]));
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Objects declared movable at the build (merged after the static
    /// ones) give the regions of a plain build, before and after updates.
    #[test]
    fn movable_objects_agree_with_a_rebuild(
        t in scene_with(3..12),
        chosen in prop::collection::vec(1_usize..12, 1..4),
        ops in ops(),
    ) {
        let movable: Vec<usize> = chosen.into_iter().filter(|&k| k < t.objects.len()).collect();
        run_movable(&t, &[], DmOptions::default(), &movable)?;
        run_movable(&t, &ops, DmOptions::default(), &movable)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Under two lights (one of which may be tilted, or low enough for
    /// objects to reach its plane) updates agree with a rebuild light by
    /// light.
    #[test]
    fn updates_under_two_lights_agree_with_a_rebuild(
        t in scene_with(3..10),
        other in (-120_i64..60, -120_i64..60, 20_i64..100, 20_i64..100, 110_i64..260, -30_i64..30),
        ops in ops(),
    ) {
        let (x, z, w, d, h, tilt) = other;
        let sources = [t.light.clone(), light(x, z, w, d, h, tilt)];
        run_under(&sources, &t, &ops, DmOptions::default(), &[])?;
    }
}

/// An index past the objects is not an object to declare movable.
#[test]
fn a_movable_index_past_the_objects_is_an_error() {
    let t = plate_over_boxes();
    let light = DmLight::new(t.light.clone(), 1.0).unwrap();
    let n = t.objects.len();
    let result = DmScene::build_movable(vec![light], t.objects, &[n], DmOptions::default());
    assert!(matches!(result, Err(dm_mesh::Error::UnknownObject)));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Enough objects that the floor starts as a tiled tree: removals
    /// collapse and re-merge within tiles only, and still agree.
    #[test]
    fn updates_on_tiled_receivers_agree_with_a_rebuild(t in scene_with(9..14), ops in ops()) {
        run(&t, &ops)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// The other way of removing (collapse and re-merge) agrees too.
    #[test]
    fn collapsing_updates_agree_with_a_rebuild(t in scene_with(3..10), ops in ops()) {
        let options = DmOptions { deletion: Deletion::Collapse, ..DmOptions::default() };
        run_with(&t, &ops, options)?;
    }

    /// Boxes face to face, parted and put back together, removed and
    /// added back: the umbra they make together only goes and comes back
    /// with them, either way of deleting.
    #[test]
    fn boxes_face_to_face_part_and_meet_again(t in facing_boxes(), gap in 1_i64..6) {
        let ops = [
            Op::Move(2, [gap, 0, 0]),
            Op::Move(2, [-gap, 0, 0]),
            Op::Move(2, [0, 0, gap]),
            Op::Move(2, [0, 0, -gap]),
            Op::Remove(1),
            Op::ReAdd(1),
        ];
        for deletion in [Deletion::Local, Deletion::Collapse] {
            run_with(&t, &ops, DmOptions { deletion, ..DmOptions::default() })?;
        }
    }

    /// Updates through the shadow overlap cube agree too.
    #[test]
    fn updates_through_the_cube_agree_with_a_rebuild(t in scene_with(3..10), ops in ops()) {
        let options = DmOptions { overlap: OverlapKind::Cube, ..DmOptions::default() };
        run_with(&t, &ops, options)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    /// Bumpy bodies moved, removed and added back agree with a rebuild:
    /// the umbra of a kernel's core goes with its body.
    #[test]
    fn bumpy_bodies_move_and_agree_with_a_rebuild(t in bumpy_bodies(), ops in ops()) {
        for (body, _) in &t.objects[1..] {
            prop_assert!(concavity(body) > 64.0, "nearly convex: {}", concavity(body));
            // It forms a body all the same: the core of its kernel.
            let groups = area_shadow::convex_groups(body, &vec![Some(0); body.len()]);
            prop_assert!(groups.len() == 1 && !groups[0].is_closed_convex());
        }
        run(&t, &ops)?;
    }

    /// A ring (no kernel) and a bumpy body moved, removed and added back
    /// agree with a rebuild: the umbrae of the ring's cores go with it.
    #[test]
    fn rings_move_and_agree_with_a_rebuild(t in ring_bodies(), ops in ops()) {
        let ring = &t.objects[1].0;
        let groups = area_shadow::convex_groups(ring, &vec![Some(0); ring.len()]);
        prop_assert!(groups.len() >= 2, "{} cores", groups.len());
        prop_assert!(groups.iter().all(|g| g.pieces.len() == ring.len() && !g.is_closed_convex()));
        run(&t, &ops)?;
    }
}

/// A plate moved over a floor of many cells (hundreds of them change
/// lists, their vertices gathered and evaluated in chunks) agrees with a
/// rebuild.
#[test]
fn a_move_over_many_cells_agrees_with_a_rebuild() {
    let t = plate_over_boxes();
    run(&t, &[Op::Move(1, [30, 0, -20]), Op::Move(1, [-9, 0, 14])]).unwrap();
}

#[test]
fn samples_helper_is_inside() {
    let p = crate::common::floor(10);
    assert!(
        interior_samples(&p, 4)
            .iter()
            .all(|q| q[0].abs() < 10.0 && q[2].abs() < 10.0)
    );
}

/// What a change lists as changed: after a build every receiver; after a
/// move the floor and the moved box's new faces, not a box far from its
/// shadow; after an illumination with nothing left to do, nothing.
#[test]
fn a_move_lists_the_receivers_it_changed() {
    let flags = PieceFlags::default();
    let t = TestScene {
        objects: vec![
            (vec![floor(400)], flags),
            (cuboid([-300, 0, -10], [-280, 20, 10]), flags),
            (cuboid([280, 0, -10], [300, 20, 10]), flags),
        ],
        light: light(-10, -10, 20, 20, 500, 0),
    };
    let (mut scene, ids) = t.build();
    let all: BTreeSet<PieceId> = scene.receivers().map(|(p, _)| p).collect();
    assert_eq!(all.len(), 13);
    assert_eq!(
        scene.receivers_changed_since(0).collect::<BTreeSet<_>>(),
        all
    );
    let built = scene.revision();
    scene.illuminate();
    assert_eq!(
        scene
            .receivers_changed_since(built)
            .collect::<BTreeSet<_>>(),
        all,
        "every receiver got its values"
    );
    let since = scene.revision();
    scene.illuminate();
    assert_eq!(scene.receivers_changed_since(since).count(), 0);
    let since = scene.revision();
    scene.translate_object(ids[1], [5, 0, 0]).unwrap();
    let listed: BTreeSet<PieceId> = scene.receivers_changed_since(since).collect();
    let floor = scene.object_pieces(ids[0]).unwrap()[0];
    let moved: BTreeSet<PieceId> = scene
        .object_pieces(ids[1])
        .unwrap()
        .iter()
        .copied()
        .collect();
    let far = scene.object_pieces(ids[2]).unwrap().to_vec();
    assert!(listed.contains(&floor));
    assert!(moved.is_subset(&listed));
    assert!(far.iter().all(|p| !listed.contains(p)), "{listed:?}");
    assert_eq!(listed.len(), 1 + moved.len());
    // A new receiver normal lists that receiver alone; its values come
    // back with the next illumination, listed again.
    let since = scene.revision();
    scene.set_receiver_normal(far[0], [0.0, 1.0, 0.0]).unwrap();
    assert_eq!(
        scene.receivers_changed_since(since).collect::<Vec<_>>(),
        [far[0]]
    );
    let since = scene.revision();
    scene.illuminate();
    assert_eq!(
        scene.receivers_changed_since(since).collect::<Vec<_>>(),
        [far[0]]
    );
}
