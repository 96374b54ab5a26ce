//! The denoiser's per-view input: the smooth parts of each pixel's
//! radiance, as means over its samples (`integrator::DenoiseSum`).

use glam::Vec3;

use crate::integrator::DenoiseSum;

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
        }
    }

    /// Sets pixel `k` to the means of `sum` over `n` samples.
    pub fn set_mean(&mut self, k: usize, sum: &DenoiseSum, n: f32) {
        (self.l_fog[k], self.opacity[k]) = (sum.l_fog / n, sum.opacity / n);
        (self.l_surf[k], self.rho[k]) = (sum.l_surf / n, sum.rho / n);
        self.behind_delta[k] = sum.behind_delta as f32 / n;
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
    }
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
        };
        v.set_mean(1, &sum, 4.0);
        assert_eq!(v.l_fog[1], Vec3::new(0.5, 1.0, 1.5));
        assert_eq!(v.opacity[1], 0.25);
        assert_eq!(v.l_surf[1], Vec3::splat(2.0));
        assert_eq!(v.rho[1], Vec3::new(0.1, 0.2, 0.3));
        assert_eq!(v.behind_delta[1], 0.75);
        // Pixel 0 untouched.
        assert!(v.l_fog[0] == Vec3::ZERO && v.behind_delta[0] == 0.0);
        assert!(v.has_first_scatter() && !v.is_empty());
    }
}
