//! Pearson chi-square goodness-of-fit test of a direction sampler against its
//! pdf, following Mitsuba 3's `chi2.py` (Jakob et al.): histogram samples over
//! a fixed (θ, φ) grid of the sphere, integrate the pdf over each cell
//! (composite Simpson on a shared fine grid, dω = sin θ dθ dφ), pool cells with
//! expected count < 5, and turn the statistic into a p-value with the
//! chi-square survival function. Cells are uniform in θ rather than cos θ so
//! lobes peaked at the poles (normal-incidence transmission) are resolved.

use super::gamma::chi2_sf;
use super::pcg::Pcg32;
use super::quadrature::{adaptive_simpson_2d, simpson_2d, Rect};
use glam::{Vec2, Vec3};
use std::f64::consts::PI;

/// Resolution and sample budget of a chi-square run.
#[derive(Clone, Copy, Debug)]
pub struct Chi2Config {
    /// Number of samples drawn (≤ 1e6 keeps tests fast).
    pub n_samples: usize,
    /// Cells along θ ∈ [0, π]; keep even so the horizon is a cell edge.
    pub n_theta: usize,
    /// Cells along φ ∈ [-π, π].
    pub n_phi: usize,
    /// Simpson intervals per (sub)cell per axis (even) in the adaptive rule.
    pub subdiv: usize,
    /// Minimum expected count before pooling (5 is the textbook rule).
    pub min_expected: f64,
    /// PCG32 seed for the sample stream.
    pub seed: u64,
}

impl Default for Chi2Config {
    fn default() -> Self {
        Chi2Config {
            n_samples: 1_000_000,
            n_theta: 40,
            n_phi: 80,
            subdiv: 4,
            min_expected: 5.0,
            seed: 0x5eed,
        }
    }
}

/// Outcome of a chi-square run.
#[derive(Clone, Copy, Debug)]
pub struct Chi2Result {
    /// Pr[χ² ≥ statistic] under the hypothesis that samples follow the pdf.
    pub p_value: f64,
    /// Pearson statistic Σ (observed − expected)² / expected over pooled cells.
    pub statistic: f64,
    /// Degrees of freedom (pooled cells − 1).
    pub dof: usize,
    /// ∫ pdf dω over the sphere (numerical); should match `valid_fraction`.
    pub pdf_integral: f64,
    /// Fraction of sample calls that returned a direction.
    pub valid_fraction: f64,
    /// Samples that were non-finite or fell in cells whose pdf integral is 0.
    pub outliers: usize,
}

impl Chi2Result {
    /// Whether the sampler is accepted at significance level `alpha`.
    pub fn passes(&self, alpha: f64) -> bool {
        self.outliers == 0 && self.p_value >= alpha
    }
}

/// Per-test significance that keeps the family-wise rejection rate at `alpha`
/// over `n_tests` independent tests (Šidák correction).
pub fn sidak_threshold(alpha: f64, n_tests: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / n_tests as f64)
}

/// [`chi2_test_with`] at the default resolution with `n_samples` samples.
///
/// `sample(u, u_lobe)` maps uniform numbers to a unit direction (or `None`);
/// `pdf(dir)` is its claimed density per solid angle.
pub fn chi2_test(
    sample: impl FnMut(Vec2, f32) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f32,
    n_samples: usize,
) -> Chi2Result {
    let config = Chi2Config {
        n_samples,
        ..Chi2Config::default()
    };
    chi2_test_with(&config, sample, pdf)
}

/// Runs the chi-square test with an explicit configuration.
pub fn chi2_test_with(
    config: &Chi2Config,
    mut sample: impl FnMut(Vec2, f32) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f32,
) -> Chi2Result {
    let (nc, np) = (config.n_theta, config.n_phi);
    let mut observed = vec![0u64; nc * np];
    let mut rng = Pcg32::new(config.seed, 0xc412);
    let (mut valid, mut outliers) = (0usize, 0usize);
    for _ in 0..config.n_samples {
        let u = rng.next_vec2();
        let u_lobe = rng.next_f32();
        let Some(dir) = sample(u, u_lobe) else {
            continue;
        };
        valid += 1;
        match cell_of(dir, nc, np) {
            Some(cell) => observed[cell] += 1,
            None => outliers += 1,
        }
    }
    let integrals = cell_integrals(config, &pdf);
    let n = config.n_samples as f64;
    let expected: Vec<f64> = integrals.iter().map(|i| i * n).collect();
    for (o, e) in observed.iter().zip(&expected) {
        if *e == 0.0 && *o > 0 {
            outliers += *o as usize;
        }
    }
    let (statistic, cells) = pearson_pooled(&observed, &expected, config.min_expected);
    let dof = cells.saturating_sub(1);
    Chi2Result {
        p_value: if dof == 0 {
            1.0
        } else {
            chi2_sf(statistic, dof)
        },
        statistic,
        dof,
        pdf_integral: integrals.iter().sum(),
        valid_fraction: valid as f64 / n,
        outliers,
    }
}

