//! SVG drawings of a reconstruction, for looking at results and at each stage.

use condt::geometry::{binary_exponent, Point, Scale};
use condt::Reconstruction;
use std::io::{self, Write};

/// Maps data coordinates to one panel of the picture (y up in the data, down in SVG).
struct Frame {
    min: Point,
    scale: f64,
    /// The panel's top left corner in the picture.
    left: f64,
    top: f64,
}

impl Frame {
    fn map(&self, p: Point) -> (f64, f64) {
        (
            self.left + (p.x - self.min.x) * self.scale,
            self.top + PANEL - (p.y - self.min.y) * self.scale,
        )
    }
}

/// A panel: its title, its edges and their colour.
type Layer<'a> = (&'a str, &'a [[usize; 2]], &'a str);

/// Side of a panel's drawing area, in SVG units.
const PANEL: f64 = 600.0;
const MARGIN: f64 = 16.0;
/// Height of the band above each panel that holds its title.
const TITLE_BAND: f64 = 44.0;
/// Height of the legend band at the bottom.
const LEGEND_BAND: f64 = 48.0;
/// Panels per row: a picture of the six stages is then 1,800 units wide, so that shown at the
/// width of a screen (about 1,200 pixels) its 26-unit titles are still 17 pixels high.
const COLUMNS: usize = 3;
const FONT: &str = r#"font-family="sans-serif" font-size="26""#;
const EDGE_COLOURS: [&str; 3] = ["#9aa5b1", "#1f6fd1", "#111111"];
const POINT_COLOUR: &str = "#333333";
const UNUSED_COLOUR: &str = "#d62728";

fn frame(points: &[Point], panel: usize) -> Frame {
    let (mut lo, mut hi) = (
        Point::new(f64::INFINITY, f64::INFINITY),
        Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for p in points {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let span = (hi.x - lo.x).max(hi.y - lo.y);
    let scale = if span > 0.0 && span.is_finite() {
        (PANEL - 2.0 * MARGIN) / span
    } else {
        1.0
    };
    let min = Point::new(lo.x - MARGIN / scale, lo.y - MARGIN / scale);
    Frame {
        min,
        scale,
        left: (panel % COLUMNS) as f64 * PANEL,
        top: (panel / COLUMNS) as f64 * (PANEL + TITLE_BAND) + TITLE_BAND,
    }
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
        write!(out, r#"<circle cx="{x:.2}" cy="{y:.2}" r="{radius}"/>"#)?;
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
    let columns = layers.len().min(COLUMNS);
    let rows = layers.len().div_ceil(COLUMNS);
    let (width, height) = (
        PANEL * columns as f64,
        (PANEL + TITLE_BAND) * rows as f64 + LEGEND_BAND,
    );
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">"#,
    )?;
    writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#)?;
    let mut degree = vec![0u32; pts.len()];
    let tri = result.triangulation();
    let representative: Vec<usize> = (0..pts.len())
        .map(|i| tri.input_of(tri.vertex(i)))
        .collect();
    for (panel, (title, edges, colour)) in layers.iter().enumerate() {
        let f = frame(pts, panel);
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
            2.5,
        )?;
        dots(
            out,
            &f,
            pts,
            (0..pts.len()).filter(unused),
            UNUSED_COLOUR,
            4.0,
        )?;
        let number = if stages {
            format!("{}. ", panel + 1)
        } else {
            String::new()
        };
        writeln!(
            out,
            r#"<text class="title" x="{}" y="{}" {FONT} font-weight="bold">{number}{title}</text>"#,
            f.left + 12.0,
            f.top - 12.0,
        )?;
    }
    // Separators between panels and above the legend.
    write!(
        out,
        r##"<path fill="none" stroke="#c8c8c8" stroke-width="2" d=""##
    )?;
    for column in 1..columns {
        let x = column as f64 * PANEL;
        write!(out, "M{x} 0V{}", height - LEGEND_BAND)?;
    }
    for row in 1..=rows {
        let y = row as f64 * (PANEL + TITLE_BAND);
        write!(out, "M0 {y}H{width}")?;
    }
    writeln!(out, r#""/>"#)?;
    let smoothing = result.smoothing().filter(|_| stages);
    legend(out, stages, smoothing, height - LEGEND_BAND / 2.0)?;
    writeln!(out, "</svg>")
}

/// One line of swatches and labels, vertically centred on `y`.
fn legend(
    out: &mut dyn Write,
    stages: bool,
    smoothing: Option<condt::Smoothing>,
    y: f64,
) -> io::Result<()> {
    let mut items: Vec<(&str, &str, bool)> = Vec::new();
    if stages {
        items.push(("Delaunay edge", EDGE_COLOURS[0], false));
        items.push(("stage edge", EDGE_COLOURS[1], false));
    }
    items.push(("result curve", EDGE_COLOURS[2], false));
    items.push(("point", POINT_COLOUR, true));
    items.push((
        if stages {
            "point without an edge there"
        } else {
            "unused point (outlier)"
        },
        UNUSED_COLOUR,
        true,
    ));
    let mut x = 16.0;
    for (label, colour, is_point) in items {
        if is_point {
            writeln!(
                out,
                r#"<circle cx="{}" cy="{y}" r="6" fill="{colour}"/>"#,
                x + 8.0
            )?;
            x += 24.0;
        } else {
            writeln!(
                out,
                r#"<path d="M{x} {y}h36" stroke="{colour}" stroke-width="4"/>"#
            )?;
            x += 46.0;
        }
        writeln!(
            out,
            r#"<text x="{x}" y="{}" font-family="sans-serif" font-size="20">{label}</text>"#,
            y + 7.0
        )?;
        // About 10 units per character at size 20, and a gap.
        x += 10.0 * label.len() as f64 + 20.0;
    }
    if let Some(s) = smoothing {
        writeln!(
            out,
            r#"<text x="{x}" y="{}" font-family="sans-serif" font-size="20">points as the stages saw them, after {} smoothing pass{}</text>"#,
            y + 7.0,
            s.passes,
            if s.passes > 1 { "es" } else { "" }
        )?;
    }
    Ok(())
}
