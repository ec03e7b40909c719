//! The command-line front end of the `condt` binary.
//!
//! Owns: argument parsing, messages and exit codes. It may not implement geometry nor check a
//! parameter's range: it calls the library and `condt::io` and reports what they say.

use condt::io::{
    read_points, write_atomically, write_edges, write_geojson, write_polylines, write_svg, IoError,
};
use condt::{reconstruct, triangulate, Error, Params, Repair, Uniformity};
use std::fmt;

const USAGE: &str = "\
condt: Delaunay triangulation and curve reconstruction of planar points

Usage:
  condt reconstruct INPUT [-o OUTPUT] [--paper] [--u X | --adaptive] [--iqr K]
                    [--no-outlier-filter] [--no-manifold-fix | --repair MODE]
                    [--outliers-first] [--[no-]local-outliers] [--[no-]close-gaps]
                    [--format F] [--stages] [--sequential]
  condt triangulate INPUT [-o OUTPUT] [--edges]

INPUT is a text file with one point `x y` per line (spaces, tabs or a comma; a third column is
ignored; `#` comments and blank lines are skipped); `-` reads standard input. Output goes to
OUTPUT (written whole or not at all) or standard output: one triangle `i j k` per line,
counter-clockwise, in input indices; with --edges one edge `i j` (i < j) per line instead.
Exact duplicate points are merged into the first of them; a note on standard error says how many.

reconstruct runs ConDT: the curves through the points. Output format by OUTPUT's extension or
--format: `edges` (.edges: one edge `i j` per line, i < j, sorted), `txt` (.txt: one curve per
line, `closed` or `open` then its indices; the default on standard output), `svg` (.svg: the
points and curves; with --stages the Delaunay triangulation and the graph after every stage that
ran, side by side), `geojson` (.geojson: one LineString per curve).

The default pipeline is the paper's (Algorithms 1-3) with the repair `needs` and gap closing;
--local-outliers adds local outlier removal (for point sets with scattered outliers; it also
removes curves under 5 points and strokes close to other curves); --paper runs the paper's
pipeline alone.

Options:
  -o, --output FILE       write to FILE instead of standard output
      --edges             (triangulate) write edges instead of triangles
      --paper             the paper's pipeline (Algorithms 1-3 as docs/condt.md reads them)
                          instead of the default; the options below still adjust it
      --u X               uniformity parameter u (default 2.75)
      --adaptive          adaptive uniformity (section 4.1 of the paper)
      --iqr K             outlier factor (default 1.7)
      --no-outlier-filter skip outlier removal
      --outliers-first    remove outliers before the non-manifold repair (see docs/condt.md)
      --[no-]local-outliers
                          (default off) after the outlier filter and the repair, remove
                          outliers locally:
                          give back edges the filter cut along regular passages; drop edges
                          far longer than their neighbours, branches of fewer than 5 points
                          and components of fewer than 5 points clearly apart from the rest
                          (a genuine 3- or 4-point curve is lost)
      --[no-]close-gaps   (default on; off with --paper) last, join loose ends that face each
                          other across a short gap or line up through a stranded point, and a
                          crossing's dropped arms
      --no-manifold-fix   keep every proximity edge (self-intersecting curves)
      --repair MODE       needs (default; paper with --paper), paper, mutual, crossing or off
      --format F          edges, txt, svg or geojson
      --stages            (svg) draw every stage
      --sequential        do not use threads (the result is the same)
  -h, --help          show this help
  -V, --version       show the version
";

/// Why a command failed, and with which exit code.
#[derive(Debug)]
pub(crate) enum CliError {
    /// The command line is wrong (exit code 2).
    Usage(String),
    /// The input or output failed (exit code 1).
    Io(IoError),
    /// The points cannot be triangulated (exit code 1).
    Input(String),
}

impl CliError {
    /// The process exit code for this error.
    pub(crate) fn exit_code(&self) -> i32 {
        match self {
            CliError::Usage(_) => 2,
            CliError::Io(_) | CliError::Input(_) => 1,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Usage(message) => write!(f, "{message}\n\nRun `condt --help` for usage."),
            CliError::Io(err) => write!(f, "{err}"),
            CliError::Input(message) => write!(f, "{message}"),
        }
    }
}

