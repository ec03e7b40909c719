//! The command line as every Unix tool reads it: values joined to their option (`--u=2.5`,
//! `-oFILE`), `--` ending the options, file names that are not UTF-8, `--quiet`; and the
//! progress bar, which changes no output whether standard error is a terminal or not.

use std::ffi::{OsStr, OsString};
use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// The binary under test: this build's, or `CONDT_TEST_BIN` (to show a test fails on another).
fn binary() -> OsString {
    std::env::var_os("CONDT_TEST_BIN").unwrap_or_else(|| env!("CARGO_BIN_EXE_condt").into())
}

fn condt<S: AsRef<OsStr>>(args: &[S]) -> Output {
    Command::new(binary())
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .output()
        .expect("the binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// 40 points on a circle and two outliers, in `dir/name`.
fn points(dir: &Path, name: &str) -> std::path::PathBuf {
    let mut text: String = (0..40)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 40.0;
            format!("{} {}\n", t.cos(), t.sin())
        })
        .collect();
    text.push_str("3 3\n0 0\n");
    let path = dir.join(name);
    fs::write(&path, text).unwrap();
    path
}

fn ok(out: &Output) {
    assert!(out.status.success(), "{}", stderr(out));
}

/// The notes `reconstruct` writes of the point file `input` with `extra` options, on a
/// successful run.
fn notes_of(input: &Path, extra: &[&str]) -> String {
    let mut args = vec![OsStr::new("reconstruct"), input.as_os_str()];
    args.extend(extra.iter().map(OsStr::new));
    args.extend([OsStr::new("-o"), OsStr::new("/dev/null")]);
    let out = condt(&args);
    ok(&out);
    stderr(&out)
}

/// [`notes_of`] `text`, written in `dir` as `name`.
fn reconstruct_notes(dir: &Path, name: &str, text: &str, extra: &[&str]) -> String {
    let input = dir.join(name);
    fs::write(&input, text).unwrap();
    notes_of(&input, extra)
}

