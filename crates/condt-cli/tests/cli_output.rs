//! Where `condt -o` writes: regular files, symbolic and hard links, named pipes, character
//! devices, the input itself, file names that are not UTF-8, and what is left behind after an
//! error or a signal. Everything happens in a fresh temporary directory; a device is made there
//! with `mknod` when the tests run as root (and skipped with a note otherwise), never taken from
//! the system's own `/dev`.
//!
//! `CONDT_TEST_BIN=/path/to/condt` runs these tests against another build of the binary, which
//! is how they were shown to fail on the tool before these rules.
#![cfg(unix)]

use std::ffi::OsStr;
use std::fs;
use std::io::{Read, Write};
use std::os::unix::ffi::OsStrExt;
use std::os::unix::fs::{FileTypeExt, MetadataExt, PermissionsExt};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Four points, two triangles: `0 1 2` and `0 2 3` in some rotation.
const SQUARE: &str = "0 0\n1 0\n1 1\n0 1\n";

fn binary() -> PathBuf {
    std::env::var_os("CONDT_TEST_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_condt")))
}

fn spawn<S: AsRef<OsStr>>(args: &[S], stdout: Stdio) -> Child {
    Command::new(binary())
        .args(args)
        .stdin(Stdio::piped())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs")
}

fn condt<S: AsRef<OsStr>>(args: &[S], stdin: &str) -> Output {
    let mut child = spawn(args, Stdio::piped());
    let written = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    if let Err(e) = written {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
    }
    child.wait_with_output().unwrap()
}

/// Writes `input` to a spawned run's standard input and closes it.
fn feed(child: &mut Child, input: &[u8]) {
    child.stdin.take().unwrap().write_all(input).unwrap();
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The triangles of SQUARE as the tool writes them, from a run to standard output.
fn square_triangles() -> String {
    let out = condt(&["triangulate", "-"], SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 2, "{text}");
    text
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn is_root() -> bool {
    fs::metadata("/proc/self")
        .map(|m| m.uid() == 0)
        .unwrap_or(false)
}

/// A character device `major:minor` (both under 256) named `name` in `dir`, or `None` (with a
/// note) when this process may not make one.
fn device(dir: &Path, name: &str, major: u32, minor: u32) -> Option<PathBuf> {
    if !is_root() {
        eprintln!("note: not root, the character-device case is skipped");
        return None;
    }
    let path = dir.join(name);
    let made = Command::new("mknod")
        .arg(&path)
        .args(["c", &major.to_string(), &minor.to_string()])
        .status();
    match made {
        Ok(status) if status.success() => Some(path),
        _ => {
            eprintln!("note: mknod failed (a container without the capability?), skipped");
            None
        }
    }
}

fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success());
}

