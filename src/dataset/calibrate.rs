//! Measures the per-class costs of `estimate` by rendering one calibration
//! frame of every (town, weather) class of the plan, at a reduced size and
//! spp, timed in process CPU seconds (all threads): unlike wall time, CPU
//! time hardly moves when other programs share the machine, so the estimate
//! is stable from run to run.
//!
//! The render's progress callback marks where the path pass starts and
//! ends, which splits a frame's CPU time into the build and ground truth
//! (before), the path pass (between) and the post-processing (after). The
//! ground truth's share of "before" is its wall time at the path pass's
//! CPU/wall ratio (both run on every thread). The path pass also holds
//! per-pixel work (image filter, pixel set-up): the first class, rendered
//! first at four times the spp, gives its per-pixel share by difference,
//! applied to every class. That render also pays the process's one-time
//! set-up, which a real run pays once per shard, not per frame. The first
//! class's frame is also written, once, to a temporary directory (removed
//! after) to time encoding and the disk.

use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Instant;

use super::config::DatasetConfig;
use super::estimate::{calibration_job, class_mix, ClassCost};
use super::frame::{render_job, write_job, Quality, StaticCache, Towns};
use super::shard::Shard;
use crate::accel::Backend;

/// Calibration pixels over all classes: 160×90 each for up to 8 classes,
/// fewer each for more classes (bounded below by `MIN_PIXELS`).
const BUDGET_PIXELS: u64 = 8 * 160 * 90;
/// The smallest calibration frame, pixels (64×36).
const MIN_PIXELS: u64 = 64 * 36;
/// The largest calibration frame, pixels (160×90).
const MAX_PIXELS: u64 = 160 * 90;
/// The most samples per pixel a calibration frame takes.
const MAX_SPP: u32 = 2;
/// The first class is rendered again at this many times the spp.
const INTERCEPT_SPP_FACTOR: u32 = 4;

/// Seconds of CPU the process has used so far, over all its threads.
pub fn process_cpu_seconds() -> f64 {
    // SAFETY: getrusage only writes the struct it is given.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) } != 0 {
        return 0.0;
    }
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

/// The calibration frame's size and spp for a plan of `classes` classes:
/// the configuration's aspect, `BUDGET_PIXELS` shared between the classes
/// (within `MIN_PIXELS`..=`MAX_PIXELS`, never above the configuration's
/// size), at most `MAX_SPP` samples.
pub fn calibration_quality(config: &DatasetConfig, classes: usize) -> Quality {
    let full = config.width as u64 * config.height as u64;
    let px = (BUDGET_PIXELS / classes.max(1) as u64)
        .clamp(MIN_PIXELS, MAX_PIXELS)
        .min(full) as f64;
    let aspect = config.width as f64 / config.height as f64;
    let width = ((px * aspect).sqrt().round() as u32).clamp(1, config.width);
    let height = ((width as f64 / aspect).round() as u32).clamp(1, config.height);
    Quality {
        width,
        height,
        spp: config.spp().min(MAX_SPP),
    }
}

/// What the calibration measured.
pub struct Calibration {
    /// Per class, in plan order.
    pub costs: Vec<ClassCost>,
}

