//! A fast hasher for the crate's own keys (slotmap handles and node
//! numbers): no protection against chosen keys is needed, and SipHash was
//! a tenth of a removal's cost.

use std::hash::{BuildHasherDefault, Hasher};

/// A multiply-rotate hasher (after rustc's FxHash).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0_u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u32(&mut self, n: u32) {
        self.write_u64(u64::from(n));
    }

    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// A `HashSet` keyed by the crate's keys.
pub(crate) type KeySet<T> = std::collections::HashSet<T, BuildHasherDefault<KeyHasher>>;

/// A `HashMap` keyed by the crate's keys.
pub(crate) type KeyMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<KeyHasher>>;
