//! Writing a large output as pieces formatted independently, in parallel with the `parallel`
//! feature, and handed to the writer in order.
//!
//! Owns: cutting a range of units (triangles, points) into pieces, the buffers they are
//! formatted into, and the order they reach the writer in. It may not know what a unit is: the
//! caller formats a piece.
//!
//! Why: formatting two million triangle lines is most of the time of writing them, and every
//! piece can be formatted without the others; only the order of the bytes is shared. The
//! pieces are formatted on rayon's threads a batch at a time while the calling thread writes
//! the batch before, so the output is the same bytes as one sequential pass and the memory
//! stays bounded (a few batches) whatever the output's size. Called on one thread (a one-thread
//! pool) or from inside a rayon job, the pieces are formatted on the calling thread.

use core::ops::Range;
use std::io::{self, Write};
use std::vec::Vec;

/// Formats the units of one piece into a buffer and returns how many of its bytes are the
/// piece's text; see [`Cursor`].
pub(super) type Format<'a> = dyn Fn(Range<usize>, &mut Vec<u8>) -> usize + Sync + 'a;

/// A piece's text written at a cursor into a buffer that is kept at its full length between
/// uses (zeroed once, when it grows), so that a line is built in place with one bounds check
/// instead of one length update per byte and no copy through a scratch array.
pub(super) struct Cursor<'a> {
    buf: &'a mut Vec<u8>,
    at: usize,
}

/// Room reserved ahead of every item a [`Cursor`] writes: the longest line any writer builds
/// at once (three 20-digit indices, two spaces and a line end).
pub(super) const ROOM: usize = 64;

impl<'a> Cursor<'a> {
    pub(super) fn new(buf: &'a mut Vec<u8>) -> Cursor<'a> {
        Cursor { buf, at: 0 }
    }

    /// The next [`ROOM`] bytes, for an item that then moves the cursor by what it used.
    #[inline]
    pub(super) fn room(&mut self) -> &mut [u8; ROOM] {
        if self.buf.len() < self.at + ROOM {
            self.grow();
        }
        (&mut self.buf[self.at..self.at + ROOM])
            .try_into()
            .expect("ROOM bytes from a range of that length")
    }

    /// Moves the cursor past `used` bytes of the room just filled.
    #[inline]
    pub(super) fn advance(&mut self, used: usize) {
        debug_assert!(used <= ROOM);
        self.at += used;
    }

    #[cold]
    fn grow(&mut self) {
        let size = (2 * self.buf.len()).max(self.at + ROOM).max(1 << 12);
        self.buf.resize(size, 0);
    }

    /// The number of bytes written.
    pub(super) fn finish(self) -> usize {
        self.at
    }
}

/// Writes `units` units, cut into pieces of `piece` units, formatted by `format` and written to
/// `out` in order: the bytes are those of formatting `0..units` in one piece.
pub(super) fn write_pieces(
    out: &mut dyn Write,
    units: usize,
    piece: usize,
    format: &Format<'_>,
) -> io::Result<()> {
    let piece = piece.max(1);
    // Not from inside a rayon job: the calling thread waits on a channel for the batches, and
    // were every worker of the pool waiting so, no thread would be left to format them. (Asked
    // first: inside a one-thread pool nothing below starts rayon's global pool.) When the
    // formatting thread cannot be started (a limit on threads or memory), the pieces are
    // formatted here, the same bytes.
    #[cfg(feature = "parallel")]
    if rayon::current_thread_index().is_none()
        && units > piece
        && condt::parallel_available()
        && rayon::current_num_threads() >= 2
    {
        if let Some(written) = parallel::write_pieces(out, units, piece, format) {
            return written;
        }
    }
    sequentially(out, units, piece, format)
}

/// [`write_pieces`] on the calling thread alone.
fn sequentially(
    out: &mut dyn Write,
    units: usize,
    piece: usize,
    format: &Format<'_>,
) -> io::Result<()> {
    let mut buf = Vec::new();
    let mut start = 0;
    while start < units {
        let end = units.min(start.saturating_add(piece));
        let used = format(start..end, &mut buf);
        out.write_all(&buf[..used])?;
        start = end;
    }
    Ok(())
}

/// The results of `run` on rayon's global pool and, with the `parallel` feature, inside a
/// one-thread pool too (where the writers format sequentially): a test asserts the same of each.
#[cfg(test)]
pub(super) fn on_rayon_and_one_thread<T: Send>(run: impl Fn() -> T + Sync + Send) -> Vec<T> {
    let mut results = std::vec![run()];
    #[cfg(feature = "parallel")]
    {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        results.push(pool.install(&run));
    }
    results
}

#[cfg(feature = "parallel")]
mod parallel {
    use super::Format;
    use rayon::prelude::*;
    use std::io::{self, Write};
    use std::sync::mpsc;
    use std::vec::Vec;

