//! Bad input gives typed errors, never panics.

use illum::{AreaLight, IllumError, vertex_plan};

#[test]
fn degenerate_lights() {
    assert_eq!(
        AreaLight::new(&[[0.0; 3], [1.0, 0.0, 0.0]], 1.0),
        Err(IllumError::TooFewVertices { count: 2 })
    );
    assert_eq!(
        AreaLight::new(&[[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]], 1.0),
        Err(IllumError::Degenerate)
    );
    assert_eq!(
        AreaLight::new(&[[0.0; 3], [0.0; 3], [0.0; 3]], 1.0),
        Err(IllumError::Degenerate)
    );
    assert_eq!(
        AreaLight::new(&[[0.0; 3], [1.0, f64::NAN, 0.0], [0.0, 1.0, 0.0]], 1.0),
        Err(IllumError::NonFinite { index: 1 })
    );
    assert!(matches!(
        AreaLight::new(
            &[[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.1], [0.0, 1.0, 0.0]],
            1.0
        ),
        Err(IllumError::NonPlanar { .. })
    ));
    // Concave (an arrow head) and self-intersecting (a pentagram).
    assert!(matches!(
        AreaLight::new(
            &[[0.0; 3], [2.0, 0.0, 0.0], [1.0, 0.5, 0.0], [1.0, 2.0, 0.0]],
            1.0
        ),
        Err(IllumError::NonConvex { .. })
    ));
    let star: Vec<_> = (0..5)
        .map(|i| {
            let t = (2 * i) as f64 * 2.0 * std::f64::consts::PI / 5.0;
            [t.cos(), t.sin(), 0.0]
        })
        .collect();
    assert!(matches!(
        AreaLight::new(&star, 1.0),
        Err(IllumError::NonConvex { .. })
    ));
    assert!(matches!(
        AreaLight::new(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], -1.0),
        Err(IllumError::BadStrength { .. })
    ));
    // Errors print.
    assert!(IllumError::Degenerate.to_string().contains("degenerate"));
    assert_eq!(vertex_plan([]), Err(IllumError::NoFragments));
}

#[test]
fn collinear_extra_vertices_are_fine() {
    let l = AreaLight::new(
        &[
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ],
        1.0,
    )
    .unwrap();
    assert!((l.area() - 4.0).abs() < 1e-15);
}
