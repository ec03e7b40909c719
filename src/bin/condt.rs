//! The `condt` command-line tool; all logic lives in `condt::cli`.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match condt::cli::run(&args) {
        Ok(text) => print!("{text}"),
        Err(err) => {
            eprintln!("condt: {err}");
            std::process::exit(err.exit_code());
        }
    }
}
