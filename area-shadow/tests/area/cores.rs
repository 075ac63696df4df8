//! Closed surfaces with no kernel (tori): the convex cores of their local
//! kernels and their flat sections, and the umbrae they cast, against the
//! exact occlusion oracle of the surface's own triangles.

use crate::kernel::{ceiling_light, floor_square, floor_umbra, proven_dark};
use crate::oracle::{Caster, blocked, gp, light_targets};
use area_shadow::{AreaSource, convex_groups, section_unions};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, Plane};
use proptest::prelude::*;

/// A torus about the vertical axis through `centre`: `rings` x
/// `segments` quads cut into triangles, the ring of radius `big`, the
/// tube of radius `small`; facing out, or in when `inward`.
fn torus(
    centre: [f64; 3],
    (big, small): (f64, f64),
    (rings, segments): (u32, u32),
    inward: bool,
) -> Vec<ConvexPolygon> {
    let at = |i: u32, j: u32| {
        let (u, v) = (
            2.0 * std::f64::consts::PI * f64::from(i % rings) / f64::from(rings),
            2.0 * std::f64::consts::PI * f64::from(j % segments) / f64::from(segments),
        );
        let r = big + small * v.cos();
        gp(
            (centre[0] + r * u.cos()).round() as i64,
            (centre[1] + small * v.sin()).round() as i64,
            (centre[2] + r * u.sin()).round() as i64,
        )
    };
    let mut faces = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            for mut t in [[a, b, c], [a, c, d]] {
                if inward {
                    t.reverse();
                }
                if let Ok(p) = ConvexPolygon::from_grid_points(&t, 0) {
                    faces.push(p);
                }
            }
        }
    }
    faces
}

/// A torus has no kernel (its hole's centre is outside it), but convex
/// cores inside it: several groups, each of all its pieces, none of them
/// convex itself.
#[test]
fn a_torus_stands_for_several_cores() {
    let faces = torus([0.0, 9000.0, 0.0], (4000.0, 1500.0), (12, 8), false);
    let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
    assert!((2..=8).contains(&groups.len()), "{} groups", groups.len());
    for group in &groups {
        assert_eq!(group.pieces.len(), faces.len());
        assert!(!group.is_closed_convex());
        assert!(group.shell().is_some());
    }
}

