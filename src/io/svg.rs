//! SVG drawings of a reconstruction, for looking at results and at each stage.

use crate::geometry::{binary_exponent, Point, Scale};
use crate::reconstruct::Reconstruction;
use std::io::{self, Write};

/// Maps data coordinates to one panel of the picture (y up in the data, down in SVG).
struct Frame {
    min: Point,
    scale: f64,
    height: f64,
    offset_x: f64,
}

impl Frame {
    fn map(&self, p: Point) -> (f64, f64) {
        (
            self.offset_x + (p.x - self.min.x) * self.scale,
            self.height - (p.y - self.min.y) * self.scale,
        )
    }
}

/// A panel: its title, its edges and their colour.
type Layer<'a> = (&'a str, &'a [[usize; 2]], &'a str);

const PANEL: f64 = 800.0;
const MARGIN: f64 = 20.0;

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
        height: PANEL,
        offset_x: panel as f64 * PANEL,
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
) -> io::Result<()> {
    write!(out, r#"<g fill="{color}">"#)?;
    for i in which {
        let (x, y) = f.map(pts[i]);
        write!(out, r#"<circle cx="{x:.2}" cy="{y:.2}" r="2"/>"#)?;
    }
    writeln!(out, "</g>")
}

/// Draws the points and the reconstructed curves; unused points (outliers) in red. With
/// `stages`, one panel per step side by side: the Delaunay triangulation, then the graph after
/// every stage in the order the stages ran (the last one in black).
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let r = reconstruct(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from), &Params::paper())?;
/// let mut out = Vec::new();
/// condt::io::write_svg(&mut out, &r, true)?;
/// let svg = String::from_utf8(out)?;
/// assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
/// assert_eq!(svg.matches("<text").count(), 1 + r.stages().count());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_svg(out: &mut dyn Write, result: &Reconstruction, stages: bool) -> io::Result<()> {
    // The frame is computed on the points times the power of two that brings the largest
    // magnitude into [1, 2): spans and offsets of coordinates near 1e308 then neither overflow
    // to infinity nor turn into NaN, and for every other set the picture is the same number for
    // number, since every step scales exactly.
    let largest = (0..result.num_points())
        .map(|i| result.point(i))
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let unit = if largest > 0.0 && largest.is_finite() {
        Scale::power_of_two(-binary_exponent(largest))
    } else {
        Scale::IDENTITY
    };
    let pts: Vec<Point> = (0..result.num_points())
        .map(|i| unit.apply(result.point(i)))
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
        (Vec::new(), vec![("", result.edges().collect())])
    };
    let last = graphs.len() - 1;
    let mut layers: Vec<Layer> = Vec::new();
    if stages {
        layers.push(("Delaunay triangulation", &delaunay, "#9aa5b1"));
    }
    for (k, (title, edges)) in graphs.iter().enumerate() {
        let color = match k {
            0 if stages => "#1f6fd1",
            k if k == last => "#111111",
            _ => "#1a8f3c",
        };
        layers.push((title, edges, color));
    }
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#,
        w = PANEL * layers.len() as f64,
        h = PANEL
    )?;
    writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#)?;
    let used = |i: &usize| result.degree(*i) > 0;
    for (panel, (title, edges, color)) in layers.into_iter().enumerate() {
        let f = frame(pts, panel);
        lines(out, &f, pts, edges, color, 1.5)?;
        dots(out, &f, pts, (0..pts.len()).filter(used), "#333333")?;
        dots(out, &f, pts, (0..pts.len()).filter(|i| !used(i)), "#d62728")?;
        if !title.is_empty() {
            writeln!(
                out,
                r#"<text x="{}" y="16" font-family="sans-serif" font-size="14">{title}</text>"#,
                f.offset_x + 8.0
            )?;
        }
    }
    writeln!(out, "</svg>")
}
