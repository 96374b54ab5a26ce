//! Environment radiance for rays leaving the scene (world directions, z up,
//! W·m⁻²·sr⁻¹ per RGB channel).
//!
//! `Gradient` interpolates linearly in elevation: t = elevation / (π/2) =
//! asin(z)·2/π, L = lerp(horizon, zenith, t) for z ≥ 0 and `ground` below.
//! Its sampling (`sampling.rs`) mixes a cosine lobe about +z with the uniform
//! sphere. `Physical` (atmosphere tables, `physical.rs`) and `Overcast` (CIE)
//! are sampled from a piecewise-constant table (`distribution.rs`); every
//! pdf is positive wherever `le` can be.

pub mod atmosphere;
pub mod clouds;
pub mod distribution;
pub mod night;
pub mod overcast;
pub mod physical;
mod sampling;
pub mod tables;

pub use clouds::CloudLayer;
pub use distribution::SkyDistribution;
pub use night::NightGlow;
pub use overcast::OvercastSky;
pub use physical::{PhysicalSky, PhysicalSkyParams};

use crate::sampling::luminance;
use glam::{DVec3, Vec2, Vec3};
use std::f32::consts::FRAC_2_PI;

/// The environment: analytic skies and the tabulated physical ones.
#[derive(Clone, Debug)]
pub enum Sky {
    /// Constant radiance in every direction.
    Constant {
        /// Radiance, W·m⁻²·sr⁻¹ per channel.
        le: Vec3,
    },
    /// Zenith-to-horizon gradient above the horizon, constant `ground` below.
    Gradient {
        /// Radiance straight up.
        zenith: Vec3,
        /// Radiance at the horizon.
        horizon: Vec3,
        /// Radiance of every downward direction.
        ground: Vec3,
    },
    /// The physical clear (or moonlit night) sky; see [`PhysicalSky`].
    Physical(Box<PhysicalSky>),
    /// CIE overcast sky with its sampling table; build with [`Sky::overcast`].
    Overcast(Box<(OvercastSky, SkyDistribution)>),
}

/// Skies are equal when built from equal parameters (tables are functions
/// of them).
impl PartialEq for Sky {
    fn eq(&self, other: &Sky) -> bool {
        match (self, other) {
            (Sky::Constant { le: a }, Sky::Constant { le: b }) => a == b,
            (
                Sky::Gradient {
                    zenith: z0,
                    horizon: h0,
                    ground: g0,
                },
                Sky::Gradient {
                    zenith: z1,
                    horizon: h1,
                    ground: g1,
                },
            ) => z0 == z1 && h0 == h1 && g0 == g1,
            (Sky::Physical(a), Sky::Physical(b)) => a.params() == b.params(),
            (Sky::Overcast(a), Sky::Overcast(b)) => a.0 == b.0,
            _ => false,
        }
    }
}

/// asin(z)·2/π for z ∈ [0, 1] (larger z clamps to 1): the elevation as a
/// fraction of the right angle, without libm's `asinf`. Abramowitz & Stegun
/// 4.4.46, asin z = π/2 − √(1 − z)·P₇(z) with |error| ≤ 2·10⁻⁸, so the
/// result is within a few f32 ulps of the exact value.
#[inline]
fn elevation_fraction(z: f32) -> f32 {
    // A&S's fitted coefficients; the first is 1.5707963050, not π/2.
    #[allow(clippy::approx_constant)]
    const A: [f32; 8] = [
        1.570_796_3,
        -0.214_598_8,
        0.088_978_99,
        -0.050_174_3,
        0.030_891_88,
        -0.017_088_126,
        0.006_670_09,
        -0.001_262_491_1,
    ];
    let z = z.min(1.0);
    let p = A.iter().rev().fold(0.0, |acc, &a| acc * z + a);
    1.0 - (1.0 - z).sqrt() * p * FRAC_2_PI
}

impl Sky {
    /// An overcast sky with its sampling distribution.
    pub fn overcast(sky: OvercastSky) -> Sky {
        let dist = SkyDistribution::new(|d| sky.le(d));
        Sky::Overcast(Box::new((sky, dist)))
    }

    /// Sun transmittance through the sky's cloud deck at world point
    /// `p_world` towards `dir_to_sun` (1 for skies without clouds).
    pub fn cloud_transmittance(&self, p_world: DVec3, dir_to_sun: Vec3) -> f32 {
        match self {
            Sky::Physical(p) => p.cloud_transmittance(p_world, dir_to_sun),
            _ => 1.0,
        }
    }

    /// The tabulated sampling distribution, for the tabulated skies.
    fn table(&self) -> Option<&SkyDistribution> {
        match self {
            Sky::Physical(p) => Some(p.distribution()),
            Sky::Overcast(o) => Some(&o.1),
            _ => None,
        }
    }

