//! Where the binary's memory comes from: large blocks are runs of pages that the process keeps
//! and moves between buffers instead of handing them back to the system and faulting them in
//! again; small blocks come from the system allocator. Linux with glibc only (elsewhere the
//! system allocator serves everything). The binary's one use of `unsafe`, confined here; every
//! block says why it is sound (`tests/unsafe_code.rs` checks that each has its `// SAFETY:`).
//!
//! Owns: the pages of every block of `LARGE` (128 KiB) or more. It knows nothing of what the
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
//! run it fits in (the rest of the run stays kept), or else a fresh mapping into which kept runs
//! are moved with `mremap` (the kernel moves page-table entries: no copy, no fault), largest
//! first, until it is covered. Growing a block (`realloc`) moves it the same way. The peak stays
//! about what the live blocks hold, as with glibc's unmapping, because kept pages are rarely
//! resident beside fresh ones:
//! - a block that needs fresh pages takes every kept run first;
//! - when the small blocks grow past their highest total so far (glibc then takes fresh pages
//!   for them), kept runs are unmapped by as many bytes.
//!
//! (A fresh page first touched after later frees filled the kept runs still adds to them.
//! Faulting fresh pages in at once, with `MAP_POPULATE`, closed that gap but moved the faults of
//! the triangulation's mesh, which both its threads touch, onto the one thread that allocates
//! it: the 100M run's triangulation took 51.7 s, against 38.6 and 42.7 s without it; at 1M and
//! 10M the peak was the same without it.)
//!
//! A block asked for zeroed is cleared where its pages were reused (a `memset` of resident
//! memory, far cheaper than a fault; fresh pages come zeroed).
//!
//! Measured against glibc with its mmap threshold fixed at 128 KiB, which this replaced (`perf
//! stat -e page-faults`, `/usr/bin/time`; `docs/performance.md`, "The binary's allocator"):
//! `reconstruct` along curves, 1M points, 64,723 page faults -> 27,825 and 0.21 -> 0.09 s of
//! system time; 10M 663,281 -> 276,141 and 2.02 -> 0.89 s; uniform points, 1M, 323,258 ->
//! 32,849. The peak resident set is 0.2 to 1.9 % higher (109,976 against 109,440 kB along curves
//! at 1M, 128,912 against 126,516 on uniform points). Every output is byte-identical.

#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[global_allocator]
static ALLOCATOR: linux::Recycling = linux::Recycling::new();

