//! Hash maps and sets keyed by the crate's own keys (slotmap handles, node
//! numbers, grid cells): rustc's Fx hash, as no protection against chosen
//! keys is needed (SipHash was a tenth of a removal's cost).

/// A `HashSet` keyed by the crate's keys.
pub(crate) type KeySet<T> = rustc_hash::FxHashSet<T>;

/// A `HashMap` keyed by the crate's keys.
pub(crate) type KeyMap<K, V> = rustc_hash::FxHashMap<K, V>;
