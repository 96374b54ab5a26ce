//! `parallax preview DIR [--frame K] [-o OUT]`: colour-coded PNGs of one
//! native frame's ground truth (`crate::preview`). A missing directory or
//! file, or a map of the wrong size, exits 2 naming it, before anything is
//! written.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::preview::{read_frame, write_previews};

/// Arguments of `parallax preview`.
#[derive(Args, Debug)]
pub struct PreviewArgs {
    /// A `parallax render` output directory or a dataset sequence directory.
    pub dir: PathBuf,
    /// The frame to show.
    #[arg(long, default_value_t = 0)]
    pub frame: u32,
    /// Output directory (default: DIR/preview).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Runs `parallax preview`.
pub fn run(a: PreviewArgs) -> Result<(), CliError> {
    let maps = read_frame(&a.dir, a.frame).map_err(|e| CliError::input(e.to_string()))?;
    let out = a.output.unwrap_or_else(|| a.dir.join("preview"));
    let files = write_previews(&maps, &out).map_err(|e| CliError::failure(e.to_string()))?;
    println!("wrote {} preview PNGs to {}", files.len(), out.display());
    Ok(())
}
