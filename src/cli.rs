//! The command-line front end of the `condt` binary (needs `std`).
//!
//! Owns: argument parsing, messages and exit codes. It may not implement geometry: it calls the
//! library and [`crate::io`] and reports what they say.

use crate::io::{read_points, write_atomically, IoError};
use crate::triangulate;
use std::fmt;

const USAGE: &str = "\
condt: Delaunay triangulation and curve reconstruction of planar points

Usage:
  condt triangulate INPUT [-o OUTPUT] [--edges]

INPUT is a text file with one point `x y` per line (spaces, tabs or a comma; a third column is
ignored; `#` comments and blank lines are skipped); `-` reads standard input. Output goes to
OUTPUT (written whole or not at all) or standard output: one triangle `i j k` per line,
counter-clockwise, in input indices; with --edges one edge `i j` (i < j) per line instead.
Exact duplicate points are merged into the first of them; a note on standard error says how many.

Options:
  -o, --output FILE   write to FILE instead of standard output
      --edges         write edges instead of triangles
  -h, --help          show this help
  -V, --version       show the version
";

/// Why a command failed, and with which exit code.
#[derive(Debug)]
pub enum CliError {
    /// The command line is wrong (exit code 2).
    Usage(String),
    /// The input or output failed (exit code 1).
    Io(IoError),
    /// The points cannot be triangulated (exit code 1).
    Input(String),
}

impl CliError {
    /// The process exit code for this error.
    pub fn exit_code(&self) -> i32 {
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

fn parse_triangulate(args: &[String]) -> Result<TriangulateArgs, CliError> {
    let mut parsed = TriangulateArgs::default();
    let mut input = None;
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "-o" | "--output" => {
                let value = rest
                    .next()
                    .ok_or_else(|| CliError::Usage(format!("{arg} needs a file name")))?;
                parsed.output = Some(value.clone());
            }
            "--edges" => parsed.edges = true,
            flag if flag.starts_with('-') && flag != "-" => {
                return Err(CliError::Usage(format!("unknown option {flag}")));
            }
            path => {
                if input.replace(path.to_string()).is_some() {
                    return Err(CliError::Usage(format!("unexpected extra argument {path}")));
                }
            }
        }
    }
    parsed.input =
        input.ok_or_else(|| CliError::Usage("triangulate needs an INPUT file (or -)".into()))?;
    Ok(parsed)
}

/// Runs the tool on `args` (without the program name); `Ok` holds what to print to stdout for
/// informational commands such as `--help`.
///
/// ```
/// let help = condt::cli::run(&["--help".to_string()]).unwrap();
/// assert!(help.contains("condt triangulate"));
/// ```
pub fn run(args: &[String]) -> Result<String, CliError> {
    let Some((command, rest)) = args.split_first() else {
        return Err(CliError::Usage("no command given".into()));
    };
    match command.as_str() {
        "-h" | "--help" | "help" => Ok(USAGE.to_string()),
        "-V" | "--version" => Ok(format!("condt {}\n", env!("CARGO_PKG_VERSION"))),
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
            let mut edges: Vec<_> = tri.edges().map(|[a, b]| (a.index(), b.index())).collect();
            edges.sort_unstable();
            for (a, b) in edges {
                writeln!(out, "{a} {b}")?;
            }
        } else {
            for [a, b, c] in tri.triangles() {
                writeln!(out, "{} {} {}", a.index(), b.index(), c.index())?;
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
