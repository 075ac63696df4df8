//! Removals from one receiver's tree against trees built without the
//! removed units.

use super::Deletion;
use crate::tree::testing::{fresh, fresh_tiled, numbered, occluders, same_regions};
use crate::tree::{LIGHT_UNIT, Node};
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_pcg::Pcg64;

fn remove_one_by_one(how: Deletion, seed: u64) {
    let mut rng = Pcg64::seed_from_u64(seed);
    let planes = occluders(&mut rng, 9);
    let units = numbered(&planes);
    // Odd seeds start from a tree whose tiles were grown apart.
    let mut dm = if seed % 2 == 1 {
        fresh_tiled(&units, 2)
    } else {
        fresh(&units, 2)
    };
    dm.check_invariants().unwrap();
    dm.check_lists(|k, _| &planes[k as usize]).unwrap();
    let mut live = units.clone();
    live.shuffle(&mut rng);
    while let Some((key, _)) = live.pop() {
        let unit = dm.units().find(|(_, (k, _))| *k == key).unwrap().0;
        dm.remove_units(&[unit].into(), |k, _| &planes[k as usize], how, None);
        dm.check_invariants().unwrap();
        dm.check_lists(|k, _| &planes[k as usize]).unwrap();
        let mut rest = live.clone();
        rest.sort_unstable_by_key(|u| u.0);
        same_regions(&dm, &fresh(&rest, 2));
    }
    // Nothing left: only the light plane's and the tiles' lines remain.
    let bare = fresh(&[], 2);
    assert!(
        dm.nodes
            .iter()
            .all(|n| !matches!(n, Node::Split { unit, .. } if *unit != LIGHT_UNIT)),
        "{:?} deletion left nodes behind",
        how
    );
    assert_eq!(dm.cell_count(), bare.cell_count());
}

#[test]
fn local_deletion_agrees_with_trees_built_without_the_unit() {
    for seed in 0..6 {
        remove_one_by_one(Deletion::Local, seed);
    }
}

#[test]
fn collapse_agrees_with_trees_built_without_the_unit() {
    for seed in 0..3 {
        remove_one_by_one(Deletion::Collapse, seed);
    }
}

/// Two threads flooding side by side find the cells one thread finds
/// alone, for one unit and for several.
#[test]
fn a_flood_shared_by_two_threads_finds_what_one_finds() {
    let mut compared = 0;
    for seed in 0..4 {
        let mut rng = Pcg64::seed_from_u64(100 + seed);
        let planes = occluders(&mut rng, 24);
        let units = numbered(&planes);
        let dm = if seed % 2 == 1 {
            fresh_tiled(&units, 2)
        } else {
            fresh(&units, 2)
        };
        let single = |k: u32, _| planes[k as usize].volumes.penumbra.len() == 1;
        for keys in [vec![3_u32], vec![0, 7, 8], (0..24).collect()] {
            let removed: Vec<_> = dm
                .units()
                .filter(|(_, (k, _))| keys.contains(k))
                .map(|(u, (k, light))| (u, light, &planes[k as usize]))
                .collect();
            let Some(flood) = dm.flood_ahead(|k| keys.contains(&k), single) else {
                continue;
            };
            let ready = std::sync::Barrier::new(2);
            std::thread::scope(|s| {
                for _ in 0..2 {
                    s.spawn(|| {
                        ready.wait();
                        flood.help(&dm);
                    });
                }
            });
            let flooded = flood.finish();
            let units: Vec<u32> = removed.iter().map(|r| r.0).collect();
            assert_eq!(flooded.units, units);
            assert_eq!(
                flooded.held,
                dm.cells_of(&removed, None),
                "seed {seed}, units {keys:?}"
            );
            compared += 1;
        }
    }
    assert!(compared >= 4, "{compared} floods compared");
}