/// Cell index of a direction, `None` if it is not finite.
fn cell_of(dir: Vec3, nc: usize, np: usize) -> Option<usize> {
    if !dir.is_finite() || dir.length_squared() == 0.0 {
        return None;
    }
    let d = dir.as_dvec3().normalize();
    let theta = d.z.clamp(-1.0, 1.0).acos();
    let ic = ((theta / PI * nc as f64) as usize).min(nc - 1);
    let phi = d.y.atan2(d.x);
    let ip = (((phi + PI) / (2.0 * PI) * np as f64) as usize).min(np - 1);
    Some(ic * np + ip)
}

/// ∫ pdf over each cell by adaptive Simpson (see `quadrature.rs`), to an
/// absolute tolerance of 0.2·√(expected count) samples so quadrature error
/// stays well below the counting noise the test is sensitive to.
fn cell_integrals(config: &Chi2Config, pdf: &impl Fn(Vec3) -> f32) -> Vec<f64> {
    let (nc, np) = (config.n_theta, config.n_phi);
    let n = config.n_samples as f64;
    let f = |theta: f64, phi: f64| {
        let (r, z) = theta.sin_cos();
        let dir = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
        // dω = sin θ dθ dφ.
        pdf(dir).max(0.0) as f64 * r
    };
    let mut out = vec![0.0f64; nc * np];
    for ic in 0..nc {
        let t = [PI * ic as f64 / nc as f64, PI * (ic + 1) as f64 / nc as f64];
        for ip in 0..np {
            let p = [
                -PI + 2.0 * PI * ip as f64 / np as f64,
                -PI + 2.0 * PI * (ip + 1) as f64 / np as f64,
            ];
            let rect = Rect { t, p };
            let whole = simpson_2d(&f, &rect, config.subdiv);
            let tol = 0.2 * (whole * n).max(1.0).sqrt() / n;
            out[ic * np + ip] = adaptive_simpson_2d(&f, &rect, whole, tol, config.subdiv, 6);
        }
    }
    out
}

/// Pearson statistic with pooling: cells sorted by expected count are merged
/// (smallest first) until each merged cell expects ≥ `min_expected`.
/// Returns (statistic, number of cells used).
fn pearson_pooled(observed: &[u64], expected: &[f64], min_expected: f64) -> (f64, usize) {
    let mut order: Vec<usize> = (0..expected.len()).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let (mut stat, mut cells) = (0.0, 0usize);
    let (mut pool_o, mut pool_e) = (0.0f64, 0.0f64);
    for idx in order {
        pool_o += observed[idx] as f64;
        pool_e += expected[idx];
        if pool_e >= min_expected {
            stat += (pool_o - pool_e).powi(2) / pool_e;
            cells += 1;
            pool_o = 0.0;
            pool_e = 0.0;
        }
    }
    if pool_e > 0.0 {
        stat += (pool_o - pool_e).powi(2) / pool_e;
        cells += 1;
    }
    (stat, cells)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere, sample_uniform_sphere};

    fn small() -> Chi2Config {
        Chi2Config {
            n_samples: 200_000,
            ..Chi2Config::default()
        }
    }

    #[test]
    fn chi2_accepts_uniform_sphere() {
        let r = chi2_test_with(
            &small(),
            |u, _| Some(sample_uniform_sphere(u)),
            |_| 0.25 / std::f32::consts::PI,
        );
        assert!((r.pdf_integral - 1.0).abs() < 1e-6, "{r:?}");
        assert!(r.passes(0.01), "{r:?}");
        // Polar cells (small solid angle) are pooled, the rest stand alone.
        assert!(r.dof > 3000 && r.dof < 40 * 80, "{r:?}");
    }

    #[test]
    fn chi2_rejects_wrong_pdf_and_stray_samples() {
        // Cosine samples judged against the uniform hemisphere pdf.
        let r = chi2_test_with(
            &small(),
            |u, _| Some(sample_cosine_hemisphere(u)),
            |w| {
                if w.z > 0.0 {
                    0.5 / std::f32::consts::PI
                } else {
                    0.0
                }
            },
        );
        assert!(!r.passes(1e-6), "{r:?}");
        // Samples in the lower hemisphere where the pdf is zero are outliers.
        let r = chi2_test_with(
            &small(),
            |u, _| Some(-sample_cosine_hemisphere(u)),
            |w| cosine_hemisphere_pdf(w.z),
        );
        assert!(r.outliers > 0 && !r.passes(0.01), "{r:?}");
    }
}
