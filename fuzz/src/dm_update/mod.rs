//! Target `dm_update`: a small scene under an area light kept as
//! discontinuity meshes (dm-mesh) through a sequence of moves, removals and
//! re-additions.
//!
//! [`DmCase::arbitrary`] decodes a floor, up to four objects of one or two
//! triangles, four (a tetrahedron, a convex body casting one unit) or
//! twelve (a box; boxes often touch face to face and make a joint body) with
//! small coordinates (they touch, share planes and cross the light's
//! plane), a parallelogram light, up to six operations and the
//! way removals work (the paper's local deletion unless the last byte asks
//! for collapse and re-merge). [`check_dm_update`] applies them and checks
//! the scene's invariants after every one (trees, meshes, and every cell's
//! occluder list against the volumes, exactly), then that every receiver
//! has the lit, penumbra and umbra areas of a from-scratch build of the
//! final scene and of area-shadow's independent classification.

mod shapes;
#[cfg(test)]
mod tests;

use arbitrary::{Arbitrary, Unstructured};
use area_shadow::{AreaSource, Class, SceneLight, ShadowGroups, compute_shadows_with_groups};
use bsp_core::{BuildOptions, ConvexPolygon, GridPoint};
use dm_mesh::{CellClass, Deletion, DmLight, DmOptions, DmScene, ObjectId, PieceId};
use std::collections::HashMap;
use svbsp::PieceFlags;

use shapes::{box_triangles, dented_box_triangles, frame_triangles, triangles};

/// One operation on object `object % objects`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// Moves it by a small offset (kept on the grid).
    Move(u8, [i8; 3]),
    /// Removes it (if present).
    Remove(u8),
    /// Adds it back (if removed).
    ReAdd(u8),
}

/// One decoded input of the `dm_update` target; its `Debug` output is Rust
/// code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DmCase {
    /// Objects of one or two triangles, a tetrahedron's four, a box's
    /// twelve, a dented box's fourteen or a square frame's 32, over the
    /// floor.
    pub objects: Vec<Vec<[[i64; 3]; 3]>>,
    /// The light: corner, extents along x and z, rise along x.
    pub light: ([i64; 3], [i64; 2], i64),
    /// The operations, in order.
    pub ops: Vec<Op>,
    /// How removals take discontinuities out.
    pub deletion: Deletion,
    /// Bit `k`: object `k` declared movable at the build
    /// (`DmScene::build_movable`: its units merged after the static ones).
    pub movable: u8,
}

fn coordinate(u: &mut Unstructured<'_>, lo: i8, hi: i8) -> arbitrary::Result<i64> {
    Ok(i64::from(u.int_in_range(lo..=hi)?))
}

