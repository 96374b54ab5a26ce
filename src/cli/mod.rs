//! The command line (the only home of `clap`): `render`, `town`, `bench`,
//! `dataset`, `verify`, `eval`, `stats`, `preview` and `export`.
//! Errors surface as one message naming the file, field or argument, and a
//! non-zero exit code; nothing is written before the inputs are validated.

mod bench;
mod dataset;
mod eval;
mod export;
mod preview;
mod render;
mod stats;
mod town;
mod verify;

use clap::{Parser, Subcommand};

/// Exit code for invalid input (scene file, arguments).
pub const EXIT_BAD_INPUT: i32 = 2;
/// Exit code for a failure while rendering or writing.
pub const EXIT_FAILURE: i32 = 1;

/// A CLI error with its exit code.
#[derive(Debug)]
pub struct CliError {
    /// Human-readable message (names the file, field or argument).
    pub message: String,
    /// Process exit code.
    pub code: i32,
}

impl CliError {
    /// An input error (exit 2).
    pub fn input(message: impl Into<String>) -> Self {
        CliError {
            message: message.into(),
            code: EXIT_BAD_INPUT,
        }
    }
    /// A runtime failure (exit 1).
    pub fn failure(message: impl Into<String>) -> Self {
        CliError {
            message: message.into(),
            code: EXIT_FAILURE,
        }
    }
}

#[derive(Parser, Debug)]
#[command(
    name = "parallax",
    version,
    about = "Path-traced stereo datasets with exact ground truth"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render one stereo frame of a scene in the native layout.
    Render(render::RenderArgs),
    /// Generate a town frame: sizes, build times, optional OBJ export.
    Town(town::TownArgs),
    /// Measure BVH build, ground-truth and path-tracing throughput against raw traversal.
    Bench(bench::BenchArgs),
    /// Score predicted disparities against a native ground-truth tree.
    Eval(eval::EvalArgs),
    /// Disparity statistics and frame counts of a native dataset.
    Stats(stats::StatsArgs),
    /// Generate (or resume) a dataset from a configuration or preset; --shard i/N is 1-based.
    Dataset(dataset::DatasetArgs),
    /// Check a dataset's manifests and checksums; --repair re-renders bad frames.
    Verify(verify::VerifyArgs),
    /// Write a frame as a Mitsuba 3 scene (XML + PLY meshes) for comparison.
    Export(export::ExportArgs),
    /// Colour-coded PNGs of a native frame's ground truth (depth, disparity, semantic, instance, mask, occlusion).
    Preview(preview::PreviewArgs),
}

/// Runs the CLI on `args` (including the program name).
pub fn run<I, T>(args: I) -> Result<(), CliError>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            // --help and --version are not errors.
            if matches!(
                e.kind(),
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion
            ) {
                print!("{e}");
                return Ok(());
            }
            // main prints "error: " before every message; clap's has its own.
            let text = e.to_string();
            let text = text.strip_prefix("error: ").unwrap_or(&text).trim_end();
            return Err(CliError::input(text));
        }
    };
    match cli.command {
        Command::Render(a) => render::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Town(a) => town::run(a),
        Command::Eval(a) => eval::run(a),
        Command::Stats(a) => stats::run(a),
        Command::Dataset(a) => dataset::run(a),
        Command::Verify(a) => verify::run(a),
        Command::Preview(a) => preview::run(a),
        Command::Export(a) => export::run(a),
    }
}

/// Baselines in centimetres from the command line.
#[derive(Clone, Debug, PartialEq)]
pub struct BaselinesCm(pub Vec<f64>);

/// Parses a comma-separated list of baselines in centimetres (`10,54,100`).
fn parse_baselines(s: &str) -> Result<BaselinesCm, String> {
    s.split(',')
        .map(|t| {
            let v: f64 = t.trim().parse().map_err(|_| {
                format!("'{t}' is not a number (baselines are centimetres, e.g. 10,54,100)")
            })?;
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("baseline {t} cm must be positive"));
            }
            Ok(v)
        })
        .collect::<Result<Vec<_>, _>>()
        .and_then(|v| match crate::output::check_baseline_dirs(&v) {
            Ok(()) => Ok(BaselinesCm(v)),
            Err(e) => Err(e.to_string()),
        })
}

/// Builds the rayon pool for `--threads` (0 = all cores).
fn thread_pool(threads: usize) -> Result<rayon::ThreadPool, CliError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::failure(format!("cannot start {threads} threads: {e}")))
}

/// A path argument shown in messages.
fn show(p: &std::path::Path) -> String {
    p.display().to_string()
}