/// Numbers in [0, 1) from a linear congruential generator started at `state`: the same on
/// every machine.
fn uniform_numbers(mut state: u64) -> impl FnMut() -> f64 {
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn a_value_is_joined_to_its_option_or_follows_it() {
    let dir = tempfile::tempdir().unwrap();
    let input = points(dir.path(), "in.txt");
    let input = input.to_str().unwrap();
    let apart = condt(&["reconstruct", input, "--u", "2.5", "--iqr", "2"]);
    ok(&apart);
    for joined in [
        &["reconstruct", input, "--u=2.5", "--iqr=2"][..],
        &["reconstruct", "--u=2.5", input, "--iqr", "2"],
    ] {
        let out = condt(joined);
        ok(&out);
        assert_eq!(out.stdout, apart.stdout, "{joined:?}");
    }
    // The same value told apart from another: joined or not, it is the value that was given.
    let said = stderr(&condt(&["reconstruct", input, "--u=2.5", "--adaptive"]));
    assert!(said.contains("--u 2.5 and --adaptive contradict"), "{said}");
    // A value that starts with a dash is still the value.
    let out = condt(&["reconstruct", input, "--u=-1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--u"), "{}", stderr(&out));
    // An option that takes no value refuses one.
    let out = condt(&["triangulate", input, "--edges=yes"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--edges"), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("condt help triangulate"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn the_output_file_is_joined_to_o_or_follows_it() {
    let dir = tempfile::tempdir().unwrap();
    let input = points(dir.path(), "in.txt");
    let input = input.to_str().unwrap();
    for command in ["reconstruct", "triangulate"] {
        // /dev/null has no extension to tell reconstruct's format by.
        let out = condt(
            &[command, input, "-o/dev/null", "--format=edges"]
                [..3 + usize::from(command == "reconstruct")],
        );
        ok(&out);
        assert!(out.stdout.is_empty(), "{command}: written to /dev/null");
        let apart = dir.path().join(format!("{command}-apart.edges"));
        let joined = dir.path().join(format!("{command}-joined.edges"));
        let long = dir.path().join(format!("{command}-long.edges"));
        ok(&condt(&[
            command.as_ref(),
            input.as_ref(),
            OsStr::new("-o"),
            apart.as_os_str(),
        ]));
        let mut o_joined = OsString::from("-o");
        o_joined.push(&joined);
        ok(&condt(&[
            command.as_ref(),
            input.as_ref(),
            o_joined.as_os_str(),
        ]));
        let mut long_joined = OsString::from("--output=");
        long_joined.push(&long);
        ok(&condt(&[
            command.as_ref(),
            long_joined.as_os_str(),
            input.as_ref(),
        ]));
        let expected = fs::read(&apart).unwrap();
        assert!(!expected.is_empty());
        assert_eq!(fs::read(&joined).unwrap(), expected, "{command}");
        assert_eq!(fs::read(&long).unwrap(), expected, "{command}");
    }
}

#[test]
fn a_double_dash_ends_the_options() {
    let dir = tempfile::tempdir().unwrap();
    let dashed = points(dir.path(), "-points.txt");
    let out = Command::new(binary())
        .current_dir(dir.path())
        .args(["triangulate", "--edges", "--", "-points.txt"])
        .output()
        .unwrap();
    ok(&out);
    let plain = condt(&[
        OsStr::new("triangulate"),
        dashed.as_os_str(),
        OsStr::new("--edges"),
    ]);
    assert_eq!(out.stdout, plain.stdout);
    // Without it, the name is an option.
    let out = Command::new(binary())
        .current_dir(dir.path())
        .args(["triangulate", "-points.txt"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("unknown option -p"),
        "{}",
        stderr(&out)
    );
    // Before the command it ends no option and leaves the command as it is (it read as "no
    // command given": a tester's review).
    let before = condt(&[
        OsStr::new("--"),
        OsStr::new("triangulate"),
        dashed.as_os_str(),
        OsStr::new("--edges"),
    ]);
    ok(&before);
    assert_eq!(before.stdout, plain.stdout);
    // After it, a word is no option: `--help` is an unknown command.
    let out = condt(&[OsStr::new("--"), OsStr::new("--help")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("unknown command --help"),
        "{}",
        stderr(&out)
    );
}

/// A value written as an option is answered with the option that takes it (a newcomer's
/// review: `--crust` was answered with `--crs`, `--svg` with nothing), where the command has it.
#[test]
fn a_value_written_as_an_option_names_its_option() {
    for (typed, meant) in [
        ("--crust", "--method crust"),
        ("--nn-crust", "--method nn-crust"),
        ("--svg", "--format svg"),
        ("--GeoJSON", "--format geojson"),
    ] {
        let out = condt(&["reconstruct", typed]);
        assert_eq!(out.status.code(), Some(2), "{typed}");
        let said = stderr(&out);
        assert!(said.contains(&format!("(did you mean {meant}?)")), "{said}");
    }
    // `triangulate` has no --format: no such answer there.
    let said = stderr(&condt(&["triangulate", "--svg"]));
    assert!(
        said.contains("unknown option --svg") && !said.contains("--format"),
        "{said}"
    );
}

/// `help --help` and `help -h` ask for the help as `help help` does (they read as unknown
/// commands: a tester's review).
#[test]
fn help_asked_of_help_is_the_global_help() {
    let global = condt(&["--help"]);
    ok(&global);
    for flag in ["--help", "-h", "help"] {
        let out = condt(&["help", flag]);
        ok(&out);
        assert_eq!(out.stdout, global.stdout, "help {flag}");
    }
}

#[cfg(unix)]
#[test]
fn file_names_need_not_be_utf8() {
    use std::os::unix::ffi::OsStrExt;
    let dir = tempfile::tempdir().unwrap();
    let source = points(dir.path(), "in.txt");
    let input = dir.path().join(OsStr::from_bytes(b"caf\xe9.txt"));
    fs::rename(&source, &input).unwrap();
    let output = dir.path().join(OsStr::from_bytes(b"r\xe9sultat.edges"));
    let mut joined = OsString::from("-o");
    joined.push(&output);
    let out = condt(&[OsStr::new("reconstruct"), input.as_os_str(), &joined]);
    ok(&out);
    assert!(fs::read(&output).unwrap().ends_with(b"\n"));
}

#[test]
fn quiet_keeps_the_output_and_drops_the_notes() {
    let dir = tempfile::tempdir().unwrap();
    let input = points(dir.path(), "in.txt");
    let input = input.to_str().unwrap();
    for command in ["reconstruct", "triangulate"] {
        let loud = condt(&[command, input]);
        ok(&loud);
        if command == "reconstruct" {
            assert!(stderr(&loud).contains("42 points"), "{}", stderr(&loud));
        }
        for quiet in ["--quiet", "-q"] {
            let out = condt(&[command, quiet, input]);
            ok(&out);
            assert_eq!(out.stdout, loud.stdout, "{command} {quiet}");
            assert!(out.stderr.is_empty(), "{command} {quiet}: {}", stderr(&out));
        }
        // --timings was asked for: its lines stay.
        let out = condt(&[command, input, "--quiet", "--timings"]);
        ok(&out);
        let said = stderr(&out);
        assert!(
            said.lines().all(|l| l.starts_with("condt: time ")),
            "{said}"
        );
        assert!(said.contains("condt: time total "), "{said}");
    }
    // Notes about the input are notes too; errors are not.
    let out = Command::new(binary())
        .args(["triangulate", "-", "-q"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .and_then(|mut child| {
            use std::io::Write;
            child.stdin.take().unwrap().write_all(b"0 0\n0 0\n1 1\n")?;
            child.wait_with_output()
        })
        .unwrap();
    ok(&out);
    assert!(out.stderr.is_empty(), "{}", stderr(&out));
    let out = condt(&["reconstruct", "-q", "/nonexistent/points.txt"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("/nonexistent/points.txt"));
}

/// Runs `args` with standard error (and input and output) on a terminal, by `script`; `None`
/// where there is no `script`.
fn on_a_terminal(dir: &Path, args: &[&str]) -> Option<Output> {
    let mut line = String::from("exec ");
    for arg in std::iter::once(binary().to_str().unwrap()).chain(args.iter().copied()) {
        line.push('\'');
        line.push_str(&arg.replace('\'', "'\\''"));
        line.push_str("' ");
    }
    Command::new("script")
        .current_dir(dir)
        .args(["-qec", &line, "/dev/null"])
        .stdin(Stdio::null())
        .output()
        .ok()
}

/// A NumPy array is not written to a terminal (a newcomer's review: its bytes filled the
/// screen); to a file, or through a pipe, it is.
#[test]
fn a_binary_output_is_refused_on_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let input = points(dir.path(), "in.txt");
    let input = input.to_str().unwrap();
    // (`triangulate` writes an array only to a file named `.npy`.)
    let args = ["reconstruct", input, "--format", "npy"];
    let Some(out) = on_a_terminal(dir.path(), &args) else {
        eprintln!("no `script` here: the terminal is not tested");
        return;
    };
    let screen = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(2), "{screen}");
    assert!(screen.contains("standard output is a terminal"), "{screen}");
    assert!(!screen.contains("NUMPY"), "{screen}");
    let piped = condt(&args);
    ok(&piped);
    assert!(piped.stdout.starts_with(b"\x93NUMPY"));
}

#[test]
fn the_progress_bar_changes_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let input = points(dir.path(), "in.txt");
    let input = input.to_str().unwrap();
    for (command, extension) in [
        ("reconstruct", "edges"),
        ("reconstruct", "svg"),
        ("reconstruct", "npy"),
        ("triangulate", "txt"),
    ] {
        let plain = dir.path().join(format!("{command}-plain.{extension}"));
        ok(&condt(&[command, input, "-o", plain.to_str().unwrap()]));
        let shown = dir.path().join(format!("{command}-shown.{extension}"));
        let Some(out) = on_a_terminal(dir.path(), &[command, input, "-o", shown.to_str().unwrap()])
        else {
            eprintln!("no `script` here: the terminal is not tested");
            return;
        };
        ok(&out);
        assert_eq!(
            fs::read(&shown).unwrap(),
            fs::read(&plain).unwrap(),
            "{command} .{extension}"
        );
    }
    // The bar is cleared before the notes, which are still written.
    let Some(out) = on_a_terminal(
        dir.path(),
        &["reconstruct", input, "-o", "/dev/null", "--format", "txt"],
    ) else {
        return;
    };
    let screen = String::from_utf8_lossy(&out.stdout);
    assert!(screen.contains("condt: 42 points"), "{screen}");
    let Some(out) = on_a_terminal(
        dir.path(),
        &["reconstruct", input, "-q", "-o/dev/null", "--format=txt"],
    ) else {
        return;
    };
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
}

/// Two 30-by-30 squares written ring by ring, the second's shared side 1e-9 off the first's
/// (a reprojection's rounding), in `dir/squares.txt`.
fn squares_exported_ring_by_ring(dir: &Path) -> std::path::PathBuf {
    let mut text = String::new();
    for (x0, wobble) in [(0.0, 0.0), (30.0, 1e-9)] {
        let corners = [
            (0.0, 0.0),
            (30.0, 0.0),
            (30.0, 30.0),
            (0.0, 30.0),
            (0.0, 0.0),
        ];
        for pair in corners.windows(2) {
            let ((ax, ay), (bx, by)) = (pair[0], pair[1]);
            for i in 0..30 {
                let t = i as f64 / 30.0;
                let (x, mut y) = (x0 + ax + t * (bx - ax), ay + t * (by - ay));
                if x == 30.0 {
                    y += wobble;
                }
                text.push_str(&format!("{x:?} {y:?}\n"));
            }
        }
    }
    let path = dir.join("squares.txt");
    fs::write(&path, text).unwrap();
    path
}

/// A curve given twice, the second copy a millionth off (a shared border exported from both
/// sides after a reprojection): every point pairs with its twin, and the summary alone read as
/// success (a GIS user's review: 462 two-point curves, "0 unused"). A note names the pattern and
/// `--snap`; none for the curve given once, or once snapped.
#[test]
fn twins_a_little_apart_are_noted() {
    let dir = tempfile::tempdir().unwrap();
    let ring = |shift: f64| -> String {
        (0..60)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / 60.0;
                format!(
                    "{} {}\n",
                    10.0 * t.cos() + 0.3 * (5.0 * t).sin() + shift,
                    10.0 * t.sin()
                )
            })
            .collect()
    };
    let once = dir.path().join("once.txt");
    let twice = dir.path().join("twice.txt");
    fs::write(&once, ring(0.0)).unwrap();
    fs::write(&twice, ring(0.0) + &ring(1e-6)).unwrap();
    let said = notes_of;
    let noted = "pairs of points that lie 16 times nearer each other than any other point";
    let notes = said(&twice, &[]);
    assert!(
        notes.contains(noted) && notes.contains("--snap D"),
        "{notes}"
    );
    assert!(!said(&once, &[]).contains(noted));
    assert!(!said(&twice, &["--snap", "1e-5"]).contains(noted));
    assert!(said(&twice, &["-q"]).is_empty());
    // At any scale: the rule once squared lengths in the input's units, where twins 1e-170
    // apart squared to 0 and pairs 1e160 apart to infinity (a diff review).
    let scaled = |text: &str, factor: f64| -> String {
        text.lines()
            .map(|line| {
                let [x, y] = [0, 1].map(|k| {
                    line.split_whitespace()
                        .nth(k)
                        .unwrap()
                        .parse::<f64>()
                        .unwrap()
                        * factor
                });
                format!("{x:e} {y:e}\n")
            })
            .collect()
    };
    let tiny = dir.path().join("tiny.txt");
    fs::write(&tiny, scaled(&(ring(0.0) + &ring(1e-6)), 1e-170)).unwrap();
    assert!(said(&tiny, &[]).contains(noted));
    // Pairs a tenth of a unit apart, a unit from the next pair: 10 times nearer, no twins.
    let pairs: String = (0..15)
        .flat_map(|i| (0..15).map(move |j| (i, j)))
        .map(|(i, j)| format!("{i} {j}\n{} {j}\n", i as f64 + 0.1))
        .collect();
    for factor in [1.0, 1e160] {
        let path = dir.path().join("pairs.txt");
        fs::write(&path, scaled(&pairs, factor)).unwrap();
        assert!(!said(&path, &[]).contains(noted), "{factor}");
    }
}

/// Two squares whose shared side is given twice, a billionth apart (each square's ring exported
/// on its own): the stages leave the side's twins unused rather than as curves of two points, and
/// the note once came only for such curves (a GIS user's review: "58 unused", no hint). Every
/// pair counts, whatever the stages made of it.
#[test]
fn twins_left_unused_are_noted_too() {
    let dir = tempfile::tempdir().unwrap();
    // The ring of the 30 x 30 square at `left`, a sample every unit, counter-clockwise.
    let square = |left: f64| -> Vec<(f64, f64)> {
        let sides = [
            (0.0, 0.0, 1.0, 0.0),
            (30.0, 0.0, 0.0, 1.0),
            (30.0, 30.0, -1.0, 0.0),
        ];
        let mut ring: Vec<(f64, f64)> = sides
            .iter()
            .chain([(0.0, 30.0, 0.0, -1.0)].iter())
            .flat_map(|&(x, y, dx, dy)| {
                (0..30).map(move |k| (x + dx * k as f64, y + dy * k as f64))
            })
            .map(|(x, y)| (left + x, y))
            .collect();
        ring.dedup();
        ring
    };
    let mut text = String::new();
    for (x, y) in square(0.0) {
        text += &format!("{x} {y}\n");
    }
    for (x, y) in square(30.0) {
        // The second square's copy of the shared side (x = 30) lies a billionth off.
        let x = if x == 30.0 { x + 1e-9 } else { x };
        text += &format!("{x} {y}\n");
    }
    let notes = reconstruct_notes(dir.path(), "squares.txt", &text, &[]);
    // The shared side's 29 points between its corners, each with its twin, both unused (the
    // corners' pairs lie on the outline, a curve through both points, and are not counted).
    assert!(
        notes.contains("29 pairs of points that lie 16 times nearer each other")
            && notes.contains("--snap D")
            && notes.contains("58 unused"),
        "{notes}"
    );
}

/// A curve given twice within a large set: its pairs are fewer than one in 33 points, which
/// chance makes along randomly sampled curves, but each lies beside the next, which chance
/// makes once in hundreds of points (a GIS user's review: 2,000 pairs among 104,000 points, all
/// unused, no note).
#[test]
fn a_curve_given_twice_within_a_large_set_is_noted() {
    let dir = tempfile::tempdir().unwrap();
    let circle = |cx: f64, cy: f64, r: f64, n: usize, shift: f64| -> String {
        (0..n)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / n as f64;
                format!("{} {}\n", cx + r * t.cos() + shift, cy + r * t.sin())
            })
            .collect()
    };
    // 20 circles of 500 points (10,000), and one of 200 points given twice, a millionth off.
    let mut text: String = (0..20)
        .map(|k| circle(30.0 * k as f64, 0.0, 10.0, 500, 0.0))
        .collect();
    text += &circle(0.0, 40.0, 10.0, 200, 0.0);
    text += &circle(0.0, 40.0, 10.0, 200, 1e-6);
    let notes = reconstruct_notes(dir.path(), "large.txt", &text, &[]);
    // 200 pairs, one in 52 points.
    assert!(
        notes.contains("200 pairs of points that lie 16 times nearer each other")
            && notes.contains("10400 points"),
        "{notes}"
    );
}

/// Points drawn at random along a curve make close pairs by chance, about one in 33 points, and
/// now and then two side by side; without the smoothing passes, which move most of them, a rule
/// that counted those noted them as a curve given twice (a diff review: 37 pairs in 2,000
/// samples of a sine). No note for them.
#[test]
fn twins_that_chance_makes_along_a_curve_are_not_noted() {
    let dir = tempfile::tempdir().unwrap();
    let mut unit = uniform_numbers(0x2545_F491_4F6C_DD1D);
    for (n, extra) in [
        (2_000, "--paper"),
        (2_000, "--no-smooth"),
        (20_000, "--no-smooth"),
    ] {
        let text: String = (0..n)
            .map(|_| {
                let x = unit() * n as f64;
                format!("{x} {}\n", 20.0 * (x / 40.0).sin())
            })
            .collect();
        let notes = reconstruct_notes(dir.path(), "sine.txt", &text, &[extra]);
        assert!(notes.contains(&format!("{n} points")), "{notes}");
        assert!(!notes.contains("16 times nearer"), "{n} {extra}: {notes}");
    }
}

/// Uniform random points make close pairs by chance, 16 times nearer each other than any other
/// point (509 in 1M): that is no curve given twice, and gets no note.
#[test]
fn twins_that_chance_makes_are_not_noted() {
    let dir = tempfile::tempdir().unwrap();
    let mut unit = uniform_numbers(0x9E37_79B9_7F4A_7C15);
    let text: String = (0..50_000)
        .map(|_| format!("{} {}\n", unit(), unit()))
        .collect();
    let scatter = dir.path().join("scatter.txt");
    fs::write(&scatter, text).unwrap();
    let out = condt(&[
        OsStr::new("reconstruct"),
        scatter.as_os_str(),
        OsStr::new("-o"),
        OsStr::new("/dev/null"),
    ]);
    ok(&out);
    let notes = stderr(&out);
    assert!(notes.contains("50000 points"), "{notes}");
    assert!(!notes.contains("16 times nearer"), "{notes}");
}

#[test]
fn snap_joins_a_shared_border_exported_twice() {
    let dir = tempfile::tempdir().unwrap();
    let input = squares_exported_ring_by_ring(dir.path());
    let plain = condt(&[
        OsStr::new("reconstruct"),
        input.as_os_str(),
        OsStr::new("-o"),
        OsStr::new("/dev/null"),
    ]);
    ok(&plain);
    assert!(!stderr(&plain).contains(" 0 unused"), "{}", stderr(&plain));
    let output = dir.path().join("out.txt");
    let snapped = condt(&[
        OsStr::new("reconstruct"),
        input.as_os_str(),
        OsStr::new("--snap=1e-6"),
        OsStr::new("-o"),
        output.as_os_str(),
    ]);
    ok(&snapped);
    let notes = stderr(&snapped);
    assert!(notes.contains("--snap 1e-6: moved 31 points"), "{notes}");
    assert!(
        notes.contains("240 points, 3 curves (0 closed, 3 open), 0 unused"),
        "{notes}"
    );
    // The shared side, x = 30 from y = 0 to 30, is one curve through the first ring's samples
    // (positions 30 to 59 and 60, the corner that starts the top side).
    let curves = fs::read_to_string(&output).unwrap();
    let border: Vec<usize> = (30..=60).collect();
    let on_border = |line: &&str| {
        let ids: Vec<usize> = line
            .split(' ')
            .skip(1)
            .map(|t| t.parse().unwrap())
            .collect();
        ids == border || ids.iter().rev().copied().eq(border.iter().copied())
    };
    assert!(curves.lines().any(|l| on_border(&l)), "{curves}");
    let triangulated = condt(&[
        OsStr::new("triangulate"),
        input.as_os_str(),
        OsStr::new("--snap"),
        OsStr::new("1e-6"),
        OsStr::new("-o"),
        OsStr::new("/dev/null"),
    ]);
    ok(&triangulated);
    assert!(
        stderr(&triangulated).contains("(209 distinct of 240)"),
        "{}",
        stderr(&triangulated)
    );
}

#[test]
fn snap_refuses_a_distance_that_is_no_length() {
    let dir = tempfile::tempdir().unwrap();
    let input = points(dir.path(), "in.txt");
    let output = dir.path().join("out.edges");
    for bad in ["-1", "nan", "inf", "x"] {
        let out = condt(&[
            OsStr::new("reconstruct"),
            input.as_os_str(),
            OsStr::new("--snap"),
            OsStr::new(bad),
            OsStr::new("-o"),
            output.as_os_str(),
        ]);
        assert_eq!(out.status.code(), Some(2), "{bad}: {}", stderr(&out));
        assert!(
            stderr(&out).contains(&format!("--snap {bad}")),
            "{}",
            stderr(&out)
        );
        assert!(!output.exists());
    }
}

/// Each command's help says that point numbers count from 0, where users of R, MATLAB and
/// Julia, which count from 1, look for it (an R and MATLAB user's review: only `condt --help`
/// said so, and in R `pts$x[e$V1]` drops the zeros without a word, 98 of 100 edges' ends).
#[test]
fn every_help_says_point_numbers_count_from_0() {
    for (command, said) in [
        ("reconstruct", "Point numbers count from 0"),
        ("triangulate", "in point numbers, which count from 0"),
        ("score", "in point numbers of POINTS counted from 0"),
    ] {
        let out = condt(&["help", command]);
        ok(&out);
        let text = String::from_utf8(out.stdout).unwrap().replace('\n', " ");
        assert!(text.contains(said), "{command}");
        assert!(
            text.contains("R, MATLAB") || text.contains("R and MATLAB"),
            "{command}"
        );
    }
}

/// Every help fits a terminal of 96 columns: the option tables' help lines at most 70 columns
/// beside the 26 of their names, the paragraphs at most 96 (a student's review found lines of
/// 104 to 267 columns, which a terminal wraps mid-word).
#[test]
fn the_helps_fit_96_columns() {
    let mut helps = vec![condt(&["--help"])];
    for command in ["reconstruct", "triangulate", "score"] {
        helps.push(condt(&["help", command]));
    }
    for out in helps {
        ok(&out);
        let text = String::from_utf8(out.stdout).unwrap();
        for line in text.lines() {
            let columns = line.chars().count();
            assert!(columns <= 96, "{columns} columns: {line}");
        }
    }
}
