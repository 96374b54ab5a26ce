//! The CIE standard overcast sky (Moon & Spencer 1942; CIE S 011/E:2003
//! type 1): L(θ) = L_z·(1 + 2 cos θ)/3 above the horizon, so zenith/horizon
//! = 3 and the diffuse horizontal irradiance is E = L_z·7π/9. Below the
//! horizon a Lambert ground lit by E, reached by a smoothstep over 3°.

use glam::Vec3;

/// An overcast sky: the sun is fully diffused into the cloud deck.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OvercastSky {
    /// Zenith radiance, W·m⁻²·sr⁻¹ per channel.
    pub zenith: Vec3,
    /// Radiance of the ground seen below the horizon.
    pub ground: Vec3,
}

/// Width of the horizon-to-ground blend in z (sin 3°).
const BLEND_Z: f32 = 0.052;

impl OvercastSky {
    /// The overcast sky giving diffuse horizontal irradiance `e_horizontal`
    /// (W·m⁻²) over a ground of albedo `ground_albedo`.
    pub fn from_irradiance(e_horizontal: Vec3, ground_albedo: f32) -> Self {
        OvercastSky {
            zenith: e_horizontal * (9.0 / (7.0 * std::f32::consts::PI)),
            ground: e_horizontal * ground_albedo / std::f32::consts::PI,
        }
    }

    /// Radiance from world direction `dir` (unit, z up).
    pub fn le(&self, dir: Vec3) -> Vec3 {
        let horizon = self.zenith / 3.0;
        if dir.z >= 0.0 {
            self.zenith * (1.0 + 2.0 * dir.z.min(1.0)) / 3.0
        } else {
            let t = (-dir.z / BLEND_Z).min(1.0);
            horizon.lerp(self.ground, t * t * (3.0 - 2.0 * t))
        }
    }
}
