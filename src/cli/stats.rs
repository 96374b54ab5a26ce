//! `parallax stats OUT [--plot DIR] [--json FILE]`: disparity range, mean and
//! median per baseline and overall, frame counts per town, configuration and
//! weather (`crate::stats`). A missing or empty directory exits 2 naming it.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::stats::{dataset_stats, format_stats, write_histogram_plots};

/// Arguments of `parallax stats`.
#[derive(Args, Debug)]
pub struct StatsArgs {
    /// A native dataset or `parallax render` output directory.
    pub dir: PathBuf,
    /// Write histogram plots (PNG) and their bins (CSV) into this directory.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Also write the statistics as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// Runs `parallax stats`.
pub fn run(a: StatsArgs) -> Result<(), CliError> {
    let r = dataset_stats(&a.dir).map_err(|e| CliError::input(e.to_string()))?;
    print!("{}", format_stats(&r.stats));
    if let Some(dir) = &a.plot {
        let files = write_histogram_plots(dir, &r.overall, &r.per_baseline)
            .map_err(|e| CliError::failure(e.to_string()))?;
        println!("wrote {} plot files to {}", files.len(), dir.display());
    }
    if let Some(path) = &a.json {
        crate::output::write_json(path, &r.stats).map_err(|e| CliError::failure(e.to_string()))?;
    }
    Ok(())
}
