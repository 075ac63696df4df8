//! Closed surfaces that are really concave (bumpy spheres): the convex
//! core of their kernel, and the umbra it casts, against the exact
//! occlusion oracle of the surface's own triangles.

use crate::oracle::{Caster, blocked, gp, light_samples, light_targets, samples};
use area_shadow::dark::{Body, sees_none};
use area_shadow::{
    AreaSource, Class, SceneLight, ShadowGroups, compute_shadows_with_groups, convex_groups,
};
use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{BuildOptions, ConvexPolygon, GridPoint};
use proptest::prelude::*;
use svbsp::PieceFlags;

/// A UV sphere of `rings` x `segments` quads cut into triangles, each
/// vertex off the radius by up to `bump` of it (`seed` picks how far),
/// facing out, or in when `inward`.
fn bumpy_sphere(
    centre: [f64; 3],
    radius: f64,
    (rings, segments): (u32, u32),
    bump: f64,
    seed: u32,
    inward: bool,
) -> Vec<ConvexPolygon> {
    let at = |i: u32, j: u32| {
        let j = j % segments;
        // The poles are one point each, whatever `j`.
        let key = if i == 0 || i == rings {
            i * 7919
        } else {
            i * 7919 + j * 104_729 + 1
        };
        let mut h = key.wrapping_mul(0x9e37_79b9) ^ seed;
        h ^= h >> 15;
        h = h.wrapping_mul(0x85eb_ca6b);
        h ^= h >> 13;
        let r = radius * (1.0 + bump * (f64::from(h % 2001) / 1000.0 - 1.0));
        let (t, f) = (
            std::f64::consts::PI * f64::from(i) / f64::from(rings),
            2.0 * std::f64::consts::PI * f64::from(j) / f64::from(segments),
        );
        gp(
            (centre[0] + r * t.sin() * f.cos()).round() as i64,
            (centre[1] + r * t.cos()).round() as i64,
            (centre[2] + r * t.sin() * f.sin()).round() as i64,
        )
    };
    let mut out = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            for mut t in [[a, b, c], [a, c, d]] {
                if inward {
                    t.reverse();
                }
                if let Ok(p) = ConvexPolygon::from_grid_points(&t, 0) {
                    out.push(p);
                }
            }
        }
    }
    out
}