/// Renders one calibration frame per class of `config` at `quality` (the
/// caller's [`calibration_quality`], computed once) and returns the
/// classes' costs; `note` is told about each class as it is measured.
pub fn calibrate(
    config: &DatasetConfig,
    towns: &Towns,
    backend: Backend,
    quality: Quality,
    note: &dyn Fn(&ClassCost),
) -> Result<Calibration, String> {
    let mix = class_mix(config, Shard::ALL);
    let ((town, weather), _, _) = mix.first().ok_or("the plan is empty")?;
    // The first class at INTERCEPT_SPP_FACTOR × the spp: the path pass's
    // per-pixel share (image filter, per-pixel set-up), which one spp
    // cannot tell from per-sample work. Also pays the one-time set-up.
    let job = calibration_job(config, 0, town, *weather);
    let hi = Quality {
        spp: quality.spp * INTERCEPT_SPP_FACTOR,
        ..quality
    };
    let path_hi = measure(config, towns, &job, hi, backend, false)?.1;
    let pixels = quality.width as f64 * quality.height as f64;
    let mut path_per_pixel = None;
    let mut costs: Vec<ClassCost> = Vec::with_capacity(mix.len());
    for (k, ((town, weather), _, _)) in mix.iter().enumerate() {
        let job = calibration_job(config, k, town, *weather);
        let (mut cost, path) = measure(config, towns, &job, quality, backend, k == 0)?;
        let per_pixel = *path_per_pixel.get_or_insert_with(|| {
            let per_spp = (path_hi - path).max(0.0) / (hi.spp - quality.spp) as f64;
            (path - per_spp * quality.spp as f64).max(0.0) / pixels
        });
        // At most 90 % of a class's path time is per pixel.
        let share = (per_pixel * pixels).min(0.9 * path);
        cost.per_pixel += share / pixels;
        cost.per_sample = (path - share) / (pixels * quality.spp as f64);
        cost.calibrated_on = Some(job);
        // Every class writes the same files: the first class's timing serves all.
        if let Some(first) = costs.first() {
            (cost.write_per_pixel, cost.write_wait) = (first.write_per_pixel, first.write_wait);
        }
        note(&cost);
        costs.push(cost);
    }
    Ok(Calibration { costs })
}

/// A mark set by the progress callback: CPU seconds and the instant.
type Mark = Mutex<Option<(f64, Instant)>>;

/// Renders `job` at `q` and splits its CPU time (module docs), the path
/// pass's CPU seconds returned apart and counted as per-sample; with
/// `write`, also times writing it to a temporary directory.
fn measure(
    config: &DatasetConfig,
    towns: &Towns,
    job: &super::plan::Job,
    q: Quality,
    backend: Backend,
    write: bool,
) -> Result<(ClassCost, f64), String> {
    let (start, end): (Mark, Mark) = (Mutex::new(None), Mutex::new(None));
    let progress = |done: usize, views: usize| {
        let slot = if done == 0 { &start } else { &end };
        if done == 0 || done == views {
            *slot.lock().unwrap_or_else(|e| e.into_inner()) =
                Some((process_cpu_seconds(), Instant::now()));
        }
    };
    let c0 = process_cpu_seconds();
    let r = render_job(
        config,
        towns,
        job,
        q,
        backend,
        &StaticCache::default(),
        &progress,
    )?;
    let c1 = process_cpu_seconds();
    let take = |m: Mark| m.into_inner().unwrap_or_else(|e| e.into_inner());
    let (Some((cs, ts)), Some((ce, te))) = (take(start), take(end)) else {
        return Err(format!(
            "{}: the calibration render traced no paths",
            job.id()
        ));
    };
    let path = (ce - cs).max(0.0);
    let ratio = path / te.duration_since(ts).as_secs_f64().max(1e-9);
    let before = (cs - c0).max(0.0);
    let gt = (r.out.stats.gt_seconds * ratio).min(before);
    let pixels = q.width as f64 * q.height as f64;
    let (write_per_pixel, write_wait) = if write {
        time_write(config, job, &r)?
    } else {
        (0.0, 0.0)
    };
    let cost = ClassCost {
        town: job.town.clone(),
        weather: job.weather,
        calibrated_on: None,
        fixed: before - gt,
        per_pixel: (gt + (c1 - ce).max(0.0)) / pixels,
        per_sample: path / (pixels * q.spp as f64),
        write_per_pixel: write_per_pixel / pixels,
        write_wait,
    };
    Ok((cost, path))
}

/// Writes `r` below a fresh temporary directory, removes it, and returns
/// the CPU seconds and the seconds spent waiting (wall minus CPU).
fn time_write(
    config: &DatasetConfig,
    job: &super::plan::Job,
    r: &super::frame::RenderedFrame,
) -> Result<(f64, f64), String> {
    let dir: PathBuf =
        std::env::temp_dir().join(format!("parallax-dry-run-{}", std::process::id()));
    let (c0, t0) = (process_cpu_seconds(), Instant::now());
    let written = write_job(&dir, config, job, r, 0.0);
    let (cpu, wall) = (process_cpu_seconds() - c0, t0.elapsed().as_secs_f64());
    let _ = std::fs::remove_dir_all(&dir);
    written.map_err(|e| format!("timing a calibration write in {}: {e}", dir.display()))?;
    Ok((cpu.max(0.0), (wall - cpu).max(0.0)))
}
