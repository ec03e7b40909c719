//! GeoJSON output, written by hand (no serializer dependency).

use condt::Point;
use condt::Reconstruction;
use std::io::{self, Write};

/// A `FeatureCollection` with one `LineString` per curve and a boolean `closed` property; a
/// closed curve repeats its first position at the end, as GeoJSON rings do. The coordinates are
/// those of `input`, the reconstruction's input, exactly as given.
///
/// # Errors
/// `InvalidInput` when `input` has not as many points as the reconstruction's input; the
/// errors of `out`.
///
/// ```
/// use condt::{reconstruct, Params};
/// use condt::Point;
/// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from);
/// let r = reconstruct(&points, &Params::paper())?;
/// let mut out = Vec::new();
/// condt_io::write_geojson(&mut out, &r, &points)?;
/// let text = String::from_utf8(out)?;
/// assert!(text.contains(r#""coordinates":[[0,0],[1,0],[0.5,2],[0,0]]"#));
/// assert!(text.contains(r#""closed":true"#));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_geojson(
    out: &mut dyn Write,
    result: &Reconstruction,
    input: &[Point],
) -> io::Result<()> {
    super::check_input(result, input)?;
    write!(out, r#"{{"type":"FeatureCollection","features":["#)?;
    for (k, curve) in result.curves().iter().enumerate() {
        if k > 0 {
            write!(out, ",")?;
        }
        write!(
            out,
            r#"{{"type":"Feature","properties":{{"closed":{}}},"#,
            curve.is_closed()
        )?;
        write!(out, r#""geometry":{{"type":"LineString","coordinates":["#)?;
        let closing = curve.points().next().filter(|_| curve.is_closed());
        for (k, i) in curve.points().chain(closing).enumerate() {
            let p = input[i];
            write!(out, "{}[{},{}]", if k > 0 { "," } else { "" }, p.x, p.y)?;
        }
        write!(out, "]}}}}")?;
    }
    writeln!(out, "]}}")
}
