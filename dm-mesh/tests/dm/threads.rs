//! Receivers are cast and illuminated in parallel: the result must not
//! depend on the number of threads (same cells, same lists, same vertex
//! irradiance, bit for bit), also after moves.

use crate::common::{TestScene, bumpy_bodies, scene_with, translated};
use bsp_core::ConvexPolygon;
use dm_mesh::DmScene;
use proptest::prelude::*;

/// One cell: vertex coordinate bits, entries, vertex irradiance bits.
type CellPrint = (Vec<[u64; 3]>, Vec<dm_mesh::Entry>, Vec<u64>);

/// Everything a scene's receivers hold, in order: per cell its vertices
/// (exact coordinates as f64 bits), entries and irradiance bits.
fn fingerprint(scene: &DmScene) -> Vec<CellPrint> {
    let mut out = Vec::new();
    for (piece, dm) in scene.receivers() {
        for (face, cell) in dm.cells() {
            let vertices = dm.mesh().face_vertices(face);
            out.push((
                vertices
                    .iter()
                    .map(|&v| {
                        let p = dm.mesh().vertex(v).unwrap().position.to_f64();
                        p.map(f64::to_bits)
                    })
                    .collect(),
                cell.entries().to_vec(),
                vertices
                    .iter()
                    .map(|&v| scene.vertex_irradiance(piece, v).unwrap_or(-1.0).to_bits())
                    .collect(),
            ));
        }
    }
    out
}

fn build_and_move(t: &TestScene) -> Vec<CellPrint> {
    let (mut scene, ids) = t.build();
    scene.illuminate();
    if let Some(&id) = ids.get(1) {
        let moved: Vec<ConvexPolygon> = t.objects[1]
            .0
            .iter()
            .map(|p| translated(p, [7, 0, -5]))
            .collect();
        scene.move_object(id, moved).unwrap();
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
