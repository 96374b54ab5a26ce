//! `parallax stats`: disparity statistics of a native dataset, as StereoCarla's
//! table 1 reports them (range, mean, median of valid disparities per baseline
//! and overall), and frame counts per town, configuration and weather.
//!
//! Valid disparity: finite and > 0 (sky is 0). Frames are found as every
//! `baseline_XXX/disp/NNNNNN.pfm` below the root (`eval::find_gt_disparities`);
//! a frame counts once however many baselines it has.

mod histogram;
mod plot;

use std::collections::BTreeMap;
use std::io;
use std::path::{Path, PathBuf};

use serde::Serialize;

pub use histogram::{DisparityHistogram, DisparitySummary, BIN_WIDTH_PX, MAX_BINNED_PX};
pub use plot::{write_histogram_plots, AXES_AT, PLOT_SIZE};

use crate::eval::find_gt_disparities;
use crate::output::read_pfm_gray;

/// The statistics of a dataset.
#[derive(Clone, Debug, Serialize)]
pub struct DatasetStats {
    /// The dataset root.
    pub root: String,
    /// Distinct frames (sequence directory + frame index).
    pub frames: u64,
    /// Disparity images read (frames × baselines).
    pub disparity_images: u64,
    /// Over every baseline.
    pub overall: DisparitySummary,
    /// Per baseline directory.
    pub per_baseline: BTreeMap<String, DisparitySummary>,
    /// Frames per town ("-" for a bare render directory).
    pub frames_per_town: BTreeMap<String, u64>,
    /// Frames per camera configuration.
    pub frames_per_config: BTreeMap<String, u64>,
    /// Frames per weather.
    pub frames_per_weather: BTreeMap<String, u64>,
    /// Histogram bin width used for the median, px.
    pub median_bin_width_px: f64,
}

/// Statistics with the histograms they came from (for plots).
pub struct StatsResult {
    /// The figures.
    pub stats: DatasetStats,
    /// Histogram over every baseline.
    pub overall: DisparityHistogram,
    /// Histogram per baseline directory.
    pub per_baseline: BTreeMap<String, DisparityHistogram>,
}

/// Reads every native disparity below `root`. Errors name the path; a root
/// without any disparity is an `InvalidData` error.
pub fn dataset_stats(root: &Path) -> io::Result<StatsResult> {
    if !root.is_dir() {
        return Err(io::Error::new(
            io::ErrorKind::NotFound,
            format!("{}: not a directory", root.display()),
        ));
    }
    let images = find_gt_disparities(root)?;
    if images.is_empty() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "{}: no native disparity (baseline_XXX/disp/NNNNNN.pfm) found",
                root.display()
            ),
        ));
    }
    let mut overall = DisparityHistogram::default();
    let mut per_baseline: BTreeMap<String, DisparityHistogram> = BTreeMap::new();
    let mut frames: BTreeMap<PathBuf, [String; 3]> = BTreeMap::new();
    for img in &images {
        let (_, _, disp) = read_pfm_gray(&root.join(&img.rel))?;
        let mut h = DisparityHistogram::default();
        disp.iter().for_each(|&d| h.add(d));
        overall.merge(&h);
        per_baseline
            .entry(img.baseline.clone())
            .or_default()
            .merge(&h);
        frames.insert(
            img.frame_id(),
            [img.town.clone(), img.config.clone(), img.weather.clone()],
        );
    }
    let mut counts: [BTreeMap<String, u64>; 3] = Default::default();
    for ids in frames.values() {
        for (c, id) in counts.iter_mut().zip(ids) {
            *c.entry(id.clone()).or_default() += 1;
        }
    }
    let [frames_per_town, frames_per_config, frames_per_weather] = counts;
    let stats = DatasetStats {
        root: root.display().to_string(),
        frames: frames.len() as u64,
        disparity_images: images.len() as u64,
        overall: overall.summary(),
        per_baseline: per_baseline
            .iter()
            .map(|(k, h)| (k.clone(), h.summary()))
            .collect(),
        frames_per_town,
        frames_per_config,
        frames_per_weather,
        median_bin_width_px: BIN_WIDTH_PX,
    };
    Ok(StatsResult {
        stats,
        overall,
        per_baseline,
    })
}

/// A readable summary table.
pub fn format_stats(s: &DatasetStats) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{} frames, {} disparity images under {}",
        s.frames, s.disparity_images, s.root
    );
    let _ = writeln!(
        out,
        "{:<14} {:>12} {:>10} {:>10} {:>10} {:>10}",
        "disparity", "pixels", "min px", "max px", "mean px", "median px"
    );
    let mut line = |name: &str, d: &DisparitySummary| {
        let _ = writeln!(
            out,
            "{name:<14} {:>12} {:>10.3} {:>10.3} {:>10.3} {:>10.3}",
            d.pixels, d.min, d.max, d.mean, d.median
        );
    };
    for (k, d) in &s.per_baseline {
        line(k, d);
    }
    line("overall", &s.overall);
    let _ = writeln!(
        out,
        "(valid: finite and > 0; median from {} px bins)",
        s.median_bin_width_px
    );
    for (label, map) in [
        ("town", &s.frames_per_town),
        ("config", &s.frames_per_config),
        ("weather", &s.frames_per_weather),
    ] {
        let parts: Vec<String> = map.iter().map(|(k, v)| format!("{k} {v}")).collect();
        let _ = writeln!(out, "frames per {label}: {}", parts.join(", "));
    }
    out
}
