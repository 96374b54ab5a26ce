//! The denoiser's per-view input: the smooth parts of each pixel's
//! radiance, as means over its samples (`integrator::DenoiseSum`).

use glam::Vec3;

use crate::integrator::{luminance, DenoiseSum};

/// One view's parts of radiance to denoise, per pixel (row-major) the mean
/// over its samples.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewInputs {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Mean first-medium-scatter radiance per pixel (part of the film's radiance).
    pub l_fog: Vec<Vec3>,
    /// Mean opacity 1 − Tr of the samples' first segments per pixel, in [0, 1].
    pub opacity: Vec<f32>,
    /// Mean light filtered over the first (Lambertian) surface per pixel
    /// (`DenoiseSample::l_surf`, part of the film's radiance).
    pub l_surf: Vec<Vec3>,
    /// Mean throughput × albedo at the first surface per pixel (`DenoiseSample::rho`).
    pub rho: Vec<Vec3>,
    /// Share of the samples whose split vertex lies behind delta scatters
    /// (`DenoiseSample::split_behind_delta`): the surface component filters
    /// pixels only with pixels of a like share.
    pub behind_delta: Vec<f32>,
    /// Mean direct light at the split vertex per pixel
    /// (`DenoiseSample::l_direct`, part of the film's radiance).
    pub l_direct: Vec<Vec3>,
    /// Variance of `l_direct`'s luminance as a pixel mean (the samples'
    /// variance over their count; with one sample, its square).
    pub var_direct: Vec<f32>,
    /// Variance of `l_surf`'s luminance as a pixel mean (as `var_direct`).
    pub var_surf: Vec<f32>,
    /// Mean throughput × albedo estimate `l_direct` is filtered against
    /// (`DenoiseSample::rho_direct`).
    pub rho_direct: Vec<Vec3>,
    /// Share of the samples split at a glossy vertex (`DenoiseSample::glossy`).
    pub glossy: Vec<f32>,
    /// Mean light along glass's reflection per pixel
    /// (`DenoiseSample::l_refl`, part of the film's radiance).
    pub l_refl: Vec<Vec3>,
    /// Variance of `l_refl`'s luminance as a pixel mean given which
    /// samples reflected: the variance of the radiance the reflected
    /// samples saw (`DenoiseSum::refl_seen`) over their count, times
    /// luminance(`rho_refl_hit`)².
    pub var_refl: Vec<f32>,
    /// Mean throughput × Fresnel reflectance over every sample that met
    /// the glass (`DenoiseSample::rho_refl`): the filtered reflected
    /// radiance is modulated back by it.
    pub rho_refl: Vec<Vec3>,
    /// Mean throughput after the reflection, on the reflected samples
    /// (`DenoiseSample::rho_refl_hit`): what `l_refl` is filtered
    /// against, so that the ratio is the radiance seen in the glass.
    pub rho_refl_hit: Vec<Vec3>,
    /// Mean openness of the split vertex's bounce over the samples with a
    /// `rho` (`DenoiseSample::openness`; 1 where none has one).
    pub openness: Vec<f32>,
}

impl ViewInputs {
    /// Inputs of `width × height` pixels with nothing to denoise.
    pub fn new(width: usize, height: usize) -> ViewInputs {
        ViewInputs {
            width,
            height,
            l_fog: vec![Vec3::ZERO; width * height],
            opacity: vec![0.0; width * height],
            l_surf: vec![Vec3::ZERO; width * height],
            rho: vec![Vec3::ZERO; width * height],
            behind_delta: vec![0.0; width * height],
            l_direct: vec![Vec3::ZERO; width * height],
            var_direct: vec![0.0; width * height],
            var_surf: vec![0.0; width * height],
            rho_direct: vec![Vec3::ZERO; width * height],
            glossy: vec![0.0; width * height],
            l_refl: vec![Vec3::ZERO; width * height],
            var_refl: vec![0.0; width * height],
            rho_refl: vec![Vec3::ZERO; width * height],
            rho_refl_hit: vec![Vec3::ZERO; width * height],
            openness: vec![1.0; width * height],
        }
    }

    /// Sets pixel `k` to the means of `sum` over `n` samples.
    pub fn set_mean(&mut self, k: usize, sum: &DenoiseSum, n: f32) {
        (self.l_fog[k], self.opacity[k]) = (sum.l_fog / n, sum.opacity / n);
        (self.l_surf[k], self.rho[k]) = (sum.l_surf / n, sum.rho / n);
        self.behind_delta[k] = sum.behind_delta as f32 / n;
        self.l_direct[k] = sum.l_direct / n;
        self.var_direct[k] = mean_variance(luminance(sum.l_direct), sum.direct_lum2, n);
        self.rho_direct[k] = sum.rho_direct / n;
        self.var_surf[k] = mean_variance(luminance(sum.l_surf), sum.surf_lum2, n);
        self.glossy[k] = sum.glossy as f32 / n;
        self.l_refl[k] = sum.l_refl / n;
        self.rho_refl[k] = sum.rho_refl / n;
        self.rho_refl_hit[k] = sum.rho_refl_hit / n;
        self.openness[k] = if sum.split_samples > 0 {
            sum.openness / sum.split_samples as f32
        } else {
            1.0
        };
        let hits = sum.refl_hits as f32;
        self.var_refl[k] = mean_variance(sum.refl_seen, sum.refl_seen2, hits)
            * luminance(self.rho_refl_hit[k]).powi(2);
    }

