//! A run whose worker threads cannot be started (a limit on processes, as a container's pids
//! limit sets) falls back to one thread with a note and writes the same output: never a panic.
//! And a run under a limit on its address space (`ulimit -v`) measures its input against that
//! limit.

#![cfg(unix)]

use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Command, Output};

fn shapes() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes.txt")
}

/// The binary under test: this build's, or `CONDT_TEST_BIN` (to show a test fails on another).
fn binary() -> std::ffi::OsString {
    std::env::var_os("CONDT_TEST_BIN").unwrap_or_else(|| env!("CARGO_BIN_EXE_condt").into())
}

/// `condt ARGS`, with or without a starved thread pool.
fn run(args: &[&str], starved: bool) -> Output {
    run_limited(args, starved.then_some(1), None)
}

/// `condt ARGS` allowed `tasks` processes and threads at most (`None`: no limit), with
/// `threads` in rayon's pool (`None`: its default).
fn run_limited(args: &[&str], tasks: Option<u64>, threads: Option<usize>) -> Output {
    let mut command = Command::new(binary());
    command.args(args);
    if let Some(threads) = threads {
        command.env("RAYON_NUM_THREADS", threads.to_string());
    }
    if let Some(tasks) = tasks {
        // Allowed `tasks` processes: no thread can be started past them; root is exempt from
        // the limit, so as root the child first becomes the unprivileged user 65534.
        // SAFETY: `setrlimit` and `setuid` are async-signal-safe, as `pre_exec` requires.
        unsafe {
            command.pre_exec(move || {
                let limit = libc::rlimit {
                    rlim_cur: tasks as libc::rlim_t,
                    rlim_max: tasks as libc::rlim_t,
                };
                if libc::getuid() == 0 && libc::setuid(65534) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                if libc::setrlimit(libc::RLIMIT_NPROC, &limit) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
    }
    command.output().expect("the binary runs")
}

#[test]
fn a_thread_pool_that_cannot_start_falls_back_to_one_thread() {
    let input = shapes();
    let input = input.to_str().unwrap();
    for command in [
        &["reconstruct", input][..],
        &["reconstruct", input, "--no-smooth"],
        &["triangulate", input, "--edges"],
    ] {
        let normal = run(command, false);
        let starved = run(command, true);
        assert!(normal.status.success(), "{command:?}");
        let stderr = String::from_utf8_lossy(&starved.stderr);
        assert_eq!(starved.status.code(), Some(0), "{command:?}: {stderr}");
        assert!(
            stderr.contains("cannot start worker threads; running on one thread"),
            "{command:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{command:?}: {stderr}");
        assert_eq!(
            starved.stdout, normal.stdout,
            "{command:?}: the same output"
        );
    }
}

/// Rayon's two threads start, and no thread after them: the writing, which formats a large
/// output on a thread of its own beside the one writing it, formats it on the writing thread
/// instead, the same bytes (a reviewer's report: `reconstruct --sequential` under a memory
/// limit panicked with "failed to spawn thread" from the writer's `thread::scope`). The
/// progress bar's threads (not drawn here) are started the same way.
#[test]
fn a_writer_thread_that_cannot_start_is_done_without() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("uniform.txt");
    // 30,000 points of a fixed sequence: tens of thousands of edges, several pieces' worth.
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let text: String = (0..30_000)
        .map(|_| format!("{} {}\n", next(), next()))
        .collect();
    std::fs::write(&input, text).unwrap();
    let input = input.to_str().unwrap();
    for command in [
        &["triangulate", input, "--edges", "-q"][..],
        &[
            "reconstruct",
            input,
            "--sequential",
            "--format",
            "edges",
            "-q",
        ],
    ] {
        let normal = run_limited(command, None, Some(2));
        assert!(normal.status.success(), "{command:?}");
        assert!(normal.stdout.len() > 100_000, "{command:?}: a large output");
        // The main thread and rayon's two: nothing more can start.
        let limited = run_limited(command, Some(3), Some(2));
        let stderr = String::from_utf8_lossy(&limited.stderr);
        assert!(!stderr.contains("panicked"), "{command:?}: {stderr}");
        assert_eq!(limited.status.code(), Some(0), "{command:?}: {stderr}");
        assert!(
            limited.stdout == normal.stdout,
            "{command:?}: the same output"
        );
    }
}

/// Under `ulimit -v` (RLIMIT_AS), a file too large to read is refused citing the memory the
/// limit leaves, not the machine's (a reviewer's report: under `ulimit -v 30000` the message
/// cited the 24 GB of the machine). The file is sparse: a gigabyte that takes no disk.
#[test]
fn a_file_larger_than_the_address_space_limit_is_measured_against_it() {
    const LIMIT: u64 = 512 << 20;
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("huge.csv");
    std::fs::File::create(&input)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    let mut command = Command::new(binary());
    command
        .args(["triangulate".as_ref(), input.as_os_str()])
        .env("RAYON_NUM_THREADS", "2");
    // SAFETY: `setrlimit` is async-signal-safe, as `pre_exec` requires.
    unsafe {
        command.pre_exec(|| {
            let limit = libc::rlimit {
                rlim_cur: LIMIT as libc::rlim_t,
                rlim_max: LIMIT as libc::rlim_t,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let out = command.output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("huge.csv"), "{stderr}");
    let cited: u64 = stderr
        .split("would not fit in the ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no memory cited: {stderr}"));
    assert!(
        cited < LIMIT,
        "{cited} bytes cited under a limit of {LIMIT}: {stderr}"
    );
}
