//! Where the binary's memory comes from: large blocks are runs of pages that the process keeps
//! and moves between buffers instead of handing them back to the system and faulting them in
//! again; small blocks come from the system allocator. Linux with glibc only (elsewhere the
//! system allocator serves everything). The binary's one use of `unsafe`, confined here; every
//! block says why it is sound (`tests/unsafe_code.rs` checks that each has its `// SAFETY:`).
//!
//! Owns: the pages of every block of `LARGE` (128 KiB) or more aligned to at most a page. It knows nothing of what the
//! blocks hold, and the library never sees it (a library caller keeps its own allocator).
//!
//! **Why.** The pipeline allocates and frees per-point arrays of 4 to 24 bytes a point, stage
//! after stage: at 10M points along curves, 663,231 page faults (2.6 GB of fresh pages) for a
//! peak of 1.07 GB. glibc maps each such block on its own and unmaps it when freed, so the
//! kernel zeroes and faults in every block's pages again, at 3 to 8 µs a page on this virtual
//! machine (2.1 s of system time at 10M, 55 s at 100M). Keeping freed blocks in glibc's heap
//! instead (a raised mmap threshold) stops the faults but raises the peak: the heap's freed
//! middle stays resident whether or not a later block fits in it.
//!
//! **How.** A freed large block's pages are kept as a run. A new block takes the smallest kept
//! run it fits in (the rest of the run stays kept); if none is large enough, the largest grows
//! into it with `mremap` (the kernel moves the page-table entries: no copy, no fault) and only
//! the rest is fresh; with no run kept, it is a fresh mapping. Growing a block (`realloc`)
//! grows it the same way. The peak stays about what the live blocks hold, as with glibc's
//! unmapping, because kept pages are rarely resident beside fresh ones:
//! - a block that needs fresh pages (made or grown) unmaps as many bytes of kept runs, smallest
//!   first;
//! - when the small blocks grow past their highest total so far (glibc then takes fresh pages
//!   for them), kept runs are unmapped by as many bytes.
//!
//! A fresh page first touched after later frees filled the kept runs still adds to them.
//! (Faulting fresh pages in at once, with `MAP_POPULATE`, closed that gap but moved the faults
//! of the triangulation's mesh, which both its threads touch, onto the one thread that
//! allocates it: the 100M run's triangulation took 51.7 s, against 38.6 and 42.7 s without it;
//! at 1M and 10M the peak was the same without it.)
//!
//! **Soundness.** Every range the allocator holds (a live block or a kept run) lies in one
//! mapping: only `mmap` makes ranges, a run is split only by address, and only `mremap` without
//! `MREMAP_FIXED` moves one, whole, to where the kernel chooses. So a move never replaces a
//! mapping and either happens whole or not at all. (An earlier version assembled a block from
//! several runs with `MREMAP_FIXED`, a fourth fewer faults; but a failed move can leave the
//! destination unmapped, which another thread's mapping may then take.)
//!
//! A block asked for zeroed is cleared where its pages were reused (fresh pages come zeroed).
//!
//! Measured against glibc with its mmap threshold fixed at 128 KiB, which this replaced (`perf
//! stat -e page-faults`, `/usr/bin/time`; `docs/perf-log.md`, "The binary's allocator"):
//! `reconstruct` along curves, 1M points, 64,723 page faults -> 32,726; 10M 663,281 -> 325,248
//! and 2.02 -> 1.13 s of system time; uniform points, 1M, 323,258 -> 73,445 and 1.06 -> 0.32 s.
//! The peak resident set is within 1.7 % (109,968 against 109,440 kB along curves at 1M,
//! 128,628 against 126,516 on uniform points). Every output is byte-identical.
//!
//! **In a library.** The Python package (`python/src/lib.rs`) uses this crate too, with
//! [`Recycling::scoped`]: a process that lives on between calls must not hold freed pages, so
//! runs are kept only while a call runs ([`Recycling::within_call`]) and unmapped when the last
//! one ends; a block freed between calls is unmapped at once, as glibc would. The binary keeps
//! them for its whole run ([`Recycling::new`]), since it exits. The package also guards forks
//! ([`Recycling::guard_forks`]), as glibc guards its own locks: a child forked while another
//! thread held the allocator's lock would otherwise wait for it forever.
//!
//! A crate of its own so that the binary and the Python package share it (and a source
//! distribution of the package carries it). Each declares the global allocator itself, on Linux
//! with glibc (the binary's `main.rs`: `#[global_allocator] static ALLOCATOR:
//! condt_alloc::Recycling = condt_alloc::Recycling::new();`). Elsewhere the crate is empty.

#[cfg(all(target_os = "linux", target_env = "gnu"))]
pub use linux::Recycling;

