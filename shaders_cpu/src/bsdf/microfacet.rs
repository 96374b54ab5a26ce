//! Isotropic Trowbridge–Reitz (GGX) microfacet distribution (pbrt-v4 §9.6).
//!
//! Local frame, z = macro normal. `d` is the normal distribution D(ωm) (§9.6.1),
//! `lambda`/`g1`/`g` the Smith masking terms with height-correlated G (§9.6.2–3),
//! `d_visible` the distribution of visible normals D_ω(ωm) (§9.6.4), sampled by
//! `sample_wm` (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").

use crate::sampling::sample_uniform_disk_polar;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Below this alpha a surface is treated as perfectly smooth (pbrt-v4
/// `EffectivelySmooth`).
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// GGX distribution with roughness `alpha` (isotropic).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrowbridgeReitz {
    /// Roughness α (slope standard deviation scale), > 0.
    pub alpha: f32,
}

impl TrowbridgeReitz {
    /// Distribution with roughness `alpha`.
    pub fn new(alpha: f32) -> Self {
        TrowbridgeReitz { alpha }
    }

    /// Whether the surface should be handled as a delta (mirror/smooth glass).
    pub fn effectively_smooth(&self) -> bool {
        self.alpha < SMOOTH_ALPHA
    }

    /// D(ωm): microfacet normal density per unit projected area (eq. 9.16).
    pub fn d(&self, wm: Vec3) -> f32 {
        let cos2 = wm.z * wm.z;
        let cos4 = cos2 * cos2;
        if cos4 < 1e-16 {
            return 0.0;
        }
        let tan2 = (1.0 - cos2).max(0.0) / cos2;
        let a2 = self.alpha * self.alpha;
        let e = tan2 / a2;
        1.0 / (PI * a2 * cos4 * (1.0 + e) * (1.0 + e))
    }

    /// Smith Λ(ω) (eq. 9.19); depends only on tan²θ.
    pub fn lambda(&self, w: Vec3) -> f32 {
        let cos2 = w.z * w.z;
        if cos2 == 0.0 {
            return f32::INFINITY;
        }
        let tan2 = (1.0 - cos2).max(0.0) / cos2;
        ((1.0 + self.alpha * self.alpha * tan2).sqrt() - 1.0) / 2.0
    }

    /// Masking function G1(ω) = 1 / (1 + Λ(ω)).
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing G(ωo, ωi) (eq. 9.27).
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Visible-normal density D_ω(ωm) = G1(ω) max(0, ω·ωm) D(ωm) / cos θ
    /// (eq. 9.23), with |·| as pbrt (callers discard back-facing ωm).
    pub fn d_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        let cos = w.z.abs();
        if cos == 0.0 {
            return 0.0;
        }
        self.g1(w) / cos * self.d(wm) * w.dot(wm).abs()
    }

    /// Samples ωm from D_ω (pbrt-v4 `Sample_wm`, §9.6.4): stretch ω to the
    /// hemisphere configuration, sample the projected visible hemisphere
    /// (a warped disk), then unstretch. Returns a normal with wm.z > 0.
    pub fn sample_wm(&self, w: Vec3, u: Vec2) -> Vec3 {
        let mut wh = Vec3::new(self.alpha * w.x, self.alpha * w.y, w.z).normalize();
        if wh.z < 0.0 {
            wh = -wh;
        }
        let t1 = if wh.z < 0.99999 {
            Vec3::Z.cross(wh).normalize()
        } else {
            Vec3::X
        };
        let t2 = wh.cross(t1);
        let mut p = sample_uniform_disk_polar(u);
        // Warp the disk so its lower half covers only the visible part of the
        // projected hemisphere (lerp between h and p.y).
        let h = (1.0 - p.x * p.x).max(0.0).sqrt();
        let s = (1.0 + wh.z) / 2.0;
        p.y = (1.0 - s) * h + s * p.y;
        let pz = (1.0 - p.length_squared()).max(0.0).sqrt();
        let nh = p.x * t1 + p.y * t2 + pz * wh;
        Vec3::new(self.alpha * nh.x, self.alpha * nh.y, nh.z.max(1e-6)).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ f(ωm) dωm over the upper hemisphere, midpoint rule in (cos θ, φ)
    /// with the cos θ axis refined near the pole where D peaks.
    fn hemisphere_integral(f: impl Fn(Vec3) -> f32) -> f64 {
        let (nt, np) = (2000, 64);
        let mut sum = 0.0f64;
        for i in 0..nt {
            // z = 1 - s², s uniform: dz = 2 s ds, denser near z = 1.
            let s = (i as f64 + 0.5) / nt as f64;
            let z = 1.0 - s * s;
            let r = (1.0 - z * z).max(0.0).sqrt();
            for j in 0..np {
                let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / np as f64;
                let w = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                sum += f(w) as f64 * 2.0 * s / nt as f64 * 2.0 * std::f64::consts::PI / np as f64;
            }
        }
        sum
    }

    #[test]
    fn ggx_projected_area_is_one() {
        // ∫ D(ωm) cos θm dωm = 1 (eq. 9.13).
        for alpha in [0.1f32, 0.3, 0.8] {
            let tr = TrowbridgeReitz::new(alpha);
            let v = hemisphere_integral(|wm| tr.d(wm) * wm.z);
            assert!((v - 1.0).abs() < 2e-3, "alpha {alpha}: {v}");
        }
    }

    #[test]
    fn visible_normals_integrate_to_one() {
        // ∫ D_ω(ωm) dωm = 1 for any ω: the definition of G1 (eq. 9.22).
        let tr = TrowbridgeReitz::new(0.4);
        for w in [
            Vec3::Z,
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(0.0, 0.995, 0.0999).normalize(),
        ] {
            let v = hemisphere_integral(|wm| {
                if w.dot(wm) > 0.0 {
                    tr.d_visible(w, wm)
                } else {
                    0.0
                }
            });
            assert!((v - 1.0).abs() < 3e-3, "w {w}: {v}");
        }
    }

    #[test]
    fn sampled_normals_face_the_viewer() {
        let tr = TrowbridgeReitz::new(0.5);
        let w = Vec3::new(0.8, 0.0, 0.6);
        for i in 0..32 {
            for j in 0..32 {
                let u = Vec2::new((i as f32 + 0.5) / 32.0, (j as f32 + 0.5) / 32.0);
                let wm = tr.sample_wm(w, u);
                assert!((wm.length() - 1.0).abs() < 1e-4 && wm.z > 0.0);
                assert!(w.dot(wm) > -1e-4);
            }
        }
    }
}
