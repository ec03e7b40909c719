//! The plain point format parsed in pieces on rayon's threads: an optional speed-up (feature
//! `parallel`) of [`parse_points_sequentially`](super::parse_points_sequentially), which is the
//! reference it must equal. The text is cut at line ends into pieces parsed at once; their
//! points are joined in order. Any piece that meets something it cannot settle alone (an
//! error, a header, a `.node` index column, a line end it cannot see) gives up, and the
//! sequential parse reads the whole text again, so every error is reported exactly as the
//! reference reports it. The tests in `points.rs` (`the_parallel_parse_equals_the_sequential_one`,
//! `files_read_in_pieces_read_as_the_whole_text`) compare the two on the same texts.

use super::{expected_points, node_index_column, parse_lines, Parsed, Source};
use condt::Point;
use condt::MAX_POINTS;
use rayon::prelude::*;

/// Below this many bytes a text is parsed on one thread: splitting would cost more.
const MIN_PIECE: usize = 1 << 20;

/// The text cut into about `pieces` stretches of whole lines, each cut just after a `\n`
/// (so a CRLF pair is never split; a CR-only file stays in one piece).
fn pieces(text: &str, pieces: usize) -> Vec<&str> {
    let size = (text.len() / pieces).max(MIN_PIECE);
    let mut out = Vec::with_capacity(pieces + 1);
    let mut rest = text;
    while rest.len() > size {
        let Some(newline) = rest.as_bytes()[size..].iter().position(|&b| b == b'\n') else {
            break;
        };
        let (piece, tail) = rest.split_at(size + newline + 1);
        out.push(piece);
        rest = tail;
    }
    out.push(rest);
    out
}

/// The points of `text` when it is large and valid, in pieces to be joined by [`join`];
/// `None` when it is small, or when any piece finds something to refuse: then the
/// sequential parse reads it again and reports the first problem exactly as it always does
/// (the line count of each piece would otherwise be needed, and the refusals that depend
/// on earlier lines would differ).
pub(super) fn parse_pieces(text: &str, file: &str) -> Option<Vec<Parsed>> {
    // Without rayon's threads (they could not be started) the sequential parse reads it.
    if !condt::parallel_available() {
        return None;
    }
    let threads = rayon::current_num_threads();
    if threads < 2 || text.len() < 2 * MIN_PIECE {
        return None;
    }
    let pieces = pieces(text, 4 * threads);
    if pieces.len() < 2 {
        return None;
    }
    let source = Source { file };
    let parsed: Vec<Parsed> = pieces
        .par_iter()
        .enumerate()
        .map(|(k, piece)| parse_piece(piece, &source, k))
        .collect::<Option<_>>()?;
    accept(parsed)
}

/// Piece `k` of a file parsed (its lines numbered from its start); `None` on anything to
/// refuse, which the sequential parse then reports.
fn parse_piece(piece: &str, source: &Source<'_>, k: usize) -> Option<Parsed> {
    parse_lines(piece, source, k == 0, expected_points(piece)).ok()
}

/// The parsed pieces of a whole file when nothing in them depends on another piece: the
/// refusals that do are left to the sequential parse.
fn accept(parsed: Vec<Parsed>) -> Option<Vec<Parsed>> {
    // A header can only be the file's first line with columns: the first piece must have one.
    if !parsed.first()?.seen_content {
        return None;
    }
    // A header whose first row lies in a later piece: that row's width against the header's
    // is the sequential parse's to check.
    if parsed[0].header.is_some() && parsed[0].first_data_line.is_none() {
        return None;
    }
    // An Octave text workspace's variables are counted by the sequential parse.
    if parsed[0].octave {
        return None;
    }
    let total = parsed
        .iter()
        .try_fold(0usize, |sum, p| sum.checked_add(p.points.len()))?;
    // No point at all: whether its header may stand alone is the sequential parse's to say.
    if total == 0 || total > MAX_POINTS || node_index_column(&parsed).is_some() {
        return None;
    }
    Some(parsed)
}

/// How far past its share of the file a piece reads to find the end of its last line;
/// a longer line sends the file to the whole-file path.
#[cfg(unix)]
const LOOK_AHEAD: usize = 1 << 16;