    /// A piece's buffer and the length of its text.
    type Formatted = (Vec<u8>, usize);

    /// Pieces formatted on rayon's threads, a batch of two per thread at a time, by a thread
    /// of their own that hands each batch to this one to write (the writer need not be
    /// `Send`: a locked standard output is not). Written buffers go back to be formatted into
    /// again, so the memory is touched once. A failed write ends the run: the formatting thread
    /// finds the channel closed and stops. `None` when the formatting thread cannot be started
    /// (nothing is written then).
    pub(super) fn write_pieces(
        out: &mut dyn Write,
        units: usize,
        piece: usize,
        format: &Format<'_>,
    ) -> Option<io::Result<()>> {
        let batch = 2 * rayon::current_num_threads();
        let ranges: Vec<core::ops::Range<usize>> = (0..units)
            .step_by(piece)
            .map(|start| start..units.min(start.saturating_add(piece)))
            .collect();
        std::thread::scope(|scope| {
            // One batch waiting while the next is formatted and the one before written.
            let (batches, formatted) = mpsc::sync_channel::<Vec<Formatted>>(1);
            let (recycle, recycled) = mpsc::channel::<Vec<Vec<u8>>>();
            let ranges = &ranges;
            let spawned = std::thread::Builder::new().spawn_scoped(scope, move || {
                let mut spare: Vec<Vec<u8>> = Vec::new();
                for group in ranges.chunks(batch) {
                    spare.extend(recycled.try_iter().flatten());
                    let buffers: Vec<Vec<u8>> = (0..group.len())
                        .map(|_| spare.pop().unwrap_or_default())
                        .collect();
                    let done: Vec<Formatted> = group
                        .par_iter()
                        .zip(buffers)
                        .map(|(range, mut buf)| {
                            let used = format(range.clone(), &mut buf);
                            (buf, used)
                        })
                        .collect();
                    if batches.send(done).is_err() {
                        return;
                    }
                }
            });
            if spawned.is_err() {
                return None;
            }
            Some((|| {
                for done in formatted {
                    for (buf, used) in &done {
                        out.write_all(&buf[..*used])?;
                    }
                    // The formatting thread may have finished: then the buffers are just freed.
                    let _ = recycle.send(done.into_iter().map(|(buf, _)| buf).collect());
                }
                Ok(())
            })())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit `i` as its own line, so the output shows every unit once and in order.
    fn numbers(range: Range<usize>, buf: &mut Vec<u8>) -> usize {
        let mut cursor = Cursor::new(buf);
        for i in range {
            let text = format!("{i}\n");
            cursor.room()[..text.len()].copy_from_slice(text.as_bytes());
            cursor.advance(text.len());
        }
        cursor.finish()
    }

    fn expected(units: usize) -> Vec<u8> {
        (0..units)
            .flat_map(|i| format!("{i}\n").into_bytes())
            .collect()
    }

    /// Every cut (pieces of one unit, pieces that divide the units or not, one piece larger
    /// than all) gives the bytes of one sequential pass, on rayon's threads and on one.
    #[test]
    fn pieces_arrive_whole_and_in_order() {
        for units in [0, 1, 2, 7, 100, 1000, 5003] {
            for piece in [0, 1, 2, 3, 64, 1000, 10_000] {
                let outputs = on_rayon_and_one_thread(|| {
                    let mut out = Vec::new();
                    write_pieces(&mut out, units, piece, &numbers).unwrap();
                    out
                });
                for out in outputs {
                    assert_eq!(out, expected(units), "{units} units, pieces of {piece}");
                }
            }
        }
    }

    /// Called from inside rayon jobs of the global pool, on every worker at once: written on
    /// each job's own thread, the same bytes, and no worker left waiting for batches that no
    /// free worker could format (this hangs without the check in `write_pieces`).
    #[cfg(feature = "parallel")]
    #[test]
    fn writers_inside_rayon_jobs_finish() {
        use rayon::prelude::*;
        let jobs = 4 * rayon::current_num_threads();
        let outputs: Vec<Vec<u8>> = (0..jobs)
            .into_par_iter()
            .map(|_| {
                let mut out = Vec::new();
                write_pieces(&mut out, 5003, 64, &numbers).unwrap();
                out
            })
            .collect();
        for out in outputs {
            assert_eq!(out, expected(5003));
        }
    }

    /// A writer that fails after some bytes: the error comes back and nothing hangs.
    #[test]
    fn a_failed_write_ends_the_run() {
        struct Failing(usize);
        impl Write for Failing {
            fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
                if self.0 < buf.len() {
                    return Err(io::Error::other("disk full"));
                }
                self.0 -= buf.len();
                Ok(buf.len())
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let err = write_pieces(&mut Failing(1000), 100_000, 7, &numbers).unwrap_err();
        assert_eq!(err.to_string(), "disk full");
    }
}
