//! The interactive stage viewer: one self-contained HTML file (inline script and style, no
//! network, opens from `file://`).
//!
//! Owns: the page's layout, its data block and its script. The data are the points (relative to
//! their bounding box, so offsets of 1e6 cost no precision on screen), every edge of
//! [`Reconstruction::provenance`] with its story in compact numeric form, and per layer (the
//! Delaunay triangulation, each stage that ran, the result) the list of its edges. The script
//! draws on one canvas (no element per edge, so 100,000 points stay responsive), switches the
//! layers, pans and zooms, and on a click shows a point's ring (its two shortest edges, the
//! uniformity test with its numbers, its final degree, the stage that last changed each of its
//! edges) or an edge's story. It may not decide anything: every verdict and ratio comes from the
//! library; the script computes only lengths and positions for display.

use condt::geometry::{binary_exponent, Point, Scale};
use condt::{EdgeStory, EndChoice, Reason};
use condt::{Reconstruction, Stage};
use std::io::{self, Write};

/// Writes the viewer page for `result`, titled `title` (HTML-escaped here).
///
/// ```
/// use condt_io::write_html;
/// use condt::{reconstruct, Params, Point};
/// let points = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 1.2)].map(Point::from);
/// let result = reconstruct(&points, &Params::default())?;
/// let mut page = Vec::new();
/// write_html(&mut page, &result, "five points")?;
/// let page = String::from_utf8(page)?;
/// assert!(page.starts_with("<!DOCTYPE html>"));
/// assert!(page.contains("<title>condt: five points</title>"));
/// assert!(!page.contains("http://") && !page.contains("https://")); // nothing to fetch
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_html(out: &mut dyn Write, result: &Reconstruction, title: &str) -> io::Result<()> {
    let stories = result.provenance();
    let mut out = io::BufWriter::with_capacity(1 << 16, out);
    let title = escape(title);
    // The result's counts head the side panel: the drawing's text alternative (the canvas is
    // described by it), and with JavaScript off the one thing the page can say (it read "Click a
    // point or an edge." over an empty canvas: a teacher's review); the panels only the script
    // fills are hidden then. The canvas is an application to a screen reader, which then hands
    // it the keys (as an image they stayed in the reader's browse mode, where NVDA's n and e
    // move to the next text and the next edit field).
    let curves = result.curves();
    let closed = curves.iter().filter(|c| c.is_closed()).count();
    let (points, unused, edges) = (
        result.num_points(),
        result.unused().len(),
        result.edges().len(),
    );
    let plural = |count: usize| if count == 1 { "" } else { "s" };
    let (points_text, edges_text, unused_text) = (grouped(points), grouped(edges), grouped(unused));
    write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\">\
         <title>condt: {title}</title><style>{STYLE}</style>\
         <noscript><style>#info, #layers, .hint {{ display: none; }}</style></noscript>\
         </head><body>\
         <header><h1>condt: {title}</h1><span id=\"status\" role=\"status\"></span></header>\
         <main><div id=\"view\"><noscript><p id=\"noscript\">This page draws the stages with \
         JavaScript, which is off: turn it on to explore them, or draw them without it with \
         <code>condt reconstruct INPUT -o stages.svg --stages</code>.</p></noscript>\
         <canvas id=\"canvas\" tabindex=\"0\" role=\"application\" \
         aria-roledescription=\"drawing\" aria-label=\"The points, their \
         Delaunay triangulation and the graph after each stage, as the layers switch them; a \
         click on a point or an edge, or the keys below, tell its story in Details\" \
         aria-describedby=\"summary keys\"></canvas></div>\
         <aside><p id=\"summary\">The result: {points_text} point{}, {edges_text} edge{} in {} \
         curve{} ({closed} closed, {} open), {unused_text} unused.</p>\
         <section id=\"info\"><h2>Details</h2><p id=\"details\" aria-live=\"polite\">\
         Click a point or an edge.</p></section><section id=\"layers\" role=\"group\" \
         aria-labelledby=\"layers-heading\"><h2 id=\"layers-heading\">Layers</h2></section>\
         <p class=\"hint\" id=\"keys\">Drag or arrow keys to pan, wheel or + and - to zoom, \
         double-click or 0 to see everything. Keys work where the drawing has the focus (Tab to \
         it): Enter selects the point nearest the middle of the view, n and p step through the \
         points, e and E through the selected point's edges; Tab goes on to the layers' \
         switches, which Space turns on and off. The number beside a layer is its count of \
         edges.</p></aside></main>\n\
         <script id=\"data\" type=\"application/json\">",
        plural(points),
        plural(edges),
        curves.len(),
        plural(curves.len()),
        curves.len() - closed,
    )?;
    write_data(&mut out, result, &stories)?;
    write!(out, "</script>\n<script>{SCRIPT}</script></body></html>\n")?;
    out.flush()
}

