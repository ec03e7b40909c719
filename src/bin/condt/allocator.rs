//! How the binary's memory comes from the system, on glibc only (other allocators and systems
//! keep their defaults): large freed blocks go back to the system at once. The binary's one use
//! of `unsafe`, confined here (`tests/unsafe_code.rs`).
//!
//! Why: peak memory. glibc's allocator serves a block of at least `M_MMAP_THRESHOLD` bytes with
//! a mapping of its own, returned to the system when freed; smaller ones come from its heap,
//! which keeps freed space in the middle for reuse. The threshold starts at 128 KiB, but by
//! default glibc raises it to the size of every mapped block freed (up to 32 MiB), so after the
//! first large buffer of a run is freed, every later one up to that size comes from the heap
//! and stays there: at 1M points, where the per-point arrays are 4 to 24 MB, `reconstruct`
//! along curves peaked at 119,796 kB instead of 109,560, and on uniform points, whose smoothing
//! passes free and allocate them four times, at 230,728-251,812 kB instead of about 150,600
//! (`docs/performance.md`, "Where the bytes per point go"). Setting the threshold fixes it at
//! 128 KiB and turns the raising off (the glibc manual, "Malloc Tunable Parameters"), so the
//! peak follows what the library holds at every size. Above 32 MiB a block was always mapped,
//! so nothing changes at 10M points and more.
//!
//! What it costs: a block the system takes back is zeroed and faulted in again, page by page,
//! when the next one is mapped: at 1M points along curves about 16,000 more page faults (a few
//! per cent of the run), on uniform points, whose smoothing passes free and map their arrays
//! four times, about 220,000 (a tenth more processor time). Advising huge pages on the mapped
//! blocks (`MADV_HUGEPAGE` from a global allocator) won that back for `reconstruct` but cost
//! `condt triangulate` 0.1 s more system time at 1M points (the kernel assembling the huge
//! pages), and is not done (`docs/performance.md`, "Where the bytes per point go").

#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod glibc {
    /// 128 KiB, glibc's default, kept fixed.
    const MMAP_THRESHOLD: libc::c_int = 128 * 1024;

    pub(super) fn release_large_blocks() {
        // SAFETY: `mallopt` sets a parameter of the allocator and returns 0 when it refuses the
        // value (then the default stands, which is harmless); it is called before any other
        // thread exists.
        unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        }
    }
}

/// Fixes glibc's mmap threshold (see the module comment); nothing elsewhere.
pub(crate) fn release_large_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    glibc::release_large_blocks();
}
