//! `parallax eval --gt OUT --pred PRED [--layout L] [--fill none|kitti]
//! [--json FILE]`: stereo metrics of predictions against a native
//! ground-truth tree (`crate::eval`). Every bad
//! input (missing directory, unreadable or wrongly sized file) exits 2 naming
//! the path.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::eval::{evaluate, format_table, EvalOptions, Fill};
use crate::output::layouts::LayoutKind;

/// Arguments of `parallax eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Ground truth: a native dataset or `parallax render` output directory.
    #[arg(long)]
    pub gt: PathBuf,
    /// Predictions: mirror each `baseline_XXX/disp/NNNNNN.pfm` of the ground
    /// truth (as laid out by --layout), as .pfm, .png (16-bit, ×256, 0 =
    /// none), .exr or .npy.
    #[arg(long)]
    pub pred: PathBuf,
    /// Layout the predictions mirror: native, kitti (disp_occ_0 names),
    /// sceneflow (disparity/…/left) or stereocarla (depth path, `disp` for `depth`).
    #[arg(long, default_value = "native", value_parser = |s: &str| s.parse::<LayoutKind>())]
    pub layout: LayoutKind,
    /// Missing predictions: `none` counts them as errors in D1/bad-x (EPE over
    /// predicted pixels); `kitti` fills them first as the KITTI devkit does.
    #[arg(long, default_value = "none", value_parser = |s: &str| s.parse::<Fill>())]
    pub fill: Fill,
    /// Also write the full report as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// Runs `parallax eval`.
pub fn run(a: EvalArgs) -> Result<(), CliError> {
    let opts = EvalOptions {
        layout: a.layout,
        fill: a.fill,
    };
    let report = evaluate(&a.gt, &a.pred, &opts).map_err(|e| CliError::input(e.to_string()))?;
    if let Some(path) = &a.json {
        crate::output::write_json(path, &report).map_err(|e| CliError::failure(e.to_string()))?;
    }
    print!("{}", format_table(&report));
    Ok(())
}