/// `n` with its thousands grouped by commas, as the script writes its counts
/// (`toLocaleString("en")`): the summary and the layers' counts read alike.
fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut text = String::with_capacity(digits.len() + digits.len() / 3);
    for (k, digit) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k) % 3 == 0 {
            text.push(',');
        }
        text.push(digit);
    }
    text
}

/// The data block: one JSON object, numbers only (no text the script would have to trust).
fn write_data(
    out: &mut impl Write,
    result: &Reconstruction,
    stories: &[EdgeStory],
) -> io::Result<()> {
    let n = result.num_points();
    // The positions are written relative to the box's corner over one power of two that spans
    // the box (so that the page keeps the set's shape and the set's own spacing survives the
    // digits written). They are first brought near 1 by another power of two, as the SVG does,
    // so that spans of coordinates near 1e308 do not overflow; both steps are exact.
    let largest = (0..n)
        .map(|i| result.stage_point(i))
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let exponent = if largest > 0.0 && largest.is_finite() {
        binary_exponent(largest)
    } else {
        0
    };
    let unit = Scale::power_of_two(-exponent);
    let points: Vec<Point> = (0..n).map(|i| unit.apply(result.stage_point(i))).collect();
    let (mut min, mut span) = (Point::new(f64::INFINITY, f64::INFINITY), 0.0f64);
    for p in &points {
        min = Point::new(min.x.min(p.x), min.y.min(p.y));
    }
    if points.is_empty() {
        // No corner: the origin is written as zero (JSON has no infinity).
        min = Point::new(0.0, 0.0);
    }
    for p in &points {
        span = span.max(p.x - min.x).max(p.y - min.y);
    }
    let scale = if span > 0.0 {
        libm::exp2(libm::ceil(libm::log2(span)))
    } else {
        1.0
    };
    // Back in input units for the page's readouts. A set wider than the largest double has a
    // scale beyond it: the page is given a part of it (a half or a quarter) and adds it `parts`
    // times (each sum stays within the doubles, as every point does).
    let input = |x: f64| libm::ldexp(x, exponent);
    let mut parts: u32 = 1;
    while !libm::ldexp(scale, exponent - parts.trailing_zeros() as i32).is_finite() {
        parts *= 2;
    }
    write!(
        out,
        "{{\"origin\":[{:e},{:e}],\"scale\":{:e},\"parts\":{parts},\"points\":[",
        input(min.x),
        input(min.y),
        libm::ldexp(scale, exponent - parts.trailing_zeros() as i32)
    )?;
    for (k, p) in points.iter().enumerate() {
        if k > 0 {
            out.write_all(b",")?;
        }
        Short((p.x - min.x) / scale, POSITION_DIGITS).write_to(out)?;
        out.write_all(b",")?;
        Short((p.y - min.y) / scale, POSITION_DIGITS).write_to(out)?;
    }
    // The smoothing passes that ran (0 when none): the positions above are the moved ones.
    let (passes, moved) = result.smoothing().map_or((0, 0), |s| (s.passes, s.moved));
    write!(out, "],\"smoothing\":[{passes},{moved}],\"unused\":")?;
    write_list(out, result.unused().iter().map(|&i| i as u64))?;
    write!(out, ",\"degree\":")?;
    write_list(out, (0..n).map(|i| result.degree(i) as u64))?;
    // Exact duplicates: each later point and the first at its position, which carries their
    // edges (a duplicate shares its point's fate), for the details panel to say so.
    let tri = result.triangulation();
    write!(out, ",\"merged\":")?;
    write_list(out, tri.merged().flatten().map(|i| i as u64))?;
    write!(out, ",\"edges\":")?;
    write_list(out, stories.iter().flat_map(|s| s.edge).map(|i| i as u64))?;
    // Per edge and end: 0 not Delaunay, 1 shortest, 2 second, k >= 3 the rank.
    write!(out, ",\"ends\":")?;
    write_list(
        out,
        stories
            .iter()
            .flat_map(|s| s.ends)
            .map(|choice| match choice {
                EndChoice::NotDelaunay => 0,
                EndChoice::Shortest => 1,
                EndChoice::Second { .. } => 2,
                EndChoice::Later { rank } => rank as u64,
            }),
    )?;
    // Per second-shortest end: edge index, end (0 or 1), ratio, bound, kept (0 or 1).
    write!(out, ",\"seconds\":[")?;
    let mut first = true;
    for (k, story) in stories.iter().enumerate() {
        for (side, choice) in story.ends.iter().enumerate() {
            if let EndChoice::Second { ratio, bound, kept } = *choice {
                if !first {
                    out.write_all(b",")?;
                }
                first = false;
                write_integer(out, k as u64)?;
                out.write_all(if side == 0 { b",0," } else { b",1," })?;
                // Every digit where the usual ones would read a ratio as its bound, so that
                // the page tells them apart as `story_text` does (2.7499999996 against 2.75).
                let digits = if ratio_digits_meet(ratio, bound) {
                    17
                } else {
                    RATIO_DIGITS
                };
                Short(ratio, digits).write_to(out)?;
                out.write_all(b",")?;
                Short(bound, digits).write_to(out)?;
                out.write_all(if kept { b",1" } else { b",0" })?;
            }
        }
    }
    // Per change: edge index, stage index, added (0 or 1), reason code, two numbers.
    let stages: Vec<Stage> = result.stage_times().map(|(stage, _)| stage).collect();
    write!(out, "],\"detourCode\":{DETOUR_CODE},\"changes\":[")?;
    let mut first = true;
    for (k, story) in stories.iter().enumerate() {
        for change in &story.changes {
            let stage = stages.iter().position(|&s| s == change.stage).unwrap_or(0);
            let (code, x, y) = reason_code(change.reason);
            // A length and its threshold with every digit, so that the page can tell apart a
            // length just above its threshold (as `story_text` does); other numbers are ids,
            // counts and ratios shown with fewer.
            let digits = if matches!(code, 1 | 12) {
                17
            } else {
                LENGTH_DIGITS
            };
            if !first {
                out.write_all(b",")?;
            }
            first = false;
            write_integer(out, k as u64)?;
            out.write_all(b",")?;
            write_integer(out, stage as u64)?;
            out.write_all(if change.added { b",1," } else { b",0," })?;
            write_integer(out, code)?;
            out.write_all(b",")?;
            Short(x, digits).write_to(out)?;
            out.write_all(b",")?;
            Short(y, digits).write_to(out)?;
        }
    }
    // Per repair change, in the order above: the neighbours its vertex selected, four numbers,
    // -1 for none.
    write!(out, "],\"repairSelected\":[")?;
    let selected = stories
        .iter()
        .flat_map(|s| &s.changes)
        .filter_map(|c| match c.reason {
            Reason::Repair { selected, .. } => Some(selected),
            _ => None,
        })
        .flatten();
    for (k, w) in selected.enumerate() {
        if k > 0 {
            out.write_all(b",")?;
        }
        match w {
            Some(w) => write_integer(out, w as u64)?,
            None => out.write_all(b"-1")?,
        }
    }
    // Layers: their names, and per edge one number whose bit 0 says it is a Delaunay edge and
    // bit k + 1 that stage k's graph has it (a list of edges per layer would be 3 times larger).
    write!(out, "],\"layers\":[\"Delaunay triangulation\"")?;
    for stage in &stages {
        write!(out, ",\"{}\"", stage.title())?;
    }
    write!(out, "],\"member\":")?;
    write_list(out, membership(result, stories, &stages))?;
    write!(out, ",\"stageNames\":[")?;
    for (k, stage) in stages.iter().enumerate() {
        let sep = if k == 0 { "" } else { "," };
        write!(out, "{sep}\"{}\"", stage.name())?;
    }
    write!(out, "],\"stageColors\":[")?;
    for (k, stage) in stages.iter().enumerate() {
        let sep = if k == 0 { "" } else { "," };
        write!(out, "{sep}\"{}\"", stage_color(*stage))?;
    }
    write!(out, "]}}")
}

