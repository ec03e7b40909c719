//! The `condt` command-line tool: argument parsing and messages live in [`cli`], where the
//! output goes in [`output`]; everything it computes comes from the library.

mod cli;
mod output;

use std::io::Write;

fn main() {
    // File names need not be UTF-8: the arguments are taken as the OS gives them.
    let args: Vec<std::ffi::OsString> = std::env::args_os().skip(1).collect();
    let code = match cli::run(&args) {
        Ok(text) => {
            let mut stdout = std::io::stdout().lock();
            match stdout
                .write_all(text.as_bytes())
                .and_then(|()| stdout.flush())
            {
                Ok(()) => 0,
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                    output::end_by_broken_pipe()
                }
                Err(e) => {
                    cli::note(format_args!("<stdout>: {e}"));
                    1
                }
            }
        }
        Err(cli::CliError::BrokenPipe) => output::end_by_broken_pipe(),
        Err(err) => {
            cli::note(format_args!("{err}"));
            err.exit_code()
        }
    };
    std::process::exit(code);
}
