//! `parallax verify ROOT [--repair]`: check every manifest line and checksum
//! of a dataset; report missing, corrupted, duplicate and extra; repair by
//! re-rendering exactly the bad frames.

use std::path::PathBuf;

use clap::Args;

use super::{show, thread_pool, CliError};
use crate::accel::Backend;
use crate::dataset::frame::Towns;
use crate::dataset::{self as ds, RunOptions, Shard, StopGuard};

/// Arguments of `parallax verify`.
#[derive(Args, Debug)]
#[command(after_help = "\
Files that are not the dataset's are listed as \"extra, kept\" and never \
removed; they do not make the dataset incomplete. The dataset's files are \
those its manifest lines name, the native-layout files of planned frames \
(<town>/<config>_<weather>/<seq>/.../NNNNNN.*) and the atomic writers' \
temporary files (*.tmp-<pid>-<n>).")]
pub struct VerifyArgs {
    /// Dataset root (holding dataset.json and manifest/).
    pub root: PathBuf,
    /// Re-render missing, corrupted and duplicated frames, then drop their
    /// old manifest lines and remove the dataset's extra files (a frame that
    /// cannot be rendered keeps its lines and files), then verify again.
    #[arg(long)]
    pub repair: bool,
    /// Directory holding the town files (NAME.toml) for --repair, instead
    /// of the built-in town descriptions.
    #[arg(long)]
    pub scenes: Option<PathBuf>,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Traversal backend (with --repair).
    #[arg(long, default_value_t = Backend::default_backend())]
    pub backend: Backend,
}

/// Runs `parallax verify`.
pub fn run(a: VerifyArgs) -> Result<(), CliError> {
    let report = ds::verify_dataset(&a.root).map_err(CliError::from)?;
    print!("{}", report.text());
    if report.is_whole() {
        println!("{}: whole", show(&a.root));
        return Ok(());
    }
    if !a.repair {
        return Err(CliError::failure(format!(
            "{}: not whole (run with --repair to fix)",
            show(&a.root)
        )));
    }
    let config = ds::verify::dataset_config(&a.root).map_err(CliError::from)?;
    // Nothing changes before the frames are rendered: other town
    // descriptions than the recorded ones are refused first.
    let towns = Towns::load(&config, a.scenes.as_deref()).map_err(CliError::input)?;
    if let Ok(Some(meta)) = ds::manifest::read_meta(&a.root) {
        meta.check_towns(&towns.sources(&config))
            .map_err(CliError::input)?;
    }
    let staged = ds::repair::stage(&a.root, &report).map_err(CliError::from)?;
    println!("repair: re-rendering {} frames", staged.redo.len());
    let stop = StopGuard::new();
    if !staged.redo.is_empty() {
        let opts = RunOptions {
            root: a.root.clone(),
            shard: Shard::ALL,
            force: false,
            check_hashes: true,
            backend: a.backend,
            scenes: a.scenes.clone(),
            only: Some(staged.redo.clone()),
        };
        stop.install(|| eprintln!("parallax: repair stopped; run verify --repair again"))
            .map_err(CliError::failure)?;
        let pool = thread_pool(a.threads)?;
        pool.install(|| ds::run_dataset(&config, &opts, &stop))
            .map_err(|mut e| {
                e.message += "; the repair dropped no manifest line and removed no file";
                CliError::from(e)
            })?;
    }
    let done = ds::repair::finish(&a.root, &staged).map_err(CliError::from)?;
    println!(
        "repair: {} frames replaced, {} not rendered (left as they were), {} manifest lines dropped, {} files removed",
        done.replaced,
        done.not_rendered,
        done.lines_dropped,
        done.removed.len()
    );
    let after = ds::verify_dataset(&a.root).map_err(CliError::from)?;
    print!("after repair: {}", after.text());
    if after.is_whole() {
        println!("{}: whole", show(&a.root));
        Ok(())
    } else {
        Err(CliError::failure(format!(
            "{}: still not whole after repair",
            show(&a.root)
        )))
    }
}