/// The temporary file in `dir` (condt names it `.condt.XXXXXX.tmp`) other than `except`,
/// waited for up to `patience`: a run blocked on its standard input is past preparing its
/// output once it exists.
fn find_temporary(dir: &Path, except: &Path, patience: Duration) -> Option<PathBuf> {
    let start = Instant::now();
    loop {
        let found = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .find(|p| {
                let name = p.file_name().unwrap().as_bytes();
                p != except && name.starts_with(b".condt.") && name.ends_with(b".tmp")
            });
        if found.is_some() || start.elapsed() > patience {
            return found;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Waits (up to a minute) until the run `pid` has prepared its output and sleeps reading its
/// input: it catches SIGTERM (it starts to while preparing the output, before reading) and its
/// main thread is asleep (in the read).
fn wait_until_reading(pid: u32) {
    let start = Instant::now();
    loop {
        let status = fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
        let field = |name: &str| {
            status
                .lines()
                .find_map(|l| l.strip_prefix(name))
                .map(|v| v.trim().to_string())
                .unwrap_or_default()
        };
        let caught = u64::from_str_radix(&field("SigCgt:"), 16).unwrap_or(0);
        let sleeping = field("State:").starts_with('S');
        if caught & (1 << (libc::SIGTERM - 1)) != 0 && sleeping {
            // Past the last steps of preparing, should the state have been read between them.
            std::thread::sleep(Duration::from_millis(50));
            return;
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the run never came to read its input"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// `condt triangulate - -o OUT` with `stdin` as the input.
fn triangulate_to(out: &Path, stdin: &str) -> Output {
    condt(
        &[
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ],
        stdin,
    )
}

fn is_symlink(path: &Path) -> bool {
    fs::symlink_metadata(path).unwrap().file_type().is_symlink()
}

#[test]
fn a_regular_file_is_replaced_whole_and_keeps_its_permissions() {
    let dir = tempfile::tempdir().unwrap();
    let expected = square_triangles();
    // 0600 from the issue; 0750 has an execute bit no new file gets, whatever the umask.
    for mode in [0o600, 0o750] {
        let target = dir.path().join("out.txt");
        fs::write(&target, "previous content\n").unwrap();
        fs::set_permissions(&target, fs::Permissions::from_mode(mode)).unwrap();
        let out = triangulate_to(&target, SQUARE);
        assert!(out.status.success(), "{}", stderr(&out));
        assert_eq!(fs::read_to_string(&target).unwrap(), expected);
        let meta = fs::symlink_metadata(&target).unwrap();
        assert!(meta.is_file());
        assert_eq!(meta.permissions().mode() & 0o7777, mode, "mode {mode:o}");
        assert_eq!(names(dir.path()), ["out.txt"], "no temporary file is left");
    }
}

#[test]
fn another_users_file_keeps_its_owner() {
    if !is_root() {
        eprintln!("note: not root, cannot give a file to another user: skipped");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("theirs.txt");
    fs::write(&target, "previous content\n").unwrap();
    std::os::unix::fs::chown(&target, Some(65534), Some(65534)).unwrap();
    let out = triangulate_to(&target, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    let meta = fs::metadata(&target).unwrap();
    assert_eq!((meta.uid(), meta.gid()), (65534, 65534));
    assert_eq!(fs::read_to_string(&target).unwrap(), square_triangles());
    assert_eq!(names(dir.path()), ["theirs.txt"]);
}

#[test]
fn a_symbolic_link_stays_and_the_file_it_points_to_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let expected = square_triangles();
    let real = dir.path().join("real.txt");
    fs::write(&real, "previous content\n").unwrap();
    fs::set_permissions(&real, fs::Permissions::from_mode(0o640)).unwrap();
    let link = dir.path().join("link.txt");
    std::os::unix::fs::symlink("real.txt", &link).unwrap();
    let out = triangulate_to(&link, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(is_symlink(&link));
    assert_eq!(fs::read_link(&link).unwrap(), Path::new("real.txt"));
    assert_eq!(fs::read_to_string(&real).unwrap(), expected);
    assert_eq!(
        fs::metadata(&real).unwrap().permissions().mode() & 0o7777,
        0o640
    );

    // A dangling link gets the file it names.
    let dangling = dir.path().join("dangling.txt");
    std::os::unix::fs::symlink("made.txt", &dangling).unwrap();
    let out = triangulate_to(&dangling, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(is_symlink(&dangling));
    assert_eq!(fs::read_link(&dangling).unwrap(), Path::new("made.txt"));
    assert_eq!(
        fs::read_to_string(dir.path().join("made.txt")).unwrap(),
        expected
    );
    assert_eq!(
        names(dir.path()),
        ["dangling.txt", "link.txt", "made.txt", "real.txt"]
    );
}

#[test]
fn a_hard_link_is_not_broken() {
    let dir = tempfile::tempdir().unwrap();
    let expected = square_triangles();
    let first = dir.path().join("first.txt");
    let second = dir.path().join("second.txt");
    fs::write(&first, "previous content, longer than the triangles are\n").unwrap();
    fs::hard_link(&first, &second).unwrap();
    let out = triangulate_to(&first, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        fs::read_to_string(&second).unwrap(),
        expected,
        "both names see it"
    );
    assert_eq!(fs::metadata(&first).unwrap().nlink(), 2);
    assert_eq!(names(dir.path()), ["first.txt", "second.txt"]);
}

#[test]
fn a_named_pipe_is_written_to_not_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let expected = square_triangles();
    let fifo = dir.path().join("pipe");
    mkfifo(&fifo);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || {
            let mut text = String::new();
            fs::File::open(fifo)
                .unwrap()
                .read_to_string(&mut text)
                .unwrap();
            text
        })
    };
    let out = triangulate_to(&fifo, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    // Checked before waiting for the reader: had the pipe been replaced, it would wait forever.
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    assert_eq!(reader.join().unwrap(), expected);
    assert_eq!(names(dir.path()), ["pipe"]);
}

#[test]
fn a_character_device_is_written_to_not_replaced() {
    let dir = tempfile::tempdir().unwrap();
    // 1:3 is the null device, 1:7 the full one: made here, not the system's.
    let (Some(null), Some(full)) = (
        device(dir.path(), "null", 1, 3),
        device(dir.path(), "full", 1, 7),
    ) else {
        return;
    };
    let out = triangulate_to(&null, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    let out = triangulate_to(&full, SQUARE);
    assert_eq!(out.status.code(), Some(1), "a full device is an error");
    assert!(stderr(&out).contains("full: "), "{}", stderr(&out));
    for (device, minor) in [(&null, 3), (&full, 7)] {
        let meta = fs::symlink_metadata(device).unwrap();
        assert!(
            meta.file_type().is_char_device(),
            "{} is still a device",
            device.display()
        );
        // Linux numbers a small device major:minor as major * 256 + minor.
        #[cfg(target_os = "linux")]
        assert_eq!(
            meta.rdev(),
            256 + minor,
            "{} is still the same device",
            device.display()
        );
        let _ = minor;
    }
    assert_eq!(names(dir.path()), ["full", "null"]);
}

#[test]
fn failing_standard_streams_are_errors_or_ignored_never_panics() {
    let dir = tempfile::tempdir().unwrap();
    let Some(full) = device(dir.path(), "full", 1, 7) else {
        return;
    };
    let open = || fs::OpenOptions::new().write(true).open(&full).unwrap();
    // Standard output full: the help cannot be shown, which is an error (1), not a panic (101).
    let out = Command::new(binary())
        .arg("--help")
        .stdout(open())
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("<stdout>"), "{}", stderr(&out));
    // Standard error full: the notes are lost, the work is done. The input has a duplicate, so
    // there is a note to write.
    let target = dir.path().join("out.txt");
    let mut child = Command::new(binary())
        .args([
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            target.as_os_str(),
        ])
        .stdin(Stdio::piped())
        .stderr(open())
        .spawn()
        .unwrap();
    feed(&mut child, format!("{SQUARE}0 0\n").as_bytes());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0));
    assert_eq!(fs::read_to_string(&target).unwrap(), square_triangles());
}

#[cfg(target_os = "linux")]
#[test]
fn a_link_to_an_open_stream_writes_to_the_stream() {
    // What /dev/stdout is, made in the temporary directory: a link through /proc.
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("stdout");
    std::os::unix::fs::symlink("/proc/self/fd/1", &link).unwrap();
    let out = triangulate_to(&link, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(String::from_utf8(out.stdout).unwrap(), square_triangles());
    assert!(is_symlink(&link));
    assert_eq!(names(dir.path()), ["stdout"]);
}

#[test]
fn the_temporary_file_is_random_exclusive_and_cannot_be_hijacked() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.txt");
    fs::write(&target, "previous content\n").unwrap();
    fs::set_permissions(&target, fs::Permissions::from_mode(0o600)).unwrap();
    let victim = dir.path().join("victim.txt");
    fs::write(&victim, "precious\n").unwrap();
    let mut child = spawn(
        &[
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            target.as_os_str(),
        ],
        Stdio::piped(),
    );
    // The name the tool once used, planted while it waits for its input.
    let planted = dir.path().join(format!(".out.txt.{}.partial", child.id()));
    std::os::unix::fs::symlink(&victim, &planted).unwrap();
    // The tool checks its output before it reads its input, but makes its temporary file only
    // once the result is ready: none while it reads (see
    // `a_run_killed_before_its_result_is_ready_leaves_nothing_beside_the_output`).
    wait_until_reading(child.id());
    assert_eq!(
        find_temporary(dir.path(), &planted, Duration::ZERO),
        None,
        "no temporary file while the run reads its input"
    );
    feed(&mut child, SQUARE.as_bytes());
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        fs::read_to_string(&victim).unwrap(),
        "precious\n",
        "the victim is untouched"
    );
    let meta = fs::symlink_metadata(&target).unwrap();
    assert!(
        meta.is_file(),
        "the output is a file, not a link to the victim"
    );
    assert_eq!(fs::read_to_string(&target).unwrap(), square_triangles());
    assert_eq!(
        fs::metadata(&target).unwrap().permissions().mode() & 0o777,
        0o600,
        "the original's mode"
    );
    let mut left = names(dir.path());
    left.retain(|n| n.starts_with(".condt."));
    assert!(left.is_empty(), "{left:?}");
}

/// A run that has prepared its output and waits for its input, then gets `signal`. The run starts
/// with the signal's default disposition, whatever the test inherited: started as a background
/// job of a script, the test process has SIGINT ignored, which the run would keep (see
/// `ignored_signal_is_left_ignored`) and wait for its input forever.
fn interrupted(signal: &str, number: i32) {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.txt");
    fs::write(&target, "previous content\n").unwrap();
    let mut command = Command::new(binary());
    command
        .args([
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            target.as_os_str(),
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    with_default_action(&mut command, number);
    let mut child = command.spawn().expect("the binary runs");
    // Half an input: the run is still reading.
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(b"0 0\n1 0\n").unwrap();
    stdin.flush().unwrap();
    wait_until_reading(child.id());
    let status = Command::new("kill")
        .args([format!("-{signal}"), child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    drop(stdin);
    assert_eq!(
        out.status.signal(),
        Some(number),
        "ended by SIG{signal}: {:?}",
        out.status
    );
    assert_eq!(names(dir.path()), ["out.txt"]);
    assert_eq!(fs::read_to_string(&target).unwrap(), "previous content\n");
}

/// A run that dies before its result is ready (here by SIGKILL, which cannot be caught, as
/// running out of memory aborts a run) leaves nothing beside its output: the temporary file is
/// made only when the result is written (a reviewer's report: under `ulimit -v`, an abort in
/// the computation left an empty `.condt.XXXXXX.tmp`, made before the input was read).
#[test]
fn a_run_killed_before_its_result_is_ready_leaves_nothing_beside_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.txt");
    fs::write(&target, "previous content\n").unwrap();
    let new_target = dir.path().join("new.txt");
    for (out, old) in [(&target, Some("previous content\n")), (&new_target, None)] {
        let mut child = spawn(
            &[
                "triangulate".as_ref(),
                "-".as_ref(),
                "-o".as_ref(),
                out.as_os_str(),
            ],
            Stdio::piped(),
        );
        let mut stdin = child.stdin.take().unwrap();
        stdin.write_all(b"0 0\n1 0\n").unwrap();
        stdin.flush().unwrap();
        wait_until_reading(child.id());
        child.kill().unwrap();
        let status = child.wait().unwrap();
        drop(stdin);
        assert_eq!(status.signal(), Some(libc::SIGKILL));
        assert_eq!(names(dir.path()), ["out.txt"], "{}", out.display());
        assert_eq!(
            fs::read_to_string(&target).ok().as_deref(),
            Some("previous content\n")
        );
        assert_eq!(fs::read_to_string(out).ok().as_deref(), old);
    }
    // An output that cannot be written is still told before the input is read: the run does
    // not wait for an input that never comes.
    let missing = dir.path().join("no/such/dir/out.txt");
    let mut child = spawn(
        &[
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            missing.as_os_str(),
        ],
        Stdio::piped(),
    );
    let _stdin = child.stdin.take().unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("cannot create the temporary file"),
        "{}",
        stderr(&out)
    );
}

/// `-o /dev/stdout`, `/dev/fd/1`, `/proc/self/fd/1` (and a link to one) write to standard
/// output as `-o -` does, through the descriptor the run was given: when that is a regular
/// file, what is written to it before and after the run stays (a reviewer's report: `{ echo a;
/// condt … -o /dev/fd/1; echo b; } > all.txt` replaced all.txt by a new file, and `-o
/// /dev/stdout` wrote from an offset of its own, over what came after). `/dev/stderr` writes
/// to standard error alike; `/dev/stdin` is refused.
#[test]
fn a_name_of_an_open_descriptor_writes_through_that_descriptor() {
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("link");
    std::os::unix::fs::symlink("/dev/stdout", &link).unwrap();
    let expected = square_triangles();
    for name in [
        "/dev/stdout",
        "/dev/fd/1",
        "/proc/self/fd/1",
        "//dev/./fd/1",
        link.to_str().unwrap(),
    ] {
        let path = dir.path().join("all.txt");
        let mut file = fs::File::create(&path).unwrap();
        file.write_all(b"# a\n").unwrap();
        let mut child = Command::new(binary())
            .args(["triangulate", "-", "-q", "-o", name])
            .stdin(Stdio::piped())
            .stdout(file.try_clone().unwrap())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        feed(&mut child, SQUARE.as_bytes());
        let out = child.wait_with_output().unwrap();
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        // The same open file, its offset moved by the run's writes.
        file.write_all(b"# b\n").unwrap();
        assert_eq!(
            fs::read_to_string(&path).unwrap(),
            format!("# a\n{expected}# b\n"),
            "{name}"
        );
        fs::remove_file(&path).unwrap();
    }
    assert_eq!(names(dir.path()), ["link"]);
    let out = condt(&["triangulate", "-", "-q", "-o", "/dev/stderr"], SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stdout.is_empty());
    assert_eq!(stderr(&out), expected);
    let out = condt(&["triangulate", "-", "-o", "/dev/stdin"], SQUARE);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("is standard input"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn sigterm_removes_the_temporary_file() {
    interrupted("TERM", 15);
}

#[test]
fn sigint_removes_the_temporary_file() {
    interrupted("INT", 2);
}

/// Starts `command` with `signal`'s default action, whatever the test process left it (a test
/// run as a background job has SIGINT and SIGQUIT ignored, which the run would keep), and no core
/// file from SIGQUIT's, wherever dumps are on.
fn with_default_action(command: &mut Command, signal: libc::c_int) {
    use std::os::unix::process::CommandExt;
    // SAFETY: `signal` is async-signal-safe and `setrlimit` a plain system call (no allocation,
    // no lock), as `pre_exec` requires.
    unsafe {
        command.pre_exec(move || {
            libc::signal(signal, libc::SIG_DFL);
            let none = libc::rlimit {
                rlim_cur: 0,
                rlim_max: 0,
            };
            libc::setrlimit(libc::RLIMIT_CORE, &none);
            Ok(())
        });
    }
}

/// `points.txt` in `dir`: `count` points in the unit square from a fixed generator.
fn random_points(dir: &Path, count: usize) -> PathBuf {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut points = String::new();
    for _ in 0..count {
        points.push_str(&format!("{} {}\n", next(), next()));
    }
    let input = dir.join("points.txt");
    fs::write(&input, points).unwrap();
    input
}

/// Each signal the run catches, sent while the output is being written (once its temporary file
/// holds bytes), leaves no temporary file: the run ends by the signal with nothing beside the
/// output, or with the whole output when the signal came after the rename, or finishes first.
/// At least one of the four must come mid-write, or the test proves nothing. SIGQUIT (`Ctrl-\`)
/// left the `.condt.XXXXXX.tmp` behind until 2026-12-06 (a reviewer's report).
#[test]
fn a_signal_while_the_output_is_written_removes_the_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    // An output of about 8 MB.
    let input = random_points(dir.path(), 200_000);
    let args = |target: &Path| -> Vec<std::ffi::OsString> {
        let mut args: Vec<std::ffi::OsString> = vec!["triangulate".into(), input.clone().into()];
        args.extend(["-q".into(), "-o".into(), target.into()]);
        args
    };
    let whole = dir.path().join("whole.txt");
    let status = Command::new(binary()).args(args(&whole)).status().unwrap();
    assert!(status.success());
    let expected = fs::read(&whole).unwrap();
    let mut interrupted_mid_write = 0;
    for signal in [libc::SIGQUIT, libc::SIGTERM, libc::SIGINT, libc::SIGHUP] {
        let out_dir = tempfile::tempdir().unwrap();
        let target = out_dir.path().join("out.txt");
        let mut command = Command::new(binary());
        command.args(args(&target)).stderr(Stdio::piped());
        with_default_action(&mut command, signal);
        let mut child = command.spawn().expect("the binary runs");
        let deadline = Instant::now() + Duration::from_secs(120);
        while child.try_wait().unwrap().is_none() && Instant::now() < deadline {
            // Not the trial file made and removed before the input is read: one with bytes.
            let temporary = find_temporary(out_dir.path(), &target, Duration::ZERO);
            if temporary.is_some_and(|t| fs::metadata(t).is_ok_and(|m| m.len() > 0)) {
                // SAFETY: `kill` takes any pid and signal number; it only sends the signal.
                unsafe { libc::kill(child.id() as libc::pid_t, signal) };
                break;
            }
            std::thread::sleep(Duration::from_micros(100));
        }
        let out = child.wait_with_output().unwrap();
        let left = names(out_dir.path());
        assert!(
            left.is_empty() || left == ["out.txt"],
            "signal {signal}: {left:?} left"
        );
        if !left.is_empty() {
            assert!(fs::read(&target).unwrap() == expected, "signal {signal}");
        }
        match out.status.signal() {
            Some(ended_by) => {
                assert_eq!(ended_by, signal, "{:?}", out.status);
                interrupted_mid_write += usize::from(left.is_empty());
            }
            None => assert!(out.status.success(), "{}", stderr(&out)),
        }
    }
    assert!(
        interrupted_mid_write > 0,
        "no signal came while the output was written"
    );
}

/// `--format` over a name whose ending says another format writes what `--format` says, with a
/// note naming both (it was silent: a reviewer's report); a name that agrees, or ends in no
/// known format, gets none, nor does `--quiet`.
#[test]
fn a_format_against_the_names_ending_is_noted() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("square.txt");
    fs::write(&input, SQUARE).unwrap();
    let run = |name: &str, format: &str, quiet: bool| {
        let target = dir.path().join(name);
        let mut args = vec![
            OsStr::new("reconstruct"),
            input.as_os_str(),
            OsStr::new("-o"),
            target.as_os_str(),
            OsStr::new("--format"),
            OsStr::new(format),
        ];
        if quiet {
            args.push(OsStr::new("-q"));
        }
        let out = condt(&args, "");
        assert!(out.status.success(), "{}", stderr(&out));
        (fs::read_to_string(&target).unwrap(), stderr(&out))
    };
    let (written, said) = run("out.edges", "svg", false);
    assert!(written.starts_with("<svg"), "{written}");
    assert!(
        said.contains("out.edges: written in the svg format (--format svg), not the edges format"),
        "{said}"
    );
    for (name, format, quiet) in [
        ("out.svg", "svg", false),
        ("out.json", "geojson", false),
        ("out.result", "txt", false),
        ("quiet.edges", "svg", true),
    ] {
        let (_, said) = run(name, format, quiet);
        assert!(!said.contains("format its name"), "{name}: {said}");
    }
}

#[test]
fn an_error_removes_the_temporary_file_and_keeps_the_old_content() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.txt");
    fs::write(&target, "previous content\n").unwrap();
    let out = condt(
        &[
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            target.as_os_str(),
        ],
        "0 0\n1 oops\n",
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("<stdin>:2:"), "{}", stderr(&out));
    assert_eq!(fs::read_to_string(&target).unwrap(), "previous content\n");
    assert_eq!(names(dir.path()), ["out.txt"]);
}

#[test]
fn the_input_cannot_be_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("points.txt");
    fs::write(&input, SQUARE).unwrap();
    let hard = dir.path().join("hard.txt");
    fs::hard_link(&input, &hard).unwrap();
    let soft = dir.path().join("soft.txt");
    std::os::unix::fs::symlink("points.txt", &soft).unwrap();
    let dotted = dir.path().join(".").join("points.txt");
    for output in [&input, &hard, &soft, &dotted] {
        for command in ["triangulate", "reconstruct"] {
            let out = condt(
                &[
                    command.as_ref(),
                    input.as_os_str(),
                    "-o".as_ref(),
                    output.as_os_str(),
                ],
                "",
            );
            assert_eq!(
                out.status.code(),
                Some(2),
                "{command} -o {}: {}",
                output.display(),
                stderr(&out)
            );
            assert!(stderr(&out).contains("is the input"), "{}", stderr(&out));
        }
    }
    // Standard input read from the file named by -o.
    let out = Command::new(binary())
        .args([
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            hard.as_os_str(),
        ])
        .stdin(fs::File::open(&input).unwrap())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert_eq!(
        fs::read_to_string(&input).unwrap(),
        SQUARE,
        "the input is untouched"
    );
    assert_eq!(names(dir.path()), ["hard.txt", "points.txt", "soft.txt"]);
}

/// Standard output the shell opened on the input (`>> points.txt`, `1<> points.txt`, and
/// `< points.txt >> points.txt` for standard input) is refused as `-o points.txt` is: appended
/// to or written over, the point file would no longer read as points.
#[test]
fn standard_output_cannot_be_the_input() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("points.txt");
    fs::write(&input, SQUARE).unwrap();
    for command in ["triangulate", "reconstruct"] {
        for (name, from_stdin) in [(input.as_os_str(), false), ("-".as_ref(), true)] {
            let appending = fs::OpenOptions::new().append(true).open(&input).unwrap();
            let stdin = if from_stdin {
                Stdio::from(fs::File::open(&input).unwrap())
            } else {
                Stdio::null()
            };
            let out = Command::new(binary())
                .args([command.as_ref(), name, "-q".as_ref()])
                .stdin(stdin)
                .stdout(appending)
                .output()
                .unwrap();
            assert_eq!(out.status.code(), Some(2), "{command}: {}", stderr(&out));
            assert!(
                stderr(&out).contains("the output <stdout> is the input"),
                "{}",
                stderr(&out)
            );
            assert_eq!(fs::read_to_string(&input).unwrap(), SQUARE, "{command}");
        }
    }
    // Another file on standard output is written as before.
    let other = fs::File::create(dir.path().join("out.txt")).unwrap();
    let out = Command::new(binary())
        .args(["triangulate".as_ref(), input.as_os_str()])
        .stdout(other)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let written = fs::read_to_string(dir.path().join("out.txt")).unwrap();
    assert_eq!(written.lines().count(), 2, "{written}");
}

#[test]
fn file_names_need_not_be_utf8() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join(OsStr::from_bytes(b"\xffpoints.txt"));
    fs::write(&input, SQUARE).unwrap();
    let output = dir.path().join(OsStr::from_bytes(b"\xfeout.txt"));
    let out = condt(
        &[
            "triangulate".as_ref(),
            input.as_os_str(),
            "-o".as_ref(),
            output.as_os_str(),
        ],
        "",
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(fs::read_to_string(&output).unwrap(), square_triangles());
    // A missing one is an error naming it as well as it can, not a panic.
    let missing = dir.path().join(OsStr::from_bytes(b"\xffmissing.txt"));
    let out = condt(&["triangulate".as_ref(), missing.as_os_str()], "");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("missing.txt"), "{}", stderr(&out));
}

#[test]
fn a_reader_that_goes_away_ends_the_run_silently() {
    // Enough triangles to fill any pipe buffer.
    let points: String = (0..3000)
        .map(|i| format!("{} {}\n", i % 60, (i / 60) as f64 + 0.01 * (i % 7) as f64))
        .collect();
    let mut child = spawn(&["triangulate", "-"], Stdio::piped());
    drop(child.stdout.take());
    feed(&mut child, points.as_bytes());
    let out = child.wait_with_output().unwrap();
    assert_eq!(stderr(&out), "", "nothing is said");
    assert_eq!(
        out.status.signal(),
        Some(13),
        "ended by SIGPIPE: {:?}",
        out.status
    );
}

/// Found by a hostile-input review: standard output open for reading only (`1<file`) refused
/// every write, and std's stream took that as done: exit 0, the output lost.
#[test]
fn a_standard_stream_that_refuses_writes_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("square.txt");
    let kept = dir.path().join("kept.txt");
    fs::write(&input, SQUARE).unwrap();
    fs::write(&kept, "kept\n").unwrap();
    for (args, shown) in [
        (vec!["reconstruct", "-q"], "<stdout>"),
        (vec!["reconstruct", "-q", "-o", "-"], "<stdout>"),
        (vec!["reconstruct", "-q", "-o", "/dev/stdout"], "<stdout>"),
        (vec!["triangulate", "-q"], "<stdout>"),
    ] {
        let mut args: Vec<&OsStr> = args.iter().map(OsStr::new).collect();
        args.push(input.as_os_str());
        let out = Command::new(binary())
            .args(&args)
            .stdout(fs::File::open(&kept).unwrap())
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(shown), "{args:?}: {}", stderr(&out));
        assert_eq!(fs::read_to_string(&kept).unwrap(), "kept\n");
    }
}

