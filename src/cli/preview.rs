//! `parallax preview DIR [--frame K] [-o OUT]`: colour-coded PNGs of one
//! native frame's ground truth (`crate::preview`). A missing directory or
//! file, or a map of the wrong size, exits 2 naming it, before anything is
//! written.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::preview::{first_frame, read_frame, write_previews};

/// Arguments of `parallax preview`.
#[derive(Args, Debug)]
pub struct PreviewArgs {
    /// A `parallax render` output directory or a dataset sequence directory.
    pub dir: PathBuf,
    /// The frame to show (default: the first frame in DIR/left/depth).
    #[arg(long)]
    pub frame: Option<u32>,
    /// Output directory (default: DIR/preview).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Runs `parallax preview`.
pub fn run(a: PreviewArgs) -> Result<(), CliError> {
    let input = |e: std::io::Error| CliError::input(e.to_string());
    let frame = match a.frame {
        Some(k) => k,
        None if !a.dir.is_dir() => {
            return Err(CliError::input(format!(
                "{}: not a directory",
                a.dir.display()
            )))
        }
        None => first_frame(&a.dir).map_err(input)?,
    };
    let maps = read_frame(&a.dir, frame).map_err(input)?;
    let out = a
        .output
        .unwrap_or_else(|| a.dir.join(crate::output::PREVIEW_DIR));
    let files = write_previews(&maps, &out).map_err(|e| CliError::failure(e.to_string()))?;
    println!("wrote {} preview PNGs to {}", files.len(), out.display());
    Ok(())
}