    /// Whether any pixel carries first-scatter radiance or opacity.
    pub fn has_first_scatter(&self) -> bool {
        self.opacity.iter().any(|&o| o != 0.0) || self.l_fog.iter().any(|&l| l != Vec3::ZERO)
    }

    /// Whether no pixel carries anything to filter: no first-scatter light
    /// and no light or rho on the first surface.
    pub fn is_empty(&self) -> bool {
        !self.has_first_scatter()
            && self.l_surf.iter().all(|&l| l == Vec3::ZERO)
            && self.rho.iter().all(|&r| r == Vec3::ZERO)
            && self.rho_direct.iter().all(|&r| r == Vec3::ZERO)
            && self.rho_refl.iter().all(|&r| r == Vec3::ZERO)
    }
}

/// Variance of a mean of `n` samples from their sum and sum of squares
/// (the unbiased sample variance over n; for one sample its square, so a
/// lone sample is never taken for noise-free).
pub(crate) fn mean_variance(sum: f32, sum2: f32, n: f32) -> f32 {
    if n <= 1.0 {
        return sum2;
    }
    let m = sum / n;
    ((sum2 - n * m * m) / (n * (n - 1.0))).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_mean_divides_every_part_by_the_sample_count() {
        let mut v = ViewInputs::new(2, 1);
        let sum = DenoiseSum {
            l_fog: Vec3::new(2.0, 4.0, 6.0),
            opacity: 1.0,
            l_surf: Vec3::splat(8.0),
            rho: Vec3::new(0.4, 0.8, 1.2),
            behind_delta: 3,
            l_direct: Vec3::new(4.0, 0.0, 0.0),
            direct_lum2: 0.2126f32.powi(2) * 10.0,
            surf_lum2: 40.0,
            rho_direct: Vec3::splat(2.0),
            glossy: 1,
            l_refl: Vec3::new(0.0, 8.0, 0.0),
            rho_refl: Vec3::splat(0.2),
            rho_refl_hit: Vec3::splat(2.0),
            refl_hits: 2,
            refl_seen: 6.0,
            refl_seen2: 20.0,
            openness: 1.5,
            split_samples: 3,
        };
        v.set_mean(1, &sum, 4.0);
        // Over the 3 samples with a rho, not all 4; none: open.
        assert_eq!((v.openness[0], v.openness[1]), (1.0, 0.5));
        assert_eq!(v.l_fog[1], Vec3::new(0.5, 1.0, 1.5));
        assert_eq!(v.opacity[1], 0.25);
        assert_eq!(v.l_surf[1], Vec3::splat(2.0));
        assert_eq!(v.rho[1], Vec3::new(0.1, 0.2, 0.3));
        assert_eq!(v.behind_delta[1], 0.75);
        assert_eq!(v.l_direct[1], Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(v.rho_direct[1], Vec3::splat(0.5));
        assert_eq!(v.glossy[1], 0.25);
        assert_eq!(v.l_refl[1], Vec3::new(0.0, 2.0, 0.0));
        assert_eq!(v.rho_refl[1], Vec3::splat(0.05));
        assert_eq!(v.rho_refl_hit[1], Vec3::splat(0.5));
        // Seen by 2 samples, 2 and 4 (sum 6, squares 20): variance 2 of
        // one, 1 of their mean; times luminance(0.5 grey)² = 0.25.
        assert!((v.var_refl[1] - 0.25).abs() < 1e-6, "{}", v.var_refl[1]);
        // Luminance sum 4y and square sum 10y² over 4 samples: variance of
        // the mean (Σx² − n·m²)/(n(n − 1)).
        let y = 0.2126f32;
        let want = (10.0 * y * y - 4.0 * y * y) / 12.0;
        assert!((v.var_direct[1] - want).abs() < 1e-7, "{}", v.var_direct[1]);
        // l_surf: luminance sum 8, square sum 40 over 4 samples.
        assert!(
            (v.var_surf[1] - (40.0 - 16.0) / 12.0).abs() < 1e-5,
            "{}",
            v.var_surf[1]
        );
        // Pixel 0 untouched.
        assert!(v.l_fog[0] == Vec3::ZERO && v.behind_delta[0] == 0.0);
        assert!(v.has_first_scatter() && !v.is_empty());
    }

    #[test]
    fn mean_variance_matches_the_two_pass_formula() {
        let xs = [0.5f32, 2.0, 3.5, 1.0, 8.0];
        let n = xs.len() as f32;
        let m = xs.iter().sum::<f32>() / n;
        let s2 = xs.iter().map(|x| (x - m).powi(2)).sum::<f32>() / (n - 1.0);
        let got = mean_variance(xs.iter().sum(), xs.iter().map(|x| x * x).sum(), n);
        assert!((got - s2 / n).abs() < 1e-5 * s2, "{got} vs {}", s2 / n);
        // Equal samples: no variance; one sample: its square.
        assert_eq!(mean_variance(6.0, 12.0, 3.0), 0.0);
        assert_eq!(mean_variance(3.0, 9.0, 1.0), 9.0);
    }
}