/// Reads and parses a plain point file of `size` bytes in pieces on rayon's threads, each
/// piece read straight from the file (`pread`) into a buffer its thread reuses, checked as
/// UTF-8 and parsed there: no copy of the whole text is made, faulted in, checked on one
/// thread and freed. Reading the file into one buffer took as long as parsing it on two
/// threads (1M points, 38.5 MB: 55 ms of the 118 ms).
///
/// The pieces are cut where the text in memory would be: piece `k` holds the lines that
/// start after the first `\n` at or past byte `k * share` and up to that of piece `k + 1`
/// (so a CRLF pair is never split). `None`, for the whole-file path to read and report on,
/// when the file is small, a piece finds no line end in its look-ahead (long lines, CR-only
/// line ends), a piece is not UTF-8 or has anything to refuse, or the file is not `size`
/// bytes long when read (it changed meanwhile).
#[cfg(unix)]
pub(super) fn read_pieces(file: &std::fs::File, size: u64, name: &str) -> Option<Vec<Point>> {
    if !condt::parallel_available() {
        return None;
    }
    let size = usize::try_from(size).ok()?;
    let threads = rayon::current_num_threads();
    if threads < 2 || size < 2 * MIN_PIECE {
        return None;
    }
    // Pieces of 1 to 2 MB whatever the file's size: each thread's buffer is faulted in
    // once and reused (1M points: 9,965 page faults in a fresh process against 12,611
    // with a quarter of the file per thread).
    let share = (size / (4 * threads)).clamp(MIN_PIECE, 2 * MIN_PIECE);
    let count = size.div_ceil(share);
    let source = Source { file: name };
    // The read buffers, shared by the jobs and freed only once every piece is parsed: a
    // buffer freed earlier (one per job, as `map_init` would) raises the C allocator's
    // threshold for giving large blocks their own mapping, after which the pieces' points
    // come from its heaps and stay held by the process when freed (13 MB more resident
    // for the rest of a 1M-point run).
    let buffers: std::sync::Mutex<Vec<Vec<u8>>> = std::sync::Mutex::new(Vec::new());
    let take = || {
        buffers
            .lock()
            .map_or_else(|_| Vec::new(), |mut b| b.pop().unwrap_or_default())
    };
    let give_back = |buffer: Vec<u8>| {
        if let Ok(mut b) = buffers.lock() {
            b.push(buffer);
        }
    };
    let parsed: Vec<Parsed> = (0..count)
        .into_par_iter()
        .map(|k| {
            let mut buffer = take();
            let parsed = read_piece(file, size, share, count, k, &mut buffer, &source);
            give_back(buffer);
            parsed
        })
        .collect::<Option<_>>()?;
    drop(buffers);
    join(accept(parsed)?)
}

/// Piece `k` of [`read_pieces`], read into `buffer` and parsed.
#[cfg(unix)]
fn read_piece(
    file: &std::fs::File,
    size: usize,
    share: usize,
    count: usize,
    k: usize,
    buffer: &mut Vec<u8>,
    source: &Source<'_>,
) -> Option<Parsed> {
    use std::os::unix::fs::FileExt;
    let newline = |bytes: &[u8]| bytes.iter().position(|&b| b == b'\n');
    let start = k * share;
    let last = k + 1 == count;
    let end = if last {
        size
    } else {
        size.min((k + 1) * share + LOOK_AHEAD)
    };
    if buffer.len() < end - start {
        buffer.resize(end - start, 0);
    }
    let bytes = &mut buffer[..end - start];
    file.read_exact_at(bytes, start as u64).ok()?;
    if last && file.read_at(&mut [0u8; 1], size as u64).ok()? != 0 {
        return None;
    }
    let first = if k == 0 {
        0
    } else {
        1 + newline(&bytes[..share.min(bytes.len())])?
    };
    let after = if last {
        bytes.len()
    } else {
        share + 1 + newline(&bytes[share..])?
    };
    let text = core::str::from_utf8(&bytes[first..after]).ok()?;
    // A byte-order mark is skipped at the very start of the file only: at the start of a
    // later piece it is inside the file, which the parse refuses as the whole-file parse does.
    let text = if k == 0 {
        text.strip_prefix('\u{feff}').unwrap_or(text)
    } else {
        text
    };
    parse_piece(text, source, k)
}

/// The points of the pieces, in order, each piece freed once copied; `None` when the
/// memory for them all is refused.
pub(super) fn join(parsed: Vec<Parsed>) -> Option<Vec<Point>> {
    let total = parsed.iter().map(|p| p.points.len()).sum();
    let mut points = Vec::new();
    points.try_reserve_exact(total).ok()?;
    for piece in parsed {
        points.extend_from_slice(&piece.points);
    }
    Some(points)
}
