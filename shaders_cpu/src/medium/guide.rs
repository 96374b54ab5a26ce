//! Where on a ray segment to estimate in-scattering: a one-sample mixture of
//! a guided density and free flight (∝ σ_t·Tr). In a height fog the sun's
//! transmittance to a point grows exponentially with its height, so along a
//! rising segment the single-scattered sunlight σ_s·Tr·f·E·Tr_sun is
//! concentrated far from where σ_t·Tr puts its points; one point ∝ σ_t·Tr
//! then makes fireflies. The guide tabulates that product (suns without
//! occlusion plus a sky term) on `BINS` bins uniform in optical depth τ from
//! the ray origin, so its density in t is p_τ(τ(t))·σ_t(t) and the estimator
//! σ_s·Tr·L_s / pdf = albedo·e^{−τ}·L_s / q(τ) never divides by a vanishing
//! density: the free-flight part (weight 1 − `GUIDED`) keeps it unbiased
//! where the table is cut off. Positions render space; directions unit; wo
//! points back along the ray (pbrt convention).

use glam::Vec3;

use super::Medium;

/// Bins of the guided table (uniform in τ).
const BINS: usize = 16;
/// Optical depth beyond which the table stops (Tr < 1e-5).
const TAU_CAP: f64 = 11.5;
/// Share of the guided component in the mixture.
const GUIDED: f32 = 0.5;

/// A distant source as the guide sees it: direction toward it and the
/// luminance of its irradiance (0 = unused slot).
pub type GuideSun = (Vec3, f32);

/// The in-scattering point density of one segment.
#[derive(Clone, Debug)]
pub struct SegmentGuide {
    /// Optical depth of the whole segment.
    tau_tot: f64,
    /// Optical depth covered by the table, ≤ `tau_tot`.
    tau_max: f64,
    /// Bin probabilities of the table (sum 1).
    pmf: [f32; BINS],
}

/// A sampled in-scattering point.
#[derive(Clone, Copy, Debug)]
pub struct GuideSample {
    /// Ray parameter (metres).
    pub t: f32,
    /// Tr(0, t)·σ_t(t) / pdf(t): the estimator's weight per unit of
    /// (albedo·in-scattered radiance), dimensionless.
    pub weight: f32,
    /// Density per metre of the point.
    pub pdf: f32,
}

impl SegmentGuide {
    /// The guide for o + t·d, t ∈ [0, `t_end`], seen from direction `wo` = −d,
    /// lit by `suns` (through the medium) and a sky of mean luminance
    /// `sky_lum`. None when the segment has no optical depth.
    pub fn new(
        m: &Medium,
        o: Vec3,
        d: Vec3,
        t_end: f32,
        suns: &[GuideSun],
        sky_lum: f32,
    ) -> Option<Self> {
        let tau_tot = m.optical_depth(o, d, t_end);
        if tau_tot.is_nan() || tau_tot <= 0.0 {
            return None;
        }
        let tau_max = tau_tot.min(TAU_CAP);
        let wo = -d;
        let mut w = [0.0f32; BINS];
        for (j, wj) in w.iter_mut().enumerate() {
            let tau = tau_max * (j as f64 + 0.5) / BINS as f64;
            let t = t_at(m, o, d, t_end, tau);
            let x = o + d * t;
            let mut h = sky_lum * (-m.optical_depth(x, Vec3::Z, f32::INFINITY)).exp() as f32;
            for &(dir, e) in suns {
                if e > 0.0 {
                    let tr = (-m.optical_depth(x, dir, f32::INFINITY)).exp() as f32;
                    h += m.phase.eval(wo, dir) * e * tr;
                }
            }
            *wj = (-tau).exp() as f32 * h;
        }
        let sum: f32 = w.iter().sum();
        let pmf = if sum > 0.0 && sum.is_finite() {
            w.map(|x| x / sum)
        } else {
            // No light estimate: follow e^{−τ} within the table.
            let mut p = [0.0f32; BINS];
            for (j, pj) in p.iter_mut().enumerate() {
                *pj = (-(tau_max * (j as f64 + 0.5) / BINS as f64)).exp() as f32;
            }
            let s: f32 = p.iter().sum();
            p.map(|x| x / s)
        };
        Some(SegmentGuide {
            tau_tot,
            tau_max,
            pmf,
        })
    }

    /// Transmittance of the whole segment.
    pub fn tr_seg(&self) -> f32 {
        (-self.tau_tot).exp() as f32
    }

    /// Mixture density per unit τ at optical depth `tau` ∈ [0, τ_tot].
    fn q_tau(&self, tau: f64) -> f32 {
        let free = (-tau).exp() / -(-self.tau_tot).exp_m1();
        let mut q = (1.0 - GUIDED) * free as f32;
        if tau < self.tau_max {
            let j = ((tau / self.tau_max * BINS as f64) as usize).min(BINS - 1);
            q += GUIDED * self.pmf[j] * BINS as f32 / self.tau_max as f32;
        }
        q
    }

