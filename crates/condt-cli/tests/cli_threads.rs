//! A run whose worker threads cannot be started (a limit on processes, as a container's pids
//! limit sets) falls back to one thread with a note and writes the same output: never a panic.

#![cfg(unix)]

use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Command, Output};

fn shapes() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes.txt")
}

/// `condt ARGS`, with or without a starved thread pool.
fn run(args: &[&str], starved: bool) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_condt"));
    command.args(args);
    if starved {
        // Allowed one process, no thread can be started; root is exempt from the limit, so
        // as root the child first becomes the unprivileged user 65534.
        // SAFETY: `setrlimit` and `setuid` are async-signal-safe, as `pre_exec` requires.
        unsafe {
            command.pre_exec(|| {
                let limit = libc::rlimit {
                    rlim_cur: 1,
                    rlim_max: 1,
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
