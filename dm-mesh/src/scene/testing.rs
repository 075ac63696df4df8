//! Scenes for the scene module's unit tests: boxes on a floor under two
//! lights, and objects moved by whole grid steps.

use super::{DmLight, DmOptions, DmScene, ObjectId};
use area_shadow::AreaSource;
use bsp_core::{ConvexPolygon, GridPoint};
use svbsp::PieceFlags;

pub(crate) fn gp(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).expect("a grid point")
}

pub(crate) fn quad(points: [GridPoint; 4]) -> ConvexPolygon {
    ConvexPolygon::from_grid_points(&points, 0).expect("a quad")
}

/// A box `[lo, hi]`, faces outwards.
pub(crate) fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Vec<ConvexPolygon> {
    // Corner `i` takes x, y and z from `hi` where bits 0, 1 and 2 of
    // `i` are set.
    let corner = |i: usize| {
        let at = |axis: usize| {
            if i >> axis & 1 == 0 {
                lo[axis]
            } else {
                hi[axis]
            }
        };
        gp(at(0), at(1), at(2))
    };
    // Each face counter-clockwise seen from outside.
    [
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ]
    .into_iter()
    .map(|face| quad(face.map(corner)))
    .collect()
}

pub(crate) fn closed() -> PieceFlags {
    PieceFlags {
        closed_surface: true,
        ..PieceFlags::default()
    }
}

/// A floor (object 0) under a grid of boxes of several heights (box
/// `3 * i + k` is object `1 + 3 * i + k`), under two tilted lights.
pub(crate) fn boxes_on_a_floor() -> (DmScene, Vec<ObjectId>) {
    boxes_on_a_floor_movable(&[])
}

/// [`boxes_on_a_floor`], the objects at `movable` declared movable.
pub(crate) fn boxes_on_a_floor_movable(movable: &[usize]) -> (DmScene, Vec<ObjectId>) {
    let floor = quad([
        gp(-400, 0, 400),
        gp(400, 0, 400),
        gp(400, 0, -400),
        gp(-400, 0, -400),
    ]);
    let mut objects = vec![(vec![floor], PieceFlags::default())];
    for i in 0..3_i64 {
        for k in 0..3_i64 {
            let (x, z) = (-250 + 180 * i + 9 * k, -250 + 180 * k - 7 * i);
            let height = 40 + 23 * ((i * 2 + k) % 3);
            objects.push((cuboid([x, 0, z], [x + 60, height, z + 45]), closed()));
        }
    }
    let light = |x: i64, z: i64, tilt: i64| {
        // (Facing down.)
        let points = [
            gp(x, 500, z),
            gp(x + 120, 500 + tilt, z),
            gp(x + 120, 500 + tilt, z + 90),
            gp(x, 500, z + 90),
        ];
        let source = AreaSource::new(quad(points)).expect("a light");
        DmLight::new(source, 1.0).expect("a light")
    };
    let lights = vec![light(-150, -60, 8), light(40, 30, -5)];
    DmScene::build_movable(lights, objects, movable, DmOptions::default()).expect("a scene")
}

/// Object `id`'s polygons moved by `by` grid units.
pub(crate) fn moved(scene: &DmScene, id: ObjectId, by: [i64; 3]) -> Vec<ConvexPolygon> {
    scene.objects[id]
        .pieces
        .iter()
        .map(|&p| {
            let polygon = &scene.pieces[p].polygon;
            let points: Vec<GridPoint> = (0..polygon.len())
                .map(|k| {
                    let g = polygon
                        .vertex_grid_point(k)
                        .expect("a grid corner")
                        .to_i64();
                    gp(g[0] + by[0], g[1] + by[1], g[2] + by[2])
                })
                .collect();
            ConvexPolygon::from_grid_points(&points, 0).expect("a polygon")
        })
        .collect()
}
