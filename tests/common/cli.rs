//! The real `parallax` binary, as every command-line test runs it.

use std::path::Path;
use std::process::{Command, Output};

/// The parallax binary with `args`, cut off from a batch engine's shard
/// variables (a `dataset` would otherwise take its shard from the
/// environment the tests run in).
pub fn parallax(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_parallax"));
    c.args(args);
    c.env_remove("SLURM_ARRAY_TASK_ID");
    c.env_remove("JOB_COMPLETION_INDEX");
    c
}

/// The repository root: relative paths such as `scenes/street.toml` in
/// arguments resolve against it.
pub fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `parallax render scenes/street.toml` at `w`×`h`, 2 spp, one 54 cm
/// baseline, 2 threads, sample seed `seed`, into `out`, then `extra`.
pub fn render_street(out: &Path, (w, h): (u32, u32), seed: u64, extra: &[&str]) -> Command {
    let scene = repo().join("scenes").join("street.toml");
    let (w, h, seed) = (w.to_string(), h.to_string(), seed.to_string());
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "--width",
        &w,
        "--height",
        &h,
        "--spp",
        "2",
        "--baselines",
        "54",
        "--seed",
        &seed,
        "--threads",
        "2",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    parallax(&args)
}

/// Runs the binary with `args` in the working directory `cwd`.
pub fn parallax_in(cwd: &Path, args: &[&str]) -> Output {
    parallax(args).current_dir(cwd).output().unwrap()
}

/// Runs the binary with `args` in the repository root.
pub fn parallax_run(args: &[&str]) -> Output {
    parallax_in(repo(), args)
}

/// Runs the binary with `args` in `cwd`; panics with its exit code and
/// output unless it succeeded.
pub fn parallax_ok(cwd: &Path, args: &[&str]) -> Output {
    let o = parallax_in(cwd, args);
    assert!(
        o.status.success(),
        "{args:?}: exit {:?}\n{}{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// Runs the binary with `args` in the repository root: its exit code (−1
/// when killed by a signal) and stderr.
pub fn parallax_status(args: &[&str]) -> (i32, String) {
    let o = parallax_run(args);
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}
