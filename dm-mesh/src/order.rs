//! The order in which occluders are merged into a receiver's tree.
//!
//! Cells' occluder lists are sets: which occluders' penumbra volumes hold
//! the cell does not depend on the order, so the light is never split to
//! make a front-to-back order exist (the paper's "offending" polygons). The
//! order only decides how much umbra culling saves: an occluder is not
//! merged into cells already in another's umbra. As in area-shadow's
//! `AreaTrees::build`, units go nearest the light's centroid first, a
//! stand-in for front-to-back that finds most of the culling.
//!
//! Occluders of objects declared movable ([`DmScene::build_movable`]) go
//! after all the others, as a move leaves an object's units: removing
//! them then deletes nodes at the bottom of the trees, not above the other
//! occluders' (the first move of a box of the 10k hall placed by the
//! build deleted its nodes from the floor's tree in 10-12 ms, later moves
//! in 1.2-1.7 ms).
//!
//! [`DmScene::build_movable`]: crate::DmScene::build_movable

use crate::scene::{DmLight, Piece, PieceId, PieceKind};
use slotmap::SlotMap;
use std::cmp::Ordering;

/// The units (occluder, light) of `candidates` that cast any shadow, light
/// by light, each light's nearest first (ties by shape: [`by_shape`]),
/// bodies that cast only their umbra after the rest (such a
/// body hides the whole light only where its polygons hide it together;
/// merged last, it culls none of them); the static objects' units so, then
/// the movable objects' units so.
pub(crate) fn unit_order(
    lights: &[DmLight],
    pieces: &SlotMap<PieceId, Piece>,
    candidates: &[PieceId],
) -> Vec<(PieceId, u8)> {
    let mut out = Vec::new();
    for movable in [false, true] {
        for (i, light) in lights.iter().enumerate() {
            let centre = light.source.centroid();
            let mut list: Vec<(bool, f64, usize)> = candidates
                .iter()
                .enumerate()
                .filter(|(_, k)| {
                    let piece = &pieces[**k];
                    piece.movable == movable && !piece.volumes[i].volumes.penumbra.is_empty()
                })
                .map(|(n, k)| {
                    let piece = &pieces[*k];
                    (piece.umbra_only(i), distance2(piece.centre(), centre), n)
                })
                .collect();
            list.sort_by(|a, b| {
                a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then_with(|| {
                    let (p, q) = (&pieces[candidates[a.2]], &pieces[candidates[b.2]]);
                    by_shape(p, q).then(a.2.cmp(&b.2))
                })
            });
            out.extend(list.into_iter().map(|(_, _, n)| (candidates[n], i as u8)));
        }
    }
    out
}

/// Occluders equally near the light, in an order of their shapes alone:
/// polygons before bodies, then by centre, then by outline. Keys would
/// order them as they were made, so the same occluders made in another
/// order (a scene's closed parts as objects of their own, or in one
/// object) would merge in another order and give other trees.
fn by_shape(p: &Piece, q: &Piece) -> Ordering {
    let rank = |p: &Piece| p.kind == PieceKind::Body;
    let coordinates = |p: &Piece| -> Vec<f64> {
        p.centre()
            .into_iter()
            .chain(p.outline.iter().flatten().copied())
            .collect()
    };
    rank(p).cmp(&rank(q)).then_with(|| {
        let (a, b) = (coordinates(p), coordinates(q));
        a.len().cmp(&b.len()).then_with(|| {
            a.iter()
                .zip(&b)
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(Ordering::Equal)
        })
    })
}

fn distance2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}

#[cfg(test)]
mod tests {
    use super::{distance2, unit_order};
    use crate::scene::testing::{boxes_on_a_floor_movable, closed, cuboid, gp, moved, quad};
    use crate::scene::{DmLight, DmScene, PieceId};
    use area_shadow::AreaSource;

    /// Per receiver, whether each of its units (in the order merged) is of
    /// one of the objects `of`.
    fn units_of(scene: &DmScene, of: &[crate::ObjectId]) -> Vec<Vec<bool>> {
        let object = |o| scene.pieces[o].object;
        scene
            .receivers
            .values()
            .map(|dm| {
                dm.units()
                    .map(|(_, (o, _))| of.contains(&object(o)))
                    .collect()
            })
            .collect()
    }

    /// Whether no `true` comes before a `false`.
    fn last(units: &[bool]) -> bool {
        units.windows(2).all(|w| w[0] <= w[1])
    }

    /// Objects declared movable are merged after the static ones (of both
    /// lights) in every receiver, at the build and after their moves; in a
    /// plain build the same boxes come before some static ones.
    #[test]
    fn movable_objects_are_merged_after_the_static_ones() {
        let movable = [2, 6];
        let (plain, ids) = boxes_on_a_floor_movable(&[]);
        let chosen = movable.map(|k| ids[k]);
        assert!(units_of(&plain, &chosen).iter().any(|u| !last(u)));
        let (mut scene, ids) = boxes_on_a_floor_movable(&movable);
        let chosen = movable.map(|k| ids[k]);
        assert!(scene.is_movable(chosen[0]) && !scene.is_movable(ids[1]));
        for step in 0..4_i64 {
            let each = units_of(&scene, &chosen);
            assert!(each.iter().all(|u| last(u)), "step {step}");
            assert!(each.iter().any(|u| u.contains(&false) && u.contains(&true)));
            let id = chosen[step as usize % 2];
            let polygons = moved(&scene, id, [7 - 5 * step, 0, 3 * step - 4]);
            scene.move_object(id, polygons).expect("a move");
        }
    }

    /// Occluders equally near the light merge in one order whichever
    /// order they come in (as their keys give it): two boxes mirrored
    /// through the light's axis, listed forwards and backwards.
    #[test]
    fn equally_near_occluders_merge_in_an_order_of_their_shapes() {
        let light = quad([
            gp(-60, 500, -45),
            gp(60, 500, -45),
            gp(60, 500, 45),
            gp(-60, 500, 45),
        ]);
        let light = AreaSource::new(light).expect("a light facing down");
        let light = DmLight::new(light, 1.0).expect("a light");
        let objects = vec![
            (cuboid([-100, 0, -30], [-40, 50, 30]), closed()),
            (cuboid([40, 0, -30], [100, 50, 30]), closed()),
        ];
        let (scene, _) = DmScene::build(vec![light], objects).expect("a scene");
        let centre = scene.lights()[0].source().centroid();
        let keys: Vec<PieceId> = scene.pieces.keys().collect();
        let near = |k: &PieceId| distance2(scene.pieces[*k].centre(), centre);
        let mut distances: Vec<f64> = keys.iter().map(near).collect();
        distances.sort_by(f64::total_cmp);
        assert!(distances.windows(2).any(|w| w[0] == w[1]), "no tie");
        let forwards = unit_order(scene.lights(), &scene.pieces, &keys);
        let backwards: Vec<PieceId> = keys.iter().rev().copied().collect();
        assert!(!forwards.is_empty());
        assert_eq!(
            forwards,
            unit_order(scene.lights(), &scene.pieces, &backwards)
        );
    }
}
