//! Running two pieces of work, a buffer fill, a map, a sort or a scan of the ids `0..n` on
//! rayon's threads (feature `parallel`) or on the caller's. Owns: only the choice of how to run
//! and whether rayon can run at all ([`parallel_available`]); it knows nothing of the work.

use alloc::vec::Vec;

/// `buffer` cleared and refilled with `n` copies of `value`, on rayon's threads when `parallel`:
/// the first touch of each page is most of the cost.
pub(crate) fn filled<T: Copy + Send + Sync>(
    mut buffer: Vec<T>,
    value: T,
    n: usize,
    parallel: bool,
) -> Vec<T> {
    buffer.clear();
    buffer.reserve_exact(n);
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::iter::{repeat_n, ParallelExtend};
        buffer.par_extend(repeat_n(value, n));
        return buffer;
    }
    let _ = parallel;
    buffer.resize(n, value);
    buffer
}

/// `f` of every element of `items`, in order, on rayon's threads when `parallel`; the list is
/// allocated by the calling thread either way (glibc's malloc keeps a freed block in the arena of
/// the thread that took it).
pub(crate) fn mapped<T: Sync, U: Send>(
    items: &[T],
    f: impl Fn(&T) -> U + Sync + Send,
    parallel: bool,
) -> Vec<U> {
    let mut list = Vec::with_capacity(items.len());
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        items.par_iter().map(f).collect_into_vec(&mut list);
        return list;
    }
    let _ = parallel;
    list.extend(items.iter().map(f));
    list
}

/// `slice` sorted by `key` (not stable), split on rayon's threads when `parallel`: in place
/// either way, so no thread allocates.
pub(crate) fn sort_unstable_by_key<T: Send, K: Ord>(
    slice: &mut [T],
    key: impl Fn(&T) -> K + Sync,
    parallel: bool,
) {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::slice::ParallelSliceMut;
        slice.par_sort_unstable_by_key(key);
        return;
    }
    let _ = parallel;
    slice.sort_unstable_by_key(key);
}

/// How many threads work at once: rayon's when `parallel`, else one.
pub(crate) fn workers(parallel: bool) -> usize {
    #[cfg(feature = "parallel")]
    if parallel {
        return rayon::current_num_threads();
    }
    let _ = parallel;
    1
}

/// `(a(), b())`, at once on rayon's threads when `parallel`.
pub(crate) fn both<A: Send, B: Send>(
    parallel: bool,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    #[cfg(feature = "parallel")]
    if parallel {
        return rayon::join(a, b);
    }
    let _ = parallel;
    (a(), b())
}

/// The values `find` gives for the ids `0..n`, in increasing id: the same list either way, split
/// into ranges on rayon's threads when `parallel` (for read-only scans applied later in order).
pub(crate) fn found_in_order<T: Send>(
    n: usize,
    parallel: bool,
    find: impl Fn(usize) -> Option<T> + Sync + Send,
) -> Vec<T> {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        // Rayon collects a filtered range in the range's order.
        return (0..n).into_par_iter().filter_map(find).collect();
    }
    let _ = parallel;
    (0..n).filter_map(find).collect()
}

/// Adds `by` to the progress counter `counter` (a caller's count of points inserted), or takes
/// it away with `up` false. A target without atomic read-modify-write (Cortex-M0, an embedded
/// review: the crate did not build there) loads and stores instead; it has no threads, so no
/// other writer comes between.
pub(crate) fn count(counter: &core::sync::atomic::AtomicUsize, by: usize, up: bool) {
    use core::sync::atomic::Ordering::Relaxed;
    #[cfg(target_has_atomic = "ptr")]
    {
        if up {
            counter.fetch_add(by, Relaxed);
        } else {
            counter.fetch_sub(by, Relaxed);
        }
    }
    #[cfg(not(target_has_atomic = "ptr"))]
    {
        let now = counter.load(Relaxed);
        counter.store(
            if up {
                now.wrapping_add(by)
            } else {
                now.wrapping_sub(by)
            },
            Relaxed,
        );
    }
}

/// Whether rayon's global pool can run work: `false` without the `parallel` feature, or when the
/// pool could not start (a limit on processes or address space, `RAYON_NUM_THREADS` beyond what
/// the system gives), where rayon would panic at first use; every parallel path then runs on the
/// caller's thread, with the same results. Asked once per process: the first call starts the
/// global pool as rayon's first use would (with the caller's settings if it built it first).
/// Called from a thread of a rayon pool (the caller's `install`), it is `true` and starts
/// nothing: the work runs in that pool. The library asks only for sets large enough to use
/// threads (65,536 points), so a smaller run starts no pool.
///
/// ```
/// // With the default features, on a machine that can start threads:
/// assert!(condt::parallel_available());
/// ```
pub fn parallel_available() -> bool {
    #[cfg(feature = "parallel")]
    {
        if rayon::current_thread_index().is_some() {
            return true;
        }
        static AVAILABLE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        *AVAILABLE.get_or_init(|| match rayon::ThreadPoolBuilder::new().build_global() {
            Ok(()) => true,
            // Built before (by the caller, or by an earlier use): an error without a source. A
            // pool that could not be started has the system's error as its source.
            Err(error) => std::error::Error::source(&error).is_none(),
        })
    }
    #[cfg(not(feature = "parallel"))]
    false
}
