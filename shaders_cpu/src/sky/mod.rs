//! Environment radiance for rays leaving the scene (world directions, z up).

use glam::{Vec2, Vec3};

/// A simple analytic sky (the physical atmosphere is a later addition).
#[derive(Clone, Copy, Debug, PartialEq)]
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
}

impl Sky {
    /// Radiance arriving from world direction `dir` (unit, z up).
    pub fn le(&self, _dir: Vec3) -> Vec3 {
        unimplemented!("shaders helper")
    }
    /// Samples a world direction; returns (dir, radiance, pdf per solid angle).
    pub fn sample(&self, _u: Vec2) -> (Vec3, Vec3, f32) {
        unimplemented!("shaders helper")
    }
    /// Pdf per solid angle of `sample` producing `dir`.
    pub fn pdf(&self, _dir: Vec3) -> f32 {
        unimplemented!("shaders helper")
    }
}
