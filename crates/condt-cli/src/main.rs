//! The `condt` command-line tool: argument parsing and messages live in [`cli`], where the
//! output goes in [`output`]; everything it computes comes from the library.

mod cli;
mod options;
mod output;
mod progress;
mod score;
mod timings;

/// Large blocks recycled instead of faulted in again (the `condt-alloc` crate says why).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[global_allocator]
static ALLOCATOR: condt_alloc::Recycling = condt_alloc::Recycling::new();

fn main() {
    // A file-size limit makes writes fail (an error, the temporary file removed) rather than
    // end the process by SIGXFSZ.
    output::survive_file_size_limit();
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
