//! Vertex irradiance: the three cases against the visible part of the
//! light past every occluder of the scene, and against Monte Carlo.

use crate::common::{TestScene, cuboid, floor, gp, level_rect, light, scene};
use crate::oracle::{hidden, interior_samples};
use bsp_core::ConvexPolygon;
use dm_mesh::{CellClass, DmScene};
use illum::{Sidedness, VisiblePart, visible_irradiance};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use svbsp::PieceFlags;

/// Every vertex's value against `illum` given every caster of the scene.
pub fn check_vertices(t: &TestScene, scene: &mut DmScene) -> Result<(), TestCaseError> {
    let stats = scene.illuminate();
    prop_assert_eq!(stats.evaluated, stats.vertices);
    let corners: Vec<[f64; 3]> = t.light.vertices().map(|g| g.to_f64()).collect();
    let light = illum::AreaLight::new(&corners, 1.0).unwrap();
    let casters: Vec<(ConvexPolygon, Vec<[f64; 3]>)> = t
        .objects
        .iter()
        .filter(|(_, f)| f.casts_shadows)
        .flat_map(|(ps, _)| ps.iter().map(|p| (p.clone(), p.vertices_f64())))
        .collect();
    let mut scratch = VisiblePart::new();
    for (r, dm) in scene.receivers() {
        let own = dm.polygon();
        let n = own.support().unit_normal_f64();
        let two_sided = t
            .objects
            .iter()
            .any(|(ps, f)| f.two_sided && ps.iter().any(|p| p == own));
        let sided = if two_sided {
            Sidedness::TwoSided
        } else {
            Sidedness::OneSided
        };
        for (f, _) in dm.cells() {
            for v in dm.mesh().face_vertices(f) {
                let position = dm.mesh().vertex(v).unwrap().position;
                // Where an occluder touches or pierces the receiver the
                // irradiance jumps (a D0 discontinuity); a vertex there
                // gets the light it sees past the casters it lies on.
                let past: Vec<&[[f64; 3]]> = casters
                    .iter()
                    .filter(|(c, _)| {
                        !c.support().is_coincident(own.support())
                            && position.side(c.support()) != bsp_core::Side::On
                    })
                    .map(|(_, o)| o.as_slice())
                    .collect();
                let p = position.to_f64();
                if position.side(t.light.support()) == bsp_core::Side::On {
                    // Edge-on to the light: nothing arrives (f64 is
                    // ill-conditioned here where the receiver pierces the
                    // light, so `illum` is no oracle).
                    prop_assert_eq!(scene.vertex_irradiance(r, v), Some(0.0));
                    continue;
                }
                let got = scene.vertex_irradiance(r, v).unwrap();
                let truth = visible_irradiance(&light, &past, p, n, sided, &mut scratch);
                let full = light.irradiance(p, n, sided);
                // The contour integral sums terms of order pi (radiance 1)
                // that cancel at grazing angles: its absolute error is
                // some ulps of pi, whatever the value.
                prop_assert!(
                    (got - truth).abs() <= 1e-9 * full + 1e-12,
                    "vertex {p:?}: {got} vs {truth} (unoccluded {full})"
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn vertex_irradiance_matches_the_visible_part_past_every_occluder(t in scene()) {
        let (mut scene, _) = t.build();
        check_vertices(&t, &mut scene)?;
    }

    /// After a move, an illuminated scene evaluates again only the vertices
    /// whose covers changed and keeps the others' values: they are the
    /// values of the same scene illuminated only after the move (every
    /// vertex evaluated then), bit for bit. Once illuminated, a scene
    /// illuminates what a change touched as it makes it: the values are
    /// current before `illuminate` is called again, which reports that
    /// work, and a call after that has nothing to do.
    #[test]
    fn reilluminating_after_a_move_gives_the_values_of_illuminating_once(
        t in scene(),
        pick in 0_usize..64,
        d in prop::array::uniform3(-6_i64..=6),
    ) {
        let k = 1 + pick % (t.objects.len() - 1).max(1);
        prop_assume!(k < t.objects.len());
        let moved: Vec<ConvexPolygon> =
            t.objects[k].0.iter().map(|p| p.translated(d).unwrap()).collect();
        let (mut lazy, ids) = t.build();
        lazy.move_object(ids[k], moved.clone()).unwrap();
        let all = lazy.illuminate();
        prop_assert_eq!(all.evaluated, all.vertices);
        let (mut eager, ids) = t.build();
        eager.illuminate();
        eager.translate_object(ids[k], d).unwrap();
        same_values(&eager, &lazy)?;
        let stats = eager.illuminate();
        prop_assert!(stats.evaluated <= stats.vertices);
        same_values(&eager, &lazy)?;
        let again = eager.illuminate();
        prop_assert_eq!((again.vertices, again.evaluated), (0, 0));
    }
}

/// Both scenes have the same meshes with the same vertex irradiance, bit
/// for bit.
fn same_values(a: &DmScene, b: &DmScene) -> Result<(), TestCaseError> {
    let (ra, rb): (Vec<_>, Vec<_>) = (a.receivers().collect(), b.receivers().collect());
    prop_assert_eq!(ra.len(), rb.len());
    for ((pa, da), (pb, db)) in ra.into_iter().zip(rb) {
        prop_assert_eq!(pa, pb);
        prop_assert_eq!(da.mesh().counts(), db.mesh().counts());
        for ((va, _), (vb, _)) in da.mesh().vertices().zip(db.mesh().vertices()) {
            prop_assert_eq!(va, vb);
            let (ea, eb) = (a.vertex_irradiance(pa, va), b.vertex_irradiance(pb, vb));
            prop_assert!(ea.is_some());
            prop_assert_eq!(ea.map(f64::to_bits), eb.map(f64::to_bits));
        }
    }
    Ok(())
}

/// A box on a floor under a square light: irradiance at penumbra vertices
/// against a Monte Carlo estimate of `L * integral of cos cos / r^2` over
/// the light points the oracle says are visible.
#[test]
fn penumbra_vertices_agree_with_monte_carlo() {
    let t = TestScene {
        objects: vec![
            (vec![floor(300)], PieceFlags::default()),
            (
                cuboid([-40, 60, -30], [40, 90, 50]),
                PieceFlags {
                    closed_surface: true,
                    ..PieceFlags::default()
                },
            ),
        ],
        light: light(-50, -50, 100, 100, 200, 0),
    };
    let (mut scene, ids) = t.build();
    let stats = scene.illuminate();
    assert!(stats.visibility > 0);
    assert!(stats.comparisons_per_vertex() > 0.0);
    let floor_piece = scene.object_pieces(ids[0]).unwrap()[0];
    let dm = scene.receiver(floor_piece).unwrap();
    let casters = t.objects[1].0.clone();
    let own = dm.polygon().clone();
    let lv: Vec<[f64; 3]> = t.light.vertices().map(|g| g.to_f64()).collect();
    let area = t.light.polygon().area();
    let ln = t.light.support().unit_normal_f64();
    let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
    let mut checked = 0;
    for (f, cell) in dm.cells() {
        if dm.class(cell, 0) != CellClass::Penumbra || checked >= 6 {
            continue;
        }
        let v = dm.mesh().face_vertices(f)[0];
        let p = dm.mesh().vertex(v).unwrap().position.to_f64();
        let n = 40_000;
        let (mut sum, mut sum2) = (0.0, 0.0);
        for _ in 0..n {
            // Uniform on the parallelogram light.
            let (s, u): (f64, f64) = (rng.random(), rng.random());
            let x: [f64; 3] = std::array::from_fn(|k| {
                lv[0][k] + s * (lv[1][k] - lv[0][k]) + u * (lv[3][k] - lv[0][k])
            });
            let d: [f64; 3] = std::array::from_fn(|k| x[k] - p[k]);
            let r2 = d.iter().map(|c| c * c).sum::<f64>();
            let cos_r = d[1] / r2.sqrt();
            let cos_l = -(ln[0] * d[0] + ln[1] * d[1] + ln[2] * d[2]) / r2.sqrt();
            let value = if hidden(p, x, &casters, &own) {
                0.0
            } else {
                area * cos_r.max(0.0) * cos_l.max(0.0) / r2
            };
            sum += value;
            sum2 += value * value;
        }
        let mean = sum / f64::from(n);
        let sigma = ((sum2 / f64::from(n) - mean * mean).max(0.0) / f64::from(n)).sqrt();
        let got = scene.vertex_irradiance(floor_piece, v).unwrap();
        assert!(
            (got - mean).abs() <= 5.0 * sigma + 1e-6,
            "vertex {p:?}: {got} vs Monte Carlo {mean} +- {sigma}"
        );
        checked += 1;
    }
    assert!(checked > 0);
    let _ = interior_samples;
    let _ = gp;
}

/// A turned triangle under a square light: the internal EV / VE edges cut
/// the floor's penumbra into more cells than its outer and umbra
/// boundaries make (3 + 3 edges: at most 8 cells around them), and no
/// vertex needs the visible part past occluders that all its cells do not
/// list.
#[test]
fn internal_discontinuities_cut_the_penumbra() {
    let t = TestScene {
        objects: vec![
            (vec![floor(300)], PieceFlags::default()),
            (
                vec![
                    ConvexPolygon::from_grid_points(
                        &[gp(-30, 50, -10), gp(30, 50, -20), gp(0, 50, 40)],
                        0,
                    )
                    .unwrap(),
                ],
                PieceFlags::default(),
            ),
        ],
        light: light(-20, -20, 40, 40, 100, 0),
    };
    let (mut scene, ids) = t.build();
    let floor_piece = scene.object_pieces(ids[0]).unwrap()[0];
    let dm = scene.receiver(floor_piece).unwrap();
    dm.check_invariants().unwrap();
    let penumbra = dm
        .cells()
        .filter(|(_, c)| dm.class(c, 0) == CellClass::Penumbra)
        .count();
    assert!(penumbra > 8, "{penumbra} penumbra cells");
    let stats = scene.illuminate();
    assert!(
        stats.visibility > 0,
        "interior penumbra vertices need a visible part"
    );
    check_vertices(&t, &mut scene).unwrap();
}

/// A wall pierces the floor, its umbra on one side and a plank's penumbra
/// on the other: a vertex on the wall's trace has an umbra cell around it,
/// yet sees the light past the wall it lies on (the irradiance jumps
/// there; the closure argument of case 2 holds only off the umbra's
/// occluder). Its value is the light past the plank, as `illum` gives it
/// past every caster that does not hold the vertex.
#[test]
fn a_vertex_on_a_piercing_wall_sees_past_it() {
    // The wall in the plane x = 0, from below the floor to y = 80; the
    // light at x > 0, so the wall hides all of it just behind, near the
    // floor; the plank between the light and the wall's foot.
    let wall = ConvexPolygon::from_grid_points(
        &[
            gp(0, -20, -60),
            gp(0, -20, 60),
            gp(0, 80, 60),
            gp(0, 80, -60),
        ],
        0,
    )
    .unwrap();
    let plank = level_rect([10, 40], 40, [-30, 30]);
    let t = TestScene {
        objects: vec![
            (vec![floor(300)], PieceFlags::default()),
            (vec![wall.clone()], PieceFlags::default()),
            (vec![plank], PieceFlags::default()),
        ],
        light: light(60, -20, 40, 40, 100, 0),
    };
    let (mut scene, ids) = t.build();
    check_vertices(&t, &mut scene).unwrap();
    // Some vertex on the wall's trace lies by an umbra cell and gets light
    // (so the case above is met).
    let floor_piece = scene.object_pieces(ids[0]).unwrap()[0];
    let dm = scene.receiver(floor_piece).unwrap();
    let lit_by_umbra = dm.mesh().vertices().any(|(v, vertex)| {
        vertex.position.side(wall.support()) == bsp_core::Side::On
            && dm
                .mesh()
                .faces_around(v)
                .flatten()
                .any(|f| dm.class(&dm.mesh().face(f).unwrap().data, 0) == CellClass::Umbra)
            && scene.vertex_irradiance(floor_piece, v).unwrap() > 0.0
    });
    assert!(lit_by_umbra);
}

/// A box standing on the floor, a plank's penumbra over its foot: the
/// vertices at the foot lie on the box, by its umbra. On the side turned
/// to the light they see the light past the faces through them, as
/// `illum` gives it past the casters that do not hold them.
#[test]
fn a_box_foot_sees_past_the_faces_through_it() {
    let plank = level_rect([20, 40], 100, [-10, 10]);
    let t = TestScene {
        objects: vec![
            (vec![floor(300)], PieceFlags::default()),
            (
                cuboid([-30, 0, -30], [30, 50, 30]),
                PieceFlags {
                    closed_surface: true,
                    ..PieceFlags::default()
                },
            ),
            (vec![plank], PieceFlags::default()),
        ],
        light: light(40, -10, 40, 30, 140, 0),
    };
    let (mut scene, ids) = t.build();
    check_vertices(&t, &mut scene).unwrap();
    // Vertices at the foot, by an umbra cell, that get light.
    let floor_piece = scene.object_pieces(ids[0]).unwrap()[0];
    let dm = scene.receiver(floor_piece).unwrap();
    let foot: Vec<f64> = dm
        .mesh()
        .vertices()
        .filter(|(v, vertex)| {
            let [x, _, z] = vertex.position.to_f64();
            let on = |c: f64| (c.abs() - 30.0).abs() < 1e-9;
            let within = |c: f64| c.abs() <= 30.0 + 1e-9;
            (on(x) && within(z) || on(z) && within(x))
                && dm
                    .mesh()
                    .faces_around(*v)
                    .flatten()
                    .any(|f| dm.class(&dm.mesh().face(f).unwrap().data, 0) == CellClass::Umbra)
        })
        .map(|(v, _)| scene.vertex_irradiance(floor_piece, v).unwrap())
        .collect();
    assert!(foot.iter().any(|&e| e > 0.0), "{foot:?}");
}

/// The normal set on a receiver is the one light falls on (the light's
/// own irradiance at each vertex a plank leaves unoccluded, along that
/// normal), kept when the receiver moves parallel to itself and dropped
/// when its plane turns; bad normals and gone receivers are errors.
#[test]
fn a_receiver_normal_set_is_what_light_falls_on() {
    let area = light(-20, -20, 40, 40, 100, 0);
    let corners: Vec<[f64; 3]> = area.vertices().map(|g| g.to_f64()).collect();
    let own_light = illum::AreaLight::new(&corners, 1.0).unwrap();
    let plank = level_rect([-10, 10], 50, [-3, 3]);
    let flags = PieceFlags {
        casts_shadows: true,
        ..PieceFlags::default()
    };
    let objects = vec![(vec![floor(200)], flags), (vec![plank], flags)];
    let dm_light = dm_mesh::DmLight::new(area.clone(), 1.0).unwrap();
    let (mut scene, ids) = DmScene::build(vec![dm_light], objects).unwrap();
    let tilted = [0.2, 1.0, 0.1].map(|x: f64| x / 1.05_f64.sqrt());
    let floor_piece = scene.object_pieces(ids[0]).unwrap()[0];
    scene
        .set_receiver_normal(floor_piece, [0.4, 2.0, 0.2])
        .unwrap();
    // Vertices the plank leaves unoccluded get the whole light along
    // `normal`; returns how many there were.
    let check = |scene: &DmScene, normal: [f64; 3]| -> usize {
        let piece = scene.object_pieces(ids[0]).unwrap()[0];
        let dm = scene.receiver(piece).unwrap();
        let mut free = 0;
        for (f, _) in dm.cells() {
            for v in dm.mesh().face_vertices(f) {
                let p = dm.mesh().vertex(v).unwrap().position.to_f64();
                let whole = own_light.irradiance(p, normal, Sidedness::OneSided);
                let got = scene.vertex_irradiance(piece, v).unwrap();
                if (got - whole).abs() <= 1e-9 * whole {
                    free += 1;
                } else {
                    // Only the plank's shadow may take light away.
                    assert!(got < whole, "{got} above the whole light {whole} at {p:?}");
                }
            }
        }
        free
    };
    scene.illuminate();
    assert!(check(&scene, tilted) >= 4);
    // Moved parallel to itself (the floor down by 1): the normal stays.
    let down = floor(200).translated([0, -1, 0]).unwrap();
    scene.move_object(ids[0], vec![down]).unwrap();
    scene.illuminate();
    assert!(check(&scene, tilted) >= 4);
    // Turned (a floor tilted along x): its own normal again.
    let turned = ConvexPolygon::from_grid_points(
        &[
            gp(-200, -20, 200),
            gp(200, 20, 200),
            gp(200, 20, -200),
            gp(-200, -20, -200),
        ],
        0,
    )
    .unwrap();
    let own = turned.support().unit_normal_f64();
    scene.move_object(ids[0], vec![turned]).unwrap();
    scene.illuminate();
    assert!(check(&scene, own) >= 4);
    // Errors.
    let piece = scene.object_pieces(ids[0]).unwrap()[0];
    assert_eq!(
        scene.set_receiver_normal(piece, [0.0; 3]),
        Err(dm_mesh::Error::BadNormal)
    );
    assert_eq!(
        scene.set_receiver_normal(piece, [f64::NAN, 1.0, 0.0]),
        Err(dm_mesh::Error::BadNormal)
    );
    scene.remove_object(ids[0]).unwrap();
    assert_eq!(
        scene.set_receiver_normal(piece, [0.0, 1.0, 0.0]),
        Err(dm_mesh::Error::UnknownPiece)
    );
}