#[test]
fn a_directory_is_not_an_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = condt(
        &[
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            dir.path().as_os_str(),
        ],
        SQUARE,
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("is a directory"), "{}", stderr(&out));
    assert!(names(dir.path()).is_empty());
    // A name ending in a slash names a directory even where none exists yet.
    let slashed = std::ffi::OsString::from(format!("{}/", dir.path().join("not-yet").display()));
    let out = condt(
        &[
            "triangulate".as_ref(),
            "-".as_ref(),
            "-o".as_ref(),
            slashed.as_os_str(),
        ],
        SQUARE,
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("names a directory"),
        "{}",
        stderr(&out)
    );
    assert!(names(dir.path()).is_empty());
    // A file in a directory that does not exist: the error names the file the user gave, not
    // the temporary one.
    let lost = dir.path().join("no-such-directory").join("out.txt");
    let out = triangulate_to(&lost, SQUARE);
    assert_eq!(out.status.code(), Some(1));
    let said = stderr(&out);
    assert!(
        said.starts_with(&format!("condt: {}: ", lost.display())),
        "{said}"
    );
    assert!(!said.contains(".condt."), "{said}");
}

/// A command for the binary, run as an unprivileged user: `nobody` when the tests run as root
/// (permissions mean nothing to root), else the current user.
fn unprivileged(args: &[&OsStr]) -> Command {
    let mut command = Command::new(binary());
    command.args(args);
    if is_root() {
        use std::os::unix::process::CommandExt;
        command.uid(65534).gid(65534);
    }
    command
}