#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod linux {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::ptr;
    use std::sync::atomic::{AtomicUsize, Ordering};
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

        /// The smallest kept run, removed.
        fn take_smallest(&mut self) -> Option<Run> {
            let k = (0..self.count).min_by_key(|&k| self.runs[k].len)?;
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
            let k = (0..self.count).min_by_key(|&k| self.runs[k].len)?;
            if self.runs[k].len >= run.len {
                return Some(run);
            }
            Some(core::mem::replace(&mut self.runs[k], run))
        }
    }

    /// The binary's global allocator (see the module comment).
    pub(crate) struct Recycling {
        kept: Mutex<Kept>,
        /// Bytes of small blocks live now.
        small_live: AtomicUsize,
        /// The most bytes of small blocks live at once so far.
        small_high: AtomicUsize,
    }

    impl Recycling {
        pub(crate) const fn new() -> Self {
            Recycling {
                kept: Mutex::new(Kept {
                    runs: [Run::EMPTY; KEPT_RUNS],
                    count: 0,
                }),
                small_live: AtomicUsize::new(0),
                small_high: AtomicUsize::new(0),
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
            let Some(start) = map(len) else {
                return ptr::null_mut();
            };
            cover(&mut kept, start, 0, len, zeroed);
            start as *mut u8
        }

        /// Counts `size` more bytes of small blocks. Past their highest count so far the system
        /// allocator takes fresh pages for them, so the kept runs give back as many bytes: kept
        /// and fresh pages together then stay under an earlier peak. (Checked in steps of
        /// [`LARGE`], so that the lock is rarely taken.)
        fn small_grown(&self, size: usize) {
            let live = self.small_live.fetch_add(size, Ordering::Relaxed) + size;
            if live > self.small_high.load(Ordering::Relaxed) + LARGE {
                let high = self.small_high.fetch_max(live, Ordering::Relaxed);
                if live > high {
                    self.release(live - high);
                }
            }
        }

        fn small_shrunk(&self, size: usize) {
            self.small_live.fetch_sub(size, Ordering::Relaxed);
        }

        /// Unmaps at least `len` bytes of kept runs (or all of them), smallest runs first.
        fn release(&self, len: usize) {
            let mut kept = self.kept();
            let mut released = 0;
            while released < len {
                let Some(run) = kept.take_smallest() else {
                    return;
                };
                let piece = whole_pages(len - released).min(run.len);
                unmap(Run {
                    start: run.start,
                    len: piece,
                });
                if let Some(rest) = run.after(piece) {
                    let _ = kept.put(rest);
                }
                released += piece;
            }
        }

        /// Keeps the pages of a freed block, or unmaps them when too many runs are kept.
        fn give_back(&self, run: Run) {
            if let Some(dropped) = self.kept().put(run) {
                unmap(dropped);
            }
        }
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

    fn unmap(run: Run) {
        // SAFETY: the run is a whole-page range mapped by this allocator that nothing uses.
        unsafe { libc::munmap(run.start as *mut libc::c_void, run.len) };
    }

    fn clear(start: usize, len: usize) {
        // SAFETY: `start..start + len` is mapped read-write and owned by the block being made.
        unsafe { ptr::write_bytes(start as *mut u8, 0, len) };
    }

    /// Moves kept runs, largest first, onto `start + from .. start + len` (a mapping of this
    /// allocator whose pages there are untouched), until it is covered or no run is left; the
    /// unused rest of the last run stays kept. Zeroes what was moved if asked.
    fn cover(kept: &mut Kept, start: usize, from: usize, len: usize, zeroed: bool) {
        let mut offset = from;
        while offset < len {
            let Some(run) = kept.take_largest() else {
                return;
            };
            let piece = run.len.min(len - offset);
            move_pages(run.start, piece, start + offset);
            if zeroed {
                clear(start + offset, piece);
            }
            if let Some(rest) = run.after(piece) {
                // One run was just taken out, so there is room for its rest.
                let _ = kept.put(rest);
            }
            offset += piece;
        }
    }

    /// Moves the pages of `from .. from + len` onto `to .. to + len` (whole pages of mappings
    /// of this allocator; nothing uses either range). `mremap` moves only within one mapping,
    /// and a block assembled from moved runs spans several, so a range it refuses as such is
    /// split in two until each part lies in one; what cannot be moved otherwise is copied and
    /// unmapped.
    fn move_pages(from: usize, len: usize, to: usize) {
        // SAFETY: both ranges are whole pages owned by the allocator and unused; MREMAP_FIXED
        // unmaps the destination's pages first. On failure nothing changes.
        let moved = unsafe {
            libc::mremap(
                from as *mut libc::c_void,
                len,
                len,
                libc::MREMAP_MAYMOVE | libc::MREMAP_FIXED,
                to as *mut libc::c_void,
            )
        };
        if moved != libc::MAP_FAILED {
            return;
        }
        let page = page_size();
        // `errno`, read without allocating.
        let spans_mappings = std::io::Error::last_os_error().raw_os_error() == Some(libc::EFAULT);
        if spans_mappings && len > page {
            let half = (len / 2) & !(page - 1);
            move_pages(from, half, to);
            move_pages(from + half, len - half, to + half);
        } else {
            // SAFETY: both ranges are mapped read-write, distinct and unused.
            unsafe { ptr::copy_nonoverlapping(from as *const u8, to as *mut u8, len) };
            unmap(Run { start: from, len });
        }
    }

    // SAFETY: every block handed out is either the system allocator's (small or over-aligned
    // layouts, freed and grown there) or a run of whole pages of its own, aligned to the page,
    // mapped read-write and used by nothing else until it is given back; the layout a block is
    // freed or grown with tells which (its size decides, and a block keeps its kind).
    unsafe impl GlobalAlloc for Recycling {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            if is_large(layout.size(), layout.align()) {
                self.take(whole_pages(layout.size()), false)
            } else {
                self.small_grown(layout.size());
                // SAFETY: the caller's contract, passed on.
                unsafe { System.alloc(layout) }
            }
        }

        unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
            if is_large(layout.size(), layout.align()) {
                self.take(whole_pages(layout.size()), true)
            } else {
                self.small_grown(layout.size());
                // SAFETY: the caller's contract, passed on.
                unsafe { System.alloc_zeroed(layout) }
            }
        }

        unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
            if is_large(layout.size(), layout.align()) {
                self.give_back(Run {
                    start: block as usize,
                    len: whole_pages(layout.size()),
                });
            } else {
                self.small_shrunk(layout.size());
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
                    self.small_shrunk(layout.size());
                    self.small_grown(new_size);
                }
                return moved;
            }
            if old_large && new_large {
                let (old_len, new_len) = (whole_pages(layout.size()), whole_pages(new_size));
                let start = block as usize;
                if new_len <= old_len {
                    if let Some(tail) = (Run {
                        start,
                        len: old_len,
                    })
                    .after(new_len)
                    {
                        self.give_back(tail);
                    }
                    return block;
                }
                // A new run: the block's pages moved to its start, its tail covered by kept runs.
                let mut kept = self.kept();
                let Some(grown) = map(new_len) else {
                    return ptr::null_mut();
                };
                move_pages(start, old_len, grown);
                cover(&mut kept, grown, old_len, new_len, false);
                return grown as *mut u8;
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

        /// Writes a pattern over a block and checks it back, so that every page is mapped
        /// read-write and holds what was written.
        fn fill_and_check(block: *mut u8, len: usize, seed: u8) {
            // SAFETY: the callers pass a live block of `len` bytes that nothing else uses.
            let bytes = unsafe { std::slice::from_raw_parts_mut(block, len) };
            for (k, b) in bytes.iter_mut().enumerate() {
                *b = seed.wrapping_add((k / 4093) as u8);
            }
            assert!(bytes
                .iter()
                .enumerate()
                .all(|(k, &b)| b == seed.wrapping_add((k / 4093) as u8)));
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
                // Fits in the kept run: reused, the rest kept.
                let b = heap.alloc_zeroed(small);
                assert_eq!(b, a);
                assert!(std::slice::from_raw_parts(b, small.size())
                    .iter()
                    .all(|&x| x == 0));
                // Needs more than the kept rest: a fresh block covered by it.
                let c = heap.alloc_zeroed(big);
                assert!(std::slice::from_raw_parts(c, big.size())
                    .iter()
                    .all(|&x| x == 0));
                assert_eq!(heap.kept().count, 0);
                fill_and_check(b, small.size(), 2);
                fill_and_check(c, big.size(), 3);
                // Grown: moved or grown in place, its contents kept, its tail usable.
                heap.dealloc(b, small);
                let grown = heap.realloc(c, big, pages(10 * unit()));
                let bytes = std::slice::from_raw_parts(grown, big.size());
                assert!(bytes
                    .iter()
                    .enumerate()
                    .all(|(k, &x)| x == 3u8.wrapping_add((k / 4093) as u8)));
                fill_and_check(grown, pages(10 * unit()), 4);
                let grown_layout = layout(10 * unit());
                // Shrunk in place below the large size: copied to the system allocator.
                let tiny = heap.realloc(grown, grown_layout, 100);
                assert!(std::slice::from_raw_parts(tiny, 100)
                    .iter()
                    .all(|&x| x == 4));
                let tiny_layout = Layout::from_size_align(100, 8).unwrap();
                // And back up: a page run again.
                let again = heap.realloc(tiny, tiny_layout, pages(5 * unit()));
                assert!(std::slice::from_raw_parts(again, 100)
                    .iter()
                    .all(|&x| x == 4));
                fill_and_check(again, pages(5 * unit()), 5);
                heap.dealloc(again, layout(5 * unit()));
                assert!(kept_bytes(&heap) >= pages(5 * unit()));
                let mut kept = heap.kept();
                while let Some(run) = kept.take_largest() {
                    unmap(run);
                }
            }
        }

        fn kept_bytes(heap: &Recycling) -> usize {
            let kept = heap.kept();
            kept.runs[..kept.count].iter().map(|r| r.len).sum()
        }

        fn layout(pages_count: usize) -> Layout {
            Layout::from_size_align(pages(pages_count), 8).unwrap()
        }

        /// A block made of several moved runs spans several mappings, which `mremap` cannot move
        /// at once: it is moved again, into a larger block and by growing, piece by piece.
        #[test]
        fn blocks_assembled_from_several_runs_move_again() {
            let heap = Recycling::new();
            // SAFETY: every block is used within its layout and freed with it, once.
            unsafe {
                let sizes = [2 * unit(), 4 * unit(), 3 * unit()];
                let parts: Vec<*mut u8> = sizes.iter().map(|&n| heap.alloc(layout(n))).collect();
                for (k, (&part, &n)) in parts.iter().zip(&sizes).enumerate() {
                    fill_and_check(part, pages(n), k as u8);
                    heap.dealloc(part, layout(n));
                }
                let whole = 9 * unit();
                assert_eq!(kept_bytes(&heap), pages(whole));
                // Covered exactly by the three runs, largest first.
                let block = heap.alloc_zeroed(layout(whole));
                assert_eq!(heap.kept().count, 0);
                assert!(std::slice::from_raw_parts(block, pages(whole))
                    .iter()
                    .all(|&x| x == 0));
                fill_and_check(block, pages(whole), 7);
                heap.dealloc(block, layout(whole));
                // The run of three mappings moved into a larger block, then grown.
                let larger = heap.alloc_zeroed(layout(12 * unit()));
                assert_eq!(heap.kept().count, 0);
                assert!(std::slice::from_raw_parts(larger, pages(12 * unit()))
                    .iter()
                    .all(|&x| x == 0));
                fill_and_check(larger, pages(12 * unit()), 9);
                let grown = heap.realloc(larger, layout(12 * unit()), pages(18 * unit()));
                assert!(std::slice::from_raw_parts(grown, pages(12 * unit()))
                    .iter()
                    .enumerate()
                    .all(|(k, &x)| x == 9u8.wrapping_add((k / 4093) as u8)));
                fill_and_check(grown, pages(18 * unit()), 11);
                heap.dealloc(grown, layout(18 * unit()));
            }
            let mut kept = heap.kept();
            while let Some(run) = kept.take_largest() {
                unmap(run);
            }
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
            let mut kept = heap.kept();
            while let Some(run) = kept.take_largest() {
                unmap(run);
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
                                    assert!(std::slice::from_raw_parts(block, layout.size())
                                        .iter()
                                        .all(|&x| x == 0));
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
    }
}
