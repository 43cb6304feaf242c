//! A bounded least-recently-used cache of compiled shaders or pipelines, keyed by the 64-bit
//! key an emitter computes for the text it would produce.
//!
//! Generic over the cached value, so the 2D renderer keeps wgpu pipelines in it and the 3D
//! raymarcher can do the same. Creating a pipeline is expensive and its text is a pure
//! function of the key, so a hit skips both the emission and the driver compile. Memory stays
//! bounded: inserting beyond the capacity evicts the entry used longest ago.

use std::collections::BTreeMap;

/// One cached value and when it was last used.
#[derive(Debug)]
struct Entry<V> {
    value: V,
    last_used: u64,
}

/// Bounded LRU cache from `u64` keys to values.
#[derive(Debug)]
pub struct PipelineCache<V> {
    capacity: usize,
    entries: BTreeMap<u64, Entry<V>>,
    /// Last-use stamp -> key, oldest first: finds the eviction victim in O(log n).
    by_age: BTreeMap<u64, u64>,
    clock: u64,
    hits: u64,
    misses: u64,
}

impl<V> PipelineCache<V> {
    /// An empty cache holding at most `capacity` values (at least one: a cache that holds
    /// nothing would recompile on every frame).
    pub fn new(capacity: usize) -> PipelineCache<V> {
        PipelineCache {
            capacity: capacity.max(1),
            entries: BTreeMap::new(),
            by_age: BTreeMap::new(),
            clock: 0,
            hits: 0,
            misses: 0,
        }
    }

    /// The value for `key`, made by `make` on a miss; `true` with it on a hit.
    pub fn get_or_insert_with(&mut self, key: u64, make: impl FnOnce() -> V) -> (&V, bool) {
        match self.get_or_try_insert_with(key, || Ok::<V, std::convert::Infallible>(make())) {
            Ok(found) => found,
            Err(never) => match never {},
        }
    }

    /// Like [`get_or_insert_with`](Self::get_or_insert_with) for fallible creation (a
    /// pipeline the driver rejects): on error nothing is stored and the miss still counts.
    pub fn get_or_try_insert_with<E>(
        &mut self,
        key: u64,
        make: impl FnOnce() -> Result<V, E>,
    ) -> Result<(&V, bool), E> {
        self.clock += 1;
        let now = self.clock;
        let hit = self.entries.contains_key(&key);
        if hit {
            self.hits += 1;
            self.touch(key, now);
        } else {
            self.misses += 1;
            self.insert(key, make()?);
        }
        let entry = &self.entries[&key];
        Ok((&entry.value, hit))
    }

    /// The value for `key`, counting a hit (and making it the most recently used) or a miss.
    pub fn get(&mut self, key: u64) -> Option<&V> {
        self.clock += 1;
        let now = self.clock;
        if self.entries.contains_key(&key) {
            self.hits += 1;
            self.touch(key, now);
        } else {
            self.misses += 1;
        }
        self.entries.get(&key).map(|e| &e.value)
    }

    /// Store `value` under `key` as the most recently used value (replacing one with the same
    /// key), evicting the least recently used values beyond the capacity. Counts nothing.
    pub fn insert(&mut self, key: u64, value: V) {
        self.clock += 1;
        let now = self.clock;
        if let Some(old) = self.entries.remove(&key) {
            self.by_age.remove(&old.last_used);
        }
        self.evict_to(self.capacity - 1);
        self.entries.insert(
            key,
            Entry {
                value,
                last_used: now,
            },
        );
        self.by_age.insert(now, key);
    }

    /// The value for `key` without counting a hit or refreshing its age.
    pub fn peek(&self, key: u64) -> Option<&V> {
        self.entries.get(&key).map(|e| &e.value)
    }

    /// Lookups answered from the cache.
    pub fn hits(&self) -> u64 {
        self.hits
    }

    /// Lookups that had to create the value.
    pub fn misses(&self) -> u64 {
        self.misses
    }

    /// Values held now.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// True when nothing is cached.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Most values held at once.
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Drop every value (counters are kept).
    pub fn clear(&mut self) {
        self.entries.clear();
        self.by_age.clear();
    }

    fn touch(&mut self, key: u64, now: u64) {
        if let Some(entry) = self.entries.get_mut(&key) {
            self.by_age.remove(&entry.last_used);
            entry.last_used = now;
            self.by_age.insert(now, key);
        }
    }

    /// Evict the least recently used values until at most `keep` remain.
    fn evict_to(&mut self, keep: usize) {
        while self.entries.len() > keep {
            let Some((_, oldest)) = self.by_age.pop_first() else {
                return;
            };
            self.entries.remove(&oldest);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_capacity_holds_one_value() {
        let mut cache = PipelineCache::<u8>::new(0);
        assert_eq!(cache.capacity(), 1);
        cache.get_or_insert_with(1, || 1);
        cache.get_or_insert_with(2, || 2);
        assert_eq!(cache.len(), 1);
        assert_eq!(cache.peek(2), Some(&2));
    }

    #[test]
    fn get_counts_and_refreshes_insert_evicts_the_least_recently_used() {
        let mut cache = PipelineCache::new(2);
        cache.insert(1, "one");
        cache.insert(2, "two");
        assert_eq!(cache.get(1), Some(&"one"));
        assert_eq!(cache.get(3), None);
        assert_eq!((cache.hits(), cache.misses()), (1, 1));
        // 2 is now the least recently used: inserting 3 evicts it, not 1.
        cache.insert(3, "three");
        assert_eq!(cache.len(), 2);
        assert_eq!(cache.peek(2), None);
        assert_eq!(cache.peek(1), Some(&"one"));
        // Replacing a key keeps the size and refreshes it; peek does not refresh.
        cache.insert(1, "uno");
        assert_eq!(cache.peek(3), Some(&"three"));
        cache.insert(4, "four");
        assert_eq!(cache.peek(3), None, "3 was older than the replaced 1");
        assert_eq!(cache.peek(1), Some(&"uno"));
        assert_eq!(cache.by_age.len(), cache.entries.len());
        assert_eq!((cache.hits(), cache.misses()), (1, 1));
    }

    #[test]
    fn failed_creation_stores_nothing() {
        let mut cache = PipelineCache::<u32>::new(2);
        let r: Result<_, &str> = cache.get_or_try_insert_with(5, || Err("rejected"));
        assert_eq!(r.unwrap_err(), "rejected");
        assert_eq!((cache.len(), cache.misses(), cache.hits()), (0, 1, 0));
        let (v, hit) = cache.get_or_try_insert_with::<&str>(5, || Ok(9)).unwrap();
        assert_eq!((*v, hit), (9, false));
    }
}