/// A directory the unprivileged user may enter, removed on drop.
fn shared_dir() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    fs::set_permissions(dir.path(), fs::Permissions::from_mode(0o777)).unwrap();
    dir
}

#[test]
fn a_file_the_user_may_not_write_is_not_replaced() {
    let dir = shared_dir();
    let input = dir.path().join("points.txt");
    fs::write(&input, SQUARE).unwrap();
    let target = dir.path().join("read-only.txt");
    fs::write(&target, "previous content\n").unwrap();
    fs::set_permissions(&target, fs::Permissions::from_mode(0o444)).unwrap();
    if is_root() {
        std::os::unix::fs::chown(&target, Some(65534), Some(65534)).unwrap();
    }
    let out = unprivileged(&[
        "triangulate".as_ref(),
        input.as_os_str(),
        "-o".as_ref(),
        target.as_os_str(),
    ])
    .output()
    .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("read-only.txt: "), "{}", stderr(&out));
    assert_eq!(fs::read_to_string(&target).unwrap(), "previous content\n");
    assert_eq!(names(dir.path()), ["points.txt", "read-only.txt"]);
}

#[test]
fn a_writable_file_in_a_closed_directory_is_written_in_place() {
    let outer = shared_dir();
    let input = outer.path().join("points.txt");
    fs::write(&input, SQUARE).unwrap();
    let closed = outer.path().join("closed");
    fs::create_dir(&closed).unwrap();
    let target = closed.join("open.txt");
    fs::write(&target, "previous content, longer than the triangles are\n").unwrap();
    fs::set_permissions(&target, fs::Permissions::from_mode(0o666)).unwrap();
    // No file can be added here, so no temporary file either.
    fs::set_permissions(&closed, fs::Permissions::from_mode(0o555)).unwrap();
    let out = unprivileged(&[
        "triangulate".as_ref(),
        input.as_os_str(),
        "-o".as_ref(),
        target.as_os_str(),
    ])
    .output()
    .unwrap();
    // Reopened so the guard can remove it, whatever happened.
    fs::set_permissions(&closed, fs::Permissions::from_mode(0o755)).unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(fs::read_to_string(&target).unwrap(), square_triangles());
    assert_eq!(names(&closed), ["open.txt"]);
}

