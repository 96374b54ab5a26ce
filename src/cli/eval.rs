//! `parallax eval --gt OUT --pred PRED [--json FILE]`: stereo metrics of
//! predictions against a native ground-truth tree (`crate::eval`). Every bad
//! input (missing directory, unreadable or wrongly sized file) exits 2 naming
//! the path.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::eval::{evaluate, format_table};

/// Arguments of `parallax eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Ground truth: a native dataset or `parallax render` output directory.
    #[arg(long)]
    pub gt: PathBuf,
    /// Predictions: mirror each `baseline_XXX/disp/NNNNNN.pfm` of the ground
    /// truth, as .pfm, .png (16-bit, ×256), .exr or .npy.
    #[arg(long)]
    pub pred: PathBuf,
    /// Also write the full report as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// Runs `parallax eval`.
pub fn run(a: EvalArgs) -> Result<(), CliError> {
    let report = evaluate(&a.gt, &a.pred).map_err(|e| CliError::input(e.to_string()))?;
    if let Some(path) = &a.json {
        crate::output::write_json(path, &report).map_err(|e| CliError::failure(e.to_string()))?;
    }
    print!("{}", format_table(&report));
    Ok(())
}
