//! Stereo error metrics over valid ground-truth pixels (KITTI 2015, Middlebury),
//! with missing predictions reported and scored by one stated rule.
//!
//! A ground-truth pixel is valid when its disparity is finite and > 0 (sky is
//! 0). A prediction is missing where it is not finite or < 0 (the KITTI
//! devkit's invalid; a 16-bit PNG's 0 is read as missing). density = share of
//! valid pixels with a prediction. error = |d_pred − d_gt| px over scored
//! pixels (predicted, or filled by `--fill kitti`); EPE = mean error over scored
//! pixels; bad-x = share of valid pixels with error > x OR not scored; D1 =
//! share with (error > 3 px AND > 5 % of d_gt) OR not scored. Shares are
//! percent. "noc" restricts to pixels whose occlusion mask is 0.

use serde::Serialize;

/// Whether a predicted value counts as a prediction (finite and ≥ 0).
pub fn predicted(d: f32) -> bool {
    d.is_finite() && d >= 0.0
}

/// Pixel sums of one image or group, from which every metric is a ratio.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PixelCounts {
    /// Valid pixels.
    pub n: u64,
    /// Valid pixels the prediction file covers (before any fill).
    pub predicted: u64,
    /// Valid pixels with a value to score (predicted, or filled).
    pub scored: u64,
    /// Sum of absolute errors over scored pixels, px.
    pub sum_err: f64,
    /// Scored pixels with error > 1 px.
    pub bad1: u64,
    /// Scored pixels with error > 2 px.
    pub bad2: u64,
    /// Scored pixels with error > 3 px.
    pub bad3: u64,
    /// Scored pixels with error > 3 px and > 5 % of the true disparity.
    pub d1: u64,
}

/// Metric values: EPE in px, the rest in percent. All NaN when no pixel counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Metrics {
    /// End-point error over scored pixels, px.
    pub epe: f64,
    /// D1 (KITTI outliers, unscored pixels included), percent.
    pub d1: f64,
    /// bad-1.0 (unscored pixels included), percent.
    pub bad1: f64,
    /// bad-2.0 (unscored pixels included), percent.
    pub bad2: f64,
    /// bad-3.0 (unscored pixels included), percent.
    pub bad3: f64,
    /// Valid pixels with a prediction (before any fill), percent.
    pub density: f64,
}

impl PixelCounts {
    /// Adds one valid pixel (precondition: `gt` valid): `raw` is the value in
    /// the prediction file, `scored` the value after any fill.
    pub fn add(&mut self, gt: f32, raw: f32, scored: f32) {
        self.n += 1;
        self.predicted += predicted(raw) as u64;
        if !predicted(scored) {
            return;
        }
        let err = (scored as f64 - gt as f64).abs();
        self.scored += 1;
        self.sum_err += err;
        self.bad1 += (err > 1.0) as u64;
        self.bad2 += (err > 2.0) as u64;
        self.bad3 += (err > 3.0) as u64;
        self.d1 += (err > 3.0 && err > 0.05 * gt as f64) as u64;
    }

    /// Adds another set of sums (pooling).
    pub fn merge(&mut self, o: &PixelCounts) {
        self.n += o.n;
        self.predicted += o.predicted;
        self.scored += o.scored;
        self.sum_err += o.sum_err;
        self.bad1 += o.bad1;
        self.bad2 += o.bad2;
        self.bad3 += o.bad3;
        self.d1 += o.d1;
    }

    /// The metrics of these sums (NaN when `n` = 0; EPE NaN when nothing scored).
    pub fn metrics(&self) -> Metrics {
        let n = self.n as f64;
        let unscored = self.n - self.scored;
        let pct = |k: u64| 100.0 * (k + unscored) as f64 / n;
        Metrics {
            epe: self.sum_err / self.scored as f64,
            d1: pct(self.d1),
            bad1: pct(self.bad1),
            bad2: pct(self.bad2),
            bad3: pct(self.bad3),
            density: 100.0 * self.predicted as f64 / n,
        }
    }
}

/// Whether a ground-truth disparity counts (finite and > 0).
pub fn gt_valid(d: f32) -> bool {
    d.is_finite() && d > 0.0
}

/// Sums of one image scored as predicted (no fill): `(all, noc)`.
/// `occlusion` is 255 (any non-zero) where occluded. Preconditions: equal lengths.
pub fn image_counts(gt: &[f32], pred: &[f32], occlusion: &[u8]) -> (PixelCounts, PixelCounts) {
    image_counts_filled(gt, pred, pred, occlusion)
}

/// Sums of one image whose prediction `raw` was filled into `scored`
/// (density from `raw`, errors from `scored`): `(all, noc)`.
pub fn image_counts_filled(
    gt: &[f32],
    raw: &[f32],
    scored: &[f32],
    occlusion: &[u8],
) -> (PixelCounts, PixelCounts) {
    let (mut all, mut noc) = (PixelCounts::default(), PixelCounts::default());
    for (((&g, &r), &s), &o) in gt.iter().zip(raw).zip(scored).zip(occlusion) {
        if gt_valid(g) {
            all.add(g, r, s);
            if o == 0 {
                noc.add(g, r, s);
            }
        }
    }
    (all, noc)
}

/// Pooled (pixel-weighted) sums and per-image means of a group of images.
#[derive(Clone, Debug, Default)]
pub struct MetricAccumulator {
    /// Images added (with or without valid pixels).
    pub images: u64,
    pooled: PixelCounts,
    image_sum: Metrics,
    images_with_pixels: u64,
    images_with_scored: u64,
}

impl MetricAccumulator {
    /// Adds one image's sums; an image without valid pixels adds to the pooled
    /// figures nothing and is left out of the per-image mean (and one without
    /// scored pixels out of the per-image EPE).
    pub fn add_image(&mut self, c: &PixelCounts) {
        self.images += 1;
        self.pooled.merge(c);
        if c.n > 0 {
            let m = c.metrics();
            if c.scored > 0 {
                self.image_sum.epe += m.epe;
                self.images_with_scored += 1;
            }
            self.image_sum.d1 += m.d1;
            self.image_sum.bad1 += m.bad1;
            self.image_sum.bad2 += m.bad2;
            self.image_sum.bad3 += m.bad3;
            self.image_sum.density += m.density;
            self.images_with_pixels += 1;
        }
    }

    /// Pixel-weighted metrics over every pixel of the group.
    pub fn pooled(&self) -> Metrics {
        self.pooled.metrics()
    }

    /// Valid pixels of the group.
    pub fn pixels(&self) -> u64 {
        self.pooled.n
    }

    /// Images that had at least one valid pixel.
    pub fn images_with_pixels(&self) -> u64 {
        self.images_with_pixels
    }

    /// Mean over images (with valid pixels) of each image's metrics.
    pub fn per_image_mean(&self) -> Metrics {
        let k = self.images_with_pixels as f64;
        let s = &self.image_sum;
        Metrics {
            epe: s.epe / self.images_with_scored as f64,
            d1: s.d1 / k,
            bad1: s.bad1 / k,
            bad2: s.bad2 / k,
            bad3: s.bad3 / k,
            density: s.density / k,
        }
    }
}
