//! `parallax dataset [CONFIG.toml | --preset NAME] -o OUT [--shard i/N]
//! [--dry-run] [--force]`: generate, resume or plan a dataset.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use super::{show, thread_pool, CliError};
use crate::accel::Backend;
use crate::dataset::frame::Towns;
use crate::dataset::{self as ds, DatasetConfig, RunOptions, Shard, StopGuard};
use crate::weather::Weather;

/// Arguments of `parallax dataset`.
#[derive(Args, Debug)]
pub struct DatasetArgs {
    /// Dataset configuration (TOML); omit with --preset.
    #[arg(conflicts_with = "preset", required_unless_present = "preset")]
    pub config: Option<PathBuf>,
    /// Built-in configuration: demo (minutes on 2 cores) or stereocarla
    /// (StereoCarla's full axes and counts, ~139k left frames; for clusters).
    #[arg(long)]
    pub preset: Option<String>,
    /// Dataset root (created; an existing root of the same configuration is resumed).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Render only shard i of N (1-based: 1/4 … 4/4). Without it, the shard is
    /// read from SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT (and
    /// SLURM_ARRAY_TASK_MIN) or from a Kubernetes Indexed Job's
    /// JOB_COMPLETION_INDEX (0-based) with PARALLAX_SHARD_COUNT; else all jobs.
    #[arg(long, value_parser = Shard::parse)]
    pub shard: Option<Shard>,
    /// Print the plan (frames, images, estimated core-hours from a short
    /// calibration render) and exit without writing.
    #[arg(long)]
    pub dry_run: bool,
    /// Start over in a non-empty directory holding another configuration
    /// (that dataset's frames and manifests are removed; other files stay).
    #[arg(long)]
    pub force: bool,
    /// On resume, check the SHA-256 of complete frames (not only their sizes).
    #[arg(long)]
    pub check_hashes: bool,
    /// Directory holding the town files (NAME.toml), instead of the
    /// built-in town descriptions.
    #[arg(long)]
    pub scenes: Option<PathBuf>,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Traversal backend: embree or bvh.
    #[arg(long, default_value_t = Backend::default_backend())]
    pub backend: Backend,
}

fn resolve_config(a: &DatasetArgs) -> Result<DatasetConfig, CliError> {
    match (&a.config, &a.preset) {
        (Some(path), _) => ds::load_config(path).map_err(|e| CliError::input(e.to_string())),
        (None, Some(name)) => ds::presets::preset(name).map_err(CliError::input),
        (None, None) => Err(CliError::input("give a CONFIG file or --preset NAME")),
    }
}

fn resolve_shard(a: &DatasetArgs) -> Result<Shard, CliError> {
    if let Some(s) = a.shard {
        return Ok(s);
    }
    let env = |k: &str| std::env::var(k).ok();
    Ok(Shard::from_env(&env)
        .map_err(CliError::input)?
        .unwrap_or(Shard::ALL))
}

impl From<ds::DatasetError> for CliError {
    fn from(e: ds::DatasetError) -> Self {
        if e.input {
            CliError::input(e.message)
        } else {
            CliError::failure(e.message)
        }
    }
}

/// Runs `parallax dataset`.
pub fn run(a: DatasetArgs) -> Result<(), CliError> {
    let config = resolve_config(&a)?;
    let shard = resolve_shard(&a)?;
    let pool = thread_pool(a.threads)?;
    if config.filter && config.denoiser.needs_oidn() {
        // Before any frame: every one would fail alike.
        crate::denoise::oidn::check().map_err(|e| {
            CliError::input(format!("config denoiser \"{}\": {e}", config.denoiser))
        })?;
    }
    if a.dry_run {
        return pool.install(|| dry_run(&config, &a, shard));
    }
    let opts = RunOptions {
        root: a.output.clone(),
        shard,
        force: a.force,
        check_hashes: a.check_hashes,
        backend: a.backend,
        scenes: a.scenes.clone(),
        only: None,
    };
    let stop = StopGuard::new();
    let root = show(&a.output);
    stop.install(move || {
        eprintln!("parallax: stopped; run the same command again to resume in {root}")
    })
    .map_err(CliError::failure)?;
    let summary = pool
        .install(|| ds::run_dataset(&config, &opts, &stop))
        .map_err(CliError::from)?;
    if stop.stopped() {
        // The loop saw the signal before the handler's thread exited: still
        // an interrupted run (exit 130), never a success.
        return Err(CliError {
            message: format!(
                "stopped by a signal after {} frames; run the same command again to resume in {}",
                summary.done,
                show(&a.output)
            ),
            code: ds::signals::EXIT_INTERRUPTED,
        });
    }
    println!(
        "dataset {} shard {}: {} frames done, {} skipped, {} failed",
        show(&a.output),
        shard,
        summary.done,
        summary.skipped,
        summary.failed.len()
    );
    if !summary.failed.is_empty() {
        return Err(CliError::failure(format!(
            "{} frames failed (listed in {}/failures/)",
            summary.failed.len(),
            show(&a.output)
        )));
    }
    Ok(())
}

