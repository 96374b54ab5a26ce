//! Stereo error metrics over valid ground-truth pixels (KITTI 2015, Middlebury).
//!
//! A ground-truth pixel is valid when its disparity is finite and > 0 (sky is
//! 0). error = |d_pred − d_gt| in px; a non-finite prediction counts as 0 px
//! (KITTI's 0 = "no estimate"). EPE = mean error; bad-x = share with error > x;
//! D1 = share with error > 3 px AND error > 5 % of d_gt. Shares are percent.
//! "noc" restricts to pixels whose occlusion mask is 0.

use serde::Serialize;

/// Pixel sums of one image or group, from which every metric is a ratio.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PixelCounts {
    /// Valid pixels.
    pub n: u64,
    /// Sum of absolute errors, px.
    pub sum_err: f64,
    /// Pixels with error > 1 px.
    pub bad1: u64,
    /// Pixels with error > 2 px.
    pub bad2: u64,
    /// Pixels with error > 3 px.
    pub bad3: u64,
    /// Pixels with error > 3 px and > 5 % of the true disparity.
    pub d1: u64,
}

/// Metric values: EPE in px, the rest in percent. All NaN when no pixel counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Metrics {
    /// End-point error, px.
    pub epe: f64,
    /// D1 (KITTI outliers), percent.
    pub d1: f64,
    /// bad-1.0, percent.
    pub bad1: f64,
    /// bad-2.0, percent.
    pub bad2: f64,
    /// bad-3.0, percent.
    pub bad3: f64,
}

impl PixelCounts {
    /// Adds one pixel pair (precondition: `gt` valid).
    pub fn add(&mut self, gt: f32, pred: f32) {
        let pred = if pred.is_finite() { pred } else { 0.0 };
        let err = (pred as f64 - gt as f64).abs();
        self.n += 1;
        self.sum_err += err;
        self.bad1 += (err > 1.0) as u64;
        self.bad2 += (err > 2.0) as u64;
        self.bad3 += (err > 3.0) as u64;
        self.d1 += (err > 3.0 && err > 0.05 * gt as f64) as u64;
    }

    /// Adds another set of sums (pooling).
    pub fn merge(&mut self, o: &PixelCounts) {
        self.n += o.n;
        self.sum_err += o.sum_err;
        self.bad1 += o.bad1;
        self.bad2 += o.bad2;
        self.bad3 += o.bad3;
        self.d1 += o.d1;
    }

    /// The metrics of these sums (NaN when `n` = 0).
    pub fn metrics(&self) -> Metrics {
        let n = self.n as f64;
        let pct = |k: u64| 100.0 * k as f64 / n;
        Metrics {
            epe: self.sum_err / n,
            d1: pct(self.d1),
            bad1: pct(self.bad1),
            bad2: pct(self.bad2),
            bad3: pct(self.bad3),
        }
    }
}

/// Whether a ground-truth disparity counts (finite and > 0).
pub fn gt_valid(d: f32) -> bool {
    d.is_finite() && d > 0.0
}

/// Sums of one image: `(all, noc)`. `occlusion` is 255 (any non-zero) where
/// occluded. Preconditions: equal lengths.
pub fn image_counts(gt: &[f32], pred: &[f32], occlusion: &[u8]) -> (PixelCounts, PixelCounts) {
    let (mut all, mut noc) = (PixelCounts::default(), PixelCounts::default());
    for ((&g, &p), &o) in gt.iter().zip(pred).zip(occlusion) {
        if gt_valid(g) {
            all.add(g, p);
            if o == 0 {
                noc.add(g, p);
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
}

impl MetricAccumulator {
    /// Adds one image's sums; an image without valid pixels adds to the pooled
    /// figures nothing and is left out of the per-image mean.
    pub fn add_image(&mut self, c: &PixelCounts) {
        self.images += 1;
        self.pooled.merge(c);
        if c.n > 0 {
            let m = c.metrics();
            self.image_sum.epe += m.epe;
            self.image_sum.d1 += m.d1;
            self.image_sum.bad1 += m.bad1;
            self.image_sum.bad2 += m.bad2;
            self.image_sum.bad3 += m.bad3;
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
            epe: s.epe / k,
            d1: s.d1 / k,
            bad1: s.bad1 / k,
            bad2: s.bad2 / k,
            bad3: s.bad3 / k,
        }
    }
}