/// `condt triangulate INPUT -o OUT` started with `signal` ignored, as `nohup` ignores SIGHUP and
/// a shell ignores SIGINT for `cmd &`; the input a named pipe, so that the signal arrives while
/// the run reads it. The run must keep the disposition it inherited: finish, exit 0, write.
fn ignored_signal_is_left_ignored(signal: libc::c_int) {
    use std::os::unix::process::CommandExt;
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.txt");
    mkfifo(&input);
    let target = dir.path().join("out.txt");
    fs::write(&target, "previous content\n").unwrap();
    let mut command = Command::new(binary());
    command
        .args([
            "triangulate".as_ref(),
            input.as_os_str(),
            "-o".as_ref(),
            target.as_os_str(),
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    // SAFETY: `signal` is async-signal-safe, as `pre_exec` requires.
    unsafe {
        command.pre_exec(move || {
            libc::signal(signal, libc::SIG_IGN);
            Ok(())
        });
    }
    let child = command.spawn().unwrap();
    // Opening the pipe waits for the run to open it: it has prepared its output by then.
    let mut pipe = fs::OpenOptions::new().write(true).open(&input).unwrap();
    pipe.write_all(b"0 0\n1 0\n").unwrap();
    pipe.flush().unwrap();
    wait_until_reading(child.id());
    // SAFETY: a plain system call on the child's id.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
    std::thread::sleep(Duration::from_millis(200));
    // A run killed by the signal closed the pipe: writing then fails, which is the failure
    // reported below.
    let _ = pipe.write_all(b"1 1\n0 1\n");
    drop(pipe);
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "signal {signal} ignored: {:?} {}",
        out.status,
        stderr(&out)
    );
    assert_eq!(fs::read_to_string(&target).unwrap(), square_triangles());
    assert_eq!(names(dir.path()), ["in.txt", "out.txt"]);
}

#[test]
fn sighup_ignored_as_under_nohup_is_left_ignored() {
    ignored_signal_is_left_ignored(libc::SIGHUP);
}

#[test]
fn sigint_ignored_as_for_a_background_job_is_left_ignored() {
    ignored_signal_is_left_ignored(libc::SIGINT);
}

/// A valid name of 255 bytes (NAME_MAX on Linux) is an output like any other: the temporary
/// file beside it must not be named after it.
#[test]
fn an_output_name_of_255_bytes_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let name = format!("{}.txt", "n".repeat(251));
    assert_eq!(name.len(), 255);
    let target = dir.path().join(&name);
    let out = triangulate_to(&target, SQUARE);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(fs::read_to_string(&target).unwrap(), square_triangles());
    // And replaced, once it exists.
    let out = triangulate_to(&target, "0 0\n1 0\n0 1\n");
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(fs::read_to_string(&target).unwrap().lines().count(), 1);
    assert_eq!(names(dir.path()), [name]);
}