#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod linux {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::cell::UnsafeCell;
    use std::ptr;
    use std::sync::atomic::{AtomicPtr, AtomicUsize, Ordering};
    use std::sync::{Mutex, MutexGuard};

    /// Blocks of this many bytes or more are page runs of their own (glibc's default mmap
    /// threshold: below it, its heap serves them well).
    const LARGE: usize = 128 * 1024;

    /// Most freed runs kept at once; beyond it the smallest is unmapped. A pipeline holds a few
    /// dozen large buffers at most.
    const KEPT_RUNS: usize = 64;

    /// A run of whole pages, mapped read-write and owned by the allocator or by a live block.
    #[derive(Copy, Clone, Debug, PartialEq, Eq)]
    struct Run {
        start: usize,
        len: usize,
    }

    impl Run {
        const EMPTY: Run = Run { start: 0, len: 0 };

        /// The part of the run after its first `len` bytes, if any.
        fn after(self, len: usize) -> Option<Run> {
            (self.len > len).then_some(Run {
                start: self.start + len,
                len: self.len - len,
            })
        }
    }

    /// The freed runs kept for reuse, in no order. A fixed array: the allocator may not
    /// allocate.
    struct Kept {
        runs: [Run; KEPT_RUNS],
        count: usize,
    }

    impl Kept {
        /// Removes and returns the run at `k`.
        fn remove(&mut self, k: usize) -> Run {
            let run = self.runs[k];
            self.count -= 1;
            self.runs[k] = self.runs[self.count];
            run
        }

        /// The smallest kept run of at least `len` bytes, removed.
        fn take_fitting(&mut self, len: usize) -> Option<Run> {
            let k = (0..self.count)
                .filter(|&k| self.runs[k].len >= len)
                .min_by_key(|&k| self.runs[k].len)?;
            Some(self.remove(k))
        }

        /// Where the smallest kept run is.
        fn smallest(&self) -> Option<usize> {
            (0..self.count).min_by_key(|&k| self.runs[k].len)
        }

        /// The smallest kept run, removed.
        fn take_smallest(&mut self) -> Option<Run> {
            let k = self.smallest()?;
            Some(self.remove(k))
        }

        /// The largest kept run, removed.
        fn take_largest(&mut self) -> Option<Run> {
            let k = (0..self.count).max_by_key(|&k| self.runs[k].len)?;
            Some(self.remove(k))
        }

        /// Keeps `run`; when full, gives back the smallest of the kept runs and `run`, which the
        /// caller unmaps.
        #[must_use]
        fn put(&mut self, run: Run) -> Option<Run> {
            if self.count < KEPT_RUNS {
                self.runs[self.count] = run;
                self.count += 1;
                return None;
            }
            let k = self.smallest()?;
            if self.runs[k].len >= run.len {
                return Some(run);
            }
            Some(core::mem::replace(&mut self.runs[k], run))
        }
    }

    /// The binary's global allocator (see the module comment).
    pub struct Recycling {
        kept: Mutex<Kept>,
        /// Bytes of glibc's heap the small blocks live now take (their chunks,
        /// [`Recycling::chunk`]).
        small_live: AtomicUsize,
        /// The most such bytes live at once so far.
        small_high: AtomicUsize,
        /// Whether freed runs are kept only while a call runs ([`Recycling::scoped`]).
        scoped: bool,
        /// The calls running now ([`Recycling::within_call`]); changed to zero only under the
        /// lock of `kept`, so that a run is never kept once the last call has ended.
        calls: AtomicUsize,
    }

    impl Default for Recycling {
        /// [`Recycling::new`]: the binary's allocator.
        fn default() -> Self {
            Self::new()
        }
    }

    impl Recycling {
        /// The binary's allocator: freed runs are kept for the whole run.
        #[cfg_attr(not(test), allow(dead_code))] // the Python package uses `scoped` only
        pub const fn new() -> Self {
            Self::with_scope(false)
        }

        /// A library's allocator (the Python package's): freed runs are kept only while a
        /// call runs ([`Recycling::within_call`]), all unmapped when the last call ends, and
        /// a run freed outside every call is unmapped at once.
        #[cfg_attr(not(test), allow(dead_code))] // the binary uses `new` only
        pub const fn scoped() -> Self {
            Self::with_scope(true)
        }

        const fn with_scope(scoped: bool) -> Self {
            Recycling {
                kept: Mutex::new(Kept {
                    runs: [Run::EMPTY; KEPT_RUNS],
                    count: 0,
                }),
                small_live: AtomicUsize::new(0),
                small_high: AtomicUsize::new(0),
                scoped,
                calls: AtomicUsize::new(0),
            }
        }

        /// Runs `work` as one call of a [`scoped`](Recycling::scoped) allocator: the runs it
        /// frees are kept for its later blocks; when the last call running ends (here, or
        /// when `work` unwinds), every kept run is unmapped.
        #[cfg_attr(not(test), allow(dead_code))] // the binary never ends a call
        pub fn within_call<T>(&self, work: impl FnOnce() -> T) -> T {
            /// Ends the call on the way out, unwinding included.
            struct End<'a>(&'a Recycling);
            impl Drop for End<'_> {
                fn drop(&mut self) {
                    let mut kept = self.0.kept();
                    if self.0.calls.fetch_sub(1, Ordering::SeqCst) == 1 {
                        while let Some(run) = kept.take_smallest() {
                            if !unmap(run.start, run.len) {
                                // Kept (the system refused to unmap it); the next call reuses it.
                                let _ = kept.put(run);
                                return;
                            }
                        }
                    }
                }
            }
            self.calls.fetch_add(1, Ordering::SeqCst);
            let _end = End(self);
            work()
        }

        /// Makes `fork` safe for this allocator, the process's guarded one (the first given;
        /// later calls, for any allocator, change nothing). `fork` copies only the calling
        /// thread: a child forked while another thread held the kept runs' lock would wait
        /// for it at its first large block, forever. With the guard a fork first takes the lock
        /// (waiting for that thread to let go), and parent and child each let it go after. The
        /// child runs no call of the parent's threads, so it counts none. For the Python
        /// package (`multiprocessing`'s fork); the binary does not fork.
        #[cfg_attr(not(test), allow(dead_code))] // the binary never forks
        pub fn guard_forks(&'static self) {
            if GUARDED
                .compare_exchange(
                    ptr::null_mut(),
                    ptr::from_ref(self).cast_mut(),
                    Ordering::SeqCst,
                    Ordering::SeqCst,
                )
                .is_ok()
            {
                // SAFETY: the three handlers are `extern "C"` functions without arguments that
                // live as long as the process, as `pthread_atfork` asks. If the system refuses
                // (no memory for the entry), forks stay as they were without the guard.
                unsafe {
                    libc::pthread_atfork(Some(fork_prepare), Some(fork_parent), Some(fork_child))
                };
            }
        }

        fn kept(&self) -> MutexGuard<'_, Kept> {
            // Nothing panics while the lock is held; a poisoned lock still holds valid runs.
            self.kept
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner())
        }

        /// A block of `len` bytes (whole pages), zeroed if asked; null if the system refuses.
        fn take(&self, len: usize, zeroed: bool) -> *mut u8 {
            let mut kept = self.kept();
            if let Some(run) = kept.take_fitting(len) {
                if let Some(rest) = run.after(len) {
                    // One run was just taken out, so there is room for its rest.
                    let _ = kept.put(rest);
                }
                drop(kept);
                if zeroed {
                    clear(run.start, len);
                }
                return run.start as *mut u8;
            }
            // No kept run holds the block: the largest grows into it, its pages moved rather
            // than copied, and fresh pages make up the rest.
            let largest = kept.take_largest();
            drop(kept);
            if let Some(run) = largest {
                if let Some(start) = grow(run.start, run.len, len) {
                    self.release(len - run.len);
                    if zeroed {
                        clear(start, run.len);
                    }
                    return start as *mut u8;
                }
                self.give_back(run);
            }
            match map(len) {
                Some(start) => {
                    self.release(len);
                    start as *mut u8
                }
                None => ptr::null_mut(),
            }
        }

        /// Counts `size` more bytes of small blocks (allocated). Past their highest count so
        /// far the system allocator takes fresh pages for them, so the kept runs give back as
        /// many bytes (checked in steps of [`LARGE`], so that the lock is rarely taken).
        fn small_grown(&self, size: usize) {
            // Atomic additions wrap; the sums are bytes allocated, far from overflowing.
            let live = self
                .small_live
                .fetch_add(size, Ordering::Relaxed)
                .wrapping_add(size);
            if live
                > self
                    .small_high
                    .load(Ordering::Relaxed)
                    .saturating_add(LARGE)
            {
                let high = self.small_high.fetch_max(live, Ordering::Relaxed);
                if live > high {
                    self.release(live - high);
                }
            }
        }

        fn small_shrunk(&self, size: usize) {
            self.small_live.fetch_sub(size, Ordering::Relaxed);
        }

        /// The bytes of glibc's heap a small block of `size` bytes takes: its chunk, the size
        /// and an 8-byte header rounded up to 16 bytes, 32 at least. Reason: the kept runs give
        /// back what the small blocks take from fresh pages, and a small block takes more than
        /// its size: the 130,393 curves of 1M uniform points, 31 bytes each on average, took
        /// 48 each, and the runs gave back 2 MB too little at the last step.
        fn chunk(size: usize) -> usize {
            ((size + 8 + 15) & !15).max(32)
        }

        /// Unmaps at least `len` bytes of kept runs (or all of them), smallest runs first, so
        /// that pages about to be faulted in fresh are not resident beside kept ones.
        fn release(&self, len: usize) {
            let mut kept = self.kept();
            let mut released = 0;
            while released < len {
                let Some(run) = kept.take_smallest() else {
                    return;
                };
                let piece = whole_pages(len - released).min(run.len);
                if !unmap(run.start, piece) {
                    // Kept as it is (the system refused to split its mapping).
                    let _ = kept.put(run);
                    return;
                }
                if let Some(rest) = run.after(piece) {
                    let _ = kept.put(rest);
                }
                released += piece;
            }
        }

        /// Keeps the pages of a freed block, or unmaps the smallest run when too many are kept;
        /// a [`scoped`](Recycling::scoped) allocator unmaps it when no call runs.
        fn give_back(&self, run: Run) {
            let mut kept = self.kept();
            if self.scoped && self.calls.load(Ordering::SeqCst) == 0 {
                drop(kept);
                if unmap(run.start, run.len) {
                    return;
                }
                // Kept, as a run the system would not unmap is below.
                kept = self.kept();
            }
            if let Some(dropped) = kept.put(run) {
                drop(kept);
                // If the system refuses, the pages stay mapped and unused: a leak, not an error.
                unmap(dropped.start, dropped.len);
            }
        }

        /// [`GlobalAlloc::alloc`], or [`GlobalAlloc::alloc_zeroed`] when `zeroed`.
        ///
        /// # Safety
        /// The contract of [`GlobalAlloc::alloc`]: `layout` has a non-zero size.
        unsafe fn allocate(&self, layout: Layout, zeroed: bool) -> *mut u8 {
            if is_large(layout.size(), layout.align()) {
                return self.take(whole_pages(layout.size()), zeroed);
            }
            let block = if zeroed {
                // SAFETY: the caller's contract, passed on.
                unsafe { System.alloc_zeroed(layout) }
            } else {
                // SAFETY: the caller's contract, passed on.
                unsafe { System.alloc(layout) }
            };
            if !block.is_null() {
                self.small_grown(Self::chunk(layout.size()));
            }
            block
        }
    }

    /// The allocator [`Recycling::guard_forks`] guards, null before.
    static GUARDED: AtomicPtr<Recycling> = AtomicPtr::new(ptr::null_mut());

    /// The kept runs' lock, held by the forking thread from [`fork_prepare`] until
    /// [`fork_parent`] or [`fork_child`] (in the parent, and in the child's copy of it).
    struct HeldForFork(UnsafeCell<Option<MutexGuard<'static, Kept>>>);

    // SAFETY: the cell is read and written only by the fork handlers, while the lock it holds is
    // held: the write after taking the lock, the read before letting it go, so the lock orders
    // the handlers of two threads forking at once.
    unsafe impl Sync for HeldForFork {}

    static HELD_FOR_FORK: HeldForFork = HeldForFork(UnsafeCell::new(None));

    /// The guarded allocator, if any.
    fn guarded() -> Option<&'static Recycling> {
        // SAFETY: only `guard_forks` stores a pointer, from a `&'static Recycling`.
        unsafe { GUARDED.load(Ordering::SeqCst).as_ref() }
    }

    extern "C" fn fork_prepare() {
        if let Some(heap) = guarded() {
            let lock = heap.kept();
            // SAFETY: the lock is held (see `HeldForFork`).
            unsafe { *HELD_FOR_FORK.0.get() = Some(lock) };
        }
    }

    extern "C" fn fork_parent() {
        // SAFETY: the lock `fork_prepare` took is still held (see `HeldForFork`).
        drop(unsafe { (*HELD_FOR_FORK.0.get()).take() });
    }

    extern "C" fn fork_child() {
        if let Some(heap) = guarded() {
            // Calls that ran on the parent's other threads do not run here.
            heap.calls.store(0, Ordering::SeqCst);
        }
        // SAFETY: the child's copy of the lock `fork_prepare` took is held by its one thread.
        drop(unsafe { (*HELD_FOR_FORK.0.get()).take() });
    }

    /// Whether a block of this layout is a page run of its own.
    fn is_large(size: usize, align: usize) -> bool {
        size >= LARGE && align <= page_size()
    }

    fn page_size() -> usize {
        static PAGE: AtomicUsize = AtomicUsize::new(0);
        match PAGE.load(Ordering::Relaxed) {
            0 => {
                // SAFETY: `sysconf` reads a system constant.
                let size = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
                let size = usize::try_from(size).ok().filter(|s| s.is_power_of_two());
                let size = size.unwrap_or(4096);
                PAGE.store(size, Ordering::Relaxed);
                size
            }
            size => size,
        }
    }

    /// `size` rounded up to whole pages (`size` is far below `usize::MAX`: a layout's size is
    /// at most `isize::MAX`).
    fn whole_pages(size: usize) -> usize {
        let page = page_size();
        (size + page - 1) & !(page - 1)
    }

    /// A fresh private mapping of `len` bytes, none of its pages touched yet.
    fn map(len: usize) -> Option<usize> {
        // SAFETY: an anonymous mapping at an address the kernel chooses touches no existing
        // memory.
        let start = unsafe {
            libc::mmap(
                ptr::null_mut(),
                len,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            )
        };
        (start != libc::MAP_FAILED).then_some(start as usize)
    }

    /// The pages `start .. start + len` (a run or block of this allocator, lying in one mapping)
    /// grown to `new_len` bytes: extended in place or moved whole, with fresh pages after its
    /// own; `None`, and nothing changed, if the system refuses.
    ///
    /// Every range the allocator holds lies in one mapping, since only `mmap` makes ranges and
    /// only this `mremap` (without `MREMAP_FIXED`, so that it never replaces a mapping) moves
    /// one, whole: a range is never assembled from pieces of several.
    fn grow(start: usize, len: usize, new_len: usize) -> Option<usize> {
        // SAFETY: the range is whole pages of one mapping that only the caller uses; the kernel
        // picks where it goes, and on failure leaves it where it was.
        let grown = unsafe {
            libc::mremap(
                start as *mut libc::c_void,
                len,
                new_len,
                libc::MREMAP_MAYMOVE,
            )
        };
        (grown != libc::MAP_FAILED).then_some(grown as usize)
    }

    /// Unmaps the pages `start .. start + len` of a run nothing uses; false if the system
    /// refuses (splitting a mapping needs room for one more in the process's table).
    fn unmap(start: usize, len: usize) -> bool {
        // SAFETY: the range is whole pages mapped by this allocator that nothing uses.
        unsafe { libc::munmap(start as *mut libc::c_void, len) == 0 }
    }

    fn clear(start: usize, len: usize) {
        // SAFETY: `start..start + len` is mapped read-write and owned by the block being made.
        unsafe { ptr::write_bytes(start as *mut u8, 0, len) };
    }

    // SAFETY: every block handed out is either the system allocator's (small or over-aligned
    // layouts, freed and grown there) or a run of whole pages of its own in one mapping, aligned
    // to the page, mapped read-write and used by nothing else until it is given back; the layout
    // a block is freed or grown with tells which (its size and alignment decide, and a block
    // keeps its kind).
    unsafe impl GlobalAlloc for Recycling {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            // SAFETY: the caller's contract, passed on.
            unsafe { self.allocate(layout, false) }
        }

        unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
            // SAFETY: the caller's contract, passed on.
            unsafe { self.allocate(layout, true) }
        }

        unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
            if is_large(layout.size(), layout.align()) {
                self.give_back(Run {
                    start: block as usize,
                    len: whole_pages(layout.size()),
                });
            } else {
                self.small_shrunk(Self::chunk(layout.size()));
                // SAFETY: the caller's contract, passed on.
                unsafe { System.dealloc(block, layout) }
            }
        }

        unsafe fn realloc(&self, block: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            let (old_large, new_large) = (
                is_large(layout.size(), layout.align()),
                is_large(new_size, layout.align()),
            );
            if !old_large && !new_large {
                // SAFETY: the caller's contract, passed on.
                let moved = unsafe { System.realloc(block, layout, new_size) };
                if !moved.is_null() {
                    self.small_shrunk(Self::chunk(layout.size()));
                    self.small_grown(Self::chunk(new_size));
                }
                return moved;
            }
            if old_large && new_large {
                let (old_len, new_len) = (whole_pages(layout.size()), whole_pages(new_size));
                let start = block as usize;
                if new_len <= old_len {
                    let whole = Run {
                        start,
                        len: old_len,
                    };
                    if let Some(tail) = whole.after(new_len) {
                        self.give_back(tail);
                    }
                    return block;
                }
                return match grow(start, old_len, new_len) {
                    Some(grown) => {
                        self.release(new_len - old_len);
                        grown as *mut u8
                    }
                    None => ptr::null_mut(),
                };
            }
            // One side small, the other large: a new block of the other kind, then a copy.
            // SAFETY: `new_size` with the old alignment is a valid layout (the caller's contract).
            let new_layout = unsafe { Layout::from_size_align_unchecked(new_size, layout.align()) };
            // SAFETY: a layout of non-zero size.
            let moved = unsafe { self.alloc(new_layout) };
            if !moved.is_null() {
                // SAFETY: both blocks are live, distinct and at least this long.
                unsafe {
                    ptr::copy_nonoverlapping(block, moved, layout.size().min(new_size));
                    self.dealloc(block, layout);
                }
            }
            moved
        }
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        /// `n` pages, in bytes.
        fn pages(n: usize) -> usize {
            n * page_size()
        }

        /// Pages in the smallest large block.
        fn unit() -> usize {
            LARGE.div_ceil(page_size())
        }

        #[test]
        fn a_full_store_gives_back_its_smallest_run() {
            let mut kept = Kept {
                runs: [Run::EMPTY; KEPT_RUNS],
                count: 0,
            };
            for k in 0..KEPT_RUNS {
                assert_eq!(
                    kept.put(Run {
                        start: k,
                        len: 10 + k
                    }),
                    None
                );
            }
            let small = Run { start: 99, len: 5 };
            assert_eq!(kept.put(small), Some(small));
            let large = Run {
                start: 98,
                len: 1000,
            };
            assert_eq!(kept.put(large), Some(Run { start: 0, len: 10 }));
            assert_eq!(kept.take_largest(), Some(large));
            assert_eq!(kept.take_fitting(11), Some(Run { start: 1, len: 11 }));
            assert_eq!(kept.take_fitting(10_000), None);
        }

        /// The bytes of a block of `len` the checks below write and read: every one, or under
        /// Miri, which interprets each access (a byte at a time, two of these tests did not end
        /// within 300 s), every 509th and the last, so still several on every page.
        fn probed(len: usize) -> impl Iterator<Item = usize> {
            let step = if cfg!(miri) { 509 } else { 1 };
            // Blocks are never empty; the last byte is added unless the steps reach it.
            (0..len)
                .step_by(step)
                .chain(((len - 1) % step != 0).then(|| len - 1))
        }

        /// Writes a pattern over a block and checks it back, so that every page is mapped
        /// read-write and holds what was written.
        fn fill_and_check(block: *mut u8, len: usize, seed: u8) {
            // SAFETY: the callers pass a live block of `len` bytes that nothing else uses.
            let bytes = unsafe { std::slice::from_raw_parts_mut(block, len) };
            for k in probed(len) {
                bytes[k] = seed.wrapping_add((k / 4093) as u8);
            }
            assert!(probed(len).all(|k| bytes[k] == seed.wrapping_add((k / 4093) as u8)));
        }

        fn kept_bytes(heap: &Recycling) -> usize {
            let kept = heap.kept();
            kept.runs[..kept.count].iter().map(|r| r.len).sum()
        }

        fn layout(pages_count: usize) -> Layout {
            Layout::from_size_align(pages(pages_count), 8).unwrap()
        }

        fn unmap_all(heap: &Recycling) {
            let mut kept = heap.kept();
            while let Some(run) = kept.take_largest() {
                assert!(unmap(run.start, run.len));
            }
        }

        /// Whether the block holds the pattern `fill_and_check` wrote with `seed`.
        fn holds(block: *const u8, len: usize, seed: u8) -> bool {
            // SAFETY: the callers pass a live block of at least `len` bytes.
            let bytes = unsafe { std::slice::from_raw_parts(block, len) };
            probed(len).all(|k| bytes[k] == seed.wrapping_add((k / 4093) as u8))
        }

        fn is_zero(block: *const u8, len: usize) -> bool {
            // SAFETY: the callers pass a live block of at least `len` bytes.
            let bytes = unsafe { std::slice::from_raw_parts(block, len) };
            probed(len).all(|k| bytes[k] == 0)
        }

        /// A scoped allocator keeps runs within a call, for the call's later blocks, and holds
        /// none once the last call ends or outside every call; the binary's keeps them.
        #[test]
        fn a_scoped_allocator_keeps_runs_only_within_calls() {
            let scoped = Recycling::scoped();
            let big = layout(4 * unit());
            // SAFETY: every block is used within its layout and freed with it, once.
            unsafe {
                let outside = scoped.alloc(big);
                fill_and_check(outside, big.size(), 1);
                scoped.dealloc(outside, big);
                assert_eq!(kept_bytes(&scoped), 0, "freed outside a call: unmapped");
                let reused = scoped.within_call(|| {
                    let a = scoped.alloc(big);
                    fill_and_check(a, big.size(), 2);
                    scoped.dealloc(a, big);
                    assert_eq!(kept_bytes(&scoped), big.size(), "kept within the call");
                    // A call inside the call (another thread's) ends without releasing.
                    scoped.within_call(|| ());
                    assert_eq!(kept_bytes(&scoped), big.size());
                    let b = scoped.alloc(big);
                    assert_eq!(a, b, "the call's own run, reused");
                    fill_and_check(b, big.size(), 3);
                    scoped.dealloc(b, big);
                    b
                });
                assert!(!reused.is_null());
                assert_eq!(kept_bytes(&scoped), 0, "the last call ended: all unmapped");
                let unwound = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    scoped.within_call(|| {
                        let a = scoped.alloc(big);
                        scoped.dealloc(a, big);
                        panic!("unwinding");
                    })
                }));
                assert!(unwound.is_err());
                assert_eq!(kept_bytes(&scoped), 0, "unwinding ends the call too");
            }
            let binary = Recycling::new();
            // SAFETY: as above.
            unsafe {
                let a = binary.alloc(big);
                binary.dealloc(a, big);
            }
            assert_eq!(kept_bytes(&binary), big.size());
            unmap_all(&binary);
        }

        #[test]
        fn reused_runs_hold_their_blocks_and_zeroed_blocks_are_zero() {
            let heap = Recycling::new();
            let big = Layout::from_size_align(pages(4 * unit()) + 7, 8).unwrap();
            let small = Layout::from_size_align(pages(unit()) + 1, 16).unwrap();
            // SAFETY: every block is used within its layout and freed with it, once.
            unsafe {
                let a = heap.alloc(big);
                fill_and_check(a, big.size(), 1);
                heap.dealloc(a, big);
                // Fits in the kept run: reused in place, the rest kept.
                let b = heap.alloc_zeroed(small);
                assert_eq!(b, a);
                assert!(is_zero(b, small.size()));
                assert_eq!(kept_bytes(&heap), pages(3 * unit()));
                // Larger than the kept rest: the rest grows into it.
                let c = heap.alloc_zeroed(big);
                assert_eq!(heap.kept().count, 0);
                assert!(is_zero(c, big.size()));
                fill_and_check(b, small.size(), 2);
                fill_and_check(c, big.size(), 3);
                heap.dealloc(b, small);
                // Grown: its contents moved with it; its fresh pages release the kept run.
                let grown = heap.realloc(c, big, pages(10 * unit()));
                assert!(holds(grown, big.size(), 3));
                assert_eq!(kept_bytes(&heap), 0);
                fill_and_check(grown, pages(10 * unit()), 4);
                // Shrunk below the large size: copied to the system allocator, its pages kept.
                let tiny = heap.realloc(grown, layout(10 * unit()), 100);
                assert!(holds(tiny, 100, 4));
                assert_eq!(kept_bytes(&heap), pages(10 * unit()));
                // And back up: a page run again, from the kept pages.
                let tiny_layout = Layout::from_size_align(100, 8).unwrap();
                let again = heap.realloc(tiny, tiny_layout, pages(5 * unit()));
                assert_eq!(again, grown);
                assert!(holds(again, 100, 4));
                fill_and_check(again, pages(5 * unit()), 5);
                heap.dealloc(again, layout(5 * unit()));
                assert_eq!(kept_bytes(&heap), pages(10 * unit()));
            }
            unmap_all(&heap);
        }

        /// A block larger than every kept run takes the largest, grown, and unmaps as many kept
        /// bytes as it needs fresh pages, smallest runs first; so does a growing block. A
        /// shrinking one keeps its place and gives its tail back.
        #[test]
        fn a_block_larger_than_every_kept_run_grows_the_largest() {
            let heap = Recycling::new();
            // SAFETY: every block is used within its layout and freed with it, once.
            unsafe {
                let sizes = [2 * unit(), 4 * unit(), 3 * unit()];
                let parts: Vec<*mut u8> = sizes.iter().map(|&n| heap.alloc(layout(n))).collect();
                for (k, (&part, &n)) in parts.iter().zip(&sizes).enumerate() {
                    fill_and_check(part, pages(n), k as u8);
                    heap.dealloc(part, layout(n));
                }
                assert_eq!(kept_bytes(&heap), pages(9 * unit()));
                // The 4-unit run grows to 6; the 2-unit run is unmapped for the 2 fresh units.
                let block = heap.alloc_zeroed(layout(6 * unit()));
                assert!(is_zero(block, pages(6 * unit())));
                assert_eq!(kept_bytes(&heap), pages(3 * unit()));
                fill_and_check(block, pages(6 * unit()), 7);
                // Grown by 2 units: 2 of the last run's 3 are unmapped.
                let grown = heap.realloc(block, layout(6 * unit()), pages(8 * unit()));
                assert!(holds(grown, pages(6 * unit()), 7));
                assert_eq!(kept_bytes(&heap), pages(unit()));
                fill_and_check(grown, pages(8 * unit()), 9);
                // Shrunk, still large: in place, its tail kept.
                let shrunk = heap.realloc(grown, layout(8 * unit()), pages(5 * unit()));
                assert_eq!(shrunk, grown);
                assert!(holds(shrunk, pages(5 * unit()), 9));
                assert_eq!(kept_bytes(&heap), pages(4 * unit()));
                heap.dealloc(shrunk, layout(5 * unit()));
            }
            unmap_all(&heap);
        }

        /// Small blocks growing past their highest count take kept pages away, as many bytes.
        #[test]
        fn small_blocks_growing_release_as_many_kept_bytes() {
            let heap = Recycling::new();
            // SAFETY: the block is used within its layout and freed with it.
            unsafe {
                let block = heap.alloc(layout(4 * unit()));
                fill_and_check(block, pages(4 * unit()), 1);
                heap.dealloc(block, layout(4 * unit()));
            }
            let before = pages(4 * unit());
            assert_eq!(kept_bytes(&heap), before);
            // Within one step of LARGE: nothing released yet.
            heap.small_grown(LARGE);
            assert_eq!(kept_bytes(&heap), before);
            // Past it: the growth since the highest count (zero) is released, in whole pages.
            heap.small_grown(pages(3));
            let released = whole_pages(LARGE + pages(3));
            assert_eq!(kept_bytes(&heap), before - released);
            // Freed and grown again up to the same count: no new pages, nothing released.
            heap.small_shrunk(LARGE + pages(3));
            heap.small_grown(LARGE + pages(3));
            assert_eq!(kept_bytes(&heap), before - released);
            unmap_all(&heap);
        }

        /// A small block's count is the chunk glibc gives it from its heap: its usable size
        /// and the 8-byte header (or less, by under 32 bytes, when glibc reuses a free chunk
        /// a little larger than needed), for every size up to 256 bytes (the chunk boundaries of the
        /// blocks the pipeline makes by the hundred thousand) and in steps up to 64 KiB. Not
        /// up to `LARGE`: glibc maps a block of nearly its mmap threshold on its own when its
        /// heap's free end is short, and the threshold can be set from the environment.
        #[test]
        fn small_blocks_count_their_chunks() {
            let sizes = (1..=256).chain((257..64 * 1024).step_by(997));
            for size in sizes {
                let layout = Layout::from_size_align(size, 8).unwrap();
                // SAFETY: a layout of non-zero size; the block is freed with it, unread.
                unsafe {
                    let block = System.alloc(layout);
                    assert!(!block.is_null());
                    let usable = libc::malloc_usable_size(block.cast());
                    System.dealloc(block, layout);
                    // A free chunk up to glibc's smallest chunk (32 bytes) larger than the
                    // request's is handed out whole, unsplit, when other tests have left one.
                    let chunk = Recycling::chunk(size);
                    assert!(
                        chunk <= usable + 8 && usable + 8 < chunk + 32,
                        "size {size}"
                    );
                }
            }
        }

        #[test]
        fn blocks_made_and_freed_on_several_threads_keep_their_contents() {
            static HEAP: Recycling = Recycling::new();
            let workers: Vec<_> = (0..4u8)
                .map(|t| {
                    std::thread::spawn(move || {
                        for round in 0..30usize {
                            let layout = layout(unit() + (round * 7 + t as usize) % 40);
                            // SAFETY: the block is used within its layout and freed with it.
                            unsafe {
                                let block = if round % 2 == 0 {
                                    HEAP.alloc(layout)
                                } else {
                                    HEAP.alloc_zeroed(layout)
                                };
                                if round % 2 == 1 {
                                    assert!(is_zero(block, layout.size()));
                                }
                                fill_and_check(block, layout.size(), t);
                                HEAP.dealloc(block, layout);
                            }
                        }
                    })
                })
                .collect();
            for worker in workers {
                worker.join().unwrap();
            }
        }

        /// A fork while another thread holds the kept runs' lock: the guarded fork waits for
        /// it, and the child takes a large block and ends. Without the guard the child
        /// inherits the lock held and waits for it forever (the parent then kills it).
        #[test]
        fn a_child_forked_while_another_thread_holds_the_lock_takes_large_blocks() {
            static HEAP: Recycling = Recycling::scoped();
            HEAP.guard_forks();
            let (locked, holding) = std::sync::mpsc::channel();
            let holder = std::thread::spawn(move || {
                let lock = HEAP.kept();
                locked.send(()).unwrap();
                std::thread::sleep(std::time::Duration::from_millis(300));
                drop(lock);
            });
            holding.recv().unwrap();
            let big = layout(4 * unit());
            // SAFETY: the child uses only this allocator and `_exit`, and the parent waits for it.
            let child = unsafe { libc::fork() };
            if child == 0 {
                // SAFETY: a block of `big`'s layout, used within it and freed with it.
                let ok = unsafe {
                    let block = HEAP.alloc(big);
                    let ok = !block.is_null();
                    if ok {
                        block.write(1);
                        HEAP.dealloc(block, big);
                    }
                    ok
                };
                // SAFETY: ends the child at once, running nothing of the parent's.
                unsafe { libc::_exit(if ok { 0 } else { 1 }) };
            }
            assert!(child > 0, "fork failed");
            let mut status = 0;
            let mut waited = 0;
            // SAFETY: `child` is this process's child; `status` is a valid place to write.
            while unsafe { libc::waitpid(child, &mut status, libc::WNOHANG) } == 0 {
                if waited == 200 {
                    // SAFETY: as above; the child is stuck, so it is stopped and reaped.
                    unsafe {
                        libc::kill(child, libc::SIGKILL);
                        libc::waitpid(child, &mut status, 0);
                    }
                    panic!("the forked child waited 10 s for the lock");
                }
                std::thread::sleep(std::time::Duration::from_millis(50));
                waited += 1;
            }
            assert!(libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0);
            holder.join().unwrap();
            unmap_all(&HEAP);
        }
    }
}
