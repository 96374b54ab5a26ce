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
    fn hg_forward_g_scatters_along_propagation() {
        let p = HenyeyGreenstein { g: 0.85 };
        let wo = Vec3::new(0.0, 0.0, 1.0);
        // Propagation is −z; forward scattering keeps going −z.
        assert!(p.eval(wo, -wo) > 100.0 * p.eval(wo, wo));
        let s = p.sample(wo, Vec2::new(0.999, 0.2));
        assert!(s.wi.z < -0.9, "{s:?}");
    }
}
