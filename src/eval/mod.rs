//! `parallax eval`: stereo metrics of predicted disparities against a native
//! ground-truth tree, overall and per baseline, configuration, weather and town.
//!
//! The ground truth is always a native tree. A prediction mirrors each
//! ground-truth `baseline_XXX/disp/NNNNNN.pfm` as laid out in the native,
//! kitti, sceneflow or stereocarla layout (`mirror`), with extension .pfm,
//! .png, .exr or .npy (`pred`). A missing prediction file is listed and
//! counted, never silently skipped; missing pixels inside a file are scored by
//! the stated rule (`fill`) and their share reported as density. Two means are
//! reported everywhere: pooled (every valid pixel weighs the same) and
//! per-image (every image with valid pixels weighs the same).

pub mod fill;
pub mod metrics;
pub mod mirror;
pub mod pred;
mod report;
mod walk;

use std::collections::BTreeMap;
use std::io;
use std::path::{Path, PathBuf};

use serde::Serialize;

pub use fill::{interpolate_background, Fill};
pub use metrics::{
    gt_valid, image_counts, image_counts_filled, predicted, MetricAccumulator, Metrics, PixelCounts,
};
pub use report::format_table;
pub use walk::{find_gt_disparities, GtImage};

use crate::output::layouts::LayoutKind;
use crate::output::{read_pfm_gray, read_png_gray8};

/// How `evaluate` finds and scores predictions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EvalOptions {
    /// The layout the prediction tree mirrors (default native).
    pub layout: LayoutKind,
    /// The rule for missing predictions (default: counted as errors).
    pub fill: Fill,
}

impl Default for EvalOptions {
    fn default() -> Self {
        EvalOptions {
            layout: LayoutKind::Native,
            fill: Fill::None,
        }
    }
}

/// Pooled and per-image-mean metrics of one pixel set.
#[derive(Clone, Debug, Serialize)]
pub struct MeanPair {
    /// Pixel-weighted.
    pub pooled: Metrics,
    /// Mean of per-image metrics over images with valid pixels.
    pub per_image_mean: Metrics,
}

/// The figures of one group of images.
#[derive(Clone, Debug, Serialize)]
pub struct GroupReport {
    /// Images evaluated (prediction present).
    pub images: u64,
    /// Valid ground-truth pixels, all.
    pub pixels_all: u64,
    /// Valid non-occluded pixels.
    pub pixels_noc: u64,
    /// Over every valid pixel.
    pub all: MeanPair,
    /// Over valid non-occluded pixels.
    pub noc: MeanPair,
}

/// Accumulates one group: all and noc.
#[derive(Clone, Debug, Default)]
pub struct GroupAccumulator {
    all: MetricAccumulator,
    noc: MetricAccumulator,
}

impl GroupAccumulator {
    /// Adds one image's `(all, noc)` sums.
    pub fn add(&mut self, all: &PixelCounts, noc: &PixelCounts) {
        self.all.add_image(all);
        self.noc.add_image(noc);
    }

    /// The group's figures.
    pub fn report(&self) -> GroupReport {
        let pair = |a: &MetricAccumulator| MeanPair {
            pooled: a.pooled(),
            per_image_mean: a.per_image_mean(),
        };
        GroupReport {
            images: self.all.images,
            pixels_all: self.all.pixels(),
            pixels_noc: self.noc.pixels(),
            all: pair(&self.all),
            noc: pair(&self.noc),
        }
    }
}

/// Everything `parallax eval` reports.
#[derive(Clone, Debug, Serialize)]
pub struct EvalReport {
    /// Ground-truth root.
    pub gt: String,
    /// Prediction root.
    pub pred: String,
    /// The layout the predictions mirror.
    pub layout: LayoutKind,
    /// The rule for missing predictions (`none` or `kitti`).
    pub fill: Fill,
    /// That rule in words.
    pub missing_rule: &'static str,
    /// Ground-truth disparity images found.
    pub gt_images: u64,
    /// Images evaluated (prediction found).
    pub images_evaluated: u64,
    /// Ground-truth images without a prediction (relative paths, no extension).
    pub missing_predictions: Vec<String>,
    /// How the figures are defined.
    pub definitions: &'static str,
    /// All images together.
    pub overall: GroupReport,
    /// Per baseline directory.
    pub per_baseline: BTreeMap<String, GroupReport>,
    /// Per camera configuration.
    pub per_config: BTreeMap<String, GroupReport>,
    /// Per weather.
    pub per_weather: BTreeMap<String, GroupReport>,
    /// Per town.
    pub per_town: BTreeMap<String, GroupReport>,
}

