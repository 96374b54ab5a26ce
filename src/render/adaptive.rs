//! Adaptive sampling under a fixed budget: how many samples each pixel of a
//! view gets, from a first (pilot) pass of a quarter of the budget.
//!
//! The view's budget is today's, `pixels × spp`. A pilot pass of `spp / 4`
//! samples per pixel gives each pixel its sample moments; from them a
//! per-pixel error: the standard deviation of one sample, carried through
//! the display transform (exposure, tone curve, sRGB) at the pixel's mean,
//! since what a viewer (and sRGB PSNR) sees is display error. It is averaged
//! over a 3 × 3 window so that a pixel whose few pilot samples happened to
//! agree is not starved. The whole budget is then shared in proportion to
//! that error (the allocation minimising the summed display variance
//! Σ σᵢ²/nᵢ for a fixed Σ nᵢ), clamped to a per-pixel minimum and maximum,
//! and rounded so that the counts sum to the budget exactly.
//!
//! Everything here depends only on the pilot pass, itself a fixed function
//! of the pixel's sample streams: the same counts on any thread count.

use crate::film::{srgb_oetf, tone_curve_aces};
use crate::sampler::MAX_SPP;

/// Smallest `spp` sampled adaptively (below it the pilot pass would be
/// the whole budget).
pub const MIN_ADAPTIVE_SPP: u32 = 4;

/// Samples per pixel of the pilot pass for a budget of `spp` per pixel.
pub fn pilot_spp(spp: u32) -> u32 {
    (spp / 4).max(1)
}

/// Least total samples of a pixel: the pilot's plus an eighth of the budget,
/// so a pixel the estimate calls noise-free still gets some more.
pub fn min_spp(spp: u32) -> u32 {
    pilot_spp(spp) + spp / 8
}

/// Most total samples of a pixel: four times the budget's mean (the
/// sequence has `MAX_SPP` points).
pub fn max_spp(spp: u32) -> u32 {
    spp.saturating_mul(4).min(MAX_SPP)
}

/// A pixel's pilot-pass luminance moments: sample count, Σy and Σy².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Moments {
    /// Samples summed.
    pub n: u32,
    /// Σ y.
    pub sum: f32,
    /// Σ y².
    pub sum2: f32,
}

impl Moments {
    /// Adds one sample of luminance `y`.
    pub fn add(&mut self, y: f32) {
        self.n += 1;
        self.sum += y;
        self.sum2 += y * y;
    }

    /// Mean and standard deviation of one sample (unbiased sample variance;
    /// 0 for fewer than two samples).
    pub fn mean_sd(&self) -> (f32, f32) {
        if self.n == 0 {
            return (0.0, 0.0);
        }
        let n = self.n as f32;
        let m = self.sum / n;
        if self.n < 2 {
            return (m, 0.0);
        }
        let var = ((self.sum2 - n * m * m) / (n - 1.0)).max(0.0);
        (m, var.sqrt())
    }
}

/// Display value of linear luminance `y` under exposure `exposure`.
fn display(y: f32, exposure: f32) -> f32 {
    srgb_oetf(tone_curve_aces(y * exposure))
}

/// Display-space standard deviation of one sample of a pixel of mean `m`
/// and sample deviation `sd`: half the display span of m ± sd (a secant, so
/// a saturated pixel or a lone firefly does not claim the budget).
pub fn display_sd(m: f32, sd: f32, exposure: f32) -> f32 {
    0.5 * (display(m + sd, exposure) - display((m - sd).max(0.0), exposure))
}

/// Each pixel's error (row-major `w × h`): `err` averaged over the 3 × 3
/// window around it, clipped at the image border.
pub fn smooth_3x3(err: &[f32], w: usize, h: usize) -> Vec<f32> {
    let mut out = vec![0.0; w * h];
    for j in 0..h {
        for i in 0..w {
            let (mut s, mut c) = (0.0f32, 0.0f32);
            for y in j.saturating_sub(1)..(j + 2).min(h) {
                for x in i.saturating_sub(1)..(i + 2).min(w) {
                    s += err[y * w + x];
                    c += 1.0;
                }
            }
            out[j * w + i] = s / c;
        }
    }
    out
}

