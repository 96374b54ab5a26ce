//! The `parallax` binary: hands the arguments to the CLI and maps errors to exit codes.

fn main() {
    if let Err(e) = parallax::cli::run(std::env::args_os()) {
        eprintln!("error: {}", e.message);
        std::process::exit(e.code);
    }
}
