//! Hash maps and sets keyed by the crate's own keys (grid points, planes,
//! piece numbers): rustc's Fx hash. No protection against chosen keys is
//! needed, and SipHash was a fifth of the sequential part of a box's move
//! in `dm-mesh` (grouping a moved object's polygons into bodies).

/// A `HashMap` keyed by the crate's keys.
pub(crate) type HashMap<K, V> = rustc_hash::FxHashMap<K, V>;

/// A `HashSet` keyed by the crate's keys.
pub(crate) type HashSet<T> = rustc_hash::FxHashSet<T>;