/// Each stage's layer colour in the viewer, named by its stage: the array's length is the number
/// of stages, so a stage added to the table does not build until it has a colour, and a test
/// checks that each stage has its own entry (by position, a misplaced entry gave a stage its
/// neighbour's colour without a failing test: a contributor's review). The NN-Crust and the Crust
/// share one: each replaces the proximity graph, never beside the other. Each stands out from
/// the white canvas by 3:1 or more (WCAG's contrast for graphics; six were lighter, down to
/// 2:1: a viewer review).
const STAGE_COLORS: [(Stage, &str); Stage::ALL.len()] = [
    (Stage::Proximity, "#3b6fd8"),
    (Stage::Repair, "#9b4dca"),
    (Stage::Outliers, "#c26a00"),
    (Stage::RepairAgain, "#6a3d9a"),
    (Stage::LocalOutliers, "#1a9e8f"),
    (Stage::GivenBack, "#8c564b"),
    (Stage::Clumps, "#8a7a00"),
    (Stage::Gaps, "#5a8a00"),
    (Stage::Junctions, "#d6337f"),
    (Stage::Crossings, "#0b87a1"),
    (Stage::Tips, "#b5179e"),
    (Stage::Spikes, "#7b2cbf"),
    (Stage::Hooks, "#c0563a"),
    (Stage::Tails, "#7f7f7f"),
    (Stage::Detours, "#2ca02c"),
    (Stage::NnCrust, "#d62728"),
    (Stage::Crust, "#d62728"),
];