impl From<IoError> for CliError {
    fn from(err: IoError) -> Self {
        CliError::Io(err)
    }
}

/// Options of `condt triangulate`.
#[derive(Debug, Default, PartialEq)]
struct TriangulateArgs {
    input: String,
    output: Option<String>,
    edges: bool,
}

/// The arguments every command takes: `-o FILE`, the one INPUT; anything else starting with `-`
/// is an unknown option.
fn shared_argument<'a>(
    arg: &str,
    rest: &mut impl Iterator<Item = &'a String>,
    output: &mut Option<String>,
    input: &mut Option<String>,
) -> Result<(), CliError> {
    match arg {
        "-o" | "--output" => {
            let value = rest
                .next()
                .ok_or_else(|| CliError::Usage(format!("{arg} needs a file name")))?;
            *output = Some(value.clone());
        }
        flag if flag.starts_with('-') && flag != "-" => {
            return Err(CliError::Usage(format!("unknown option {flag}")));
        }
        path => {
            if input.replace(path.to_string()).is_some() {
                return Err(CliError::Usage(format!("unexpected extra argument {path}")));
            }
        }
    }
    Ok(())
}

fn parse_triangulate(args: &[String]) -> Result<TriangulateArgs, CliError> {
    let mut parsed = TriangulateArgs::default();
    let mut input = None;
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--edges" => parsed.edges = true,
            _ => shared_argument(arg, &mut rest, &mut parsed.output, &mut input)?,
        }
    }
    parsed.input =
        input.ok_or_else(|| CliError::Usage("triangulate needs an INPUT file (or -)".into()))?;
    Ok(parsed)
}

/// Runs the tool on `args` (without the program name); `Ok` holds what to print to stdout for
/// informational commands such as `--help`.
pub(crate) fn run(args: &[String]) -> Result<String, CliError> {
    let Some((command, rest)) = args.split_first() else {
        return Err(CliError::Usage("no command given".into()));
    };
    match command.as_str() {
        "-h" | "--help" | "help" => Ok(USAGE.to_string()),
        "-V" | "--version" => Ok(format!("condt {}\n", env!("CARGO_PKG_VERSION"))),
        "reconstruct" => {
            if rest.iter().any(|a| a == "-h" || a == "--help") {
                return Ok(USAGE.to_string());
            }
            reconstruct_command(&parse_reconstruct(rest)?)?;
            Ok(String::new())
        }
        "triangulate" => {
            if rest.iter().any(|a| a == "-h" || a == "--help") {
                return Ok(USAGE.to_string());
            }
            triangulate_command(&parse_triangulate(rest)?)?;
            Ok(String::new())
        }
        other => Err(CliError::Usage(format!("unknown command {other}"))),
    }
}

/// Output formats of `condt reconstruct`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Format {
    Edges,
    Polylines,
    Svg,
    GeoJson,
}

impl Format {
    fn named(name: &str) -> Option<Format> {
        match name {
            "edges" => Some(Format::Edges),
            "txt" => Some(Format::Polylines),
            "svg" => Some(Format::Svg),
            "geojson" | "json" => Some(Format::GeoJson),
            _ => None,
        }
    }
}

/// Options of `condt reconstruct`.
#[derive(Debug, PartialEq)]
struct ReconstructArgs {
    input: String,
    output: Option<String>,
    params: Params,
    format: Format,
    stages: bool,
}

/// The number after `flag`; whether its value is accepted is for the library to say.
fn number(flag: &str, value: Option<&String>) -> Result<f64, CliError> {
    let text = value.ok_or_else(|| CliError::Usage(format!("{flag} needs a number")))?;
    text.parse::<f64>()
        .map_err(|_| CliError::Usage(format!("{flag} {text}: not a number")))
}