impl<'a> Arbitrary<'a> for DmCase {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        let n = u.int_in_range(1_usize..=4)?;
        let mut objects = Vec::with_capacity(n);
        let point = |u: &mut Unstructured<'a>| -> arbitrary::Result<[i64; 3]> {
            Ok([
                coordinate(u, -8, 8)?,
                coordinate(u, 1, 14)?,
                coordinate(u, -8, 8)?,
            ])
        };
        for _ in 0..n {
            // One or two triangles, (3) a tetrahedron: a convex body, (4)
            // an axis-aligned box of twelve triangles (small sizes on the
            // small grid: boxes often touch face to face and join), or (5)
            // a box with its top dented: a closed surface no nudge makes
            // convex, which a core of its kernel stands for, or (6) a
            // square frame: a closed surface with no kernel, which cores
            // of local kernels stand for.
            let k = u.int_in_range(1_usize..=6)?;
            let triangles = if k == 6 {
                let lo = point(u)?;
                let size = [
                    coordinate(u, 3, 6)?,
                    coordinate(u, 1, 3)?,
                    coordinate(u, 3, 6)?,
                ];
                let hi = [0, 1, 2].map(|a| lo[a] + size[a]);
                let hole_lo = [
                    u.int_in_range(lo[0] + 1..=hi[0] - 2)?,
                    u.int_in_range(lo[2] + 1..=hi[2] - 2)?,
                ];
                let hole_hi = [
                    u.int_in_range(hole_lo[0] + 1..=hi[0] - 1)?,
                    u.int_in_range(hole_lo[1] + 1..=hi[2] - 1)?,
                ];
                frame_triangles(lo, hi, hole_lo, hole_hi)
            } else if k == 5 {
                let lo = point(u)?;
                let size = [
                    coordinate(u, 2, 4)?,
                    coordinate(u, 2, 4)?,
                    coordinate(u, 2, 4)?,
                ];
                let hi = [0, 1, 2].map(|a| lo[a] + size[a]);
                let apex = [
                    u.int_in_range(lo[0] + 1..=hi[0] - 1)?,
                    u.int_in_range(lo[1] + 1..=hi[1] - 1)?,
                    u.int_in_range(lo[2] + 1..=hi[2] - 1)?,
                ];
                dented_box_triangles(lo, hi, apex)
            } else if k == 4 {
                let lo = point(u)?;
                let size = [
                    coordinate(u, 1, 4)?,
                    coordinate(u, 1, 4)?,
                    coordinate(u, 1, 4)?,
                ];
                box_triangles(lo, [0, 1, 2].map(|a| lo[a] + size[a]))
            } else if k == 3 {
                let [a, b, c, d] = [point(u)?, point(u)?, point(u)?, point(u)?];
                // Consistently oriented: every edge once each way.
                vec![[a, b, c], [a, c, d], [a, d, b], [b, d, c]]
            } else {
                let mut triangles = Vec::with_capacity(k);
                for _ in 0..k {
                    triangles.push([point(u)?, point(u)?, point(u)?]);
                }
                triangles
            };
            objects.push(triangles);
        }
        let corner = [
            coordinate(u, -6, 4)?,
            coordinate(u, 9, 12)?,
            coordinate(u, -6, 4)?,
        ];
        let size = [coordinate(u, 1, 5)?, coordinate(u, 1, 5)?];
        let rise = coordinate(u, -3, 3)?;
        let m = u.int_in_range(0_usize..=6)?;
        let mut ops = Vec::with_capacity(m);
        for _ in 0..m {
            let object = u.arbitrary::<u8>()?;
            ops.push(match u.int_in_range(0_u8..=3)? {
                0 | 1 => Op::Move(
                    object,
                    [
                        u.int_in_range(-3_i8..=3)?,
                        u.int_in_range(-2_i8..=2)?,
                        u.int_in_range(-3_i8..=3)?,
                    ],
                ),
                2 => Op::Remove(object),
                _ => Op::ReAdd(object),
            });
        }
        // Past the end of the data this reads `false`: local deletion.
        let deletion = if u.arbitrary::<bool>()? {
            Deletion::Collapse
        } else {
            Deletion::Local
        };
        // Past the end of the data: no object declared movable.
        let movable = u.arbitrary::<u8>()?;
        Ok(Self {
            objects,
            light: (corner, size, rise),
            ops,
            deletion,
            movable,
        })
    }
}

/// Decodes fuzzer bytes.
pub fn decode(data: &[u8]) -> Option<DmCase> {
    DmCase::arbitrary_take_rest(Unstructured::new(data)).ok()
}

/// The body of the `dm_update` fuzz target.
pub fn run(data: &[u8]) {
    let Some(case) = decode(data) else { return };
    if let Err(problem) = check_dm_update(&case) {
        panic!("dm_update invariant violated: {problem}\n{case:?}");
    }
}

fn gp(p: [i64; 3]) -> Option<GridPoint> {
    GridPoint::new(p[0], p[1], p[2]).ok()
}

/// Flags of the case's object `k` (from 0): two-sided, and every other
/// one said to have closed parts (the DM finds which, and skips their
/// faces turned away from a light clear of them).
fn object_flags(k: usize) -> PieceFlags {
    PieceFlags {
        two_sided: true,
        closed_surface: k % 2 == 1,
        ..PieceFlags::default()
    }
}

