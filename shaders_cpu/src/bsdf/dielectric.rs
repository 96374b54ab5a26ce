//! GGX microfacet dielectric with reflection and transmission (pbrt-v4 §9.5 and
//! §9.7, `DielectricBxDF`), light transport mode = radiance.
//!
//! `eta` is η_inside/η_outside, the outside being +z. A transmitted path scales
//! radiance by 1/η'² where η' is the relative IOR crossed (§9.5.2, eq. 9.30),
//! and is tinted by `tint`. Rough transmission uses the generalised half vector
//! ωm = normalize(η' ωi + ωo) (eq. 9.34) and the Walter et al. 2007 Jacobian
//! (eq. 9.37). Lobes are chosen with probability R/(R+T) vs T/(R+T).
//! Smooth (α < 1e-3) or index-matched (η = 1) interfaces are deltas.

use super::fresnel::{fr_dielectric, reflect, refract};
use super::microfacet::TrowbridgeReitz;
use super::BsdfSample;
use glam::{Vec2, Vec3};

/// Whether this interface has only delta lobes.
pub fn is_delta(eta: f32, alpha: f32) -> bool {
    eta == 1.0 || TrowbridgeReitz::new(alpha).effectively_smooth()
}

/// Shared geometry of a rough (wo, wi) pair: the face-forwarded microfacet
/// normal, whether it is a reflection, and the η' crossed (1 for reflection).
/// `None` when the configuration is impossible (grazing, back-facing ωm).
fn half_vector(eta: f32, wo: Vec3, wi: Vec3) -> Option<(Vec3, bool, f32)> {
    let (cos_o, cos_i) = (wo.z, wi.z);
    if cos_o == 0.0 || cos_i == 0.0 {
        return None;
    }
    let is_reflect = cos_o * cos_i > 0.0;
    let etap = if is_reflect {
        1.0
    } else if cos_o > 0.0 {
        eta
    } else {
        1.0 / eta
    };
    let wm = wi * etap + wo;
    if wm.length_squared() == 0.0 {
        return None;
    }
    let mut wm = wm.normalize();
    if wm.z < 0.0 {
        wm = -wm;
    }
    // Discard back-facing microfacets (pbrt-v4 §9.7.2).
    if wm.dot(wi) * cos_i < 0.0 || wm.dot(wo) * cos_o < 0.0 {
        return None;
    }
    Some((wm, is_reflect, etap))
}

/// f(wo, wi); zero for delta interfaces.
pub fn eval(eta: f32, alpha: f32, tint: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    if is_delta(eta, alpha) {
        return Vec3::ZERO;
    }
    let Some((wm, is_reflect, etap)) = half_vector(eta, wo, wi) else {
        return Vec3::ZERO;
    };
    let tr = TrowbridgeReitz::new(alpha);
    let fr = fr_dielectric(wo.dot(wm), eta);
    if is_reflect {
        return Vec3::splat(tr.d(wm) * tr.g(wo, wi) * fr / (4.0 * wi.z * wo.z).abs());
    }
    let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2) * wi.z * wo.z;
    let ft = tr.d(wm) * (1.0 - fr) * tr.g(wo, wi) * (wi.dot(wm) * wo.dot(wm) / denom).abs();
    tint * (ft / (etap * etap))
}

/// Pdf per solid angle of [`sample`]; zero for delta interfaces.
pub fn pdf(eta: f32, alpha: f32, wo: Vec3, wi: Vec3) -> f32 {
    if is_delta(eta, alpha) {
        return 0.0;
    }
    let Some((wm, is_reflect, etap)) = half_vector(eta, wo, wi) else {
        return 0.0;
    };
    let tr = TrowbridgeReitz::new(alpha);
    let r = fr_dielectric(wo.dot(wm), eta);
    let t = 1.0 - r;
    if is_reflect {
        tr.d_visible(wo, wm) / (4.0 * wo.dot(wm).abs()) * r / (r + t)
    } else {
        // dωm/dωi for refraction (eq. 9.37).
        let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
        let dwm_dwi = wi.dot(wm).abs() / denom;
        tr.d_visible(wo, wm) * dwm_dwi * t / (r + t)
    }
}

/// Samples reflection or transmission with `u_lobe`, the microfacet with `u`.
pub fn sample(
    eta: f32,
    alpha: f32,
    tint: Vec3,
    wo: Vec3,
    u_lobe: f32,
    u: Vec2,
) -> Option<BsdfSample> {
    if wo.z == 0.0 {
        return None;
    }
    if is_delta(eta, alpha) {
        return sample_smooth(eta, tint, wo, u_lobe);
    }
    let tr = TrowbridgeReitz::new(alpha);
    let wm = tr.sample_wm(wo, u);
    let r = fr_dielectric(wo.dot(wm), eta);
    let t = 1.0 - r;
    if u_lobe < r / (r + t) {
        let wi = reflect(wo, wm);
        if wo.z * wi.z <= 0.0 {
            return None;
        }
        let pdf = tr.d_visible(wo, wm) / (4.0 * wo.dot(wm).abs()) * r / (r + t);
        let f = tr.d(wm) * tr.g(wo, wi) * r / (4.0 * wi.z * wo.z).abs();
        finish(wi, Vec3::splat(f), pdf)
    } else {
        let (wi, etap) = refract(wo, wm, eta)?;
        if wo.z * wi.z >= 0.0 {
            return None;
        }
        let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
        let dwm_dwi = wi.dot(wm).abs() / denom;
        let pdf = tr.d_visible(wo, wm) * dwm_dwi * t / (r + t);
        let ft =
            t * tr.d(wm) * tr.g(wo, wi) * (wi.dot(wm) * wo.dot(wm) / (wi.z * wo.z * denom)).abs();
        finish(wi, tint * (ft / (etap * etap)), pdf)
    }
}

/// Wraps a rough sample, rejecting degenerate pdfs.
fn finish(wi: Vec3, f: Vec3, pdf: f32) -> Option<BsdfSample> {
    if !(pdf > 0.0 && pdf.is_finite() && f.is_finite()) {
        return None;
    }
    Some(BsdfSample {
        wi,
        f,
        pdf,
        delta: false,
    })
}

/// Smooth interface: specular reflection with probability R, refraction with T
/// (pbrt-v4 §9.5.2); f carries 1/|cosθi| so that f·|cosθi|/pdf = 1 (reflect)
/// or tint/η'² (transmit).
fn sample_smooth(eta: f32, tint: Vec3, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
    let r = fr_dielectric(wo.z, eta);
    let t = 1.0 - r;
    if u_lobe < r / (r + t) {
        let wi = Vec3::new(-wo.x, -wo.y, wo.z);
        Some(BsdfSample {
            wi,
            f: Vec3::splat(r / wi.z.abs()),
            pdf: r / (r + t),
            delta: true,
        })
    } else {
        let (wi, etap) = refract(wo, Vec3::Z, eta)?;
        if wi.z == 0.0 {
            return None;
        }
        let ft = t / wi.z.abs() / (etap * etap);
        Some(BsdfSample {
            wi,
            f: tint * ft,
            pdf: t / (r + t),
            delta: true,
        })
    }
}