/// A parameter the library refused, told with the option that set it.
fn refused(err: Error) -> CliError {
    let flag = match err {
        Error::InvalidParameter { name: "u", .. } => "--u",
        Error::InvalidParameter { name: "k", .. } => "--iqr",
        _ => "",
    };
    CliError::Usage(format!("{flag}: {err}"))
}

fn parse_reconstruct(args: &[String]) -> Result<ReconstructArgs, CliError> {
    // `--paper` chooses the starting point wherever it stands; the other options adjust it.
    let mut params = if args.iter().any(|a| a == "--paper") {
        Params::paper()
    } else {
        Params::default()
    };
    let (mut input, mut output, mut format, mut stages) = (None, None, None, false);
    let (mut fixed_u, mut adaptive) = (false, false);
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--u" => {
                params.uniformity = Uniformity::Fixed(number(arg, rest.next())?);
                fixed_u = true;
            }
            "--adaptive" => {
                params.uniformity = Uniformity::Adaptive;
                adaptive = true;
            }
            "--iqr" => params.outlier_factor = Some(number(arg, rest.next())?),
            "--no-outlier-filter" => params.outlier_factor = None,
            "--outliers-first" => params.outliers_first = true,
            "--local-outliers" => params.local_outliers = true,
            "--no-local-outliers" => params.local_outliers = false,
            "--close-gaps" => params.close_gaps = true,
            "--no-close-gaps" => params.close_gaps = false,
            "--no-manifold-fix" => params.repair = Repair::Off,
            "--repair" => {
                params.repair = match rest.next().map(String::as_str) {
                    Some("paper") => Repair::Paper,
                    Some("mutual") => Repair::Mutual,
                    Some("crossing") => Repair::CrossingAware,
                    Some("needs") => Repair::Needs,
                    Some("off") => Repair::Off,
                    other => {
                        return Err(CliError::Usage(format!(
                            "--repair takes paper, mutual, crossing, needs or off, not {other:?}"
                        )))
                    }
                }
            }
            "--format" => {
                let name = rest
                    .next()
                    .ok_or_else(|| CliError::Usage("--format needs a name".into()))?;
                format = Some(
                    Format::named(name)
                        .ok_or_else(|| CliError::Usage(format!("unknown format {name}")))?,
                );
            }
            "--stages" => stages = true,
            "--paper" => {}
            "--sequential" => params.parallel = false,
            _ => shared_argument(arg, &mut rest, &mut output, &mut input)?,
        }
    }
    if fixed_u && adaptive {
        return Err(CliError::Usage(
            "--u and --adaptive exclude each other".into(),
        ));
    }
    params.check().map_err(refused)?;
    let input =
        input.ok_or_else(|| CliError::Usage("reconstruct needs an INPUT file (or -)".into()))?;
    let format = match (format, output.as_deref()) {
        (Some(f), _) => f,
        (None, None | Some("-")) => Format::Polylines,
        (None, Some(path)) => {
            let extension = std::path::Path::new(path)
                .extension()
                .and_then(|e| e.to_str())
                .unwrap_or("");
            Format::named(extension).ok_or_else(|| {
                CliError::Usage(format!(
                    "cannot tell the format of {path} from its extension; use --format"
                ))
            })?
        }
    };
    Ok(ReconstructArgs {
        input,
        output,
        params,
        format,
        stages,
    })
}

fn reconstruct_command(args: &ReconstructArgs) -> Result<(), CliError> {
    let points = read_points(&args.input)?;
    let result = reconstruct(&points, &args.params)
        .map_err(|err| CliError::Input(format!("{}: {err}", args.input)))?;
    let output = args.output.as_deref().unwrap_or("-");
    write_atomically(output, |out| match args.format {
        Format::Edges => write_edges(out, &result),
        Format::Polylines => write_polylines(out, &result),
        Format::Svg => write_svg(out, &result, args.stages),
        Format::GeoJson => write_geojson(out, &result),
    })?;
    let curves = result.curves();
    let closed = curves.iter().filter(|c| c.is_closed()).count();
    eprintln!(
        "condt: {} points, {} curves ({closed} closed, {} open), {} unused",
        points.len(),
        curves.len(),
        curves.len() - closed,
        result.unused().len()
    );
    Ok(())
}