    /// Radiance arriving from world direction `dir` (unit, z up).
    pub fn le(&self, dir: Vec3) -> Vec3 {
        match *self {
            Sky::Physical(ref p) => p.le(dir),
            Sky::Overcast(ref o) => o.0.le(dir),
            Sky::Constant { le } => le,
            Sky::Gradient {
                zenith,
                horizon,
                ground,
            } => {
                if dir.z < 0.0 {
                    ground
                } else {
                    horizon.lerp(zenith, elevation_fraction(dir.z))
                }
            }
        }
    }
    /// Samples a world direction; returns (dir, radiance, pdf per solid angle).
    pub fn sample(&self, u: Vec2) -> (Vec3, Vec3, f32) {
        let (dir, pdf) = self.sample_dir(u);
        (dir, self.le(dir), pdf)
    }
    /// [`Sky::sample`] without the radiance: (dir, pdf per solid angle), for
    /// callers that evaluate `le` only for directions they keep.
    pub fn sample_dir(&self, u: Vec2) -> (Vec3, f32) {
        if let Some(t) = self.table() {
            return t.sample(u);
        }
        // `pdf` without its second table check and mixture weight.
        let p_cos = self.cosine_lobe_prob();
        let dir = sampling::sample_dir(p_cos, u);
        (dir, sampling::dir_pdf(p_cos, dir))
    }
    /// Pdf per solid angle of `sample` producing `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if let Some(t) = self.table() {
            return t.pdf(dir);
        }
        sampling::dir_pdf(self.cosine_lobe_prob(), dir)
    }
    /// Mean radiance over the sphere, (1/4π)∫ le dω, per channel (closed
    /// form for the analytic skies, the sampling table's quadrature else).
    pub fn mean_le(&self) -> Vec3 {
        if let Some(t) = self.table() {
            return t.mean_le();
        }
        match *self {
            Sky::Constant { le } => le,
            Sky::Gradient {
                zenith,
                horizon,
                ground,
            } => {
                // Upper hemisphere: 2π ∫₀¹ lerp(h, z, asin(z)·2/π) dz with
                // ∫₀¹ asin z dz = π/2 − 1, so the zenith weight is 1 − 2/π.
                let wz = 1.0 - FRAC_2_PI;
                let upper = horizon * (1.0 - wz) + zenith * wz;
                (upper + ground) * 0.5
            }
            Sky::Physical(_) | Sky::Overcast(_) => unreachable!("tabulated"),
        }
    }
    /// Luminance of [`Sky::mean_le`] (Rec.709 Y), e.g. for exposure hints.
    pub fn luminance_avg(&self) -> f32 {
        luminance(self.mean_le())
    }
    /// Probability of drawing from the cosine lobe about +z: 0 for a constant
    /// sky (uniform sphere is exact), else 0.8 × the upper hemisphere's share
    /// of the power, so the uniform-sphere part always keeps pdf > 0.
    fn cosine_lobe_prob(&self) -> f32 {
        match *self {
            Sky::Constant { .. } | Sky::Physical(_) | Sky::Overcast(_) => 0.0,
            Sky::Gradient {
                zenith,
                horizon,
                ground,
            } => {
                let up = luminance((zenith + horizon) * 0.5).max(0.0);
                let down = luminance(ground).max(0.0);
                if up + down > 0.0 {
                    0.8 * up / (up + down)
                } else {
                    0.0
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gradient() -> Sky {
        Sky::Gradient {
            zenith: Vec3::new(0.2, 0.4, 1.0),
            horizon: Vec3::new(0.8, 0.9, 1.0),
            ground: Vec3::new(0.1, 0.1, 0.1),
        }
    }

    #[test]
    fn gradient_hits_its_end_points() {
        let s = gradient();
        assert!((s.le(Vec3::Z) - Vec3::new(0.2, 0.4, 1.0)).length() < 1e-6);
        assert!((s.le(Vec3::X) - Vec3::new(0.8, 0.9, 1.0)).length() < 1e-6);
        assert_eq!(s.le(Vec3::new(0.0, 0.6, -0.8)), Vec3::splat(0.1));
        // 30° elevation is a third of the way up.
        let d = Vec3::new(0.866_025_4, 0.0, 0.5);
        let expect = Vec3::new(0.8, 0.9, 1.0).lerp(Vec3::new(0.2, 0.4, 1.0), 1.0 / 3.0);
        assert!((s.le(d) - expect).length() < 1e-5);
    }

    #[test]
    fn elevation_fraction_matches_asin_to_f32_precision() {
        let mut worst = 0.0f64;
        for i in 0..=100_000 {
            let z = i as f32 / 100_000.0;
            let exact = (z as f64).asin() * std::f64::consts::FRAC_2_PI;
            worst = worst.max((elevation_fraction(z) as f64 - exact).abs());
        }
        assert!(worst < 3e-7, "worst error {worst:e}");
        assert!(elevation_fraction(0.0).abs() < 1e-7);
        assert!((elevation_fraction(1.0) - 1.0).abs() < 1e-7);
        assert!((elevation_fraction(1.5) - 1.0).abs() < 1e-7);
    }

    #[test]
    fn mean_le_matches_quadrature() {
        let s = gradient();
        let n = 2000;
        let mut sum = Vec3::ZERO;
        for i in 0..n {
            // φ-symmetric: integrate over z ∈ [-1, 1] only (dω = dz dφ).
            let z = -1.0 + 2.0 * (i as f32 + 0.5) / n as f32;
            let r = (1.0 - z * z).sqrt();
            sum += s.le(Vec3::new(r, 0.0, z));
        }
        let mean = sum / n as f32;
        assert!(
            (mean - s.mean_le()).length() < 1e-3,
            "{mean} vs {}",
            s.mean_le()
        );
        assert!((Sky::Constant { le: Vec3::ONE }.luminance_avg() - 1.0).abs() < 1e-6);
    }
}
