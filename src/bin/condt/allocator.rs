//! How the binary's memory comes from the system, on glibc only (other allocators and systems
//! keep their defaults): large freed blocks go back to the system at once, and large blocks are
//! served in huge pages where the system allows them. The binary's one use of `unsafe`, confined
//! here (`tests/unsafe_code.rs`).
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
//! What it costs, and the huge pages: a block the system takes back is zeroed and faulted in
//! again, page by page, when the next one is mapped (at 1M points along curves 16,000 more page
//! faults, 3-7 % more time; on uniform points 220,000, a tenth more processor time). A block of
//! two huge pages up to 32 MiB, the sizes whose blocks the fixed threshold maps, is therefore
//! advised `MADV_HUGEPAGE` (what glibc does for its mapped blocks with the tunable
//! `glibc.malloc.hugetlb=1`, which a program cannot set for itself): where the system gives
//! huge pages on advice (`/sys/kernel/mm/transparent_hugepage/enabled`), it faults in 2 MiB at
//! once, and the time is back to what it was; elsewhere the advice does nothing.

#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod glibc {
    use std::alloc::{GlobalAlloc, Layout, System};

    /// 128 KiB, glibc's default, kept fixed.
    const MMAP_THRESHOLD: libc::c_int = 128 * 1024;

    /// The size of a huge page on x86-64 and of the usual one on aarch64 (2 MiB). Blocks of at
    /// least two get the advice: a smaller one holds at most one whole huge page.
    const HUGE_PAGE: usize = 2 << 20;

    /// Blocks from this size (glibc's highest dynamic threshold on 64-bit systems, 32 MiB) were
    /// always mapped, the threshold fixed or not: they get no advice, so runs of 10M points and
    /// more fault in their large blocks as before (with the advice, huge pages that the kernel
    /// must first assemble cost more system time than they save there: 4.2 s against 2.1 s
    /// for `reconstruct` along curves at 10M points, one run).
    const ALWAYS_MAPPED: usize = 32 << 20;

    pub(super) fn release_large_blocks() {
        // SAFETY: `mallopt` sets a parameter of the allocator and returns 0 when it refuses the
        // value (then the default stands, which is harmless); it is called before any other
        // thread exists.
        unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        }
    }

    /// The system allocator, advising huge pages on the blocks from two [`HUGE_PAGE`]s up to
    /// [`ALWAYS_MAPPED`].
    pub(super) struct Allocator;

    /// Advises huge pages for the block of `size` bytes at `ptr`, from the huge page it starts
    /// in (glibc maps a large block from a boundary the kernel aligns, its header before `ptr`).
    fn advise(ptr: *mut u8, size: usize) {
        if ptr.is_null() || !(2 * HUGE_PAGE..ALWAYS_MAPPED).contains(&size) {
            return;
        }
        let start = ptr as usize & !(HUGE_PAGE - 1);
        let len = ptr as usize + size - start;
        // SAFETY: the advice changes only which page size backs the range, never its contents;
        // a part of the range that is not mapped makes the call fail, which is ignored.
        unsafe {
            libc::madvise(start as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
        }
    }

    // SAFETY: every call goes to `System` with the same arguments; the advice does not change
    // the memory handed out.
    unsafe impl GlobalAlloc for Allocator {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            // SAFETY: as the caller's contract for `GlobalAlloc::alloc`.
            let ptr = unsafe { System.alloc(layout) };
            advise(ptr, layout.size());
            ptr
        }

        unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
            // SAFETY: as the caller's contract for `GlobalAlloc::alloc_zeroed`.
            let ptr = unsafe { System.alloc_zeroed(layout) };
            advise(ptr, layout.size());
            ptr
        }

        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            // SAFETY: as the caller's contract for `GlobalAlloc::dealloc`.
            unsafe { System.dealloc(ptr, layout) }
        }

        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            // SAFETY: as the caller's contract for `GlobalAlloc::realloc`.
            let new = unsafe { System.realloc(ptr, layout, new_size) };
            if new_size > layout.size() {
                advise(new, new_size);
            }
            new
        }
    }

    #[global_allocator]
    static ALLOCATOR: Allocator = Allocator;
}

/// Fixes glibc's mmap threshold (see the module comment); nothing elsewhere.
pub(crate) fn release_large_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    glibc::release_large_blocks();
}
