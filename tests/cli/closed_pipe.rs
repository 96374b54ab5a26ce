//! `parallax … | head`: a reader that closes stdout early ends the process
//! quietly by SIGPIPE, as any Unix filter, not with a panic message.

use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::process::Stdio;

use crate::common::cli::{parallax, repo};

#[test]
fn a_closed_stdout_ends_the_process_by_sigpipe_without_a_panic() {
    // Thousands of JSON lines: far more than a pipe buffers.
    let mut child = parallax(&["town", "town01", "--seed", "1", "--trajectory", "3000"])
        .current_dir(repo())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut head = [0u8; 100];
    child.stdout.take().unwrap().read_exact(&mut head).unwrap();
    // The read end is dropped here: later writes hit a closed pipe.
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(
        out.status.signal(),
        Some(libc::SIGPIPE),
        "{:?} {stderr}",
        out.status
    );
}
