//! (e) The memory of one reconstruction, step by step: after each step of a `Pipeline`, the
//! bytes the global allocator holds (a counting wrapper around the system allocator), the most it
//! held during the step and so far, and on Linux the process's resident set and its peak (`/proc/self/status`).
//!
//! `cargo run --release --example step_memory -- POINT_FILE [owned]` (default parameters; with
//! `owned` the pipeline takes the points, as `reconstruct_owned` does). Run it with
//! `GLIBC_TUNABLES=glibc.malloc.mmap_threshold=131072` to see what glibc keeps beyond the live
//! bytes: with the threshold fixed, large blocks go back to the system when freed.

use condt::{Params, Pipeline, StepReport};
use condt_io::read_points;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

/// The system allocator, counting the bytes it holds for the program and their peak.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
/// The peak since the last printed line (the step's own).
static STEP_PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(bytes: usize) {
    let now = LIVE.fetch_add(bytes, Relaxed) + bytes;
    PEAK.fetch_max(now, Relaxed);
    STEP_PEAK.fetch_max(now, Relaxed);
}

// SAFETY: every call is passed on to `System` unchanged; the counters only observe sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract for `alloc`, passed on.
        let block = unsafe { System.alloc(layout) };
        if !block.is_null() {
            grew(layout.size());
        }
        block
    }
    unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract for `dealloc`, passed on.
        unsafe { System.dealloc(block, layout) };
        LIVE.fetch_sub(layout.size(), Relaxed);
    }
    unsafe fn realloc(&self, block: *mut u8, layout: Layout, size: usize) -> *mut u8 {
        // SAFETY: the caller's contract for `realloc`, passed on.
        let moved = unsafe { System.realloc(block, layout, size) };
        if !moved.is_null() {
            LIVE.fetch_sub(layout.size(), Relaxed);
            grew(size);
        }
        moved
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// `VmRSS` and `VmHWM` in MB, where `/proc/self/status` has them.
fn resident() -> String {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |key: &str| {
        let line = status.lines().find(|line| line.starts_with(key))?;
        let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kb * 1024.0 / 1e6)
    };
    match (field("VmRSS:"), field("VmHWM:")) {
        (Some(now), Some(peak)) => format!("  resident {now:6.1} MB, peak {peak:6.1} MB"),
        _ => String::new(),
    }
}

fn line(step: &str) {
    let mb = |bytes: &AtomicUsize| bytes.load(Relaxed) as f64 / 1e6;
    println!(
        "{step:>45}: live {:6.1} MB, step's peak {:6.1} MB, peak {:6.1} MB{}",
        mb(&LIVE),
        mb(&STEP_PEAK),
        mb(&PEAK),
        resident()
    );
    STEP_PEAK.store(LIVE.load(Relaxed), Relaxed);
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().unwrap_or_else(|| "data/shapes.txt".into());
    let owned = args.next().as_deref() == Some("owned");
    let points = read_points(&path)?;
    line("points read");
    let params = Params::default();
    // Borrowed, the points stay alive beside the pipeline, as a caller's would.
    let (mut pipeline, _caller_points) = if owned {
        (Pipeline::new_owned(points, &params)?, None)
    } else {
        (Pipeline::new(&points, &params)?, Some(points))
    };
    line("triangulated");
    while let Some(step) = pipeline.step()? {
        match step {
            StepReport::Stage(report) => line(&report.stage.to_string()),
            StepReport::SmoothingPass { pass, .. } => line(&format!("smoothing pass {pass}")),
            _ => line("another step"),
        }
    }
    let result = pipeline.finish()?;
    line("curves and tally");
    drop(result);
    Ok(())
}