    /// Density per metre of [`SegmentGuide::sample`] choosing ray parameter `t`.
    pub fn pdf(&self, m: &Medium, o: Vec3, d: Vec3, t: f32) -> f32 {
        let sigma_t = m.sigma_t(o + d * t) as f32;
        if sigma_t == 0.0 {
            return 0.0;
        }
        self.q_tau(m.optical_depth(o, d, t)) * sigma_t
    }

    /// Draws a point with `u` ∈ [0, 1): `u` < `GUIDED` picks the table,
    /// the rest free flight conditioned on colliding in the segment.
    pub fn sample(&self, m: &Medium, o: Vec3, d: Vec3, t_end: f32, u: f32) -> Option<GuideSample> {
        let tau = if u < GUIDED {
            let v = (u / GUIDED).min(1.0 - 1e-7);
            let mut acc = 0.0f32;
            let mut j = BINS - 1;
            for (k, &p) in self.pmf.iter().enumerate() {
                if v < acc + p {
                    j = k;
                    break;
                }
                acc += p;
            }
            let frac = if self.pmf[j] > 0.0 {
                ((v - acc) / self.pmf[j]).clamp(0.0, 1.0 - 1e-6)
            } else {
                0.5
            };
            self.tau_max * (j as f64 + frac as f64) / BINS as f64
        } else {
            // Inverse cdf of e^{−τ} on [0, τ_tot].
            let v = ((u - GUIDED) / (1.0 - GUIDED)).min(1.0 - 1e-7) as f64;
            -(v * (-self.tau_tot).exp_m1()).ln_1p()
        };
        let t = t_at(m, o, d, t_end, tau);
        let sigma_t = m.sigma_t(o + d * t) as f32;
        let tau_t = m.optical_depth(o, d, t);
        let q = self.q_tau(tau_t);
        if sigma_t == 0.0 || q <= 0.0 || !q.is_finite() {
            return None;
        }
        Some(GuideSample {
            t,
            weight: (-tau_t).exp() as f32 / q,
            pdf: q * sigma_t,
        })
    }
}

/// Ray parameter where the optical depth from the origin reaches `tau`
/// (< τ of the segment), by free flight's closed-form inverse.
fn t_at(m: &Medium, o: Vec3, d: Vec3, t_end: f32, tau: f64) -> f32 {
    let u = -(-tau).exp_m1();
    m.sample_distance(o, d, t_end, u as f32).t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::medium::{Density, HenyeyGreenstein};

    fn fog() -> Medium {
        Medium {
            density: Density::HeightExp {
                sigma0: 0.04,
                z0: 0.0,
                height_scale: 30.0,
            },
            albedo: Vec3::splat(0.99),
            phase: HenyeyGreenstein { g: 0.85 },
            z_min: f64::NEG_INFINITY,
            z_max: f64::INFINITY,
        }
    }

    #[test]
    fn guide_pdf_integrates_to_one_and_matches_its_samples() {
        let m = fog();
        let o = Vec3::new(0.0, 0.0, 1.5);
        let d = Vec3::new(0.8, 0.0, 0.6);
        let sun = (Vec3::new(0.9, 0.0, 0.436).normalize(), 300.0);
        let t_end = 400.0;
        let g = SegmentGuide::new(&m, o, d, t_end, &[sun], 10.0).unwrap();
        // Midpoint rule of the density over the segment.
        let n = 200_000;
        let dt = t_end / n as f32;
        let integral: f64 = (0..n)
            .map(|i| g.pdf(&m, o, d, (i as f32 + 0.5) * dt) as f64 * dt as f64)
            .sum();
        assert!((integral - 1.0).abs() < 2e-3, "{integral}");
        for k in 0..64 {
            let s = g.sample(&m, o, d, t_end, (k as f32 + 0.5) / 64.0).unwrap();
            let p = g.pdf(&m, o, d, s.t);
            assert!((s.pdf - p).abs() <= 1e-3 * p, "{k}: {} vs {p}", s.pdf);
        }
    }

    #[test]
    fn guide_weight_averages_to_one_minus_tr() {
        // E[weight] = ∫ σ_t·Tr dt = 1 − Tr(segment), whatever the table.
        let m = fog();
        let o = Vec3::new(0.0, 0.0, 2.0);
        let d = Vec3::new(0.6, 0.8, 0.0);
        let sun = (Vec3::new(0.0, 1.0, 0.3).normalize(), 500.0);
        let t_end = 150.0;
        let g = SegmentGuide::new(&m, o, d, t_end, &[sun], 20.0).unwrap();
        let n = 100_000;
        let mean: f64 = (0..n)
            .map(|k| {
                let u = (k as f32 + 0.5) / n as f32;
                g.sample(&m, o, d, t_end, u).map_or(0.0, |s| s.weight as f64)
            })
            .sum::<f64>()
            / n as f64;
        let expect = 1.0 - g.tr_seg() as f64;
        assert!((mean - expect).abs() < 2e-3 * expect, "{mean} vs {expect}");
    }
}
