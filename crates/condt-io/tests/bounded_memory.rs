//! What the readers allocate, counted by a global allocator of this test binary (issue 29,
//! items 1 and 10): a `.npy` header cannot make the reader allocate the points it promises
//! before the bytes for them are there, and GeoJSON input is streamed into the point vector,
//! its memory bounded by the points' size, an exhausted memory an error rather than an abort.
//!
//! The counts are per thread (the readers measured here run on the calling thread), so the
//! tests of this binary, run on parallel threads, do not see each other's allocations.

use condt::Point;
use condt_io::{parse_geojson, parse_npy, read_points};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Bytes allocated and not yet freed by this thread.
    static LIVE: Cell<usize> = const { Cell::new(0) };
    /// The most `LIVE` reached since the last [`measure`] began.
    static PEAK: Cell<usize> = const { Cell::new(0) };
    /// Allocations that would take `LIVE` above this fail (return null).
    static LIMIT: Cell<usize> = const { Cell::new(usize::MAX) };
}

/// Counts `grow` more bytes as live; `false` (nothing counted) when that passes the limit.
fn grow(bytes: usize) -> bool {
    let Ok(live) = LIVE.try_with(Cell::get) else {
        return true;
    };
    let new = live.saturating_add(bytes);
    if new > LIMIT.try_with(Cell::get).unwrap_or(usize::MAX) {
        return false;
    }
    let _ = LIVE.try_with(|l| l.set(new));
    let _ = PEAK.try_with(|p| p.set(p.get().max(new)));
    true
}

fn shrink(bytes: usize) {
    let _ = LIVE.try_with(|l| l.set(l.get().saturating_sub(bytes)));
}