fn dry_run(config: &DatasetConfig, a: &DatasetArgs, shard: Shard) -> Result<(), CliError> {
    let towns = Towns::load(config, a.scenes.as_deref()).map_err(CliError::input)?;
    let frames = ds::plan::frame_count(config);
    println!(
        "plan: {} towns × {} configurations × {} weathers × {} sequences × {} frames = {} frames",
        config.towns.len(),
        config.configs.len(),
        config.weathers.len(),
        config.sequences,
        config.frames_per_sequence,
        frames,
    );
    println!(
        "      {} RGB images ({} views per frame), {}×{} px, {}, baselines {:?} cm, layouts {}",
        frames * (1 + config.baselines_cm.len() as u64),
        1 + config.baselines_cm.len(),
        config.width,
        config.height,
        spp_text(config),
        config.baselines_cm,
        config
            .layouts
            .iter()
            .map(|k| k.name())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let threads = rayon::current_num_threads();
    let t0 = Instant::now();
    let q = ds::calibrate::calibration_quality(
        config,
        ds::estimate::class_mix(config, Shard::ALL).len(),
    );
    println!(
        "calibrating each (town, weather) class on one {}×{} {} spp frame (CPU time, {threads} threads):",
        q.width, q.height, q.spp
    );
    let note = |c: &ds::estimate::ClassCost| {
        let on = c.calibrated_on.as_ref().map_or(String::new(), |j| {
            format!(" ({} frame {})", j.config.name(), j.frame)
        });
        println!(
            "  {} {}{on}: {:.2} core-s fixed + {:.3} µs/pixel + {:.3} µs/pixel-sample → {:.2} s per frame",
            c.town,
            c.weather.name(),
            c.fixed,
            c.per_pixel * 1e6,
            c.per_sample * 1e6,
            c.frame_seconds(config, threads)
        );
    };
    let cal =
        ds::calibrate::calibrate(config, &towns, a.backend, q, &note).map_err(CliError::failure)?;
    let e =
        ds::estimate::estimate(config, &cal.costs, shard, threads).map_err(CliError::failure)?;
    println!(
        "  writing {} files per frame: {:.3} µs/pixel + {:.2} s waiting (timed once in a temporary directory)",
        e.files_per_frame,
        cal.costs[0].write_per_pixel * 1e6,
        cal.costs[0].write_wait
    );
    println!(
        "estimate: {:.2} s per frame on {} threads ({:.2} core-s of CPU; mean over the plan's mix), \
         {} core-hours in all, {} for the {} frames of shard {shard} (calibrated in {:.1} s)",
        e.seconds_per_frame,
        e.cores,
        e.cpu_seconds_per_frame,
        hours(e.core_hours),
        hours(e.shard_core_hours),
        e.frames_in_shard,
        t0.elapsed().as_secs_f64(),
    );
    Ok(())
}

/// The plan's samples per pixel, with the foggy frames' where they differ.
fn spp_text(config: &DatasetConfig) -> String {
    let spp = config.spp();
    let fog = config.frame_spp(Weather::Foggy, spp);
    let has_fog = config.weathers.iter().any(|w| w == Weather::Foggy.name());
    if has_fog && fog != spp {
        format!("{spp} spp ({fog} in fog)")
    } else {
        format!("{spp} spp")
    }
}

/// Core-hours with the precision their size deserves.
fn hours(h: f64) -> String {
    match h {
        h if h >= 100.0 => format!("{h:.0}"),
        h if h >= 1.0 => format!("{h:.1}"),
        h => format!("{h:.3}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plan_shows_the_foggy_frames_sample_count_where_it_differs() {
        let config = |extra: &str| {
            let text = format!("seed = 1\ntowns = [\"town01\"]\nframes_per_sequence = 1\n{extra}");
            ds::parse_config(&text, "c.toml").unwrap()
        };
        let fog = "weathers = [\"clear\", \"foggy\"]\n";
        assert_eq!(spp_text(&config(fog)), "64 spp (48 in fog)");
        assert_eq!(spp_text(&config(&format!("{fog}spp = 64\n"))), "64 spp");
        assert_eq!(spp_text(&config("weathers = [\"clear\"]\n")), "64 spp");
    }
}
