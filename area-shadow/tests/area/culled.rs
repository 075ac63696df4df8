//! An occluder inside the umbra of earlier ones still makes umbra where it
//! alone hides the whole light (found by cargo-fuzz `dm_update`: the two
//! pipelines disagreed, and the point below sees none of the light past
//! the third triangle alone).

use crate::oracle::gp;
use area_shadow::{AreaSource, Class, SceneLight, compute_shadows};
use bsp_core::{BuildOptions, ConvexPolygon};
use svbsp::PieceFlags;

fn polygon(points: &[[i64; 3]]) -> ConvexPolygon {
    let pts: Vec<_> = points.iter().map(|&[x, y, z]| gp(x, y, z)).collect();
    ConvexPolygon::from_grid_points(&pts, 0).expect("a polygon")
}

/// Whether `p` (in the plane y = 0) lies strictly inside `outline`.
fn inside_xz(outline: &[[f64; 3]], p: [f64; 3]) -> bool {
    let n = outline.len();
    let cross = |i: usize| {
        let (a, b) = (outline[i], outline[(i + 1) % n]);
        (b[0] - a[0]) * (p[2] - a[2]) - (b[2] - a[2]) * (p[0] - a[0])
    };
    let first = cross(0);
    first != 0.0 && (1..n).all(|i| cross(i) * first > 0.0)
}

#[test]
fn an_occluder_in_others_umbra_keeps_its_own_umbra() {
    let floor = polygon(&[[-20, 0, 20], [20, 0, 20], [20, 0, -20], [-20, 0, -20]]);
    let occluders = [
        polygon(&[[0, 6, 5], [8, 4, -8], [-8, 4, -6]]),
        polygon(&[[5, 2, -8], [-8, 2, -8], [-8, 12, -1]]),
        // In the two others' combined umbra, which hide the point below
        // only together; this one hides it alone.
        polygon(&[[-6, 1, -8], [-8, 4, -8], [-8, 2, -8]]),
    ];
    let quad = polygon(&[[-5, 11, 1], [-3, 11, 1], [-3, 11, 4], [-5, 11, 4]]);
    let quad = if quad.support().normal()[1] < 0 {
        quad
    } else {
        quad.flipped()
    };
    let light = AreaSource::new(quad).expect("a light facing down");
    let two_sided = PieceFlags {
        two_sided: true,
        ..PieceFlags::default()
    };
    let mut pieces = vec![floor];
    pieces.extend(occluders);
    let flags = vec![two_sided; pieces.len()];
    let shadows = compute_shadows(
        &pieces,
        &flags,
        &[SceneLight::Area(light)],
        &BuildOptions::default(),
    )
    .expect("shadows");
    let p = [-8.425, 0.0, -10.575];
    let classes: Vec<Class> = shadows
        .fragments
        .iter()
        .filter(|f| f.polygon.source() == 0 && inside_xz(&f.polygon.vertices_f64(), p))
        .map(|f| Class::of(f, 0))
        .collect();
    assert_eq!(classes, vec![Class::Umbra]);
}
