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
        dm.remove_units(&[unit].into(), |k, _| &planes[k as usize], how);
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