/// Sample counts per pixel summing to exactly `budget`, each in
/// `[lo, hi]` and, between those, proportional to `err`: nᵢ =
/// clamp(λ·errᵢ, lo, hi) with λ found by bisection, rounded by carrying the
/// fractions along in pixel order. Where every error is zero the budget is
/// shared evenly. Precondition: `lo · n ≤ budget ≤ hi · n`, `lo ≤ hi`.
pub fn allocate(err: &[f32], budget: u64, lo: u32, hi: u32) -> Vec<u32> {
    let n = err.len() as u64;
    assert!(
        lo <= hi && lo as u64 * n <= budget && budget <= hi as u64 * n,
        "budget {budget} outside [{lo}, {hi}] × {n} pixels"
    );
    let total = |lambda: f64| -> f64 {
        err.iter()
            .map(|&e| (lambda * e as f64).clamp(lo as f64, hi as f64))
            .sum()
    };
    let max_err = err.iter().fold(0.0f32, |a, &e| a.max(e)) as f64;
    let targets: Vec<f64> = if max_err <= 0.0 || !max_err.is_finite() {
        vec![budget as f64 / n.max(1) as f64; err.len()]
    } else {
        // total(λ) grows from n·lo (λ = 0) to n·hi (λ = hi / min positive
        // error): bisect for total(λ) = budget.
        let min_pos = err
            .iter()
            .filter(|&&e| e > 0.0)
            .fold(f32::INFINITY, |a, &e| a.min(e)) as f64;
        let (mut a, mut b) = (0.0f64, hi as f64 / min_pos);
        for _ in 0..100 {
            let mid = 0.5 * (a + b);
            if total(mid) < budget as f64 {
                a = mid;
            } else {
                b = mid;
            }
        }
        err.iter()
            .map(|&e| (b * e as f64).clamp(lo as f64, hi as f64))
            .collect()
    };
    // Carry the fractions: pixel k gets ⌊Σ₀..ₖ t⌋ − ⌊Σ₀..ₖ₋₁ t⌋.
    let mut counts = Vec::with_capacity(err.len());
    let (mut acc, mut given) = (0.0f64, 0u64);
    for &t in &targets {
        acc += t;
        let upto = (acc.floor() as u64).min(budget);
        let c = upto.saturating_sub(given).clamp(lo as u64, hi as u64);
        counts.push(c as u32);
        given += c;
    }
    // Rounding and the clamps leave at most a few samples over or under:
    // settle them one per pixel, in pixel order, where there is room.
    let (mut k, len) = (0, counts.len());
    while given != budget {
        let c = &mut counts[k % len];
        if given < budget && *c < hi {
            *c += 1;
            given += 1;
        } else if given > budget && *c > lo {
            *c -= 1;
            given -= 1;
        }
        k += 1;
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moments_give_the_two_pass_sample_deviation() {
        let xs = [0.5f32, 2.0, 3.5, 1.0];
        let mut m = Moments::default();
        xs.iter().for_each(|&x| m.add(x));
        let mean = 1.75f32;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / 3.0;
        let (got_m, got_sd) = m.mean_sd();
        assert_eq!(got_m, mean);
        assert!((got_sd - var.sqrt()).abs() < 1e-6, "{got_sd}");
        // One sample: no deviation known.
        let mut one = Moments::default();
        one.add(3.0);
        assert_eq!(one.mean_sd(), (3.0, 0.0));
    }

    #[test]
    fn display_error_follows_the_tone_curve() {
        // No deviation, no error; a saturated pixel (exposed far past the
        // curve's shoulder) has none either; a dark pixel's deviation
        // weighs more than the same deviation on a bright one.
        assert_eq!(display_sd(0.5, 0.0, 1.0), 0.0);
        assert_eq!(display_sd(100.0, 1.0, 1.0), 0.0);
        assert!(display_sd(0.05, 0.01, 1.0) > display_sd(1.0, 0.01, 1.0));
        // Small deviation: the derivative of the display transform.
        let (m, sd, e) = (0.2f32, 1e-3f32, 1.0);
        let d = (display(m + 1e-3, e) - display(m - 1e-3, e)) / 2e-3;
        assert!((display_sd(m, sd, e) - d * sd).abs() < 1e-3 * d * sd);
    }

    #[test]
    fn smoothing_averages_the_clipped_window() {
        // 3 × 2 image, one hot pixel at (0, 0).
        let err = [9.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let s = smooth_3x3(&err, 3, 2);
        assert_eq!(s[0], 9.0 / 4.0); // corner: 2 × 2 window
        assert_eq!(s[1], 9.0 / 6.0); // edge: 3 × 2 window
        assert_eq!(s[2], 0.0);
    }

    #[test]
    fn allocation_spends_the_budget_in_proportion_within_bounds() {
        // Errors 1 : 3 over 100 pixels each, budget 16 per pixel, bounds 6..64:
        // 8 and 24 per pixel.
        let err: Vec<f32> = (0..200).map(|k| if k < 100 { 1.0 } else { 3.0 }).collect();
        let c = allocate(&err, 200 * 16, 6, 64);
        assert_eq!(c.iter().map(|&c| c as u64).sum::<u64>(), 3200);
        assert!(c[..100].iter().all(|&c| c == 8), "{:?}", &c[..4]);
        assert!(c[100..].iter().all(|&c| c == 24), "{:?}", &c[100..104]);
        // One hot pixel among cold ones: capped at hi, the rest shared.
        let mut err = vec![0.01f32; 50];
        err[7] = 100.0;
        let c = allocate(&err, 50 * 16, 6, 64);
        assert_eq!(c[7], 64);
        assert_eq!(c.iter().map(|&c| c as u64).sum::<u64>(), 800);
        assert!(c.iter().all(|&c| (6..=64).contains(&c)));
        // All zero: even shares; fractions carried (budget 7 over 3).
        assert_eq!(allocate(&[0.0; 4], 64, 6, 64), vec![16; 4]);
        assert_eq!(allocate(&[0.0; 3], 7, 1, 8), vec![2, 2, 3]);
        // Ten shares of 0.1 sum to 0.999… in floating point: the last
        // sample is settled, not lost.
        assert_eq!(allocate(&[0.0; 10], 1, 0, 1).iter().sum::<u32>(), 1);
        // Zero errors among positive ones get the minimum.
        let c = allocate(&[0.0, 1.0, 1.0, 0.0], 4 * 16, 6, 64);
        assert_eq!(c, vec![6, 26, 26, 6]);
    }

    #[test]
    fn budget_is_exact_for_awkward_errors() {
        // Errors spanning decades, odd sizes: the sum is always the budget.
        for n in [1usize, 7, 33, 257] {
            let err: Vec<f32> = (0..n)
                .map(|k| ((k * 7919) % 101) as f32 * 10f32.powi((k % 5) as i32 - 2))
                .collect();
            for spp in [4u32, 5, 16, 31] {
                let budget = n as u64 * spp as u64;
                let c = allocate(&err, budget, min_spp(spp), max_spp(spp));
                assert_eq!(
                    c.iter().map(|&c| c as u64).sum::<u64>(),
                    budget,
                    "n {n} spp {spp}"
                );
                assert!(c.iter().all(|&c| c >= min_spp(spp) && c <= max_spp(spp)));
            }
        }
    }
}
