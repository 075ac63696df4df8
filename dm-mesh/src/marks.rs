//! A set of numbers below a bound (node numbers, arena slots) kept as one
//! bit each, that threads mark side by side.
//!
//! A flood over a big receiver's cells asks of each cell, again and again
//! from its neighbours, whether it was reached yet. As bits by leaf number
//! the answers for the 10k hall floor (1.3M nodes) take 160 kB, with no
//! hashing and no table to grow: a small box's removal floods about 4k of
//! its cells (some 20k questions) in 0.9-1.2 ms, where a hash set of their
//! faces took 1.1-1.3 ms (2 cores, loaded machine). Two threads may flood
//! side by side (module `tree::removal::flood`), and threads gathering a
//! big receiver's changed vertices side by side mark them by arena slot.
//! Most questions are about numbers marked already, which a load answers
//! (the atomic read-modify-write only marks).

use slotmap::Key;
use std::sync::atomic::{AtomicU64, Ordering};

/// Numbers below a bound, each marked or not, that threads mark side by
/// side.
pub(crate) struct SharedMarks {
    words: Vec<AtomicU64>,
}

impl SharedMarks {
    /// No number below `len` marked.
    pub(crate) fn new(len: usize) -> Self {
        Self {
            words: (0..len.div_ceil(64)).map(|_| AtomicU64::new(0)).collect(),
        }
    }

    /// Marks `n`; whether it was not marked before, by this call or
    /// another's. (A number past the bound is new every time: its user
    /// then does its work twice, which is all that goes wrong.)
    pub(crate) fn insert(&self, n: u32) -> bool {
        let (word, bit) = ((n / 64) as usize, 1_u64 << (n % 64));
        // (Most numbers asked about are marked already: a load answers
        // them without the exclusive access a read-modify-write takes.)
        self.words.get(word).is_none_or(|w| {
            w.load(Ordering::Relaxed) & bit == 0 && w.fetch_or(bit, Ordering::Relaxed) & bit == 0
        })
    }
}

/// The slot of an arena key: distinct for the live keys of a slot map,
/// and below its capacity plus one.
pub(crate) fn slot<K: Key>(key: K) -> u32 {
    // (A key's FFI form holds its slot in the low half, which `slotmap`
    // does not promise: the test `slots_are_distinct_and_bounded` checks
    // it for the version in use.)
    key.data().as_ffi() as u32
}

#[cfg(test)]
mod tests {
    use super::SharedMarks;

    #[test]
    fn a_number_is_new_once() {
        let marks = SharedMarks::new(130);
        for n in [0, 63, 64, 129, 5] {
            assert!(marks.insert(n), "{n} is new");
        }
        for n in [0, 63, 64, 129, 5] {
            assert!(!marks.insert(n), "{n} was marked");
        }
        assert!(marks.insert(1));
        assert!(marks.insert(128));
    }

    /// The slots of a slot map's live keys, after removals and insertions
    /// that reuse slots, are distinct and below its capacity plus one.
    #[test]
    fn slots_are_distinct_and_bounded() {
        use super::slot;
        use slotmap::{DefaultKey, SlotMap};
        let mut map: SlotMap<DefaultKey, u32> = SlotMap::new();
        let keys: Vec<DefaultKey> = (0..1000).map(|i| map.insert(i)).collect();
        for k in keys.iter().step_by(3) {
            map.remove(*k);
        }
        for i in 0..500 {
            map.insert(i);
        }
        let mut slots: Vec<u32> = map.keys().map(slot).collect();
        assert!(slots.iter().all(|&s| (s as usize) < map.capacity() + 1));
        slots.sort_unstable();
        slots.dedup();
        assert_eq!(slots.len(), map.len());
    }

    /// Threads marking the same numbers side by side: each number is new
    /// to exactly one of them.
    #[test]
    fn a_shared_number_is_new_to_one_thread() {
        use rayon::prelude::*;
        let marks = SharedMarks::new(5000);
        let fresh: usize = (0..8)
            .into_par_iter()
            .map(|_| (0..5000).filter(|&n| marks.insert(n)).count())
            .sum();
        assert_eq!(fresh, 5000);
        assert!(!marks.insert(4999));
        assert!(marks.insert(9000) && marks.insert(9000), "past the bound");
    }
}