/// No point of `points` (raised by 4,000, off the torus's planes) in any
/// of the convex volumes `umbrae` sees a point of `light` past the
/// torus's own triangles `faces`.
fn umbrae_are_dark(
    faces: &[ConvexPolygon],
    light: &AreaSource,
    umbrae: &[Vec<Plane>],
    points: &[[i64; 3]],
) -> Result<(), TestCaseError> {
    let casters: Vec<Caster> = faces.iter().map(Caster::new).collect();
    let targets = light_targets(light);
    // No receiver: a plane none of the torus's faces lie in.
    let own =
        ConvexPolygon::from_grid_points(&[gp(0, -9, 0), gp(1, -9, 0), gp(0, -9, -1)], 0).unwrap();
    for c in points {
        let p = gp(c[0], c[1] + 4_000, c[2]);
        if faces
            .iter()
            .any(|f| side_of_point(f.support(), p) == Side::On)
        {
            continue;
        }
        for planes in umbrae {
            if !planes.iter().all(|q| side_of_point(q, p) == Side::Back) {
                continue;
            }
            let q = p.to_f64();
            for x in &targets {
                prop_assert!(
                    blocked(q, *x, &casters, &own),
                    "{q:?} in an umbra sees {x:?}"
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Tori of any proportions, wound either way, under a light above:
    /// no point of any core's umbra, nor of any section's, sees the light
    /// past the torus's own triangles. Both have umbrae under a light
    /// narrower than 3,000 (one as wide as the ring leaves a section's
    /// none).
    #[test]
    fn a_torus_hides_the_light_from_its_cores_and_sections_umbrae(
        centre in prop::array::uniform3(-2000.0_f64..2000.0),
        big in 2500.0_f64..6000.0,
        thickness in 0.15_f64..0.6,
        rings in 8_u32..24,
        segments in 6_u32..14,
        inward in any::<bool>(),
        light in (-6000_i64..2000, -6000_i64..2000, 500_i64..5000, 20_000_i64..26_000),
        points in prop::collection::vec(prop::array::uniform3(-12_000_i64..12_000), 80),
    ) {
        let centre = [centre[0], centre[1] + 10_000.0, centre[2]];
        let faces = torus(centre, (big, big * thickness), (rings, segments), inward);
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        prop_assert!(!groups.is_empty());
        let narrow = light.2 < 3000;
        let light = ceiling_light(light.0, light.1, light.2, light.3);
        let umbrae: Vec<_> = groups.iter().filter_map(|g| g.umbra_planes(&light)).collect();
        prop_assert!(!umbrae.is_empty(), "the torus is below the light");
        umbrae_are_dark(&faces, &light, &umbrae, &points)?;
        let unions = section_unions(&faces, &vec![Some(0); faces.len()]);
        let parts: Vec<_> = unions.iter().flat_map(|u| u.umbra_parts(&light)).collect();
        prop_assert!(!narrow || !parts.is_empty(), "{} sections, no umbra", unions.len());
        umbrae_are_dark(&faces, &light, &parts, &points)?;
    }
}

/// The floor under a torus, below a light over its ring: the umbra the
/// pipeline finds (every point of which the oracle finds dark) is most of
/// the true umbra, which the oracle measures on a grid of floor points
/// (95 % of it when written).
#[test]
fn a_torus_casts_most_of_its_umbra_by_its_section() {
    let light = ceiling_light(-2000, -2000, 4000, 24_000);
    let faces = torus([0.0, 9000.0, 0.0], (5000.0, 2000.0), (24, 12), false);
    let found = floor_umbra(faces.clone(), &light, true);
    let casters: Vec<Caster> = faces.iter().map(Caster::new).collect();
    let floor = floor_square(-10_000, -10_000, 20_000);
    let targets: Vec<[f64; 3]> = light_targets(&light);
    let step = 200.0;
    let mut truth = 0.0;
    for i in 0..100 {
        for j in 0..100 {
            let q = [
                -10_000.0 + step * (f64::from(i) + 0.5),
                0.0,
                -10_000.0 + step * (f64::from(j) + 0.5),
            ];
            if targets.iter().all(|x| blocked(q, *x, &casters, &floor)) {
                truth += step * step;
            }
        }
    }
    assert!(found > 0.85 * truth, "umbra {found} of {truth}");
}

/// Under a light about as wide as the tube, a torus casts on the floor
/// an umbra of its cores where its triangles cast none of their own
/// (each is far smaller than the light), every point of which the oracle
/// finds dark.
#[test]
fn a_torus_darkens_the_floor_by_its_cores() {
    let light = ceiling_light(-2000, -2000, 4000, 24_000);
    let faces = torus([0.0, 9000.0, 0.0], (5000.0, 2000.0), (24, 12), false);
    let alone = floor_umbra(faces.clone(), &light, false);
    let together = floor_umbra(faces, &light, true);
    assert!(
        together > 1.0e6 && together > 10.0 * alone,
        "umbra {together} against {alone}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    /// Joint-umbra proofs with a torus's triangles and the shells of its
    /// cores: a floor square proven dark sees none of the light past the
    /// triangles (the oracle), and the floor right under the tube, below
    /// a light over it, is proven (not with the triangles alone).
    #[test]
    fn proofs_through_cores_shells_hold(
        inward in any::<bool>(),
        squares in prop::collection::vec((-9000_i64..9000, -9000_i64..9000, 200_i64..2500), 6),
    ) {
        let faces = torus([0.0, 9000.0, 0.0], (5000.0, 2000.0), (16, 10), inward);
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        let shells: Vec<_> = groups.iter().filter_map(|g| g.shell()).collect();
        prop_assert!(shells.len() >= 2);
        let shells: Vec<_> = shells.iter().collect();
        let light = ceiling_light(3500, -1500, 3000, 24_000);
        // Under the tube, on the side towards +x.
        let under = floor_square(4700, -300, 600);
        prop_assert!(proven_dark(&under, &faces, &shells, &light));
        prop_assert!(!proven_dark(&under, &faces, &[], &light));
        for (x, z, w) in squares {
            proven_dark(&floor_square(x, z, w), &faces, &shells, &light);
        }
    }
}