/// How far (grid units) the surface is from convex: the most any vertex
/// stands in front of a face's plane (facing out).
fn concavity(faces: &[ConvexPolygon], inward: bool) -> f64 {
    let vertices: Vec<[f64; 3]> = faces.iter().flat_map(|f| f.vertices_f64()).collect();
    faces
        .iter()
        .map(|f| {
            let [a, b, c, d] = f.support().approx();
            let norm = (a * a + b * b + c * c).sqrt();
            let sign = if inward { -1.0 } else { 1.0 };
            vertices
                .iter()
                .map(|v| sign * (a * v[0] + b * v[1] + c * v[2] + d) / norm)
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// A light over x, z in `[x0, x0 + w]`, `[z0, z0 + w]` at height `h`,
/// facing down.
pub fn ceiling_light(x0: i64, z0: i64, w: i64, h: i64) -> AreaSource {
    let pts = [
        gp(x0, h, z0),
        gp(x0 + w, h, z0),
        gp(x0 + w, h, z0 + w),
        gp(x0, h, z0 + w),
    ];
    AreaSource::from_grid_points(&pts).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// A bumpy sphere, far from convex (vertices hundreds of grid units
    /// out of their neighbours' planes), still forms one body: a core of
    /// its kernel, which holds its centre. No point of that body's umbra
    /// sees the light past the sphere's own triangles.
    #[test]
    fn a_bumpy_sphere_hides_the_light_from_its_kernels_umbra(
        centre in prop::array::uniform3(-2000.0_f64..2000.0),
        radius in 3000.0_f64..6000.0,
        rings in 6_u32..12,
        segments in 8_u32..16,
        bump in 0.04_f64..0.1,
        seed in any::<u32>(),
        inward in any::<bool>(),
        light in (-6000_i64..2000, -6000_i64..2000, 500_i64..5000, 20_000_i64..26_000),
        points in prop::collection::vec(prop::array::uniform3(-12_000_i64..12_000), 60),
    ) {
        let centre = [centre[0], centre[1] + 10_000.0, centre[2]];
        let faces = bumpy_sphere(centre, radius, (rings, segments), bump, seed, inward);
        prop_assume!(concavity(&faces, inward) > 100.0);
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        prop_assert_eq!(groups.len(), 1);
        prop_assert_eq!(groups[0].pieces.len(), faces.len());
        prop_assert!(!groups[0].is_closed_convex());
        let light = ceiling_light(light.0, light.1, light.2, light.3);
        let planes = groups[0].umbra_planes(&light).expect("the sphere is below the light");
        let middle = gp(centre[0].round() as i64, centre[1].round() as i64, centre[2].round() as i64);
        prop_assert!(planes.iter().all(|q| side_of_point(q, middle) == Side::Back));
        let casters: Vec<Caster> = faces.iter().map(Caster::new).collect();
        let corners: Vec<[f64; 3]> = light.vertices().map(GridPoint::to_f64).collect();
        let inside_light = light_samples(light.polygon());
        // No receiver: a plane none of the sphere's faces lie in.
        let own = ConvexPolygon::from_grid_points(&[gp(0, -9, 0), gp(1, -9, 0), gp(0, -9, -1)], 0)
            .unwrap();
        // The core reaches most of the way out: half the radius along
        // each axis lies in it, so in its umbra.
        for a in 0..3 {
            for sign in [-0.5, 0.5] {
                let mut p = centre;
                p[a] += sign * radius;
                let p = gp(p[0].round() as i64, p[1].round() as i64, p[2].round() as i64);
                prop_assert!(planes.iter().all(|q| side_of_point(q, p) == Side::Back));
            }
        }
        for c in points {
            let p = gp(c[0], c[1] + 8_000, c[2]);
            if faces.iter().any(|f| side_of_point(f.support(), p) == Side::On)
                || !planes.iter().all(|q| side_of_point(q, p) == Side::Back)
            {
                continue;
            }
            let q = p.to_f64();
            for x in corners.iter().chain(&inside_light) {
                prop_assert!(blocked(q, *x, &casters, &own), "{q:?} in the umbra sees {x:?}");
            }
        }
    }
}

/// The floor's fragments under a closed surface (a bumpy sphere): umbra ones see none of the
/// light (the oracle), lit ones all of it; returns the floor's umbra area.
pub fn floor_umbra(faces: Vec<ConvexPolygon>, light: &AreaSource, groups: bool) -> f64 {
    let floor = [
        gp(-40_000, 0, 40_000),
        gp(40_000, 0, 40_000),
        gp(40_000, 0, -40_000),
        gp(-40_000, 0, -40_000),
    ];
    let mut pieces = vec![ConvexPolygon::from_grid_points(&floor, 0).unwrap()];
    pieces.extend(faces);
    let pieces: Vec<ConvexPolygon> = pieces
        .into_iter()
        .enumerate()
        .map(|(k, p)| p.with_source(k as u32))
        .collect();
    let flags = vec![PieceFlags::default(); pieces.len()];
    let groups = if groups {
        ShadowGroups::connected(&pieces, &flags)
    } else {
        ShadowGroups::default()
    };
    let lights = [SceneLight::Area(light.clone())];
    let out =
        compute_shadows_with_groups(&pieces, &flags, &groups, &lights, &BuildOptions::default())
            .unwrap();
    let casters: Vec<Caster> = pieces[1..].iter().map(Caster::new).collect();
    let targets: Vec<[f64; 3]> = light_targets(light);
    let mut umbra = 0.0;
    for f in out.fragments.iter().filter(|f| f.polygon.source() == 0) {
        let class = Class::of(f, 0);
        for q in samples(&f.polygon) {
            let seen = targets
                .iter()
                .filter(|x| !blocked(q, **x, &casters, &pieces[0]))
                .count();
            match class {
                Class::Umbra => assert_eq!(seen, 0, "umbra at {q:?} sees the light"),
                Class::Lit => assert_eq!(seen, targets.len(), "lit at {q:?} misses some light"),
                Class::Penumbra => {}
            }
        }
        if class == Class::Umbra {
            umbra += f.polygon.area();
        }
    }
    umbra
}

/// Under a light wider than one triangle's umbra reaches, a bumpy sphere
/// of 288 triangles casts on the floor an umbra of its kernel's core far
/// larger than its triangles' own, every point of which the oracle finds
/// dark.
#[test]
fn a_bumpy_sphere_darkens_the_floor_by_its_kernel() {
    let light = ceiling_light(-3000, -3000, 6000, 24_000);
    let faces = bumpy_sphere([0.0, 9000.0, 0.0], 5000.0, (12, 12), 0.06, 7, false);
    assert!(concavity(&faces, false) > 100.0);
    let alone = floor_umbra(faces.clone(), &light, false);
    let together = floor_umbra(faces, &light, true);
    // A core of radius about 4,400 under this light: an umbra of radius
    // about 5,000 on the floor.
    assert!(
        together > 3.0e7 && together > 10.0 * alone,
        "umbra {together} against {alone}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Joint-umbra proofs with a bumpy sphere's triangles and the shell of
    /// its kernel's core: a floor square proven dark sees none of the
    /// light past the triangles (the oracle), and the floor right under
    /// the sphere is proven.
    #[test]
    fn proofs_through_a_kernels_shell_hold(
        seed in any::<u32>(),
        inward in any::<bool>(),
        bump in 0.03_f64..0.08,
        squares in prop::collection::vec((-7000_i64..7000, -7000_i64..7000, 200_i64..2500), 6),
    ) {
        let faces = bumpy_sphere([0.0, 9000.0, 0.0], 5000.0, (10, 12), bump, seed, inward);
        let groups = convex_groups(&faces, &vec![Some(0); faces.len()]);
        prop_assert_eq!(groups.len(), 1);
        let shell = groups[0].shell().expect("a kernel's core is a shell");
        let light = ceiling_light(-2000, -2000, 4000, 24_000);
        prop_assert!(proven_dark(&floor_square(-300, -300, 600), &faces, &[&shell], &light));
        for (x, z, w) in squares {
            proven_dark(&floor_square(x, z, w), &faces, &[&shell], &light);
        }
    }
}

/// The floor square (facing up) of side `w` from `x, z`.
pub fn floor_square(x: i64, z: i64, w: i64) -> ConvexPolygon {
    let c = [
        gp(x, 0, z),
        gp(x, 0, z + w),
        gp(x + w, 0, z + w),
        gp(x + w, 0, z),
    ];
    ConvexPolygon::from_grid_points(&c, 0).unwrap()
}

/// Whether a joint-umbra proof with the triangles `faces` and the bodies
/// `shells` finds the floor `square` dark under `light`; when it does,
/// the oracle must find that it sees none of the light past the
/// triangles (else this panics).
pub fn proven_dark(
    square: &ConvexPolygon,
    faces: &[ConvexPolygon],
    shells: &[&Body],
    light: &AreaSource,
) -> bool {
    let triangles: Vec<&ConvexPolygon> = faces.iter().collect();
    if !sees_none(square, false, light, &triangles, shells) {
        return false;
    }
    let casters: Vec<Caster> = faces.iter().map(Caster::new).collect();
    let targets: Vec<[f64; 3]> = light_targets(light);
    for q in samples(square) {
        for x in &targets {
            assert!(
                blocked(q, *x, &casters, square),
                "{q:?} proven dark sees {x:?}"
            );
        }
    }
    true
}