/// The viewer's layer colour of `stage`.
fn stage_color(stage: Stage) -> &'static str {
    let entry = STAGE_COLORS.iter().find(|&&(named, _)| named == stage);
    entry.expect("STAGE_COLORS names every stage").1
}

/// A change's reason as the page stores it: a code (an index into the page's list of words in
/// `viewer.js`, or from [`DETOUR_CODE`] a detour) and two numbers.
fn reason_code(reason: Reason) -> (u64, f64, f64) {
    match reason {
        Reason::Repair { vertex, degree, .. } => (0, vertex as f64, degree as f64),
        Reason::LongerThanThreshold {
            length,
            threshold,
            floored: false,
        } => (1, length, threshold),
        Reason::LongerThanThreshold {
            length,
            threshold,
            floored: true,
        } => (12, length, threshold),
        Reason::GivenBack => (2, 0.0, 0.0),
        Reason::LongAt { vertex, ratio } => (3, vertex as f64, ratio),
        Reason::Component => (4, 0.0, 0.0),
        Reason::Spur => (5, 0.0, 0.0),
        Reason::GapClosed => (6, 0.0, 0.0),
        Reason::NotConfirmed => (7, 0.0, 0.0),
        Reason::Baseline => (8, 0.0, 0.0),
        Reason::Junction => (9, 0.0, 0.0),
        Reason::Clump => (10, 0.0, 0.0),
        Reason::RepairedAgain => (11, 0.0, 0.0),
        Reason::Crossing { vertex } => (13, vertex as f64, 0.0),
        Reason::Tip => (14, 0.0, 0.0),
        Reason::Tail { vertex, points } => (15, vertex as f64, points as f64),
        Reason::LastEdge => (16, 0.0, 0.0),
        Reason::Hook => (17, 0.0, 0.0),
        Reason::Spike => (18, 0.0, 0.0),
        // A loop's one end; else the route's points in the code (`DETOUR_CODE` +
        // points), which the page's words need beside the two ends.
        Reason::Detour { from, to, .. } if from == to => (19, from as f64, to as f64),
        Reason::Detour { from, to, points } => {
            (DETOUR_CODE + points as u64, from as f64, to as f64)
        }
    }
}

/// A change's reason code from this one up is a detour through `code - DETOUR_CODE` points
/// (the page reads it as `data.detourCode`); below it, a reason's index in the page's list of
/// words (`viewer.js`), so that a new reason takes the next free index.
const DETOUR_CODE: u64 = 1000;

/// Significant digits of positions (relative to the box, over its longer side): a ten-millionth
/// of the view, below a pixel at any zoom a page needs to tell samples apart.
const POSITION_DIGITS: usize = 7;
/// Of the uniformity ratios and bounds, shown with three decimals: enough digits that the page
/// rounds the value itself to those, as the Python package and `story_text` do (five rounded
/// twice, 1.0705 from 1.07049..., showed 1.071 where they say 1.070).
const RATIO_DIGITS: usize = 9;
/// Whether a ratio and its bound, different, read alike with [`RATIO_DIGITS`].
fn ratio_digits_meet(ratio: f64, bound: f64) -> bool {
    let (mut a, mut b) = (Text::default(), Text::default());
    ratio != bound
        && Short(ratio, RATIO_DIGITS).spell(&mut a) == Short(bound, RATIO_DIGITS).spell(&mut b)
}

/// Of the changes' other numbers (vertex ids, counts, the long-edge ratio shown with two
/// decimals).
const LENGTH_DIGITS: usize = 6;

/// Per story, the layers that have its edge (bit 0 the triangulation, bit `k + 1` stage `k`'s
/// graph). Only the first stage's graph is rebuilt and searched: a later stage's graph differs
/// from the one before it by exactly the edges whose stories list a change by that stage
/// ([`Reconstruction::provenance`] compares the two graphs to list them), so its bit is the one
/// before, flipped where the story has such a change. Searching every stage's graph for every
/// edge took most of the page's time beside the stories themselves at a million points.
fn membership<'s>(
    result: &Reconstruction,
    stories: &'s [EdgeStory],
    stages: &'s [Stage],
) -> impl Iterator<Item = u64> + use<'s> {
    let first: Vec<[usize; 2]> = result
        .stages()
        .next()
        .map_or_else(Vec::new, |r| r.graph.edges());
    // Both sorted by edge: one walk along the first graph.
    let mut in_first = first.into_iter().peekable();
    stories.iter().map(move |story| {
        let mut bits = u64::from(!story.ends.contains(&EndChoice::NotDelaunay));
        if stages.is_empty() {
            return bits;
        }
        let mut member = in_first.next_if_eq(&story.edge).is_some();
        bits |= u64::from(member) << 1;
        for (k, stage) in stages.iter().enumerate().skip(1) {
            member ^= story.changes.iter().any(|c| c.stage == *stage);
            bits |= u64::from(member) << (k + 1);
        }
        bits
    })
}