// SAFETY: every call is forwarded to `System` unchanged; only counters are kept beside it.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !grow(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: the caller's contract, passed on.
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            shrink(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !grow(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: the caller's contract, passed on.
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            shrink(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        shrink(layout.size());
        // SAFETY: the caller's contract, passed on.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        // Both blocks may be held at once while the contents move.
        if !grow(new_size) {
            return std::ptr::null_mut();
        }
        // SAFETY: the caller's contract, passed on.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        shrink(if p.is_null() { new_size } else { old });
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Runs `f` and returns its result with the most bytes it held at once beyond what was live
/// when it began (on this thread).
fn measure<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let start = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(start));
    let result = f();
    (result, PEAK.with(Cell::get) - start)
}

/// Runs `f` with allocations beyond `extra` more bytes than are live now refused.
fn limited<T>(extra: usize, f: impl FnOnce() -> T) -> T {
    let start = LIVE.with(Cell::get);
    LIMIT.with(|l| l.set(start + extra));
    let result = f();
    LIMIT.with(|l| l.set(usize::MAX));
    result
}

/// A version 1.0 `.npy` header for `rows` float64 points, padded as NumPy pads it.
fn npy_header(rows: usize, fortran_order: bool) -> Vec<u8> {
    let order = if fortran_order { "True" } else { "False" };
    let dict = format!("{{'descr': '<f8', 'fortran_order': {order}, 'shape': ({rows}, 2), }}");
    let unpadded = 10 + dict.len() + 1;
    let header = format!("{dict}{}\n", " ".repeat((64 - unpadded % 64) % 64));
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out
}

/// A header announcing 20M points (320 MB), with nothing or a little data after it, is refused
/// without allocating anything near the points it promises: in memory and as a file, C order
/// and Fortran order.
#[test]
fn a_npy_header_alone_does_not_allocate_the_points_it_announces() {
    const ROWS: usize = 20_000_000;
    const BOUND: usize = 8 << 20;
    let dir = tempfile::tempdir().unwrap();
    for fortran_order in [false, true] {
        for data in [0usize, 1000, 4 << 20] {
            let mut bytes = npy_header(ROWS, fortran_order);
            bytes.resize(bytes.len() + data, 0);
            let (result, peak) = measure(|| parse_npy(&bytes, "big.npy"));
            let err = result.unwrap_err().to_string();
            assert!(
                err.starts_with("big.npy: the header announces 20000000 points"),
                "{err}"
            );
            assert!(
                err.ends_with(&format!("the file ends after {data} bytes of them")),
                "{err}"
            );
            assert!(
                peak < BOUND,
                "fortran_order {fortran_order}, {data} bytes of data: {peak} bytes allocated"
            );

            let path = dir.path().join("big.npy");
            std::fs::write(&path, &bytes).unwrap();
            let (result, peak) = measure(|| read_points(&path));
            let err = result.unwrap_err().to_string();
            assert!(
                err.contains("the header announces 20000000 points"),
                "{err}"
            );
            assert!(
                peak < BOUND,
                "file, fortran_order {fortran_order}, {data} bytes: {peak} bytes allocated"
            );
        }
    }
}

/// A read through a pipe, whose length is not known: memory follows the data that arrived, not
/// the header's promise, and the points read are the file's.
#[cfg(unix)]
#[test]
fn a_npy_stream_of_unknown_length_allocates_as_its_data_arrive() {
    use std::io::Write;
    const ROWS: usize = 20_000_000;
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.npy");
    let status = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(status.success());
    for fortran_order in [false, true] {
        let mut bytes = npy_header(ROWS, fortran_order);
        bytes.resize(bytes.len() + (3 << 20), 0);
        let writer = {
            let fifo = fifo.clone();
            std::thread::spawn(move || {
                let mut f = std::fs::OpenOptions::new().write(true).open(fifo).unwrap();
                let _ = f.write_all(&bytes);
            })
        };
        let (result, peak) = measure(|| read_points(&fifo));
        writer.join().unwrap();
        let err = result.unwrap_err().to_string();
        assert!(
            err.ends_with("the file ends after 3145728 bytes of them"),
            "{err}"
        );
        assert!(
            peak < 16 << 20,
            "fortran_order {fortran_order}: {peak} bytes"
        );
    }
    // Valid data through the pipe read as from memory.
    let points: Vec<Point> = (0..300_000)
        .map(|i| Point::new(i as f64, 0.5 - i as f64))
        .collect();
    for fortran_order in [false, true] {
        let mut bytes = npy_header(points.len(), fortran_order);
        if fortran_order {
            bytes.extend(points.iter().flat_map(|p| p.x.to_le_bytes()));
            bytes.extend(points.iter().flat_map(|p| p.y.to_le_bytes()));
        } else {
            bytes.extend(
                points
                    .iter()
                    .flat_map(|p| [p.x.to_le_bytes(), p.y.to_le_bytes()])
                    .flatten(),
            );
        }
        assert_eq!(parse_npy(&bytes, "mem.npy").unwrap(), points);
        let writer = {
            let fifo = fifo.clone();
            std::thread::spawn(move || {
                let mut f = std::fs::OpenOptions::new().write(true).open(fifo).unwrap();
                f.write_all(&bytes).unwrap();
            })
        };
        assert_eq!(read_points(&fifo).unwrap(), points);
        writer.join().unwrap();
    }
}

/// A MultiPoint of 1M points: the reader holds less than twice the points' size beyond the
/// text (no tree of the document, the positions pushed into the point vector as they are met).
fn multipoint(n: usize) -> (String, Vec<Point>) {
    let points: Vec<Point> = (0..n)
        .map(|i| Point::new(i as f64 * 0.25, (i % 1000) as f64 - 0.5))
        .collect();
    let mut text = String::from(r#"{"type":"MultiPoint","coordinates":["#);
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            text.push(',');
        }
        text.push_str(&format!("[{:?},{:?}]", p.x, p.y));
    }
    text.push_str("]}");
    (text, points)
}

#[test]
fn geojson_memory_is_bounded_by_the_points() {
    let n = 1_000_000;
    let (text, points) = multipoint(n);
    let size = n * std::mem::size_of::<Point>();
    let (read, peak) = measure(|| parse_geojson(&text, "many.geojson").unwrap());
    assert!(read == points);
    drop(read);
    assert!(
        peak < 2 * size,
        "{peak} bytes held for {size} bytes of points ({} bytes of text)",
        text.len()
    );
}

/// When the memory for the points runs out, the reader reports it as an error (the test's
/// allocator refuses any block past a limit); no abort.
#[test]
fn geojson_memory_exhausted_is_an_error() {
    let (text, _) = multipoint(200_000);
    let err = limited(1 << 20, || parse_geojson(&text, "many.geojson")).unwrap_err();
    let message = err.to_string();
    assert!(
        message.starts_with("many.geojson") && message.contains("memory"),
        "{message}"
    );
}
