//! The cone a sun disk subtends, held so that any angular size works in f32.
//!
//! The sun's half-angle α is tiny (0.0047 rad; the scene format accepts any
//! diameter in (0, 90)°): cos α rounds to 1 in f32 once α < 2.4e-4 rad
//! (diameter ≤ 0.028°), which made the cone's solid angle 0 and its radiance
//! and pdf infinite. The cone is therefore kept as h_max = 1 − cos α =
//! 2 sin²(α/2) (computed in f64, no cancellation) and sampled by h = 1 − cos θ
//! uniform in [0, h_max], with sin θ = √(h (2 − h)); membership is tested on
//! sin² θ = |axis × d|², which keeps its relative precision near the axis
//! where cos θ has none. Radiance, pdf and sampled region all derive from the
//! one f32 value h_max, so the estimator stays consistent for every size.

use glam::{Vec2, Vec3};
use shaders_cpu::sampling::sin_cos_turns;

/// A cone around an axis by its half-angle's 1 − cos, see the module header.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunCone {
    /// 1 − cos α of the half-angle α (> 0 for any α > 1e-22 rad).
    pub one_minus_cos: f32,
    /// sin² α, derived from `one_minus_cos`: the membership bound.
    pub sin2_max: f32,
}

impl SunCone {
    /// The cone of half-angle `angular_radius_rad` (in (0, π/2)).
    pub fn new(angular_radius_rad: f32) -> SunCone {
        let s = (angular_radius_rad as f64 * 0.5).sin();
        let h = (2.0 * s * s) as f32;
        SunCone {
            one_minus_cos: h,
            sin2_max: h * (2.0 - h),
        }
    }

    /// Solid angle 2π (1 − cos α), sr.
    pub fn solid_angle(&self) -> f32 {
        (2.0 * std::f64::consts::PI * self.one_minus_cos as f64) as f32
    }

    /// Pdf per solid angle of [`SunCone::sample_local`].
    pub fn pdf(&self) -> f32 {
        1.0 / self.solid_angle()
    }

    /// Radiance of a uniform disk filling the cone that gives `irradiance`
    /// on a surface facing it: E = L·π·sin²α = L·Ω·(1 − h/2).
    pub fn radiance(&self, irradiance: Vec3) -> Vec3 {
        irradiance / (self.solid_angle() * (1.0 - 0.5 * self.one_minus_cos))
    }

    /// A direction uniform in the cone around +z (unit up to f32 rounding).
    #[inline]
    pub fn sample_local(&self, u: Vec2) -> Vec3 {
        let h = u.x * self.one_minus_cos;
        let sin_theta = (h * (2.0 - h)).max(0.0).sqrt();
        let (sin_phi, cos_phi) = sin_cos_turns(u.y);
        Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, 1.0 - h)
    }

    /// Whether unit direction `d` lies in the cone around unit `axis`.
    #[inline]
    pub fn contains(&self, axis: Vec3, d: Vec3) -> bool {
        axis.dot(d) > 0.0 && axis.cross(d).length_squared() <= self.sin2_max
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every accepted size, tiny ones included, gives a finite cone whose
    /// solid angle matches 2π(1 − cos α) to f32 precision (the reference
    /// from the f64 cosine for large cones, from the series
    /// α²/2 − α⁴/24 + α⁶/720 for small ones, where even f64 cancels).
    #[test]
    fn cone_is_finite_and_exact_for_every_size() {
        for diameter_deg in [1e-6, 1e-3, 0.02, 0.03, 0.533, 10.0, 89.9] {
            let a = (diameter_deg / 2.0f64).to_radians();
            let c = SunCone::new(a as f32);
            let a = a as f32 as f64;
            let one_minus_cos = if a < 1e-2 {
                a * a / 2.0 - a.powi(4) / 24.0 + a.powi(6) / 720.0
            } else {
                1.0 - a.cos()
            };
            let exact = 2.0 * std::f64::consts::PI * one_minus_cos;
            let rel = (c.solid_angle() as f64 - exact).abs() / exact;
            assert!(
                rel < 1e-5,
                "{diameter_deg}°: Ω {} vs {exact}",
                c.solid_angle()
            );
            assert!(c.pdf().is_finite() && c.radiance(Vec3::ONE).is_finite());
        }
    }

    /// Samples fill the cone: all inside, and the mean of 1 − cos θ is
    /// h_max/2 (uniform in solid angle), also where cos θ rounds to 1.
    #[test]
    fn samples_are_uniform_inside_the_cone() {
        for diameter_deg in [1e-3, 0.02, 0.533, 30.0] {
            let c = SunCone::new((diameter_deg / 2.0f64).to_radians() as f32);
            let axis = Vec3::Z;
            let n = 64;
            let mut mean_sin2 = 0.0f64;
            for i in 0..n {
                for j in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    let d = c.sample_local(u);
                    assert!(d.is_finite());
                    assert!(c.contains(axis, d), "{diameter_deg}°: {d:?} outside");
                    mean_sin2 += axis.cross(d).length_squared() as f64;
                }
            }
            mean_sin2 /= (n * n) as f64;
            // sin²θ = h(2 − h) with h uniform on [0, H]: mean H − H²/3.
            let h = c.one_minus_cos as f64;
            let expect = h - h * h / 3.0;
            assert!(
                (mean_sin2 / expect - 1.0).abs() < 1e-3,
                "{diameter_deg}°: {mean_sin2} vs {expect}"
            );
            let outside = Vec3::new((2.0 * c.sin2_max).sqrt(), 0.0, 1.0).normalize();
            assert!(!c.contains(axis, outside));
        }
    }
}
