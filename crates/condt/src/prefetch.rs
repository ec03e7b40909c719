//! A hint to the processor that an element of a slice will be read soon: the crate's one use of
//! `unsafe`, confined here.
//!
//! Owns: [`prefetch`] and [`PREFETCH_FROM`]. It may not read or write memory, and nothing else
//! in the crate may use `unsafe`: `lib.rs` denies unsafe code, this module alone allows it, and
//! `tests/unsafe_code.rs` fails if any other source file does (but for the binary's allocator,
//! `src/bin/condt/allocator.rs`).
//!
//! Why: the proximity sweep reads the point and the candidate record of each triangle's three
//! corners. Triangles are stored in the order the insertion made them and vertices in insertion
//! order, so at a million points most of those reads miss the caches, and the sweep waited on
//! them (about 40 % of its samples in a `perf` profile). A prefetch issued some triangles ahead
//! retires at once, unlike a load, so the misses overlap: the sweep took 90 instead of 143 ms
//! at 1M points (medians of alternated runs, `docs/performance.md`). The final tally, which
//! reads the curve graph in input order, does the same for shuffled input. It changes no
//! result.

/// Fewest points for which loops over them prefetch (the proximity sweep and the final tally):
/// 2^16 points take 1 MB in coordinates alone, and with what a loop reads beside them (the
/// sweep's 24-byte records) more than the second-level caches of current processors (1 MB per
/// core here). Below that the reads hit the caches anyway and the prefetches only add work (a
/// third more time for the proximity sweep at 10k points). On targets where [`prefetch`] does
/// nothing, never: the loops then skip the work of asking.
pub(crate) const PREFETCH_FROM: usize = if cfg!(target_arch = "x86_64") {
    1 << 16
} else {
    usize::MAX
};

/// Asks for the cache line that holds `slice[index]`; does nothing when `index` is out of
/// range or on targets other than x86-64.
#[inline(always)]
pub(crate) fn prefetch<T>(slice: &[T], index: usize) {
    #[cfg(target_arch = "x86_64")]
    if let Some(element) = slice.get(index) {
        let address: *const T = element;
        // SAFETY: PREFETCHT0 only hints the cache; it reads no data, cannot fault, and has no
        // effect the program can observe. SSE, which provides it, is part of the x86-64
        // baseline. The address is that of a live element in any case.
        #[allow(unsafe_code)]
        unsafe {
            core::arch::x86_64::_mm_prefetch::<{ core::arch::x86_64::_MM_HINT_T0 }>(address.cast());
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (slice, index);
}
