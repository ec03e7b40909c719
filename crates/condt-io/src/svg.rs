//! SVG drawings of a reconstruction, for looking at results and at each stage.
//!
//! A panel takes the shape of the points' bounding box, its sides' ratio kept between 1:4 and
//! 4:1 (a river's long thin set fills a wide panel instead of a tenth of a square one; past
//! those ratios the panel stays 4:1 and the data a band in it), and holds as much as a 600 by 600
//! square does; stage panels go three to a row, or fewer when wide.

use condt::geometry::{binary_exponent, Point, Scale};
use condt::Reconstruction;
use std::io::{self, Write};

/// Maps data coordinates to one panel of the picture (y up in the data, down in SVG), the
/// centre of the points' bounding box at the panel's centre.
struct Frame {
    centre: Point,
    scale: f64,
    /// The panel's top left corner in the picture.
    left: f64,
    top: f64,
    /// The panel's size.
    width: f64,
    height: f64,
}

impl Frame {
    fn map(&self, p: Point) -> (f64, f64) {
        (
            self.left + self.width / 2.0 + (p.x - self.centre.x) * self.scale,
            self.top + self.height / 2.0 - (p.y - self.centre.y) * self.scale,
        )
    }
}

/// A panel: its title, its edges and their colour.
type Layer<'a> = (&'a str, &'a [[usize; 2]], &'a str);

/// Side of a square panel, in SVG units; a panel of another shape has the same area.
const PANEL: f64 = 600.0;
/// The widest panel's sides' ratio (and the tallest's, inverted).
const MAX_RATIO: f64 = 4.0;
const MARGIN: f64 = 16.0;
/// Height of the band above each panel that holds its title.
const TITLE_BAND: f64 = 44.0;
/// Height of a line of the legend at the bottom.
const LEGEND_BAND: f64 = 48.0;
/// Most panels per row: a picture of square stage panels is then 1,800 units wide, so that
/// shown at the width of a screen (about 1,200 pixels) its 26-unit titles are still 17 pixels
/// high. Wider panels go fewer to a row, so that a row is at most a quarter wider.
const COLUMNS: usize = 3;
const ROW_WIDTH: f64 = 1.25 * PANEL * COLUMNS as f64;
/// Size of the titles, and the smallest they are made to fit a narrow panel.
const TITLE_SIZE: f64 = 26.0;
const SMALLEST_TITLE: f64 = 14.0;
const EDGE_COLOURS: [&str; 3] = ["#9aa5b1", "#1f6fd1", "#111111"];
const POINT_COLOUR: &str = "#333333";
/// A stage panel's edges the stage removed and added, drawn as wide translucent halos under
/// the panel's own edges (no stage's line colour: detours are green, hooks pink).
const REMOVED_COLOUR: &str = "#d62728";
const ADDED_COLOUR: &str = "#2ca02c";
/// Their width and opacity.
const CHANGE_WIDTH: f64 = 6.0;
const CHANGE_OPACITY: f64 = 0.35;
const UNUSED_COLOUR: &str = "#d62728";

/// The edges of `a` not in `b`, both sorted (a stage graph's edges are).
fn difference(a: &[[usize; 2]], b: &[[usize; 2]]) -> Vec<[usize; 2]> {
    a.iter()
        .filter(|e| b.binary_search(e).is_err())
        .copied()
        .collect()
}