/// Per polygon of `objects`, its flags for area-shadow: the object's, a
/// closed surface only where the polygon is part of a closed part facing
/// out (of an object said to have some) that `light` lies clear of, as
/// the DM decides it.
fn piece_flags(
    objects: &[(Vec<ConvexPolygon>, PieceFlags)],
    light: &AreaSource,
) -> Vec<PieceFlags> {
    let mut flags = Vec::new();
    for (polygons, object) in objects {
        let mut closed = vec![false; polygons.len()];
        if object.closed_surface && object.casts_shadows {
            for part in area_shadow::closed_parts(polygons, &vec![0; polygons.len()]) {
                if part.six_volume > 0 && light.clear_of(&part.corners(polygons)) {
                    for &k in &part.pieces {
                        closed[k as usize] = true;
                    }
                }
            }
        }
        flags.extend(closed.into_iter().map(|closed_surface| PieceFlags {
            closed_surface,
            ..*object
        }));
    }
    flags
}

/// Area per class (lit, penumbra, umbra) of each receiver, objects in
/// order.
fn areas(scene: &DmScene, ids: &[ObjectId]) -> Result<Vec<[f64; 3]>, String> {
    let mut out = Vec::new();
    for id in ids {
        let pieces: &[PieceId] = scene.object_pieces(*id).ok_or("object lost")?;
        for &p in pieces {
            let dm = scene.receiver(p).ok_or("receiver lost")?;
            let mut a = [0.0; 3];
            for (f, cell) in dm.cells() {
                let area = dm
                    .mesh()
                    .face_polygon(f, 0)
                    .map_err(|e| e.to_string())?
                    .area();
                a[match dm.class(cell, 0) {
                    CellClass::Lit => 0,
                    CellClass::Penumbra => 1,
                    CellClass::Umbra => 2,
                }] += area;
            }
            out.push(a);
        }
    }
    Ok(out)
}

/// Vertex irradiance of the updated scene `a` against the rebuilt `b`,
/// where both have a vertex (at the same coordinates).
/// Per receiver, what it holds: per cell its vertices (coordinate bits),
/// entries and vertex irradiance bits.
type ReceiverPrints = HashMap<PieceId, Vec<(Vec<[u64; 3]>, Vec<dm_mesh::Entry>, Vec<u64>)>>;

fn receiver_prints(scene: &DmScene) -> ReceiverPrints {
    scene
        .receivers()
        .map(|(piece, dm)| {
            let cells = dm
                .cells()
                .map(|(face, cell)| {
                    let vertices = dm.mesh().face_vertices(face);
                    let position = |v| dm.mesh().vertex(v).map(|v| v.position.to_f64());
                    (
                        vertices
                            .iter()
                            .map(|&v| position(v).unwrap_or_default().map(f64::to_bits))
                            .collect(),
                        cell.entries().to_vec(),
                        vertices
                            .iter()
                            .map(|&v| scene.vertex_irradiance(piece, v).unwrap_or(-1.0).to_bits())
                            .collect(),
                    )
                })
                .collect();
            (piece, cells)
        })
        .collect()
}

/// Every receiver a change left unlisted (`receivers_changed_since`)
/// holds what it held before, and every new one is listed.
fn unlisted_unchanged(scene: &DmScene, before: &ReceiverPrints, since: u64) -> Result<(), String> {
    let listed: std::collections::HashSet<PieceId> = scene.receivers_changed_since(since).collect();
    let now = receiver_prints(scene);
    for (piece, print) in &now {
        if !listed.contains(piece) && before.get(piece) != Some(print) {
            return Err(format!("receiver {piece:?} changed, but is not listed"));
        }
    }
    Ok(())
}

