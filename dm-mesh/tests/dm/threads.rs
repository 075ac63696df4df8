//! Receivers are cast and illuminated in parallel: the result must not
//! depend on the number of threads (same cells, same lists, same vertex
//! irradiance, bit for bit), also after moves.

use crate::common::{
    CellPrint, TestScene, bumpy_bodies, plate_over_boxes, receiver_print, scene_with,
};
use dm_mesh::DmScene;
use proptest::prelude::*;

/// Everything a scene's receivers hold, in order.
fn fingerprint(scene: &DmScene) -> Vec<CellPrint> {
    scene
        .receivers()
        .flat_map(|(piece, _)| receiver_print(scene, piece))
        .collect()
}

fn build_and_move(t: &TestScene) -> Vec<CellPrint> {
    let (mut scene, ids) = t.build();
    scene.illuminate();
    if let Some(&id) = ids.get(1) {
        scene.translate_object(id, [7, 0, -5]).unwrap();
        scene.illuminate();
    }
    fingerprint(&scene)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn results_do_not_depend_on_the_thread_count(t in scene_with(9..14)) {
        prop_assert!(same_on_1_and_3_threads(&t));
    }

    /// Bodies of 32 triangles: a move makes their pieces beside the old
    /// units' removal.
    #[test]
    fn big_objects_move_alike_on_any_thread_count(t in bumpy_bodies()) {
        prop_assert!(same_on_1_and_3_threads(&t));
    }
}

fn same_on_1_and_3_threads(t: &TestScene) -> bool {
    let runs: Vec<_> = [1, 3]
        .iter()
        .map(|&n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
                .install(|| build_and_move(t))
        })
        .collect();
    runs[0] == runs[1]
}

/// A plate moved over a floor of many cells: the floor's cells whose
/// lists change are many (their vertices are gathered and evaluated a
/// chunk of faces at a time, the chunks in parallel), and the result is
/// the same on any number of threads.
#[test]
fn a_move_over_many_cells_is_alike_on_any_thread_count() {
    let t = plate_over_boxes();
    let (scene, ids) = t.build();
    let plate = scene.object_pieces(ids[1]).unwrap().to_vec();
    let floor = scene.object_pieces(ids[0]).unwrap()[0];
    let dm = scene.receiver(floor).unwrap();
    let listing = dm
        .cells()
        .filter(|(_, c)| {
            c.entries().iter().any(|e| {
                dm.unit_source(e.unit)
                    .is_some_and(|(o, _)| plate.contains(&o))
            })
        })
        .count();
    // (From 512 faces touched on one receiver on, a change's vertices are
    // gathered in chunks.)
    assert!(
        listing > 512,
        "{listing} of the floor's cells list the plate"
    );
    assert!(same_on_1_and_3_threads(&t));
}