/// `triangulate -` of 2,000 points (some 40 kB of triangles) with the further `args` and
/// standard output `stdout`, under a file-size limit (`ulimit -f`) of 4 kB.
fn triangulate_under_a_file_size_limit(args: &[&OsStr], stdout: Stdio) -> Output {
    use std::os::unix::process::CommandExt;
    let input: String = (0..2000)
        .map(|i| format!("{} {}\n", i % 50, (i / 50) as f64 + 0.01 * (i % 7) as f64))
        .collect();
    let mut command = Command::new(binary());
    command
        .args(["triangulate", "-"])
        .args(args)
        .stdin(Stdio::piped())
        .stdout(stdout)
        .stderr(Stdio::piped());
    // SAFETY: `setrlimit` is async-signal-safe, as `pre_exec` requires.
    unsafe {
        command.pre_exec(|| {
            let limit = libc::rlimit {
                rlim_cur: 4096,
                rlim_max: 4096,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let mut child = command.spawn().unwrap();
    std::io::BufWriter::new(child.stdin.take().unwrap())
        .write_all(input.as_bytes())
        .unwrap();
    child.wait_with_output().unwrap()
}

/// `triangulate` of 2,000 points (some 40 kB of triangles) into `target`, under a file-size
/// limit (`ulimit -f`) of 4 kB.
fn triangulate_past_a_file_size_limit(target: &Path) -> Output {
    let out =
        triangulate_under_a_file_size_limit(&["-o".as_ref(), target.as_os_str()], Stdio::piped());
    assert_eq!(
        out.status.code(),
        Some(1),
        "{:?} {}",
        out.status,
        stderr(&out)
    );
    let said = stderr(&out);
    assert!(
        said.contains("out.txt") && said.contains("File too large"),
        "{said}"
    );
    out
}

/// Found by a hostile-input review: a hard-linked output (rewritten in place, so that every
/// name sees the result) past a file-size limit kept the first 4 kB of the result and lost its
/// old content. The room is checked first: refused, the old content whole.
#[test]
fn a_hard_linked_output_past_a_file_size_limit_keeps_its_old_content() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.txt");
    fs::write(&target, "previous content\n").unwrap();
    fs::hard_link(&target, dir.path().join("other name.txt")).unwrap();
    triangulate_past_a_file_size_limit(&target);
    assert_eq!(fs::read_to_string(&target).unwrap(), "previous content\n");
    assert_eq!(names(dir.path()), ["other name.txt", "out.txt"]);
}

/// A file-size limit (`ulimit -f`) that the output passes: the write fails (EFBIG) instead of
/// SIGXFSZ ending the run, so the run reports it, exits 1, removes its temporary file and
/// leaves the old output as it was.
#[test]
fn a_file_size_limit_is_an_error_that_leaves_no_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.txt");
    fs::write(&target, "previous content\n").unwrap();
    triangulate_past_a_file_size_limit(&target);
    assert_eq!(fs::read_to_string(&target).unwrap(), "previous content\n");
    assert_eq!(names(dir.path()), ["out.txt"]);
}

/// Where the temporary file beside an existing output cannot be made (`/proc` takes no new
/// file), the message says so: the operating system's "No such file or directory" alone, said
/// of a file that exists, was a puzzle (found by a fuzzer).
#[cfg(target_os = "linux")]
#[test]
fn a_temporary_file_that_cannot_be_made_is_named_as_such() {
    let out = condt(&["triangulate", "-", "-o", "/proc/version"], SQUARE);
    assert_eq!(out.status.code(), Some(1));
    let said = stderr(&out);
    assert!(
        said.contains(
            "/proc/version: cannot create the temporary file it is written through in /proc"
        ),
        "{said}"
    );
}

/// A result in many short pieces says that the set may be noisy and names the README's advice on
/// scans (a robotics user's review: a raw scan's 23,120 curves read as success); a clean set of
/// as many points says nothing, nor does `-q`.
#[test]
fn a_result_in_many_short_pieces_says_the_set_may_be_noisy() {
    // 3,000 points scattered at random: pieces of a few points.
    let dir = tempfile::tempdir().unwrap();
    let scattered = fs::read_to_string(random_points(dir.path(), 3000)).unwrap();
    let out = condt(&["reconstruct", "-", "-o", "/dev/null"], &scattered);
    assert!(out.status.success(), "{}", stderr(&out));
    let said = stderr(&out);
    assert!(
        said.contains("points on average: a noisy set") && said.contains("*Scans*"),
        "{said}"
    );
    let quiet = condt(&["reconstruct", "-", "-o", "/dev/null", "-q"], &scattered);
    assert!(stderr(&quiet).is_empty(), "{}", stderr(&quiet));
    // 100 ellipses of 30 points each: 100 curves, 30 points each.
    let clean: String = (0..100)
        .flat_map(|e| {
            (0..30).map(move |k| {
                let t = k as f64 * std::f64::consts::TAU / 30.0;
                format!("{} {}\n", 10.0 * e as f64 + 2.0 * t.cos(), t.sin())
            })
        })
        .collect();
    let out = condt(&["reconstruct", "-", "-o", "/dev/null"], &clean);
    let said = stderr(&out);
    assert!(
        said.contains("3000 points, 100 curves (100 closed"),
        "{said}"
    );
    assert!(!said.contains("on average"), "{said}");
    // A street grid of 8 by 8 blocks of 8 spacings: 140 curves of 9.2 points between its
    // junctions, exact, and no piece ends loose: no note (it had one when every curve counted).
    let mut grid = std::collections::BTreeSet::new();
    for line in 0..9 {
        for t in 0..65 {
            grid.insert((8 * line, t));
            grid.insert((t, 8 * line));
        }
    }
    let grid: String = grid.iter().map(|(x, y)| format!("{x} {y}\n")).collect();
    let out = condt(&["reconstruct", "-", "-o", "/dev/null"], &grid);
    let said = stderr(&out);
    assert!(
        said.contains("1089 points, 140 curves (0 closed, 140 open), 0 unused"),
        "{said}"
    );
    assert!(!said.contains("on average"), "{said}");
}

/// A viewer review: `--stages` on 100,000 points wrote a 120 MB drawing without a word. Past
/// 200,000 dots (points times panels) a note says so and names the HTML viewer; below, none.
#[test]
fn a_stage_drawing_of_many_points_says_it_is_slow_to_open() {
    let circle = |n: usize| -> String {
        (0..n)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / n as f64;
                format!("{} {}\n", t.cos(), t.sin())
            })
            .collect()
    };
    let args = [
        "reconstruct",
        "-",
        "-o",
        "/dev/null",
        "--format",
        "svg",
        "--stages",
    ];
    let out = condt(&args, &circle(70_000));
    assert!(out.status.success(), "{}", stderr(&out));
    let said = stderr(&out);
    assert!(
        said.contains("slow to open") && said.contains("-o out.html"),
        "{said}"
    );
    let out = condt(&args, &circle(500));
    assert!(out.status.success());
    assert!(!stderr(&out).contains("slow to open"));
    let quiet = condt(&[&args[..], &["-q"]].concat(), &circle(70_000));
    assert!(!stderr(&quiet).contains("slow to open"));
    // One panel too (a GIS review: 2.6M points, a 183 MB drawing, no word). 200,001 points,
    // three of them distinct: the rest merge as duplicates, each still drawn.
    let many: String = circle(3)
        .lines()
        .cycle()
        .take(200_001)
        .map(|l| format!("{l}\n"))
        .collect();
    let out = condt(&args[..6], &many);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("the drawing has 200001 points, slow to open"),
        "{}",
        stderr(&out)
    );
    let out = condt(
        &args[..6],
        &many[..many.len() - many.lines().last().unwrap().len() - 1],
    );
    assert!(!stderr(&out).contains("slow to open"), "{}", stderr(&out));
}