fn same_irradiance(
    a: &DmScene,
    ids_a: &[ObjectId],
    b: &DmScene,
    ids_b: &[ObjectId],
) -> Result<(), String> {
    let pieces = |scene: &DmScene, ids: &[ObjectId]| -> Result<Vec<PieceId>, String> {
        let mut out = Vec::new();
        for id in ids {
            out.extend_from_slice(scene.object_pieces(*id).ok_or("object lost")?);
        }
        Ok(out)
    };
    for (ra, rb) in pieces(a, ids_a)?.into_iter().zip(pieces(b, ids_b)?) {
        let (da, db) = (
            a.receiver(ra).ok_or("receiver lost")?,
            b.receiver(rb).ok_or("receiver lost")?,
        );
        let mut at: HashMap<[u64; 3], f64> = HashMap::new();
        for (v, vertex) in db.mesh().vertices() {
            let e = b
                .vertex_irradiance(rb, v)
                .ok_or("a rebuilt vertex has no value")?;
            at.insert(vertex.position.to_f64().map(f64::to_bits), e);
        }
        for (v, vertex) in da.mesh().vertices() {
            let ea = a
                .vertex_irradiance(ra, v)
                .ok_or("an updated vertex has no value")?;
            let p = vertex.position.to_f64();
            if let Some(&eb) = at.get(&p.map(f64::to_bits))
                && (ea - eb).abs() > 1e-9 * ea.abs().max(eb.abs()) + 1e-15
            {
                return Err(format!("irradiance at {p:?}: updated {ea} vs rebuilt {eb}"));
            }
        }
    }
    Ok(())
}

