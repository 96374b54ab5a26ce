//! `--dry-run`: the plan's size and an estimate of its cost, from measured
//! per-class costs (`calibrate`) weighted by the plan's own mix.
//!
//! A class is a (town, weather) pair of the plan: towns differ in geometry
//! (acceleration-structure build) and weathers in path cost (fog and storm
//! cost several times clear). A frame of a class costs
//!
//! - `fixed` core-seconds once (town, scene and acceleration build), run
//!   serially;
//! - `per_pixel` core-seconds per pixel (ground truth of every view, the
//!   rain composite), run on every thread;
//! - `per_sample` core-seconds per pixel-sample (the path pass of every
//!   view), run on every thread;
//! - writing: `write_per_pixel` core-seconds per pixel (encoding, hashing)
//!   plus `write_wait` seconds of waiting for the disk (fsync).
//!
//! On `threads` threads a frame then takes `fixed + write + (per_pixel · P +
//! per_sample · P · spp) / threads` seconds, for P pixels per view.

use std::collections::BTreeMap;

use super::config::DatasetConfig;
use super::plan::{frame_count, plan, Job};
use super::shard::Shard;
use crate::weather::Weather;

/// Measured costs of one class (see the module docs for the model).
#[derive(Clone, Debug, PartialEq)]
pub struct ClassCost {
    /// Town of the class.
    pub town: String,
    /// Weather of the class.
    pub weather: Weather,
    /// The job the class was calibrated on (its configuration and frame).
    pub calibrated_on: Option<Job>,
    /// Core-seconds per frame independent of the image size.
    pub fixed: f64,
    /// Core-seconds per pixel (all views), independent of spp.
    pub per_pixel: f64,
    /// Core-seconds per pixel-sample (all views).
    pub per_sample: f64,
    /// Core-seconds per pixel for writing the frame's files.
    pub write_per_pixel: f64,
    /// Seconds per frame spent waiting for the disk while writing.
    pub write_wait: f64,
}

impl ClassCost {
    /// Estimated seconds per frame of `config`'s size and spp on `threads` threads.
    pub fn frame_seconds(&self, config: &DatasetConfig, threads: usize) -> f64 {
        let p = config.width as f64 * config.height as f64;
        let parallel = self.per_pixel * p + self.per_sample * p * config.spp() as f64;
        self.fixed + self.write_per_pixel * p + self.write_wait + parallel / threads.max(1) as f64
    }

    /// Estimated CPU core-seconds per frame of `config` (no waiting).
    pub fn frame_cpu_seconds(&self, config: &DatasetConfig) -> f64 {
        let p = config.width as f64 * config.height as f64;
        self.fixed
            + (self.per_pixel + self.per_sample * config.spp() as f64 + self.write_per_pixel) * p
    }
}

/// One class of the plan with its estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct ClassEstimate {
    /// The class's measured costs.
    pub cost: ClassCost,
    /// Frames of the class in the plan.
    pub frames: u64,
    /// Frames of the class in the shard.
    pub frames_in_shard: u64,
    /// Estimated seconds per frame on `Estimate::cores` threads.
    pub seconds_per_frame: f64,
}

/// The size of a plan and its estimated cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Frames (left images) in the plan.
    pub frames: u64,
    /// Frames in the shard.
    pub frames_in_shard: u64,
    /// Files per frame in the native layout.
    pub files_per_frame: u64,
    /// Per class, in plan order.
    pub classes: Vec<ClassEstimate>,
    /// Estimated seconds per frame (mean over the plan's mix) on `cores` threads.
    pub seconds_per_frame: f64,
    /// Estimated CPU core-seconds per frame (mean over the plan's mix).
    pub cpu_seconds_per_frame: f64,
    /// Threads a frame is rendered with.
    pub cores: usize,
    /// Estimated core-hours (seconds × threads) for the whole plan.
    pub core_hours: f64,
    /// Estimated core-hours for the shard's frames.
    pub shard_core_hours: f64,
}

/// The plan's (town, weather) classes in plan order, with each one's
/// frames in the plan and in `shard`.
pub fn class_mix(config: &DatasetConfig, shard: Shard) -> Vec<((String, Weather), u64, u64)> {
    let mut order: Vec<(String, Weather)> = Vec::new();
    let mut counts: BTreeMap<(String, Weather), (u64, u64)> = BTreeMap::new();
    for (i, job) in plan(config).into_iter().enumerate() {
        let key = (job.town, job.weather);
        let c = counts.entry(key.clone()).or_insert_with(|| {
            order.push(key);
            (0, 0)
        });
        c.0 += 1;
        c.1 += shard.owns(i) as u64;
    }
    order
        .into_iter()
        .map(|k| {
            let (all, mine) = counts[&k];
            (k, all, mine)
        })
        .collect()
}

/// The job a class is calibrated on: a frame from the middle of its first
/// sequence, the configurations taken in turn over the classes so that
/// every one of the plan's configurations is sampled.
pub fn calibration_job(config: &DatasetConfig, class: usize, town: &str, weather: Weather) -> Job {
    let configs = config.camera_configs();
    Job {
        town: town.to_string(),
        config: configs[class % configs.len()],
        weather,
        sequence: 0,
        frame: config.frames_per_sequence / 2,
    }
}

/// The estimate of `config` (and `shard` of it) on `threads` threads from
/// the measured cost of every class of the plan.
pub fn estimate(
    config: &DatasetConfig,
    costs: &[ClassCost],
    shard: Shard,
    threads: usize,
) -> Result<Estimate, String> {
    let b = config.baselines_cm.len() as u64;
    let mut classes = Vec::new();
    for ((town, weather), frames, frames_in_shard) in class_mix(config, shard) {
        let cost = costs
            .iter()
            .find(|c| c.town == town && c.weather == weather)
            .ok_or_else(|| format!("no calibration of {town} {}", weather.name()))?;
        classes.push(ClassEstimate {
            seconds_per_frame: cost.frame_seconds(config, threads),
            cost: cost.clone(),
            frames,
            frames_in_shard,
        });
    }
    let frames = frame_count(config);
    let total: f64 = classes
        .iter()
        .map(|c| c.frames as f64 * c.seconds_per_frame)
        .sum();
    let shard_total: f64 = classes
        .iter()
        .map(|c| c.frames_in_shard as f64 * c.seconds_per_frame)
        .sum();
    let cpu: f64 = classes
        .iter()
        .map(|c| c.frames as f64 * c.cost.frame_cpu_seconds(config))
        .sum();
    let hours = |seconds: f64| seconds * threads as f64 / 3600.0;
    // Every map the registry declares for the left view and per baseline,
    // plus the camera file.
    let maps = |per_baseline| {
        crate::output::registry::maps_in(per_baseline)
            .filter(|m| config.hdr || !m.hdr_only)
            .count() as u64
    };
    Ok(Estimate {
        frames,
        frames_in_shard: classes.iter().map(|c| c.frames_in_shard).sum(),
        files_per_frame: maps(false) + 1 + maps(true) * b,
        seconds_per_frame: total / frames.max(1) as f64,
        cpu_seconds_per_frame: cpu / frames.max(1) as f64,
        cores: threads,
        core_hours: hours(total),
        shard_core_hours: hours(shard_total),
        classes,
    })
}