/// The integers `items` as a JSON list.
fn write_list(out: &mut impl Write, items: impl IntoIterator<Item = u64>) -> io::Result<()> {
    out.write_all(b"[")?;
    for (k, item) in items.into_iter().enumerate() {
        if k > 0 {
            out.write_all(b",")?;
        }
        write_integer(out, item)?;
    }
    out.write_all(b"]")
}

/// `value` in decimal, as `write!(out, "{value}")` writes it, without the formatting machinery's
/// cost per call (tens of millions of numbers at a million points).
fn write_integer(out: &mut impl Write, mut value: u64) -> io::Result<()> {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    loop {
        at -= 1;
        digits[at] = b'0' + (value % 10) as u8;
        value /= 10;
        if value == 0 {
            break;
        }
    }
    out.write_all(&digits[at..])
}

/// A number with the given number of significant digits, as JSON (which has no NaN or infinity: those become 0,
/// and cannot occur for finite input).
struct Short(f64, usize);

impl Short {
    /// The number written as [`Display`](core::fmt::Display) writes it, without allocating.
    fn write_to(&self, out: &mut impl Write) -> io::Result<()> {
        let mut text = Text::default();
        let spelled = self
            .spell(&mut text)
            .ok_or_else(|| io::Error::other(LONGER))?;
        out.write_all(spelled.as_bytes())
    }

    /// The number's text in `text`'s buffer; `None` only for a spelling longer than the buffer,
    /// which holds the longest ([`Text`]).
    fn spell<'t>(&self, text: &'t mut Text) -> Option<&'t str> {
        use core::fmt::Write as _;
        let (x, digits) = (self.0, self.1);
        if !x.is_finite() {
            return Some("0");
        }
        if x == x.trunc() && x.abs() < 1e15 {
            write!(text, "{}", x as i64).ok()?;
            return text.as_str(0..text.len);
        }
        // Shortest of the two spellings that keep `digits` significant digits, both in `text`.
        write!(text, "{:.*}", digits_after_point(x, digits), x).ok()?;
        let plain_end = text.len;
        let plain = text.as_str(0..plain_end)?;
        let plain_len = without_trailing_zeros(plain).len();
        // The exponent spelling has a sign, `digits` digits, a point past the first, an `e` and
        // at least one exponent digit: a plain spelling no longer needs no comparison.
        let sign = usize::from(x.is_sign_negative());
        let shortest_exp = sign + digits + usize::from(digits > 1) + 2;
        if plain_len > shortest_exp {
            write!(text, "{:.*e}", digits - 1, x).ok()?;
            if text.len - plain_end < plain_len {
                return text.as_str(plain_end..text.len);
            }
        }
        text.as_str(0..plain_len)
    }
}

/// A stack buffer `write!` fills (an error once full), for [`Short`]'s two spellings at once:
/// the plain one is at most a sign, 309 digits before the point (the largest double) or 40
/// after it ([`digits_after_point`]), and the point; the exponent one a sign, the digits asked
/// for (at most [`RATIO_DIGITS`] here), a point, `e` and four more: under [`TEXT_BYTES`] together.
struct Text {
    bytes: [u8; TEXT_BYTES],
    len: usize,
}

/// [`Text`]'s size.
const TEXT_BYTES: usize = 512;

/// The error for a spelling [`Text`] cannot hold (none can, for the digits used here).
const LONGER: &str = "a number longer than its spelling buffer";

impl Default for Text {
    fn default() -> Self {
        Text {
            bytes: [0; TEXT_BYTES],
            len: 0,
        }
    }
}

impl Text {
    fn as_str(&self, range: core::ops::Range<usize>) -> Option<&str> {
        core::str::from_utf8(&self.bytes[range]).ok()
    }
}

impl core::fmt::Write for Text {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        let end = self.len + s.len();
        let room = self.bytes.get_mut(self.len..end).ok_or(core::fmt::Error)?;
        room.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

impl core::fmt::Display for Short {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.spell(&mut Text::default()).ok_or(core::fmt::Error)?)
    }
}

/// `plain` without the zeros after its decimal point's last significant digit (and the point,
/// if none is left); a number without a point keeps its zeros (123450, not 12345).
fn without_trailing_zeros(plain: &str) -> &str {
    if plain.contains('.') {
        plain.trim_end_matches('0').trim_end_matches('.')
    } else {
        plain
    }
}

fn digits_after_point(x: f64, digits: usize) -> usize {
    let magnitude = libm::floor(libm::log10(x.abs())) as i32;
    (digits as i32 - 1 - magnitude).clamp(0, 40) as usize
}

fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            c => escaped.push(c),
        }
    }
    escaped
}

