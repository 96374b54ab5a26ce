//! Optional sensor noise on the linear film, before the tone curve: photon shot
//! noise, read noise and photo-response non-uniformity (PRNU), the three terms
//! of the EMVA 1288 linear camera model (EMVA Standard 1288, release 4.0, §2):
//! electrons e = Poisson(μ·g_prnu) + N(0, σ_read²), with μ ∝ exposed signal.
//!
//! Scale: an exposed linear value x = L·exposure_scale (0.18 = middle grey)
//! collects μ = x · full_well_e · BASE_ISO / iso electrons, so ISO trades
//! electrons per unit of exposure (a higher ISO is a higher analogue gain on
//! fewer photons). Each channel is treated as its own photosite (no Bayer
//! mosaic). Draws are pure functions of (seed, frame, view, pixel, channel):
//! views are independent, any thread count gives the same bytes. PRNU is a
//! fixed pattern of each sensor (view), so it does not depend on the frame.

use super::Film;
use crate::sampler::{hash_words, mix64};
pub use crate::scene::desc::SensorNoise;

/// ISO at which an exposed value of 1.0 fills the full well.
pub const BASE_ISO: f32 = 100.0;

/// Stream tags (apart from every other stream of the renderer).
const SHOT_TAG: u64 = 0x5345_4e53_4f52_0001;
const PRNU_TAG: u64 = 0x5345_4e53_4f52_0002;

/// Which frame and view a noise draw belongs to (the render's stream key).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoiseKey {
    /// The frame's seed.
    pub seed: u64,
    /// Frame index.
    pub frame: u32,
    /// View index (0 = left, 1 + b = right camera of baseline b).
    pub view: u32,
}

impl SensorNoise {
    /// Electrons collected per unit of exposed linear value: full_well · BASE_ISO / iso.
    pub fn electrons_per_unit(&self) -> f32 {
        self.full_well_e * BASE_ISO / self.iso
    }

    /// Model variance of the noisy linear radiance of a pixel of radiance `l`
    /// (PRNU left out: it is a fixed pattern, not a temporal variance), for a
    /// frame exposed by `exposure_scale`: (μ + σ_read²) / (k·s)², μ = l·s·k.
    pub fn variance(&self, l: f32, exposure_scale: f32) -> f64 {
        let ks = self.electrons_per_unit() as f64 * exposure_scale as f64;
        let mu = (l as f64 * ks).max(0.0);
        (mu + (self.read_noise_e as f64).powi(2)) / (ks * ks)
    }

    /// Adds noise to `film` in place. `exposure_scale` is the frame's shared
    /// exposure (it fixes how many electrons a radiance value is); the film
    /// stays linear and un-exposed. Non-finite pixels are left alone; the
    /// result may dip below zero in the dark (read noise), as raw data does.
    pub fn apply(&self, film: &mut Film, exposure_scale: f32, key: NoiseKey) {
        let ks = self.electrons_per_unit() as f64 * exposure_scale as f64;
        if !(ks.is_finite() && ks > 0.0) {
            return;
        }
        for (p, rgb) in film.rgb.iter_mut().enumerate() {
            let mut out = rgb.to_array();
            for (c, v) in out.iter_mut().enumerate() {
                if !v.is_finite() {
                    continue;
                }
                let site = (p as u64) * 3 + c as u64;
                let gain = 1.0 + self.prnu as f64 * self.prnu_normal(key, site);
                let mu = (*v as f64 * ks * gain).max(0.0);
                let mut rng = Stream(hash_words(&[
                    SHOT_TAG,
                    key.seed,
                    key.frame as u64,
                    key.view as u64,
                    site,
                ]));
                let electrons = poisson(mu, &mut rng) + self.read_noise_e as f64 * rng.normal();
                *v = (electrons / ks) as f32;
            }
            *rgb = out.into();
        }
    }

    /// The fixed PRNU pattern's standard normal at photosite `site` of the view.
    fn prnu_normal(&self, key: NoiseKey, site: u64) -> f64 {
        if self.prnu == 0.0 {
            return 0.0;
        }
        Stream(hash_words(&[PRNU_TAG, key.seed, key.view as u64, site])).normal()
    }
}

/// Adds independent sensor noise to every view of a frame (view index = its
/// position in `images`), all exposed by the frame's shared `exposure_scale`.
pub fn apply_sensor_noise(
    images: &mut [Film],
    noise: &SensorNoise,
    exposure_scale: f32,
    seed: u64,
    frame: u32,
) {
    for (view, film) in images.iter_mut().enumerate() {
        let key = NoiseKey {
            seed,
            frame,
            view: view as u32,
        };
        noise.apply(film, exposure_scale, key);
    }
}

/// A SplitMix64 counter stream: cheap, and a pure function of its start.
struct Stream(u64);

impl Stream {
    /// Uniform in (0, 1): never 0, so logarithms stay finite.
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(1);
        ((mix64(self.0) >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
    }

    /// Standard normal by Box–Muller (one of the pair).
    fn normal(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// Poisson draw of mean `mu`: exact (Knuth's product of uniforms) below 30
/// electrons, where the skew matters; above, the normal N(μ, μ) whose error
/// in the variance is nil and in the shape below 1% of σ.
fn poisson(mu: f64, rng: &mut Stream) -> f64 {
    if mu <= 0.0 {
        return 0.0;
    }
    if mu >= 30.0 {
        return mu + mu.sqrt() * rng.normal();
    }
    let limit = (-mu).exp();
    let (mut k, mut prod) = (0u32, rng.uniform());
    while prod > limit {
        k += 1;
        prod *= rng.uniform();
    }
    k as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_mean_poisson_has_mean_and_variance_mu() {
        let mut rng = Stream(42);
        let mu = 4.0;
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|_| poisson(mu, &mut rng)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        assert!((mean - mu).abs() < 0.03, "mean {mean}");
        assert!((var / mu - 1.0).abs() < 0.03, "variance {var}");
        assert!(xs.iter().all(|x| x.fract() == 0.0 && *x >= 0.0));
    }

    #[test]
    fn large_mean_poisson_has_mean_and_variance_mu() {
        // μ ≥ 30 takes the normal branch: still mean μ and variance μ. Bounds
        // are 5 standard errors: √(μ/n) on the mean, √(2/n) relative on the
        // variance (plus the Poisson excess kurtosis 1/μ).
        let n = 200_000;
        for mu in [30.0, 1000.0] {
            let mut rng = Stream(7 + mu as u64);
            let xs: Vec<f64> = (0..n).map(|_| poisson(mu, &mut rng)).collect();
            let mean = xs.iter().sum::<f64>() / n as f64;
            let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
            let se_mean = (mu / n as f64).sqrt();
            let se_var = ((2.0 + 1.0 / mu) / n as f64).sqrt();
            assert!((mean - mu).abs() < 5.0 * se_mean, "μ {mu}: mean {mean}");
            assert!(
                (var / mu - 1.0).abs() < 5.0 * se_var,
                "μ {mu}: variance {var}"
            );
        }
    }

    #[test]
    fn iso_halves_electrons_per_doubling() {
        let n = |iso| SensorNoise {
            iso,
            full_well_e: 20_000.0,
            read_noise_e: 3.0,
            prnu: 0.0,
        };
        assert_eq!(n(100.0).electrons_per_unit(), 20_000.0);
        assert_eq!(n(800.0).electrons_per_unit(), 2_500.0);
    }
}
