//! A hint to the processor that a slice element will be read soon: the crate's one use of
//! `unsafe`, confined here (`lib.rs` denies it elsewhere; `tests/unsafe_code.rs` checks).
//!
//! Owns: [`prefetch`] and [`PREFETCH_FROM`]; it may not read or write memory, and changes no
//! result (it lets the cache misses of large sweeps overlap).

/// Fewest points for which loops prefetch (below it the reads fit the second-level cache); never
/// on targets where [`prefetch`] does nothing.
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