/// Applies the operations and checks; `Err` describes the first violated
/// invariant.
pub fn check_dm_update(case: &DmCase) -> Result<(), String> {
    let corners = [[-20, 0, 20], [20, 0, 20], [20, 0, -20], [-20, 0, -20]];
    let floor: Vec<GridPoint> = corners.iter().filter_map(|&c| gp(c)).collect();
    let floor = ConvexPolygon::from_grid_points(&floor, 0).map_err(|e| e.to_string())?;
    let ([x, y, z], [w, d], rise) = case.light;
    let quad: Vec<GridPoint> = [
        [x, y, z],
        [x + w, y + rise, z],
        [x + w, y + rise, z + d],
        [x, y, z + d],
    ]
    .iter()
    .filter_map(|&p| gp(p))
    .collect();
    let polygon = ConvexPolygon::from_grid_points(&quad, 0).map_err(|e| e.to_string())?;
    let polygon = if polygon.support().normal()[1] < 0 {
        polygon
    } else {
        polygon.flipped()
    };
    let source = AreaSource::new(polygon).map_err(|e| e.to_string())?;
    let light = DmLight::new(source.clone(), 1.0).map_err(|e| e.to_string())?;

    let mut objects: Vec<(Vec<ConvexPolygon>, PieceFlags)> =
        vec![(vec![floor], PieceFlags::default())];
    objects.extend(
        case.objects
            .iter()
            .enumerate()
            .map(|(k, ts)| (triangles(ts, [0; 3]), object_flags(k))),
    );
    let options = DmOptions {
        deletion: case.deletion,
        ..DmOptions::default()
    };
    // (Scene object 0 is the floor.)
    let declared: Vec<usize> = (0..case.objects.len())
        .filter(|k| case.movable >> k & 1 == 1)
        .map(|k| k + 1)
        .collect();
    let (mut scene, ids) =
        DmScene::build_movable(vec![light.clone()], objects.clone(), &declared, options)
            .map_err(|e| e.to_string())?;
    // The model: per object its offset and whether it is present.
    let mut state: Vec<(Option<ObjectId>, [i64; 3])> =
        ids.iter().map(|id| (Some(*id), [0; 3])).collect();
    let check = |scene: &DmScene, what: &str| -> Result<(), String> {
        scene
            .check_invariants()
            .map_err(|e| format!("after {what}: {e}"))
    };
    check(&scene, "the build")?;
    // Illuminated once, the scene illuminates what each change touches as
    // it makes it.
    scene.illuminate();
    let movable = case.objects.len();
    for op in &case.ops {
        let k = |o: u8| 1 + usize::from(o) % movable;
        let (since, before) = (scene.revision(), receiver_prints(&scene));
        match *op {
            Op::Move(o, by) => {
                let k = k(o);
                if let (Some(id), offset) = state[k] {
                    let next = [0, 1, 2].map(|i| offset[i] + i64::from(by[i]));
                    let moved = triangles(&case.objects[k - 1], next);
                    scene.move_object(id, moved).map_err(|e| e.to_string())?;
                    state[k].1 = next;
                }
            }
            Op::Remove(o) => {
                let k = k(o);
                if let Some(id) = state[k].0.take() {
                    scene.remove_object(id).map_err(|e| e.to_string())?;
                }
            }
            Op::ReAdd(o) => {
                let k = k(o);
                if state[k].0.is_none() {
                    let polygons = triangles(&case.objects[k - 1], state[k].1);
                    state[k].0 = Some(
                        scene
                            .add_object(polygons, object_flags(k - 1))
                            .map_err(|e| e.to_string())?,
                    );
                }
            }
        }
        check(&scene, &format!("{op:?}"))?;
        unlisted_unchanged(&scene, &before, since).map_err(|e| format!("after {op:?}: {e}"))?;
    }
    scene.illuminate();

    // The final scene from scratch, and area-shadow's classification of it.
    let mut live_ids = Vec::new();
    let mut live = Vec::new();
    for (k, (id, offset)) in state.iter().enumerate() {
        let Some(id) = id else { continue };
        live_ids.push(*id);
        live.push(if k == 0 {
            objects[0].clone()
        } else {
            (
                triangles(&case.objects[k - 1], *offset),
                object_flags(k - 1),
            )
        });
    }
    let (mut fresh, fresh_ids) =
        DmScene::build(vec![light], live.clone()).map_err(|e| e.to_string())?;
    fresh.illuminate();
    same_irradiance(&scene, &live_ids, &fresh, &fresh_ids)?;
    let got = areas(&scene, &live_ids)?;
    let want = areas(&fresh, &fresh_ids)?;
    let polygons: Vec<ConvexPolygon> = live
        .iter()
        .flat_map(|(ps, _)| ps.iter().cloned())
        .enumerate()
        .map(|(k, p)| p.with_source(k as u32))
        .collect();
    let flags = piece_flags(&live, &source);
    // Bodies (pieces hiding the light together) form within objects, as
    // in dm-mesh.
    let objects_of: Vec<u32> = live
        .iter()
        .enumerate()
        .flat_map(|(o, (ps, _))| std::iter::repeat_n(o as u32, ps.len()))
        .collect();
    let groups = ShadowGroups::of_objects(&polygons, &flags, &objects_of);
    let shadows = compute_shadows_with_groups(
        &polygons,
        &flags,
        &groups,
        &[SceneLight::Area(source)],
        &BuildOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    let mut truth = vec![[0.0; 3]; polygons.len()];
    for f in &shadows.fragments {
        let c = match Class::of(f, 0) {
            Class::Lit => 0,
            Class::Penumbra => 1,
            Class::Umbra => 2,
        };
        truth[f.polygon.source() as usize][c] += f.polygon.area();
    }
    if got.len() != want.len() || got.len() != polygons.len() {
        return Err(format!("{} receivers, rebuilt {}", got.len(), want.len()));
    }
    for (k, p) in polygons.iter().enumerate() {
        let scale = p.area();
        for c in 0..3 {
            if (got[k][c] - want[k][c]).abs() > 1e-9 * scale {
                return Err(format!(
                    "receiver {k} class {c}: updated {} vs rebuilt {}",
                    got[k][c], want[k][c]
                ));
            }
            if (got[k][c] - truth[k][c]).abs() > 1e-9 * scale {
                return Err(format!(
                    "receiver {k} class {c}: updated {} vs area-shadow {}",
                    got[k][c], truth[k][c]
                ));
            }
        }
    }
    Ok(())
}
