//! `--dry-run`: the plan's size and an estimate of its cost. One small frame
//! (64 px wide) is rendered twice for calibration, at 1 and 2 spp: the
//! difference of the path times is the cost of one sample per pixel (the
//! rest, light and surface tables, is fixed per frame). Ground-truth time is
//! scaled by pixels, sample time by pixels × spp, the scene build counted once
//! per frame, and the total expressed in core-hours.

use std::time::Instant;

use super::config::DatasetConfig;
use super::frame::{render_job, Quality, Towns};
use super::plan::{frame_count, plan};
use crate::accel::Backend;

/// The size of a plan and its estimated cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Frames (left images) in the plan.
    pub frames: u64,
    /// RGB images (left + one right per baseline, per frame).
    pub images: u64,
    /// Files per frame in the native layout.
    pub files_per_frame: u64,
    /// Estimated seconds per frame on this machine with `cores` threads.
    pub seconds_per_frame: f64,
    /// Threads used by the calibration.
    pub cores: usize,
    /// Estimated core-hours for the whole plan.
    pub core_hours: f64,
}

/// Counts the plan and calibrates on its first frame.
pub fn estimate(
    config: &DatasetConfig,
    towns: &Towns,
    backend: Backend,
) -> Result<Estimate, String> {
    let frames = frame_count(config);
    let b = config.baselines_cm.len() as u64;
    let first = plan(config).into_iter().next().ok_or("the plan is empty")?;
    let cal_w = config.width.min(64);
    let cal = Quality {
        width: cal_w,
        height: ((config.height as f64 * cal_w as f64 / config.width as f64).round() as u32).max(1),
        spp: 1,
    };
    let cal2 = Quality { spp: 2, ..cal };
    let cal1 = Quality { spp: 1, ..cal };
    let t0 = Instant::now();
    let r1 = render_job(config, towns, &first, cal1, backend, &|_, _| {})?;
    let wall = t0.elapsed().as_secs_f64();
    let r2 = render_job(config, towns, &first, cal2, backend, &|_, _| {})?;
    let (s1, s2) = (r1.out.stats, r2.out.stats);
    let build = (wall - s1.gt_seconds - s1.path_seconds).max(0.0);
    let per_spp = (s2.path_seconds - s1.path_seconds).max(0.0);
    let path_fixed = (s1.path_seconds - per_spp).max(0.0);
    let px_ratio = (config.width as f64 * config.height as f64) / (cal.width * cal.height) as f64;
    let gt = s1.gt_seconds.min(s2.gt_seconds);
    let seconds_per_frame =
        build + path_fixed + gt * px_ratio + per_spp * px_ratio * config.spp as f64;
    let cores = rayon::current_num_threads();
    let hdr = if config.hdr { 1 + b } else { 0 };
    Ok(Estimate {
        frames,
        images: frames * (1 + b),
        files_per_frame: 7 + 5 * b + hdr,
        seconds_per_frame,
        cores,
        core_hours: frames as f64 * seconds_per_frame * cores as f64 / 3600.0,
    })
}
