//! Thread counts: what a caller asks for, resolved to what the target can run. Every
//! parallel loop in craterfield gives the same bits on any thread count, so a target that
//! cannot start threads (WebAssembly in a browser, where `std::thread::spawn` fails) runs
//! the same work on the calling thread instead of failing.

/// Whether this target can start threads. WebAssembly has no `std::thread::spawn` (even
/// with shared memory, a browser's threads are workers that the embedder starts).
pub const CAN_SPAWN: bool = !cfg!(target_family = "wasm");

/// The threads to run on for a request of `requested` (0: every core), at least one.
pub fn resolve(requested: usize) -> usize {
    if !CAN_SPAWN {
        return 1;
    }
    match requested {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    }
}

/// `threads` where the target can start threads, else at most one (0 stays 0, for
/// callers that give 0 a meaning of their own).
pub fn spawnable(threads: usize) -> usize {
    if CAN_SPAWN { threads } else { threads.min(1) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolved_counts_are_at_least_one_and_keep_explicit_requests() {
        assert!(resolve(0) >= 1);
        assert_eq!(resolve(3), if CAN_SPAWN { 3 } else { 1 });
        assert_eq!(spawnable(0), 0);
        assert_eq!(spawnable(5), if CAN_SPAWN { 5 } else { 1 });
    }
}