/// The definitions stored in every report.
pub const DEFINITIONS: &str = "valid: GT disparity finite and > 0; missing prediction: not finite or < 0 (16-bit PNG: 0); \
density = % of valid pixels predicted; error = |pred - gt| px; EPE = mean error px over scored pixels; \
bad-x = % of valid pixels with error > x px or not scored; D1 = % with error > 3 px and > 5% of gt, or not scored; \
all = every valid pixel, noc = valid and occlusion mask 0; \
pooled = pixel-weighted over the group, per_image_mean = mean of per-image figures over images with valid pixels";

fn invalid(path: &Path, msg: impl std::fmt::Display) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidData,
        format!("{}: {msg}", path.display()),
    )
}

/// Evaluates every prediction below `pred_root` (laid out as `opts.layout`)
/// against the native ground truth below `gt_root`. Errors (unreadable file,
/// size mismatch, no ground truth, a layout the tree cannot have) name the
/// path; a missing prediction is not an error but listed in the report.
pub fn evaluate(gt_root: &Path, pred_root: &Path, opts: &EvalOptions) -> io::Result<EvalReport> {
    for (flag, dir) in [("--gt", gt_root), ("--pred", pred_root)] {
        if !dir.is_dir() {
            return Err(io::Error::new(
                io::ErrorKind::NotFound,
                format!("{flag} {}: not a directory", dir.display()),
            ));
        }
    }
    let images = find_gt_disparities(gt_root)?;
    if images.is_empty() {
        return Err(invalid(
            gt_root,
            "no ground-truth disparity (baseline_XXX/disp/NNNNNN.pfm) found",
        ));
    }
    let mut overall = GroupAccumulator::default();
    let mut groups: [BTreeMap<String, GroupAccumulator>; 4] = Default::default();
    let mut missing = Vec::new();
    for img in &images {
        let stem = mirror::prediction_stem(img, opts.layout).map_err(|e| invalid(gt_root, e))?;
        let stem_path: PathBuf = pred_root.join(&stem);
        let Some(pred_path) = pred::find_prediction(&stem_path) else {
            missing.push(stem.display().to_string());
            continue;
        };
        let (w, h, gt) = read_pfm_gray(&gt_root.join(&img.rel))?;
        let occ_path = gt_root.join(img.occ_rel());
        let (ow, oh, occ) = read_png_gray8(&occ_path)?;
        if (ow, oh) != (w, h) {
            return Err(invalid(
                &occ_path,
                format!("is {ow}×{oh}, disparity is {w}×{h}"),
            ));
        }
        let (pw, ph, p) = pred::read_prediction(&pred_path)?;
        if (pw, ph) != (w, h) {
            return Err(invalid(
                &pred_path,
                format!("prediction is {pw}×{ph}, ground truth is {w}×{h}"),
            ));
        }
        let scored = opts.fill.apply(w, &p);
        let (all, noc) = image_counts_filled(&gt, &p, &scored, &occ);
        overall.add(&all, &noc);
        let keys = [&img.baseline, &img.config, &img.weather, &img.town];
        for (g, k) in groups.iter_mut().zip(keys) {
            g.entry(k.clone()).or_default().add(&all, &noc);
        }
    }
    let [per_baseline, per_config, per_weather, per_town] =
        groups.map(|g| g.into_iter().map(|(k, v)| (k, v.report())).collect());
    Ok(EvalReport {
        gt: gt_root.display().to_string(),
        pred: pred_root.display().to_string(),
        layout: opts.layout,
        fill: opts.fill,
        missing_rule: opts.fill.rule(),
        gt_images: images.len() as u64,
        images_evaluated: (images.len() - missing.len()) as u64,
        missing_predictions: missing,
        definitions: DEFINITIONS,
        overall: overall.report(),
        per_baseline,
        per_config,
        per_weather,
        per_town,
    })
}
