//! The `condt` command-line tool: argument parsing and messages live in [`cli`]; everything it
//! computes comes from the library.

mod cli;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match cli::run(&args) {
        Ok(text) => print!("{text}"),
        Err(err) => {
            eprintln!("condt: {err}");
            std::process::exit(err.exit_code());
        }
    }
}
