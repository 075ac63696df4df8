//! The 1992 paper's Figure 4, a two-dimensional example, as a 3D scene
//! extruded along z: a linear light over two segments (occluders 1 and 2)
//! and segment 3, which the penumbra tree splits into 3.1 (outside: lit)
//! and 3.2, and the umbra tree splits 3.2 into 3.2.1 (penumbra) and 3.2.2
//! (umbra). The light, the occluders and the receiver are long in z, and
//! only the receiver's middle (|z| <= 10) is looked at, where every
//! boundary runs along z as in the figure.

use crate::oracle::gp;
use area_shadow::{AreaSource, Class, SceneLight, compute_shadows};
use bsp_core::{BuildOptions, ConvexPolygon};
use svbsp::PieceFlags;

/// A strip `x0 <= x <= x1` at height `y`, `|z| <= half`, facing up.
fn strip(x0: i64, x1: i64, y: i64, half: i64) -> ConvexPolygon {
    ConvexPolygon::from_grid_points(
        &[
            gp(x0, y, half),
            gp(x1, y, half),
            gp(x1, y, -half),
            gp(x0, y, -half),
        ],
        0,
    )
    .unwrap()
}

#[test]
fn three_segments_under_a_linear_light() {
    // Light: x in [-2, 2] at y = 20, facing down.
    let light = AreaSource::from_grid_points(&[
        gp(-2, 20, -1000),
        gp(2, 20, -1000),
        gp(2, 20, 1000),
        gp(-2, 20, 1000),
    ])
    .unwrap();
    let one = strip(-6, -2, 10, 1000);
    let two = strip(4, 6, 10, 1000);
    let three = strip(-8, 0, 0, 10);
    let out = compute_shadows(
        &[one, two, three],
        &[PieceFlags::default(); 3],
        &[SceneLight::Area(light)],
        &BuildOptions::default(),
    )
    .unwrap();
    // Segment 3 at height 0 sees light point (l, 20) across height 10 at
    // x' = (x + l) / 2: hidden by segment 1 for all l in [-2, 2] when
    // x in [-10, -6], for some l when x in [-14, -2]; segment 2 hides
    // nothing of it.
    let mut pieces: Vec<(Class, f64, f64)> = out
        .fragments
        .iter()
        .filter(|f| f.polygon.source() == 2)
        .map(|f| {
            let xs: Vec<f64> = f.polygon.vertices_f64().iter().map(|v| v[0]).collect();
            let zs: Vec<f64> = f.polygon.vertices_f64().iter().map(|v| v[2]).collect();
            assert_eq!(zs.iter().copied().fold(f64::MAX, f64::min), -10.0);
            assert_eq!(zs.iter().copied().fold(f64::MIN, f64::max), 10.0);
            (
                Class::of(f, 0),
                xs.iter().copied().fold(f64::MAX, f64::min),
                xs.iter().copied().fold(f64::MIN, f64::max),
            )
        })
        .collect();
    pieces.sort_by(|a, b| a.1.total_cmp(&b.1));
    assert_eq!(
        pieces,
        vec![
            (Class::Umbra, -8.0, -6.0),    // 3.2.2
            (Class::Penumbra, -6.0, -2.0), // 3.2.1
            (Class::Lit, -2.0, 0.0),       // 3.1
        ]
    );
    // Both occluders are lit: nothing is in front of them.
    for f in out.fragments.iter().filter(|f| f.polygon.source() < 2) {
        assert_eq!(Class::of(f, 0), Class::Lit);
    }
}