fn triangulate_command(args: &TriangulateArgs) -> Result<(), CliError> {
    let points = read_points(&args.input)?;
    let tri =
        triangulate(&points).map_err(|err| CliError::Input(format!("{}: {err}", args.input)))?;
    let merged = points.len() - tri.num_vertices();
    if merged > 0 {
        eprintln!("condt: {merged} exact duplicate point(s) merged into the first point at the same position");
    }
    let output = args.output.as_deref().unwrap_or("-");
    write_atomically(output, |out| {
        if args.edges {
            let mut edges: Vec<_> = tri.edges().map(|[a, b]| (a, b)).collect();
            edges.sort_unstable();
            for (a, b) in edges {
                writeln!(out, "{a} {b}")?;
            }
        } else {
            for [a, b, c] in tri.triangles() {
                writeln!(out, "{a} {b} {c}")?;
            }
        }
        Ok(())
    })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strings(args: &[&str]) -> Vec<String> {
        args.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn options_are_parsed_in_any_order() {
        let a = parse_triangulate(&strings(&["--edges", "in.txt", "-o", "out.txt"])).unwrap();
        assert_eq!(
            a,
            TriangulateArgs {
                input: "in.txt".into(),
                output: Some("out.txt".into()),
                edges: true
            }
        );
    }

    #[test]
    fn reconstruct_options_and_format_by_extension() {
        let a = parse_reconstruct(&strings(&[
            "in.txt",
            "-o",
            "out.svg",
            "--stages",
            "--adaptive",
            "--iqr",
            "2",
            "--close-gaps",
        ]))
        .unwrap();
        assert_eq!(a.format, Format::Svg);
        assert!(a.stages);
        assert_eq!(a.params.uniformity, Uniformity::Adaptive);
        assert_eq!(a.params.outlier_factor, Some(2.0));
        assert!(a.params.close_gaps);
        let b = parse_reconstruct(&strings(&[
            "in.txt",
            "--no-manifold-fix",
            "--no-outlier-filter",
        ]))
        .unwrap();
        assert_eq!(
            (b.format, b.params.repair, b.params.outlier_factor),
            (Format::Polylines, Repair::Off, None)
        );
        assert!(
            !b.params.local_outliers && b.params.close_gaps,
            "the defaults"
        );
        let c = parse_reconstruct(&strings(&["--local-outliers", "in.txt", "--no-close-gaps"]))
            .unwrap();
        assert!(c.params.local_outliers && !c.params.close_gaps);
        let paper = parse_reconstruct(&strings(&["in.txt", "--paper"])).unwrap();
        assert_eq!(paper.params, condt::Params::paper());
        let paper_plus =
            parse_reconstruct(&strings(&["--close-gaps", "--paper", "in.txt"])).unwrap();
        assert!(paper_plus.params.close_gaps && !paper_plus.params.local_outliers);
        let d = parse_reconstruct(&strings(&["in.txt", "--repair", "needs"])).unwrap();
        assert_eq!(d.params.repair, Repair::Needs);
        for bad in [
            &["in.txt", "--u", "2", "--adaptive"][..],
            &["in.txt", "-o", "out.png"],
            &["in.txt", "--u", "nan"],
            &["in.txt", "--u", "-1"],
            &["in.txt", "--iqr", "inf"],
            &["in.txt", "--repair", "x"],
        ] {
            assert_eq!(
                parse_reconstruct(&strings(bad)).unwrap_err().exit_code(),
                2,
                "{bad:?}"
            );
        }
    }

    #[test]
    fn usage_errors_exit_with_two() {
        for bad in [
            &["in.txt", "-o"][..],
            &["--frobnicate", "in.txt"],
            &[],
            &["a", "b"],
        ] {
            let err = parse_triangulate(&strings(bad)).unwrap_err();
            assert_eq!(err.exit_code(), 2, "{bad:?}");
        }
    }
}
