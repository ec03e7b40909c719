//! The `condt` command-line tool: argument parsing and messages live in [`cli`], where the
//! output goes in [`output`]; everything it computes comes from the library.

mod cli;
mod output;
mod score;
mod timings;

fn main() {
    release_large_blocks();
    // File names need not be UTF-8: the arguments are taken as the OS gives them.
    let args: Vec<std::ffi::OsString> = std::env::args_os().skip(1).collect();
    // What `run` returns (help, or results without -o) goes out as -o - would.
    let result = cli::run(&args)
        .and_then(|text| output::Destination::Stdout.write(|out| out.write_all(text.as_bytes())));
    let code = match result {
        Ok(()) => 0,
        Err(cli::CliError::BrokenPipe) => output::end_by_broken_pipe(),
        Err(err) => {
            cli::note(format_args!("{err}"));
            err.exit_code()
        }
    };
    std::process::exit(code);
}

/// glibc's allocator serves a block of at least `M_MMAP_THRESHOLD` bytes with a mapping of its
/// own, returned to the system when freed; smaller ones come from its heap, which keeps freed
/// space in the middle for reuse. The threshold starts at 128 KiB, but by default glibc raises it
/// to the size of every mapped block freed (up to 32 MiB), so after the first large buffer of a
/// run is freed, every later one up to that size comes from the heap and stays there: at 1M
/// points, where the per-point arrays are 4 to 24 MB, `reconstruct` peaked at 119,768 kB
/// instead of 109,560 (uniform points, whose smoothing passes free and allocate them four times:
/// 251,812 kB instead of 150,608). Setting the threshold fixes it at 128 KiB and turns the
/// raising off (the glibc manual, "Malloc Tunable Parameters"), so the peak follows what the
/// library holds at every size; above 32M bytes a block was always mapped, so nothing changes
/// there. Other allocators do not have the parameter.
fn release_large_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        /// 128 KiB, glibc's default, kept fixed.
        const MMAP_THRESHOLD: libc::c_int = 128 * 1024;
        // SAFETY: `mallopt` sets a parameter of the allocator and returns 0 when it refuses the
        // value (then the default stands, which is harmless); it is called before any other
        // thread exists.
        unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        }
    }
}