/// SIGTERM while a file is rewritten in place (here, one with a second name) leaves it whole:
/// the old content or the new, never the new one's start on the old one's rest. The signal is
/// sent as soon as the file's time changes, that is once the rewrite has begun (a power user's
/// review: 2 MiB of triangles, then the rest of the old file); the run ends when the rewrite is
/// done, by the signal or, when it finishes first, normally.
#[test]
fn a_signal_during_an_in_place_rewrite_waits_for_it() {
    use std::os::unix::fs::MetadataExt;
    let dir = tempfile::tempdir().unwrap();
    // An output of about 12 MB, written in one go.
    let input = random_points(dir.path(), 300_000);
    let target = dir.path().join("out.txt");
    let old = vec![b'Z'; 40_000_000];
    fs::write(&target, &old).unwrap();
    fs::hard_link(&target, dir.path().join("second name.txt")).unwrap();
    let before = fs::metadata(&target).unwrap();
    let mut child = Command::new(binary())
        .args([
            "triangulate".as_ref(),
            input.as_os_str(),
            "-q".as_ref(),
            "-o".as_ref(),
            target.as_os_str(),
        ])
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let deadline = Instant::now() + Duration::from_secs(120);
    while child.try_wait().unwrap().is_none() && Instant::now() < deadline {
        let now = fs::metadata(&target).unwrap();
        if (now.mtime(), now.mtime_nsec(), now.len())
            != (before.mtime(), before.mtime_nsec(), before.len())
        {
            // At once: starting `kill` would take longer than the rewrite.
            // SAFETY: `kill` takes any pid and signal number; it only sends the signal.
            unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGTERM) };
            break;
        }
        std::thread::sleep(Duration::from_micros(200));
    }
    let out = child.wait_with_output().unwrap();
    let written = fs::read(&target).unwrap();
    if written != old {
        assert!(
            !written.contains(&b'Z'),
            "old bytes after new ones: {:?}",
            out.status
        );
        let text = String::from_utf8(written).unwrap();
        assert!(text.ends_with('\n') && text.lines().all(|l| l.split(' ').count() == 3));
    }
}

