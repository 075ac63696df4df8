//! Input the scene rejects, as values: polygons whose vertices are not
//! grid points, whether they come in a build (the first bad polygon in
//! order is the one named, on one thread or two: objects are made side by
//! side), an addition or a move, which then leave the scene as it was;
//! translations that would take an object off the grid.

use crate::common::{floor, gp, level_rect, light};
use bsp_core::{ConvexPolygon, Plane, Split};
use dm_mesh::{DmLight, DmScene, Error};
use svbsp::PieceFlags;

/// A square cut along x + z/3 = 1: each part has two corners (x = 8/3
/// and x = -2/3 at its ends) that are no grid points.
fn implicit_part() -> ConvexPolygon {
    let slanted = Plane::through(gp(1, 0, 0), gp(0, 1, 0), gp(0, 0, 3)).expect("a plane");
    let Split::Both(part, _) = level_rect([-5, 5], 0, [-5, 5]).split(&slanted) else {
        panic!("the plane cuts the square");
    };
    assert!((0..part.len()).any(|k| part.vertex_grid_point(k).is_none()));
    part
}

fn lights() -> Vec<DmLight> {
    vec![DmLight::new(light(-10, -10, 20, 20, 100, 0), 1.0).expect("a light")]
}

#[test]
fn build_names_the_first_bad_polygon() {
    let flags = PieceFlags::default();
    let objects = vec![
        (vec![floor(100)], flags),
        (
            vec![level_rect([-5, 5], 10, [-5, 5]), implicit_part()],
            flags,
        ),
        (vec![implicit_part()], flags),
    ];
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        let built = pool.install(|| DmScene::build(lights(), objects.clone()));
        assert_eq!(
            built.err(),
            Some(Error::ImplicitInput(1)),
            "{threads} threads"
        );
    }
}

#[test]
fn additions_and_moves_reject_bad_polygons() {
    let flags = PieceFlags::default();
    let box_top = level_rect([-5, 5], 10, [-5, 5]);
    let (mut scene, ids) = DmScene::build(
        lights(),
        vec![(vec![floor(100)], flags), (vec![box_top.clone()], flags)],
    )
    .expect("the scene builds");
    scene.illuminate();
    let cells =
        |scene: &DmScene| -> usize { scene.receivers().map(|(_, dm)| dm.cell_count()).sum() };
    let before = cells(&scene);
    assert_eq!(
        scene
            .add_object(vec![box_top.clone(), implicit_part()], flags)
            .err(),
        Some(Error::ImplicitInput(1))
    );
    assert_eq!(
        scene.move_object(ids[1], vec![implicit_part()]).err(),
        Some(Error::ImplicitInput(0))
    );
    assert_eq!(scene.objects().count(), 2);
    assert_eq!(scene.object_pieces(ids[1]).map(<[_]>::len), Some(1));
    assert_eq!(cells(&scene), before);
    scene.check_invariants().expect("the scene as it was");
}

#[test]
fn translations_off_the_grid_or_of_no_object_are_refused() {
    let flags = PieceFlags::default();
    let (mut scene, ids) = DmScene::build(
        lights(),
        vec![
            (vec![floor(100)], flags),
            (
                vec![
                    level_rect([-5, 5], 10, [-5, 5]),
                    level_rect([-5, 5], 12, [-5, 5]),
                ],
                flags,
            ),
        ],
    )
    .expect("the scene builds");
    scene.illuminate();
    let before: Vec<ConvexPolygon> = scene
        .object_pieces(ids[1])
        .unwrap()
        .iter()
        .map(|&p| scene.piece_polygon(p).unwrap().clone())
        .collect();
    let cells = scene
        .receivers()
        .map(|(_, dm)| dm.cell_count())
        .sum::<usize>();
    // Both polygons would leave the grid; the first is named.
    let limit = i64::from(bsp_core::GRID_LIMIT);
    assert_eq!(
        scene.translate_object(ids[1], [0, limit, 0]).err(),
        Some(Error::OffGrid(0))
    );
    // y = 10 + (limit - 11) stays on the grid, y = 12 + (limit - 11) does not.
    assert_eq!(
        scene.translate_object(ids[1], [0, limit - 11, 0]).err(),
        Some(Error::OffGrid(1))
    );
    let after: Vec<ConvexPolygon> = scene
        .object_pieces(ids[1])
        .unwrap()
        .iter()
        .map(|&p| scene.piece_polygon(p).unwrap().clone())
        .collect();
    assert_eq!(after, before);
    assert_eq!(
        scene
            .receivers()
            .map(|(_, dm)| dm.cell_count())
            .sum::<usize>(),
        cells
    );
    scene.check_invariants().expect("the scene as it was");
    // A removed object's handle names nothing.
    scene.remove_object(ids[1]).unwrap();
    assert_eq!(
        scene.translate_object(ids[1], [1, 0, 0]).err(),
        Some(Error::UnknownObject)
    );
}
