//! Work distribution of the twin's passes: units of work (row bands) handed out one at a
//! time to scoped worker threads, so bands of sky and bands of terrain balance out.
//! Each unit writes only its own output, so results do not depend on the thread count.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

/// The thread count a `threads` argument asks for: 0 means every core.
pub(super) fn resolve(threads: usize) -> usize {
    craterfield_core::threads::resolve(threads)
}

/// Runs `work` on every unit, on up to `threads` threads (0: all cores), each thread with
/// its own scratch from `scratch`. Returns the first error; after one, units not yet
/// started are skipped.
pub(super) fn run_units<U, S, E>(
    units: Vec<U>,
    threads: usize,
    scratch: impl Fn() -> S + Sync,
    work: impl Fn(&mut S, U) -> Result<(), E> + Sync,
) -> Result<(), E>
where
    U: Send,
    E: Send,
{
    let workers = resolve(threads).min(units.len()).max(1);
    if workers == 1 {
        let mut s = scratch();
        return units.into_iter().try_for_each(|u| work(&mut s, u));
    }
    let queue = Mutex::new(units.into_iter());
    let failed = AtomicBool::new(false);
    let next = || {
        if failed.load(Ordering::Relaxed) {
            return None;
        }
        // A worker that panicked holding the lock left the iterator intact.
        queue.lock().unwrap_or_else(|e| e.into_inner()).next()
    };
    let worker = || -> Result<(), E> {
        let mut s = scratch();
        while let Some(unit) = next() {
            if let Err(e) = work(&mut s, unit) {
                failed.store(true, Ordering::Relaxed);
                return Err(e);
            }
        }
        Ok(())
    };
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers).map(|_| scope.spawn(worker)).collect();
        let mut result = Ok(());
        for handle in handles {
            let outcome = handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            if result.is_ok() {
                result = outcome;
            }
        }
        result
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    #[test]
    fn every_unit_runs_once_on_any_thread_count() {
        for threads in [1, 2, 3, 8] {
            let mut out = vec![0u32; 100];
            let units: Vec<(usize, &mut [u32])> = out.chunks_mut(7).enumerate().collect();
            run_units(
                units,
                threads,
                || (),
                |_, (i, chunk)| {
                    chunk.iter_mut().for_each(|v| *v += i as u32 + 1);
                    Ok::<(), ()>(())
                },
            )
            .unwrap();
            let expected: Vec<u32> = (0..100).map(|j| j as u32 / 7 + 1).collect();
            assert_eq!(out, expected, "{threads} threads");
        }
    }

    #[test]
    fn an_error_stops_the_queue_and_is_returned() {
        let done = AtomicUsize::new(0);
        let r = run_units(
            (0..1000).collect(),
            2,
            || (),
            |_, u: usize| {
                done.fetch_add(1, Ordering::Relaxed);
                if u == 3 { Err(u) } else { Ok(()) }
            },
        );
        assert_eq!(r, Err(3));
        assert!(done.load(Ordering::Relaxed) < 1000);
    }
}