/// The frame of the first panel for `points` (scaled so that their largest magnitude is below
/// 2: their spans are finite): a panel of the bounding box's shape, its sides' ratio clamped to
/// between 1:[`MAX_RATIO`] and [`MAX_RATIO`]:1, of the area of a [`PANEL`]-sided square (whole
/// units), the box scaled to fill it within [`MARGIN`]. One point, or none, gets a square.
fn frame(points: &[Point]) -> Frame {
    let (mut lo, mut hi) = (
        Point::new(f64::INFINITY, f64::INFINITY),
        Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for p in points {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let (dx, dy) = (hi.x - lo.x, hi.y - lo.y);
    let finite = dx.is_finite() && dy.is_finite();
    let ratio = match (finite, dx > 0.0, dy > 0.0) {
        (true, true, true) => (dx / dy).clamp(1.0 / MAX_RATIO, MAX_RATIO),
        (true, true, false) => MAX_RATIO,
        (true, false, true) => 1.0 / MAX_RATIO,
        _ => 1.0,
    };
    let root = libm::sqrt(ratio);
    let (width, height) = ((PANEL * root).round(), (PANEL / root).round());
    // The scale that fits each span, the smaller of them; a zero span sets none.
    let fit = |span: f64, side: f64| {
        if span > 0.0 && finite {
            (side - 2.0 * MARGIN) / span
        } else {
            f64::INFINITY
        }
    };
    let scale = fit(dx, width).min(fit(dy, height));
    let (scale, centre) = if scale.is_finite() {
        (scale, Point::new(lo.x + dx / 2.0, lo.y + dy / 2.0))
    } else {
        (1.0, points.first().copied().unwrap_or(Point::new(0.0, 0.0)))
    };
    Frame {
        centre,
        scale,
        left: 0.0,
        top: TITLE_BAND,
        width,
        height,
    }
}

/// How many panels of `width` go in a row: as many as [`ROW_WIDTH`] holds, one to
/// [`COLUMNS`].
fn columns_for(width: f64) -> usize {
    let fit = (ROW_WIDTH / width).floor();
    if fit >= COLUMNS as f64 {
        COLUMNS
    } else if fit >= 1.0 {
        fit as usize
    } else {
        1
    }
}

/// A title as one line, or where it is longer than `fit` characters two, cut at the space
/// nearest its middle (a title without a space stays one line).
fn title_lines(title: &str, fit: f64) -> Vec<String> {
    let chars: Vec<char> = title.chars().collect();
    if chars.len() as f64 <= fit {
        return vec![title.to_string()];
    }
    let middle = chars.len() / 2;
    let cut = (0..chars.len())
        .filter(|&k| chars[k] == ' ')
        .min_by_key(|&k| k.abs_diff(middle));
    match cut {
        Some(k) => vec![chars[..k].iter().collect(), chars[k + 1..].iter().collect()],
        None => vec![title.to_string()],
    }
}

/// The largest title size at which two lines fit the band above a panel.
const TWO_LINE_TITLE: f64 = 15.0;

/// The size of a title of `chars` characters in a panel of `width`: [`TITLE_SIZE`], or smaller
/// (not below [`SMALLEST_TITLE`]) where a bold character about 0.6 of the size wide would run
/// past the panel; the drawing uses the smallest of its titles' for all.
fn title_size(chars: usize, width: f64) -> f64 {
    let fits = ((width - 24.0) / (0.6 * chars.max(1) as f64)).floor();
    fits.clamp(SMALLEST_TITLE, TITLE_SIZE)
}

fn lines(
    out: &mut dyn Write,
    f: &Frame,
    pts: &[Point],
    edges: &[[usize; 2]],
    color: &str,
    width: f64,
) -> io::Result<()> {
    write!(
        out,
        r#"<path fill="none" stroke="{color}" stroke-width="{width}" d=""#
    )?;
    for [a, b] in edges {
        let ((x1, y1), (x2, y2)) = (f.map(pts[*a]), f.map(pts[*b]));
        write!(out, "M{x1:.2} {y1:.2}L{x2:.2} {y2:.2}")?;
    }
    writeln!(out, r#""/>"#)
}

/// The radii of the points and of the unused points: 2.5 and 4 units, or smaller where the
/// points stand closer (a third of the median length on the page of `edges`, the first panel's:
/// the Delaunay edges, or the result's), so that dense points do not cover the edges between
/// them; not below 0.6 and 1.
fn dot_radii(f: &Frame, pts: &[Point], edges: &[[usize; 2]]) -> (f64, f64) {
    let mut lengths: Vec<f64> = edges
        .iter()
        .map(|&[a, b]| {
            let ((ax, ay), (bx, by)) = (f.map(pts[a]), f.map(pts[b]));
            (ax - bx).hypot(ay - by)
        })
        .collect();
    if lengths.is_empty() {
        return (2.5, 4.0);
    }
    let middle = lengths.len() / 2;
    let (_, &mut median, _) = lengths.select_nth_unstable_by(middle, f64::total_cmp);
    let point = (median / 3.0).clamp(0.6, 2.5);
    (point, (1.6 * point).max(1.0))
}

fn dots(
    out: &mut dyn Write,
    f: &Frame,
    pts: &[Point],
    which: impl Iterator<Item = usize>,
    color: &str,
    radius: f64,
) -> io::Result<()> {
    write!(out, r#"<g fill="{color}">"#)?;
    for i in which {
        let (x, y) = f.map(pts[i]);
        write!(out, r#"<circle cx="{x:.2}" cy="{y:.2}" r="{radius:.2}"/>"#)?;
    }
    writeln!(out, "</g>")
}

/// Draws the points of `input`, the reconstruction's input, and the reconstructed curves, with
/// a legend; points without an edge in the result (outliers) in red.
///
/// # Errors
/// `InvalidInput` when `input` has not as many points as the reconstruction's input (the
/// result keeps no copy of them: [`Reconstruction::stage_point`]); the errors of `out`.
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from);
/// let r = reconstruct(&points, &Params::paper())?;
/// let mut out = Vec::new();
/// condt_io::write_svg(&mut out, &r, &points)?;
/// let svg = String::from_utf8(out)?;
/// assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
/// // One panel: the result alone.
/// assert_eq!(svg.matches("class=\"title\"").count(), 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_svg(out: &mut dyn Write, result: &Reconstruction, input: &[Point]) -> io::Result<()> {
    super::check_input(result, input)?;
    draw(out, result, Some(input))
}

/// Draws every step, one panel each, three to a row: the Delaunay triangulation, then the graph
/// after every stage in the order the stages ran (the result in black), each titled; in each
/// stage's panel the points that graph leaves without an edge are red, so a point turns red in
/// the panel of the stage that removed its last edge. The points are where the stages saw them
/// ([`Reconstruction::stage_point`]: moved, when smoothing passes ran), since the rings and
/// lengths the stages tested are theirs.
///
/// # Errors
/// The errors of `out`.
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let r = reconstruct(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from), &Params::paper())?;
/// let mut out = Vec::new();
/// condt_io::write_svg_stages(&mut out, &r)?;
/// let svg = String::from_utf8(out)?;
/// assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
/// // A title per panel: the triangulation and each stage.
/// assert_eq!(svg.matches("class=\"title\"").count(), 1 + r.stages().count());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_svg_stages(out: &mut dyn Write, result: &Reconstruction) -> io::Result<()> {
    draw(out, result, None)
}

/// [`write_svg`] on `input`, or [`write_svg_stages`] without it.
fn draw(out: &mut dyn Write, result: &Reconstruction, input: Option<&[Point]>) -> io::Result<()> {
    let stages = input.is_none();
    // The frame is computed on the points times the power of two that brings the largest
    // magnitude into [1, 2): spans and offsets of coordinates near 1e308 then neither overflow
    // to infinity nor turn into NaN, and for every other set the picture is the same number for
    // number, since every step scales exactly.
    // The stage panels show the points where the stages saw them (moved by the smoothing
    // passes, if any ran: their rings and lengths are those); the result alone is drawn on the
    // input points.
    let position = |i: usize| match input {
        Some(points) => points[i],
        None => result.stage_point(i),
    };
    let largest = (0..result.num_points())
        .map(position)
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let unit = if largest > 0.0 && largest.is_finite() {
        Scale::power_of_two(-binary_exponent(largest))
    } else {
        Scale::IDENTITY
    };
    let pts: Vec<Point> = (0..result.num_points())
        .map(|i| unit.apply(position(i)))
        .collect();
    let pts = &pts[..];
    // Only what is drawn: the final edges alone, or the triangulation and every stage.
    type Titled<'a> = (&'a str, Vec<[usize; 2]>);
    let (delaunay, graphs): (Vec<[usize; 2]>, Vec<Titled>) = if stages {
        let graphs = result
            .stages()
            .map(|report| (report.stage.title(), report.graph.edges()))
            .collect();
        (result.triangulation().edges().collect(), graphs)
    } else {
        (Vec::new(), vec![("the result", result.edges().collect())])
    };
    let last = graphs.len() - 1;
    let mut layers: Vec<Layer> = Vec::new();
    if stages {
        layers.push(("Delaunay triangulation", &delaunay, EDGE_COLOURS[0]));
    }
    for (k, (title, edges)) in graphs.iter().enumerate() {
        let colour = if k == last {
            EDGE_COLOURS[2]
        } else {
            EDGE_COLOURS[1]
        };
        layers.push((title, edges, colour));
    }
    let first = frame(pts);
    let (panel_width, panel_height) = (first.width, first.height);
    let per_row = columns_for(panel_width);
    let columns = layers.len().min(per_row);
    let rows = layers.len().div_ceil(per_row);
    let panels_height = (panel_height + TITLE_BAND) * rows as f64;
    let smoothing = result.smoothing().filter(|_| stages);
    // The legend in lines as wide as the panels; an item wider than them makes the picture
    // as wide as it.
    let (legend, legend_width, legend_lines) = legend(
        stages,
        smoothing,
        panels_height,
        panel_width * columns as f64,
    );
    let width = (panel_width * columns as f64).max(legend_width.ceil());
    let height = panels_height + LEGEND_BAND * legend_lines as f64;
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">"#,
    )?;
    writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#)?;
    let mut degree = vec![0u32; pts.len()];
    let tri = result.triangulation();
    let representative: Vec<usize> = (0..pts.len()).map(|i| tri.first_at(i)).collect();
    // One title size for every panel (the largest at which every title fits, not below
    // SMALLEST_TITLE); a title too long for its panel even then goes on two lines, not into
    // the next panel.
    let number = |panel: usize| {
        if stages {
            format!("{}. ", panel + 1)
        } else {
            String::new()
        }
    };
    // What each stage changed, against the panel before (from the second stage on: the
    // proximity graph is a choice among the Delaunay edges, not a change of them): the edges it
    // removed and those it added, drawn as halos under the panel's own edges.
    let changes: Vec<[Vec<[usize; 2]>; 2]> = (0..layers.len())
        .map(|panel| {
            if stages && panel >= 2 {
                let (before, after) = (layers[panel - 1].1, layers[panel].1);
                [difference(before, after), difference(after, before)]
            } else {
                [Vec::new(), Vec::new()]
            }
        })
        .collect();
    let titles: Vec<String> = layers
        .iter()
        .enumerate()
        .map(|(panel, (title, _, _))| {
            let [removed, added] = &changes[panel];
            let unchanged = if panel >= 2 && stages && removed.is_empty() && added.is_empty() {
                " (no change)"
            } else {
                ""
            };
            format!("{}{title}{unchanged}", number(panel))
        })
        .collect();
    let room = panel_width - 24.0;
    let wrapped: Vec<Vec<String>> = titles
        .iter()
        .map(|t| title_lines(t, room / (0.6 * SMALLEST_TITLE)))
        .collect();
    let two_lines = wrapped.iter().any(|lines| lines.len() > 1);
    let size = wrapped
        .iter()
        .flatten()
        .map(|line| title_size(line.chars().count(), panel_width))
        .fold(TITLE_SIZE, f64::min)
        // Two lines share the band above the panel.
        .min(if two_lines {
            TWO_LINE_TITLE
        } else {
            TITLE_SIZE
        });
    let (point_radius, unused_radius) = dot_radii(&first, pts, layers[0].1);
    for (panel, (_, edges, colour)) in layers.iter().enumerate() {
        let f = Frame {
            left: (panel % per_row) as f64 * panel_width,
            top: (panel / per_row) as f64 * (panel_height + TITLE_BAND) + TITLE_BAND,
            ..first
        };
        let [removed, added] = &changes[panel];
        for (changed, halo) in [(removed, REMOVED_COLOUR), (added, ADDED_COLOUR)] {
            if !changed.is_empty() {
                write!(out, r#"<g stroke-opacity="{CHANGE_OPACITY}">"#)?;
                lines(out, &f, pts, changed, halo, CHANGE_WIDTH)?;
                writeln!(out, "</g>")?;
            }
        }
        lines(
            out,
            &f,
            pts,
            edges,
            colour,
            if *colour == EDGE_COLOURS[2] { 2.0 } else { 1.2 },
        )?;
        // Red where this panel's graph leaves a point without an edge; the triangulation leaves
        // none.
        let is_delaunay = stages && panel == 0;
        degree.iter_mut().for_each(|d| *d = 0);
        for &[a, b] in edges.iter() {
            degree[a] += 1;
            degree[b] += 1;
        }
        // A merged duplicate shares its point's edges.
        let unused = |i: &usize| !is_delaunay && degree[representative[*i]] == 0;
        dots(
            out,
            &f,
            pts,
            (0..pts.len()).filter(|i| !unused(i)),
            POINT_COLOUR,
            point_radius,
        )?;
        dots(
            out,
            &f,
            pts,
            (0..pts.len()).filter(unused),
            UNUSED_COLOUR,
            unused_radius,
        )?;
        let lines = &wrapped[panel];
        let (x, last) = (f.left + 12.0, f.top - 12.0);
        let first = last - 1.15 * size * (lines.len() - 1) as f64;
        write!(
            out,
            r#"<text class="title" x="{x}" y="{first:.1}" font-family="sans-serif" font-size="{size}" font-weight="bold">"#
        )?;
        for (k, line) in lines.iter().enumerate() {
            if k == 0 {
                write!(out, "{line}")?;
            } else {
                write!(
                    out,
                    r#"<tspan x="{x}" dy="{:.1}">{line}</tspan>"#,
                    1.15 * size
                )?;
            }
        }
        writeln!(out, "</text>")?;
    }
    // Separators between panels and above the legend.
    write!(
        out,
        r##"<path fill="none" stroke="#c8c8c8" stroke-width="2" d=""##
    )?;
    for column in 1..columns {
        let x = column as f64 * panel_width;
        write!(out, "M{x} 0V{panels_height}")?;
    }
    for row in 1..=rows {
        let y = row as f64 * (panel_height + TITLE_BAND);
        write!(out, "M0 {y}H{width}")?;
    }
    writeln!(out, r#""/>"#)?;
    out.write_all(legend.as_bytes())?;
    writeln!(out, "</svg>")
}

/// The legend's swatches and labels, laid out in lines of [`LEGEND_BAND`] from `top`, each no
/// wider than `width` (an item wider than that alone on its line): the SVG, how far right it
/// reaches, and how many lines it takes.
fn legend(
    stages: bool,
    smoothing: Option<condt::Smoothing>,
    top: f64,
    width: f64,
) -> (String, f64, usize) {
    use std::fmt::Write as _;
    /// A swatch (a dot, a line, or none) and its label.
    enum Swatch {
        Dot,
        Line,
        Halo,
        None,
    }
    let mut items: Vec<(Swatch, &str, String)> = Vec::new();
    if stages {
        items.push((Swatch::Line, EDGE_COLOURS[0], "Delaunay edge".into()));
        items.push((Swatch::Line, EDGE_COLOURS[1], "stage edge".into()));
        items.push((Swatch::Halo, ADDED_COLOUR, "added by the stage".into()));
        items.push((Swatch::Halo, REMOVED_COLOUR, "removed by the stage".into()));
    }
    items.push((Swatch::Line, EDGE_COLOURS[2], "result curve".into()));
    items.push((Swatch::Dot, POINT_COLOUR, "point".into()));
    let unused = if stages {
        "point without an edge there"
    } else {
        "unused point (outlier)"
    };
    items.push((Swatch::Dot, UNUSED_COLOUR, unused.into()));
    if let Some(s) = smoothing {
        let note = format!(
            "points as the stages saw them, after {} smoothing pass{}",
            s.passes,
            if s.passes > 1 { "es" } else { "" }
        );
        items.push((Swatch::None, "", note));
    }
    let mut out = String::new();
    let (mut x, mut line, mut reach) = (16.0, 0, 0.0f64);
    for (swatch, colour, label) in items {
        let swatch_width = match swatch {
            Swatch::Dot => 24.0,
            Swatch::Line | Swatch::Halo => 46.0,
            Swatch::None => 0.0,
        };
        // About 10 units per character at size 20, and a gap.
        let label_width = 10.0 * label.len() as f64 + 20.0;
        if x > 16.0 && x + swatch_width + label_width > width {
            (x, line) = (16.0, line + 1);
        }
        let y = top + LEGEND_BAND * (line as f64 + 0.5);
        match swatch {
            Swatch::Dot => {
                let _ = writeln!(
                    out,
                    r#"<circle cx="{}" cy="{y}" r="6" fill="{colour}"/>"#,
                    x + 8.0
                );
            }
            Swatch::Line => {
                let _ = writeln!(
                    out,
                    r#"<path d="M{x} {y}h36" stroke="{colour}" stroke-width="4"/>"#
                );
            }
            Swatch::Halo => {
                let _ = writeln!(
                    out,
                    r#"<path d="M{x} {y}h36" stroke="{colour}" stroke-width="{CHANGE_WIDTH}" stroke-opacity="{CHANGE_OPACITY}"/>"#
                );
            }
            Swatch::None => {}
        }
        x += swatch_width;
        let _ = writeln!(
            out,
            r#"<text x="{x}" y="{}" font-family="sans-serif" font-size="20">{label}</text>"#,
            y + 7.0
        );
        x += label_width;
        reach = reach.max(x);
    }
    (out, reach, line + 1)
}
