//! The `parallax` binary: hands the arguments to the CLI and maps errors to exit codes.

fn main() {
    // A closed pipe on stdout (`parallax … | head`) ends the process quietly,
    // as it does every Unix filter, instead of a panic in `println!`.
    // SAFETY: called before any thread starts; SIG_DFL is a valid disposition.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    if let Err(e) = parallax::cli::run(std::env::args_os()) {
        eprintln!("error: {}", e.message);
        std::process::exit(e.code);
    }
}
