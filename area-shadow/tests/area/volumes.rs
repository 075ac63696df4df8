//! The volumes one occluder casts, in the cases the papers split away.

use crate::oracle::gp;
use area_shadow::{AreaSource, AreaTrees, Class, cast_volumes, volume_planes};
use bsp_core::ConvexPolygon;
use svbsp::PieceFlags;

fn down_light() -> AreaSource {
    AreaSource::from_grid_points(&[gp(-2, 20, -2), gp(2, 20, -2), gp(2, 20, 2), gp(-2, 20, 2)])
        .unwrap()
}

fn square(y: i64, half: i64) -> ConvexPolygon {
    ConvexPolygon::from_grid_points(
        &[
            gp(-half, y, half),
            gp(half, y, half),
            gp(half, y, -half),
            gp(-half, y, -half),
        ],
        0,
    )
    .unwrap()
}

#[test]
fn square_over_square_has_both_volumes() {
    let planes = volume_planes(&square(10, 4), &down_light());
    // Cap + one plane per occluder edge for each volume.
    assert_eq!(planes.penumbra.len(), 1);
    assert_eq!(planes.penumbra[0].len(), 5);
    assert_eq!(planes.umbra.as_ref().unwrap().len(), 5);
}

#[test]
fn occluder_behind_the_light_casts_nothing() {
    let v = cast_volumes(&square(30, 4), &down_light());
    assert!(v.penumbra.is_empty() && v.umbra.is_none());
    let v = cast_volumes(&square(20, 4), &down_light());
    assert!(v.penumbra.is_empty() && v.umbra.is_none());
}

#[test]
fn light_straddling_the_occluder_plane_has_no_umbra() {
    // A vertical wall x = 0 under the light's middle.
    let wall = ConvexPolygon::from_grid_points(
        &[gp(0, 0, -5), gp(0, 0, 5), gp(0, 10, 5), gp(0, 10, -5)],
        0,
    )
    .unwrap();
    let v = cast_volumes(&wall, &down_light());
    assert_eq!(v.penumbra.len(), 2);
    assert!(v.umbra.is_none());
}

#[test]
fn occluder_straddling_the_light_plane_casts_from_its_front_part() {
    // A tilted quad from y = 10 up through the light's plane to y = 30,
    // beside the light.
    let tilted = ConvexPolygon::from_grid_points(
        &[gp(3, 10, -5), gp(3, 10, 5), gp(13, 30, 5), gp(13, 30, -5)],
        0,
    )
    .unwrap();
    let v = cast_volumes(&tilted, &down_light());
    assert_eq!(v.penumbra.len(), 1);
    let floor = square(0, 100);
    let mut trees = AreaTrees::default();
    for p in v.penumbra {
        trees.penumbra.insert(p);
    }
    // The floor under the quad's lower edge, away from the light, is in
    // penumbra; far on the other side it is lit.
    let classes = trees.classify(floor, PieceFlags::default(), &down_light());
    assert!(classes.iter().any(|(_, c)| *c == Class::Penumbra));
    assert!(classes.iter().any(|(_, c)| *c == Class::Lit));
    assert!(!classes.iter().any(|(_, c)| *c == Class::Umbra));
}

#[test]
fn light_edge_in_the_occluder_plane_leaves_no_umbra() {
    // The light's edge x = 0 lies in the occluder's plane x = 0: points
    // behind the occluder see the light next to that edge, so no point is
    // hidden from all of it (found by the `area` fuzz target's inputs).
    let light =
        AreaSource::from_grid_points(&[gp(0, 12, -1), gp(4, 13, -1), gp(4, 13, 0), gp(0, 12, 0)])
            .unwrap();
    let occluder =
        ConvexPolygon::from_grid_points(&[gp(0, 3, 3), gp(0, 11, -4), gp(0, 2, 6)], 0).unwrap();
    assert!(light.support().normal()[1] < 0, "the light faces down");
    let v = cast_volumes(&occluder, &light);
    assert_eq!(v.penumbra.len(), 1);
    assert!(v.umbra.is_none());
}