/// Another process's descriptor named as `/proc/PID/fd/N` is written through, as a link to it
/// is: the file behind it is not replaced (a power user's review: `-o /proc/$$/fd/1` in a
/// script gave the script's output file a new inode, and its other lines were lost).
#[test]
fn another_processes_descriptor_is_written_through() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("square.txt");
    fs::write(&input, SQUARE).unwrap();
    let log = dir.path().join("log.txt");
    let script = format!(
        "echo before; '{}' triangulate '{}' -q -o /proc/$$/fd/1; echo after",
        binary().display(),
        input.display()
    );
    let status = Command::new("sh")
        .args(["-c", &script])
        .stdout(fs::File::create(&log).unwrap())
        .status()
        .unwrap();
    assert!(status.success());
    // The shell's file is still the one at `log`: both its lines are in it. (Where condt's
    // lines land among them is the kernel's: the name opens the file anew, at its own offset.)
    let text = fs::read_to_string(&log).unwrap();
    assert!(
        text.starts_with("before\n") && text.contains("after\n"),
        "{text:?}"
    );
}

/// A hard-linked output is rewritten in place under an exclusive `fcntl` lock, so that two runs
/// given the same `-o` (`xargs -P` jobs) write one after the other, not into each other (an
/// operations review: 2 of 32 pairs of runs rewriting one 41 MB file left a mix of both). Here
/// the test holds such a lock (`lockf`): the run says it waits, leaves the file alone until the
/// lock goes, then writes it whole. A `flock` lock, which `flock OUTPUT condt ... -o OUTPUT`
/// holds for its whole run, does not stop it. Linux only (the lock is taken there); skipped
/// where the test's own lock fails (a file system without such locks).
#[cfg(target_os = "linux")]
#[test]
fn an_in_place_rewrite_waits_for_a_lock_on_the_file() {
    use std::io::BufRead;
    use std::os::fd::AsRawFd;
    let dir = tempfile::tempdir().unwrap();
    let expected = square_triangles();
    let target = dir.path().join("out.txt");
    let old = "old content, in place until the lock goes\n";
    fs::write(&target, old).unwrap();
    fs::hard_link(&target, dir.path().join("second name.txt")).unwrap();
    let run = || {
        let mut child = spawn(
            &[
                "triangulate".as_ref(),
                "-".as_ref(),
                "-o".as_ref(),
                target.as_os_str(),
            ],
            Stdio::null(),
        );
        feed(&mut child, SQUARE.as_bytes());
        child
    };
    // A `flock` lock, as `flock(1)` takes: not waited for (it would be the run's own caller's).
    let flocked = fs::File::open(&target).unwrap();
    // SAFETY: `flock` on a descriptor `flocked` keeps open; it only takes a lock.
    if unsafe { libc::flock(flocked.as_raw_fd(), libc::LOCK_EX) } == 0 {
        let mut child = run();
        let deadline = Instant::now() + Duration::from_secs(60);
        while child.try_wait().unwrap().is_none() {
            if Instant::now() > deadline {
                child.kill().unwrap();
                panic!("the run waited for a flock lock");
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        let out = child.wait_with_output().unwrap();
        assert!(out.status.success(), "{}", stderr(&out));
        assert_eq!(fs::read_to_string(&target).unwrap(), expected);
        fs::write(&target, old).unwrap();
    }
    drop(flocked);
    let held = fs::OpenOptions::new().write(true).open(&target).unwrap();
    // SAFETY: `lockf` on a descriptor `held` keeps open; it only takes a lock.
    if unsafe { libc::lockf(held.as_raw_fd(), libc::F_TLOCK, 0) } != 0 {
        eprintln!(
            "skipped: no lockf here ({})",
            std::io::Error::last_os_error()
        );
        return;
    }
    let mut child = run();
    let mut err = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut said = String::new();
    // The note comes before the wait; without the lock the run writes and ends, and the
    // stream ends without it.
    loop {
        let mut line = String::new();
        let done = err.read_line(&mut line).unwrap() == 0 || line.contains("waiting");
        said.push_str(&line);
        if done {
            break;
        }
    }
    assert!(
        said.contains("out.txt: waiting for another program's lock on it"),
        "the run did not wait: {said:?}"
    );
    assert_eq!(
        fs::read_to_string(&target).unwrap(),
        old,
        "untouched meanwhile"
    );
    drop(held);
    let status = child.wait().unwrap();
    assert!(status.success(), "{status:?}");
    assert_eq!(fs::read_to_string(&target).unwrap(), expected);
    assert_eq!(names(dir.path()), ["out.txt", "second name.txt"]);
}

/// A standard error that refuses writes (its reader gone, as in `condt score ... 2>&1 >x |
/// true`, or `2>/dev/full`) loses `score`'s notes, not its result: the note on a truth that
/// repeats a point went out by `eprintln!`, which panics when it cannot write (an operations
/// review: exit 101 and no score on standard output). The points come on standard input, so
/// the run cannot write its note before the reader of its standard error is gone.
#[test]
fn score_scores_when_its_standard_error_refuses_writes() {
    let dir = tempfile::tempdir().unwrap();
    // A closed ring written with its first point again at its end: a note to write.
    let ring = "0 0\n1 0\n1 1\n0 1\n0 0\n";
    let truth = dir.path().join("ring.edges");
    fs::write(&truth, "0 1\n1 2\n2 3\n3 4\n").unwrap();
    let args = [
        "score".as_ref(),
        "-".as_ref(),
        truth.as_os_str(),
        truth.as_os_str(),
    ];
    // With its standard error read, the run says it (what is lost below).
    let said = condt(&args, ring);
    assert!(
        stderr(&said).contains("repeats an earlier point"),
        "{}",
        stderr(&said)
    );
    let mut child = spawn(&args, Stdio::piped());
    drop(child.stderr.take());
    feed(&mut child, ring.as_bytes());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{:?}", out.status);
    assert_eq!(out.stdout, said.stdout, "the same score");
}

/// A write to standard output that fails names the file behind it where that is a regular file
/// (`condt ... > out.txt` past a file-size limit or on a full disk), not `<stdout>` alone, which
/// left a batch job's log without the file (an operations review). Linux only (read from
/// `/proc/self/fd`).
#[cfg(target_os = "linux")]
#[test]
fn a_failed_write_to_standard_output_names_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("redirected.txt");
    let out = triangulate_under_a_file_size_limit(&[], fs::File::create(&target).unwrap().into());
    let said = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{said}");
    assert!(
        said.contains(&format!("<stdout> ({})", target.display())) && said.contains("too large"),
        "{said}"
    );
}
