//! The night sky's own light, added to the moonlit atmosphere: airglow with
//! the van Rhijn brightening towards the horizon (emitting layer at 90 km),
//! artificial sky glow (a warm dome near the horizon), and stars.
//!
//! Levels in the renderer's units (≈ 100 lux per W·m⁻², so 1 W·m⁻²·sr⁻¹ ≈
//! 100 cd·m⁻²): natural sky ≈ 2e-4 cd·m⁻² → 2e-6; suburban glow 1e-2 cd·m⁻²
//! → 1e-4. Stars: ~9000 to magnitude 6.5, irradiance 2.5e-8·10^(−0.4 m)
//! W·m⁻² (Vega ≈ 2.5e-6 lux), each a disk of 0.023° radius in its own cell of
//! an equal-area (z, φ) grid, dimmed by a Rayleigh-like air mass.

use super::clouds::hash;
use glam::Vec3;
use std::f32::consts::PI;

/// Airglow, sky glow and stars.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NightGlow {
    /// Airglow radiance at the zenith, W·m⁻²·sr⁻¹ (≈ 1e-6 natural).
    pub airglow: Vec3,
    /// Artificial sky glow at the horizon (0 in wilderness, ~1e-4 suburban).
    pub sky_glow: Vec3,
    /// Whether stars are drawn.
    pub stars: bool,
    /// Star-field seed.
    pub seed: u32,
}

const STAR_GRID: (usize, usize) = (1024, 2048);
const STAR_PROB: f64 = 0.0043;
const STAR_RADIUS_RAD: f32 = 4e-4;

impl NightGlow {
    /// Natural airglow plus `sky_glow` (horizon radiance, grey-warm) and stars.
    pub fn new(sky_glow: f32, stars: bool, seed: u32) -> Self {
        NightGlow {
            airglow: Vec3::new(0.9e-6, 1.1e-6, 0.8e-6),
            sky_glow: Vec3::new(1.3, 1.0, 0.7) * sky_glow,
            stars,
            seed,
        }
    }

    /// Radiance from world direction `dir` (unit, z up); fades to zero over
    /// 3° below the horizon (the ground is dark at night).
    pub fn le(&self, dir: Vec3) -> Vec3 {
        let z = dir.z.clamp(-1.0, 1.0);
        let above = z.max(0.0);
        // van Rhijn: path length through a thin shell at 90 km.
        let k = 6360.0f32 / 6450.0;
        let van_rhijn = 1.0 / (1.0 - k * k * (1.0 - above * above)).sqrt();
        let air_mass = 1.0 / (above + 0.15 * (above * 57.3 + 3.885).powf(-1.253));
        let extinction = (-Vec3::new(0.1, 0.17, 0.32) * (air_mass - 1.0)).exp();
        let dome = (-above / 0.2).exp();
        let mut l = self.airglow * van_rhijn * extinction + self.sky_glow * dome;
        if self.stars && z > 0.0 {
            l += self.star(dir) * extinction;
        }
        if z < 0.0 {
            l *= (1.0 + z / 0.052).max(0.0);
        }
        l
    }

    /// Star radiance along `dir`: the star of its grid cell, if any, when
    /// `dir` falls inside its disk.
    fn star(&self, dir: Vec3) -> Vec3 {
        let (nz, nphi) = STAR_GRID;
        let j = (((dir.z + 1.0) * 0.5 * nz as f32) as usize).min(nz - 1);
        let phi = dir.y.atan2(dir.x);
        let i = (((phi + PI) / (2.0 * PI) * nphi as f32) as usize).min(nphi - 1);
        let h = hash(i as i64, j as i64, self.seed);
        if h >= STAR_PROB {
            return Vec3::ZERO;
        }
        let u = h / STAR_PROB; // uniform in [0, 1) given a star
        let zc = -1.0 + 2.0 * (j as f32 + 0.5) / nz as f32;
        let pc = -PI + 2.0 * PI * (i as f32 + 0.5) / nphi as f32;
        let rc = (1.0 - zc * zc).sqrt();
        let centre = Vec3::new(rc * pc.cos(), rc * pc.sin(), zc);
        if dir.dot(centre) < STAR_RADIUS_RAD.cos() {
            return Vec3::ZERO;
        }
        // N(< m) ∝ 10^(0.5 m): m = 6.5 + 2 log10 u, brightest −1.5.
        let mag = (6.5 + 2.0 * u.max(1e-12).log10()).max(-1.5) as f32;
        let e = 2.5e-8 * 10f32.powf(-0.4 * mag);
        let solid_angle = PI * STAR_RADIUS_RAD * STAR_RADIUS_RAD;
        // Colour from a second hash: blue-white to orange.
        let c = hash(j as i64, i as i64, self.seed ^ 0x5a5a) as f32;
        let tint = Vec3::new(0.8 + 0.4 * c, 1.0, 1.2 - 0.5 * c);
        tint * (e / solid_angle)
    }
}