const STYLE: &str = include_str!("html/viewer.css");
const SCRIPT: &str = include_str!("html/viewer.js");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_group_their_thousands_as_the_script_does() {
        for (n, text) in [
            (0, "0"),
            (999, "999"),
            (1_000, "1,000"),
            (12_345, "12,345"),
            (1_234_567, "1,234,567"),
        ] {
            assert_eq!(grouped(n), text);
        }
    }

    #[test]
    fn numbers_keep_their_significant_digits_in_the_shorter_spelling() {
        for (x, text) in [
            (0.5, "0.5"),
            (3.0, "3"),
            (0.123456789123, "0.1234568"),
            (1.5e-7, "0.00000015"),
            (1.25e-12, "1.250000e-12"),
            (f64::NAN, "0"),
            (2.75, "2.75"),
            // Large numbers keep the zeros before their point (a reviewer's probe: 12345).
            (1234500.3, "1234500"),
            (20000000.5, "20000000"),
            (-3000000.25, "-3000000"),
        ] {
            assert_eq!(Short(x, 7).to_string(), text);
        }
        let x = 1.0 / 3.0;
        let back: f64 = Short(x, 9).to_string().parse().unwrap();
        assert!((back - x).abs() < 1e-9);
    }

    /// The stack-buffer spelling writes what the allocating one wrote before it (which picked
    /// the shorter of the two spellings after making both), over numbers of every magnitude.
    #[test]
    fn the_buffered_spelling_is_the_allocating_one() {
        fn reference(x: f64, digits: usize) -> String {
            if !x.is_finite() {
                return "0".into();
            }
            if x == x.trunc() && x.abs() < 1e15 {
                return (x as i64).to_string();
            }
            let plain = format!("{:.*}", digits_after_point(x, digits), x);
            // Zeros are cut only after a point (before 2026-12-06 they were cut from a number
            // without one too: 123450.3 with six digits read 12345).
            let plain = match plain.contains('.') {
                true => plain.trim_end_matches('0').trim_end_matches('.'),
                false => &plain,
            };
            let exp = format!("{:.*e}", digits - 1, x);
            if plain.len() <= exp.len() {
                plain.to_string()
            } else {
                exp
            }
        }
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for k in 0..40_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Random bit patterns (every magnitude), and numbers near 1 as positions are.
            let x = if k % 2 == 0 {
                f64::from_bits(state)
            } else {
                (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 0.5
            };
            // The longest spellings too: the buffer holds them ([`TEXT_BYTES`]).
            let x = match k {
                0 => -f64::MAX,
                2 => f64::MIN_POSITIVE,
                4 => -5e-324,
                _ => x,
            };
            for digits in [POSITION_DIGITS, RATIO_DIGITS, LENGTH_DIGITS, 1] {
                let mut written = Vec::new();
                Short(x, digits).write_to(&mut written).unwrap();
                assert_eq!(
                    String::from_utf8(written).unwrap(),
                    reference(x, digits),
                    "{x:e}"
                );
            }
        }
    }

    #[test]
    fn coordinates_near_the_largest_double_give_finite_json() {
        use condt::{reconstruct, Params};
        let points = [
            (-1e308, -1e308),
            (1e308, -1e308),
            (0.0, 1e308),
            (1e307, 0.0),
        ]
        .map(|(x, y)| Point::new(x, y));
        let result = reconstruct(&points, &Params::default()).unwrap();
        let mut page = Vec::new();
        write_html(&mut page, &result, "huge").unwrap();
        let page = String::from_utf8(page).unwrap();
        let data = &page[page.find("{\"origin\"").unwrap()..page.find("</script>").unwrap()];
        assert!(!data.contains("inf") && !data.contains("NaN"), "{data}");
        // The four points keep distinct positions.
        let start = data.find("\"points\":[").unwrap() + 10;
        let end = start + data[start..].find(']').unwrap();
        let numbers: Vec<&str> = data[start..end].split(',').collect();
        let pairs: Vec<(&str, &str)> = numbers.chunks(2).map(|c| (c[0], c[1])).collect();
        assert_eq!(pairs.len(), 4);
        for (i, a) in pairs.iter().enumerate() {
            assert!(pairs[i + 1..].iter().all(|b| b != a), "{pairs:?}");
        }
        // The readouts, computed as the page computes them, land on the input points (to the
        // digits written): the set is wider than the largest double, so the page adds a part of
        // the scale `parts` times. (The scale was clamped to the largest double: readouts off by
        // 100 %.)
        let field = |name: &str| {
            let at = data.find(&format!("\"{name}\":")).unwrap() + name.len() + 3;
            let end = at + data[at..].find([',', '}']).unwrap();
            &data[at..end]
        };
        let origin_at = data.find("\"origin\":[").unwrap() + 10;
        let origin: Vec<f64> = data[origin_at..origin_at + data[origin_at..].find(']').unwrap()]
            .split(',')
            .map(|x| x.parse().unwrap())
            .collect();
        let scale: f64 = field("scale").parse().unwrap();
        let parts: usize = field("parts").parse().unwrap();
        assert!(parts > 1);
        for (p, (x, y)) in points.iter().zip(&pairs) {
            let at = |o: f64, v: &str| {
                let t = v.parse::<f64>().unwrap() * scale;
                (0..parts).fold(o, |sum, _| sum + t)
            };
            let (rx, ry) = (at(origin[0], x), at(origin[1], y));
            assert!((rx - p.x).abs() <= 1e-5 * 1e308 && (ry - p.y).abs() <= 1e-5 * 1e308);
        }
    }

    /// Each stage has one colour entry of its own: an entry placed by position gave a stage its
    /// neighbour's colour and no test failed (a contributor's review).
    #[test]
    fn each_stage_has_its_own_colour_entry() {
        for stage in Stage::ALL {
            let named = STAGE_COLORS.iter().filter(|&&(s, _)| s == stage).count();
            assert_eq!(named, 1, "{stage:?} has {named} entries in STAGE_COLORS");
        }
        let colours: std::collections::BTreeSet<&str> = STAGE_COLORS.iter().map(|e| e.1).collect();
        // Only the NN-Crust and the Crust share theirs (one replaces the other).
        assert_eq!(colours.len(), Stage::ALL.len() - 1);
        assert_eq!(stage_color(Stage::NnCrust), stage_color(Stage::Crust));
    }

    /// WCAG's contrast ratio of a `#rrggbb` colour against white.
    fn contrast_on_white(colour: &str) -> f64 {
        let channel = |at: usize| {
            let c = f64::from(u8::from_str_radix(&colour[at..at + 2], 16).unwrap()) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        let luminance = 0.2126 * channel(1) + 0.7152 * channel(3) + 0.0722 * channel(5);
        1.05 / (luminance + 0.05)
    }

    /// A layer's edges stand out from the canvas as WCAG asks of graphics (3:1); the ratio
    /// itself is checked on two known colours.
    #[test]
    fn every_stage_colour_stands_out_from_the_canvas() {
        assert!((contrast_on_white("#000000") - 21.0).abs() < 1e-9);
        assert!((contrast_on_white("#777777") - 4.48).abs() < 0.01);
        for (stage, colour) in STAGE_COLORS {
            let ratio = contrast_on_white(colour);
            assert!(ratio >= 3.0, "{stage:?}: {colour} is {ratio:.2}:1 on white");
        }
    }

    /// Every reason's code below [`DETOUR_CODE`] has its words in the page's list (a new reason
    /// took code 20, which the page read as a detour's, before `DETOUR_CODE`).
    #[test]
    fn every_reason_has_its_words_on_the_page() {
        let list = SCRIPT.split("const words = [").nth(1).unwrap();
        let list = list.split("\n    ];").next().unwrap();
        let words = list
            .lines()
            .filter(|l| l.starts_with("      () =>"))
            .count() as u64;
        assert!((20..DETOUR_CODE).contains(&words), "{words}");
        let reasons = [
            Reason::Repair {
                vertex: 1,
                degree: 3,
                selected: [Some(2), Some(4), None, None],
            },
            Reason::LongerThanThreshold {
                length: 2.0,
                threshold: 1.0,
                floored: false,
            },
            Reason::LongerThanThreshold {
                length: 2.0,
                threshold: 1.0,
                floored: true,
            },
            Reason::GivenBack,
            Reason::LastEdge,
            Reason::LongAt {
                vertex: 1,
                ratio: 3.0,
            },
            Reason::RepairedAgain,
            Reason::Component,
            Reason::Spur,
            Reason::Clump,
            Reason::GapClosed,
            Reason::Junction,
            Reason::Crossing { vertex: 1 },
            Reason::Tip,
            Reason::Spike,
            Reason::Hook,
            Reason::Tail {
                vertex: 1,
                points: 2,
            },
            Reason::Detour {
                from: 1,
                to: 1,
                points: 2,
            },
            Reason::Detour {
                from: 1,
                to: 2,
                points: 0,
            },
            Reason::Baseline,
            Reason::NotConfirmed,
        ];
        let mut codes = Vec::new();
        for reason in reasons {
            // Names every variant, so that a new one must join the list above.
            match reason {
                Reason::Repair { .. }
                | Reason::LongerThanThreshold { .. }
                | Reason::GivenBack
                | Reason::LastEdge
                | Reason::LongAt { .. }
                | Reason::RepairedAgain
                | Reason::Component
                | Reason::Spur
                | Reason::Clump
                | Reason::GapClosed
                | Reason::Junction
                | Reason::Crossing { .. }
                | Reason::Tip
                | Reason::Spike
                | Reason::Hook
                | Reason::Tail { .. }
                | Reason::Detour { .. }
                | Reason::Baseline
                | Reason::NotConfirmed => {}
            }
            let (code, _, _) = reason_code(reason);
            assert!(
                code < words || code >= DETOUR_CODE,
                "no words for reason code {code} ({reason:?}) in viewer.js's list"
            );
            codes.push(code);
        }
        // Each reason's own words (the two readings of a detour share theirs).
        codes.sort_unstable();
        codes.dedup();
        assert_eq!(codes.len(), reasons.len());
        assert_eq!(
            codes.iter().filter(|&&c| c < DETOUR_CODE).count() as u64,
            words
        );
    }

    /// A ratio that nine digits would read as its bound is written with every digit, so that
    /// the page tells them apart as `story_text` does (a diff review: "2.750 |e1| < 2.750 |e1|").
    #[test]
    fn a_ratio_a_hair_under_its_bound_keeps_its_digits() {
        use condt::{reconstruct, Params, Point};
        let points = [(0.0, 0.0), (1.0, 0.0), (-2.749_999_999_6, 0.0)].map(Point::from);
        let result = reconstruct(&points, &Params::paper()).unwrap();
        let mut page = Vec::new();
        write_html(&mut page, &result, "a hair").unwrap();
        let page = String::from_utf8(page).unwrap();
        assert!(
            page.contains("\"seconds\":[1,0,2.7499999996,2.75,1]"),
            "{page}"
        );
        assert!(ratio_digits_meet(2.749_999_999_6, 2.75));
        assert!(!ratio_digits_meet(2.7496, 2.75) && !ratio_digits_meet(2.75, 2.75));
    }

    /// With no points there is no corner: the page's data must still be JSON (it had an origin of
    /// `inf`, which the viewer's `JSON.parse` refused, leaving a blank page).
    #[test]
    fn no_points_give_valid_json() {
        use condt::{reconstruct, Params};
        let result = reconstruct(&[], &Params::default()).unwrap();
        let mut page = Vec::new();
        write_html(&mut page, &result, "empty").unwrap();
        let page = String::from_utf8(page).unwrap();
        let data = &page[page.find("{\"origin\"").unwrap()..page.find("</script>").unwrap()];
        let value: serde_json::Value = serde_json::from_str(data.trim()).expect("valid JSON");
        assert_eq!(value["origin"], serde_json::json!([0.0, 0.0]), "{data}");
    }

    /// Without JavaScript the page says so, with the result's counts, and hides the panels only
    /// the script fills (it read "Click a point or an edge." over an empty canvas: a teacher's
    /// review).
    #[test]
    fn without_javascript_the_page_says_so_with_the_counts() {
        use condt::{reconstruct, Params};
        let mut points: Vec<Point> = (0..40)
            .map(|k| {
                let t = core::f64::consts::TAU * k as f64 / 40.0;
                Point::new(10.0 * t.cos(), 10.0 * t.sin())
            })
            .collect();
        points.push(Point::new(30.0, 30.0));
        let result = reconstruct(&points, &Params::default()).unwrap();
        assert_eq!(result.unused(), &[40]);
        let mut page = Vec::new();
        write_html(&mut page, &result, "circle").unwrap();
        let page = String::from_utf8(page).unwrap();
        let at = page.find("<noscript><p").expect("a noscript paragraph");
        let text = &page[at..at + page[at..].find("</noscript>").unwrap()];
        assert!(text.contains("--stages"), "{text}");
        // The counts, shown with JavaScript or without, are the drawing's text alternative.
        let summary = "<p id=\"summary\">The result: 41 points, 40 edges in 1 curve \
                       (1 closed, 0 open), 1 unused.</p>";
        assert!(page.contains(summary), "{page}");
        // A screen reader is told what the canvas shows and hears the details a click gives (a
        // teacher's review: neither was said), and the keys that work there.
        assert!(page.contains(
            "<canvas id=\"canvas\" tabindex=\"0\" role=\"application\" \
             aria-roledescription=\"drawing\" aria-label=\"The points,"
        ));
        assert!(page.contains("aria-describedby=\"summary keys\"></canvas>"));
        assert!(page.contains("<p class=\"hint\" id=\"keys\">"));
        assert!(page.contains("<p id=\"details\" aria-live=\"polite\">Click a point or an edge."));
        assert!(page.contains("<span id=\"status\" role=\"status\">"));
        let head = &page[..page.find("</head>").unwrap()];
        assert!(
            head.contains("<noscript><style>#info, #layers, .hint { display: none; }"),
            "{head}"
        );
    }

    #[test]
    fn a_title_cannot_break_out_of_its_element() {
        assert_eq!(escape("<script>&\""), "&lt;script&gt;&amp;&quot;");
    }
}
