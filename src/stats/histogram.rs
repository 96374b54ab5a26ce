//! A fixed-bin disparity histogram: exact count, sum, min and max; the median
//! and other quantiles come from the bins, so memory does not grow with the
//! number of pixels.
//!
//! Bins are [`BIN_WIDTH_PX`] = 1/32 px wide from 0 up to [`MAX_BINNED_PX`]; each
//! bin also keeps the sum of its values, and a quantile is the mean of the bin
//! holding its rank, so it is exact when that bin holds one distinct value and
//! off by less than one bin width otherwise. Larger values go to one overflow
//! bin (their quantile is its mean). numpy's median convention: the mean of
//! the values of rank ⌊(n−1)/2⌋ and ⌊n/2⌋ (0-based, sorted).

use serde::Serialize;

/// Width of a histogram bin, px.
pub const BIN_WIDTH_PX: f64 = 1.0 / 32.0;
/// Upper end of the binned range, px (2^15; StereoCarla's maximum is 3318).
pub const MAX_BINNED_PX: f64 = 32768.0;

/// Histogram of valid disparities (finite, > 0).
#[derive(Clone, Debug, Default)]
pub struct DisparityHistogram {
    counts: Vec<u64>,
    sums: Vec<f64>,
    over_count: u64,
    over_sum: f64,
    n: u64,
    sum: f64,
    min: f64,
    max: f64,
}

/// Summary figures of a histogram.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct DisparitySummary {
    /// Valid pixels.
    pub pixels: u64,
    /// Smallest valid disparity, px.
    pub min: f64,
    /// Largest disparity, px.
    pub max: f64,
    /// Mean, px (exact).
    pub mean: f64,
    /// Median, px (see the module header for its precision).
    pub median: f64,
}

impl DisparityHistogram {
    /// Adds one disparity; values that are not finite and > 0 are ignored.
    pub fn add(&mut self, d: f32) {
        if !crate::eval::gt_valid(d) {
            return;
        }
        let d = d as f64;
        if self.n == 0 {
            (self.min, self.max) = (d, d);
        }
        self.n += 1;
        self.sum += d;
        self.min = self.min.min(d);
        self.max = self.max.max(d);
        if d >= MAX_BINNED_PX {
            self.over_count += 1;
            self.over_sum += d;
            return;
        }
        let i = (d / BIN_WIDTH_PX) as usize;
        if i >= self.counts.len() {
            self.counts.resize(i + 1, 0);
            self.sums.resize(i + 1, 0.0);
        }
        self.counts[i] += 1;
        self.sums[i] += d;
    }

    /// Adds every value of another histogram.
    pub fn merge(&mut self, o: &DisparityHistogram) {
        if o.n == 0 {
            return;
        }
        if self.n == 0 {
            (self.min, self.max) = (o.min, o.max);
        }
        self.n += o.n;
        self.sum += o.sum;
        self.min = self.min.min(o.min);
        self.max = self.max.max(o.max);
        self.over_count += o.over_count;
        self.over_sum += o.over_sum;
        if o.counts.len() > self.counts.len() {
            self.counts.resize(o.counts.len(), 0);
            self.sums.resize(o.counts.len(), 0.0);
        }
        for (i, (&c, &s)) in o.counts.iter().zip(&o.sums).enumerate() {
            self.counts[i] += c;
            self.sums[i] += s;
        }
    }

    /// The mean of the bin holding the value of 0-based sorted `rank`.
    fn value_at_rank(&self, rank: u64) -> f64 {
        let mut seen = 0;
        for (&c, &s) in self.counts.iter().zip(&self.sums) {
            seen += c;
            if seen > rank {
                return s / c as f64;
            }
        }
        self.over_sum / self.over_count as f64
    }

    /// The summary (NaN figures when empty).
    pub fn summary(&self) -> DisparitySummary {
        if self.n == 0 {
            return DisparitySummary {
                min: f64::NAN,
                max: f64::NAN,
                mean: f64::NAN,
                median: f64::NAN,
                ..Default::default()
            };
        }
        let median = 0.5 * (self.value_at_rank((self.n - 1) / 2) + self.value_at_rank(self.n / 2));
        DisparitySummary {
            pixels: self.n,
            min: self.min,
            max: self.max,
            mean: self.sum / self.n as f64,
            median,
        }
    }

    /// Counts re-binned into `bars` equal bars over [0, hi): `(lo, hi, count)`
    /// per bar; values ≥ hi land in the last bar.
    pub fn coarse(&self, bars: usize, hi: f64) -> Vec<(f64, f64, u64)> {
        let width = hi / bars as f64;
        let mut out: Vec<(f64, f64, u64)> = (0..bars)
            .map(|b| (b as f64 * width, (b + 1) as f64 * width, 0))
            .collect();
        for (i, &c) in self.counts.iter().enumerate() {
            let centre = (i as f64 + 0.5) * BIN_WIDTH_PX;
            let b = ((centre / width) as usize).min(bars - 1);
            out[b].2 += c;
        }
        out[bars - 1].2 += self.over_count;
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_follows_numpy_for_odd_and_even_counts() {
        let mut h = DisparityHistogram::default();
        for d in [5.0, 1.0, 3.0, 0.0, f32::NAN, 100.0] {
            h.add(d);
        }
        // valid: 1, 3, 5, 100 → median (3 + 5) / 2 = 4, mean 27.25
        let s = h.summary();
        assert_eq!((s.pixels, s.min, s.max), (4, 1.0, 100.0));
        assert_eq!((s.mean, s.median), (27.25, 4.0));
        h.add(40000.0);
        assert_eq!(h.summary().median, 5.0);
    }
}
