//! A two-sided sheet lying on a one-sided floor, under a light whose plane
//! cuts theirs (found by cargo-fuzz `pipeline`: `umbra shadow` left the
//! sheet in penumbra where `umbra dm` had it lit). A ray from a point of
//! the sheet leaves the common plane at once, so the floor hides nothing
//! from it, though the point lies in both of the floor's penumbra volumes
//! (one each side of the plane, glued along it).

use crate::oracle::gp;
use area_shadow::{AreaSource, Class, SceneLight, compute_shadows};
use bsp_core::predicates::Side;
use bsp_core::{BuildOptions, ConvexPolygon};
use svbsp::PieceFlags;

fn polygon(points: &[[i64; 3]]) -> ConvexPolygon {
    let pts: Vec<_> = points.iter().map(|&[x, y, z]| gp(x, y, z)).collect();
    ConvexPolygon::from_grid_points(&pts, 0).expect("a polygon")
}

/// The classes of the sheet's fragments (piece 1), each with the side of
/// the light's plane its centroid lies on.
fn sheet_classes(floor: PieceFlags, sheet: PieceFlags) -> Vec<(Class, Side)> {
    let up = polygon(&[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]);
    let down = up.flipped();
    let light = AreaSource::new(polygon(&[[3, -5, -8], [-7, 3, 0], [-10, -10, -10]]))
        .expect("a triangle light");
    let support = *light.support();
    let shadows = compute_shadows(
        &[up, down],
        &[floor, sheet],
        &[SceneLight::Area(light)],
        &BuildOptions::default(),
    )
    .expect("shadows");
    shadows
        .fragments
        .iter()
        .filter(|f| f.polygon.source() == 1)
        .map(|f| {
            // Centroids lie well off the light's plane: floats decide.
            let c = f.polygon.centroid();
            let [a, b, cz, d] = support.approx();
            let side = if a * c[0] + b * c[1] + cz * c[2] + d > 0.0 {
                Side::Front
            } else {
                Side::Back
            };
            (Class::of(f, 0), side)
        })
        .collect()
}

#[test]
fn a_two_sided_sheet_on_a_floor_is_lit_by_a_light_their_plane_cuts() {
    let floor = PieceFlags::default();
    for casts in [false, true] {
        let sheet = PieceFlags {
            two_sided: true,
            casts_shadows: casts,
            ..PieceFlags::default()
        };
        // Also with the floor two-sided: two coincident sheets.
        let two_sided_floor = PieceFlags {
            two_sided: true,
            ..floor
        };
        for floor in [floor, two_sided_floor] {
            let classes = sheet_classes(floor, sheet);
            assert!(classes.iter().any(|&(c, _)| c == Class::Lit), "{classes:?}");
            for (class, side) in classes {
                let expected = if side == Side::Front {
                    Class::Lit
                } else {
                    Class::Umbra
                };
                assert_eq!(class, expected, "casts {casts}, floor {floor:?}");
            }
        }
    }
}
