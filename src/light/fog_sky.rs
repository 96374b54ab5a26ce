//! Sky sampling seen through fog: from a point under a horizontal medium the
//! sky arrives dimmed by Tr(ω) = exp(−s/cos θ) above the horizon, s the
//! optical depth of the vertical column above the point (exact for every
//! medium of `shaders_cpu::medium`: a slab, homogeneous or exponential in
//! height). Sampling the sky ∝ luminance alone wastes most samples on the
//! bright, fog-blind horizon; here each point draws from a table ∝ L·Tr_k
//! for a ladder of column depths s_k ≤ s (chosen by the point, so the pdf
//! is a function of (point, direction) and MIS stays exact). Because
//! s_k ≤ s the weight Tr/Tr_k ≤ 1: no direction is under-sampled.
//!
//! Directions are render space, z up; depths are dimensionless.

use glam::Vec3;
use shaders_cpu::medium::Medium;
use shaders_cpu::sky::SkyDistribution;

/// Column depths of the ladder: 0, then S0·√2^k for k = 0..LEVELS-1.
const S0: f32 = 1.0 / 32.0;
/// Tables above the clear one (the deepest column is S0·√2^(LEVELS−1) ≈ 11).
const LEVELS: usize = 16;

/// Fog-weighted sky tables of one frame.
#[derive(Clone, Debug)]
pub struct FogSky {
    /// The medium whose column depth selects the table.
    medium: Medium,
    /// Table k ∝ L·Tr at column depth `depth(k)`; index 0 is the clear sky.
    tables: Vec<SkyDistribution>,
}

/// Column depth of table `k` (0 for the clear table).
fn depth(k: usize) -> f32 {
    if k == 0 {
        0.0
    } else {
        S0 * 2f32.powf((k - 1) as f32 * 0.5)
    }
}

impl FogSky {
    /// Tables for sky radiance `le` (world direction → radiance) seen
    /// through `medium`.
    pub fn new(medium: Medium, le: impl Fn(Vec3) -> Vec3) -> Self {
        let clear = SkyDistribution::new(le);
        let mut tables = Vec::with_capacity(LEVELS + 1);
        for k in 1..=LEVELS {
            let s = depth(k);
            // The largest Tr over the row (at its highest z); below the
            // horizon the ground takes the ray, so only the floor remains.
            tables.push(clear.reweighted(
                |_, z_hi| {
                    if z_hi <= 0.0 {
                        0.0
                    } else {
                        (-s / z_hi).exp()
                    }
                },
            ));
        }
        tables.insert(0, clear);
        FogSky { medium, tables }
    }

    /// The table a point `p` (render space) samples from: the deepest
    /// column of the ladder not deeper than the column above `p`.
    pub fn table_at(&self, p: Vec3) -> &SkyDistribution {
        let s = self.medium.optical_depth(p, Vec3::Z, f32::INFINITY) as f32;
        let k = if s.is_nan() || s < S0 {
            0
        } else if s.is_infinite() {
            LEVELS
        } else {
            // s ≥ S0·√2^(k−1)  ⇔  k ≤ 1 + 2·log2(s/S0).
            ((1.0 + 2.0 * (s / S0).log2()).floor() as usize).min(LEVELS)
        };
        debug_assert!(depth(k) <= s || k == 0);
        &self.tables[k]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shaders_cpu::medium::{Density, HenyeyGreenstein};

    fn fog(sigma0: f64) -> Medium {
        Medium {
            density: Density::HeightExp {
                sigma0,
                z0: 0.0,
                height_scale: 30.0,
            },
            albedo: Vec3::splat(0.99),
            phase: HenyeyGreenstein { g: 0.85 },
            z_min: f64::NEG_INFINITY,
            z_max: f64::INFINITY,
        }
    }

    fn sky(d: Vec3) -> Vec3 {
        // Bright horizon, dim zenith, dark ground.
        if d.z < 0.0 {
            Vec3::splat(2.0)
        } else {
            Vec3::splat(10.0 - 8.0 * d.z)
        }
    }

    #[test]
    fn table_depth_never_exceeds_the_column_above_the_point() {
        let fs = FogSky::new(fog(0.04), sky);
        for z in [0.0f32, 1.0, 10.0, 50.0, 200.0] {
            let p = Vec3::new(3.0, -2.0, z);
            let s = fs.medium.optical_depth(p, Vec3::Z, f32::INFINITY) as f32;
            let t = fs.table_at(p) as *const _;
            let k = fs.tables.iter().position(|x| std::ptr::eq(x, t)).unwrap();
            assert!(depth(k) <= s * (1.0 + 1e-6), "z {z}: level {k} s {s}");
            if k < LEVELS {
                assert!(
                    depth(k + 1) > s,
                    "z {z}: level {k} s {s} is not the deepest"
                );
            }
        }
    }

    #[test]
    fn fog_table_pdf_integrates_to_one_and_favours_the_zenith() {
        let fs = FogSky::new(fog(0.04), sky);
        let t = fs.table_at(Vec3::new(0.0, 0.0, 1.0));
        // Midpoint rule over the sphere, uniform in (z, φ): dω = dz dφ.
        let (n_z, n_phi) = (256, 256);
        let mut sum = 0.0f64;
        for j in 0..n_z {
            for i in 0..n_phi {
                let z = -1.0 + 2.0 * (j as f32 + 0.5) / n_z as f32;
                let phi = std::f32::consts::TAU * (i as f32 + 0.5) / n_phi as f32;
                let r = (1.0 - z * z).sqrt();
                let d = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                sum += t.pdf(d) as f64;
            }
        }
        let integral = sum * 4.0 * std::f64::consts::PI / (n_z * n_phi) as f64;
        assert!((integral - 1.0).abs() < 1e-3, "{integral}");
        // Tr·L at the zenith (e^{-1.2}·2 ≈ 0.6) beats the horizon's
        // (e^{-1.2/0.05}·10 ≈ 0), unlike the clear table.
        let up = Vec3::new(0.0, 0.0, 1.0);
        let side = Vec3::new(1.0, 0.0, 0.03).normalize();
        assert!(
            t.pdf(up) > 20.0 * t.pdf(side),
            "{} {}",
            t.pdf(up),
            t.pdf(side)
        );
        let clear = &fs.tables[0];
        assert!(clear.pdf(side) > clear.pdf(up));
    }
}
