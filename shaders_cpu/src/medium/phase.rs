//! Henyey–Greenstein phase function (Henyey & Greenstein 1941; sampling by
//! CDF inversion as pbrt-v4 §11.3.1).
//!
//! Convention (pbrt): `wo` points back toward the viewer, `wi` toward the
//! light, both away from the scattering point. The scattering angle θ is
//! between the propagation direction −wo and wi, so g > 0 scatters forward
//! (wi ≈ −wo). Values are per steradian; the phase is its own sampling pdf.

use glam::{Vec2, Vec3};

use crate::sampling::Frame;

/// A Henyey–Greenstein lobe with asymmetry `g` in (−1, 1) (fog ≈ 0.85).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    /// Mean cosine of the scattering angle.
    pub g: f32,
}

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseSample {
    /// Unit direction toward the light (away from the point).
    pub wi: Vec3,
    /// Phase value = pdf per solid angle.
    pub pdf: f32,
}

/// Added to the largest cosine of a z band (`max_in_z_band`): far above
/// the f32 rounding of a unit direction's components and dot product.
const BAND_COS_SLACK: f32 = 1e-3;

/// p(cos θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}), cos θ between the
/// propagation direction and the scattered direction.
pub fn hg(cos_theta: f32, g: f32) -> f32 {
    let denom = 1.0 + g * g - 2.0 * g * cos_theta;
    (1.0 - g * g) / (4.0 * std::f32::consts::PI * denom * denom.max(0.0).sqrt())
}

impl HenyeyGreenstein {
    /// Phase value for light arriving along −wi and leaving along wo (1/sr).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        hg(-wo.dot(wi), self.g)
    }

    /// An upper bound of `eval(wo, wi)` over every unit `wi` whose z lies
    /// in [`z_lo`, `z_hi`] (a row of a sky table): the value toward the
    /// direction of that band nearest the propagation direction −wo, its
    /// cosine raised by `BAND_COS_SLACK` so that directions drawn in the
    /// band, and a wo a rounding off unit length, stay under it.
    pub fn max_in_z_band(&self, wo: Vec3, z_lo: f32, z_hi: f32) -> f32 {
        if self.g <= 0.0 {
            // The lobe peaks backward (or is flat): its global maximum.
            return hg(-1.0, self.g);
        }
        let z_f = (-wo.z).clamp(-1.0, 1.0);
        let z_e = z_f.clamp(z_lo, z_hi);
        let r_f = (1.0 - z_f * z_f).max(0.0).sqrt();
        let r_e = (1.0 - z_e * z_e).max(0.0).sqrt();
        hg((z_f * z_e + r_f * r_e + BAND_COS_SLACK).min(1.0), self.g)
    }

    /// Pdf per solid angle of `sample` choosing `wi` (equals `eval`).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval(wo, wi)
    }

    /// Samples `wi` from the lobe around the propagation direction −wo.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> PhaseSample {
        let g = self.g;
        // Inverting the CDF of cos θ: F(μ) = (1 − g²)/(2g) ·
        // [(1 + g² − 2gμ)^{-1/2} − (1 + g)^{-1}]; isotropic limit separately.
        let cos_theta = if g.abs() < 1e-3 {
            1.0 - 2.0 * u.x
        } else {
            let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
            ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
        };
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let phi = 2.0 * std::f32::consts::PI * u.y;
        let local = Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta);
        let wi = Frame::from_z(-wo).from_local(local).normalize();
        PhaseSample {
            wi,
            pdf: hg(cos_theta, g),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hg_isotropic_is_one_over_four_pi() {
        let v = hg(0.3, 0.0);
        assert!((v - 1.0 / (4.0 * std::f32::consts::PI)).abs() < 1e-7);
    }

    #[test]
    fn band_bound_holds_over_the_band_and_is_reached_near_its_nearest_direction() {
        // Every 64th of z (a sky table's rows) against wo all round the
        // sphere: the phase value toward directions spread over the band
        // (edges included) never exceeds the bound, and the band's
        // direction nearest −wo comes within the slack of it (g ≥ 0).
        let mut worst_ratio = 0.0f32;
        for g in [0.0, 0.3, 0.7, 0.85, -0.5] {
            let p = HenyeyGreenstein { g };
            for a in 0..24 {
                for b in 0..13 {
                    let wo = unit(b as f32 / 12.0, a as f32 / 24.0);
                    for j in 0..64 {
                        let (z_lo, z_hi) = (j as f32 / 32.0 - 1.0, (j + 1) as f32 / 32.0 - 1.0);
                        let bound = p.max_in_z_band(wo, z_lo, z_hi);
                        let mut best = 0.0f32;
                        for s in 0..=8 {
                            let z = z_lo + (z_hi - z_lo) * s as f32 / 8.0;
                            for k in 0..64 {
                                let wi = unit((z + 1.0) / 2.0, k as f32 / 64.0);
                                let f = p.eval(wo, wi);
                                assert!(f <= bound, "g {g} wo {wo} z {z}: {f} > {bound}");
                                best = best.max(f);
                            }
                            // The band's direction at −wo's azimuth.
                            let az = (-wo.y).atan2(-wo.x) / std::f32::consts::TAU;
                            let f = p.eval(wo, unit((z + 1.0) / 2.0, az));
                            assert!(f <= bound, "g {g} wo {wo} z {z}: {f} > {bound}");
                            best = best.max(f);
                        }
                        // Backward lobes (g < 0) take the global maximum.
                        if g >= 0.0 {
                            worst_ratio = worst_ratio.max(bound / best);
                        }
                    }
                }
            }
        }
        // At g = 0.85 the slack's 1e-3 in cosine is 12 % at the peak.
        assert!(
            worst_ratio < 1.2,
            "bound {worst_ratio}× the band's largest value"
        );
    }

    /// Unit direction at z = 2·`v` − 1 and azimuth `turns`·2π.
    fn unit(v: f32, turns: f32) -> Vec3 {
        let z = (2.0 * v - 1.0).clamp(-1.0, 1.0);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = turns * std::f32::consts::TAU;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    #[test]
    fn hg_forward_g_scatters_along_propagation() {
        let p = HenyeyGreenstein { g: 0.85 };
        let wo = Vec3::new(0.0, 0.0, 1.0);
        // Propagation is −z; forward scattering keeps going −z.
        assert!(p.eval(wo, -wo) > 100.0 * p.eval(wo, wo));
        let s = p.sample(wo, Vec2::new(0.999, 0.2));
        assert!(s.wi.z < -0.9, "{s:?}");
    }
}
