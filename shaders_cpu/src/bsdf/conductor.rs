//! GGX microfacet conductor (pbrt-v4 §9.4–9.6, `ConductorBxDF`).
//!
//! Rough: Torrance–Sparrow f = D(ωm) F(ωo·ωm) G(ωo,ωi) / (4 cosθo cosθi)
//! (eq. 9.33) with ωm the half vector, sampled by visible normals with pdf
//! D_ωo(ωm) / (4 |ωo·ωm|) (eq. 9.28 and the reflection Jacobian, eq. 9.32).
//! Smooth (α < 1e-3): a delta mirror with f = F(cosθ)/|cosθi|.
//! Two-sided: `wo` below the surface is handled by mirroring both directions
//! through z = 0 (the metal looks the same from either side).

use super::fresnel::{fr_complex_rgb, reflect};
use super::microfacet::TrowbridgeReitz;
use super::BsdfSample;
use glam::{Vec2, Vec3};

/// Mirror through the tangent plane.
fn flip_z(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}

/// Bring (wo, wi) to the upper side; `None` if they are in opposite hemispheres.
fn to_upper(wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
    if wo.z * wi.z <= 0.0 {
        return None;
    }
    if wo.z < 0.0 {
        Some((flip_z(wo), flip_z(wi)))
    } else {
        Some((wo, wi))
    }
}

/// f(wo, wi); zero for the smooth (delta) case.
pub fn eval(eta: Vec3, k: Vec3, alpha: f32, wo: Vec3, wi: Vec3) -> Vec3 {
    let tr = TrowbridgeReitz::new(alpha);
    if tr.effectively_smooth() {
        return Vec3::ZERO;
    }
    let Some((wo, wi)) = to_upper(wo, wi) else {
        return Vec3::ZERO;
    };
    let wm = wo + wi;
    if wm.length_squared() == 0.0 {
        return Vec3::ZERO;
    }
    let wm = wm.normalize();
    let f = fr_complex_rgb(wo.dot(wm).abs(), eta, k);
    f * (tr.d(wm) * tr.g(wo, wi) / (4.0 * wo.z * wi.z))
}

/// Pdf per solid angle of [`sample`]; zero for the smooth case.
pub fn pdf(alpha: f32, wo: Vec3, wi: Vec3) -> f32 {
    let tr = TrowbridgeReitz::new(alpha);
    if tr.effectively_smooth() {
        return 0.0;
    }
    let Some((wo, wi)) = to_upper(wo, wi) else {
        return 0.0;
    };
    let wm = wo + wi;
    if wm.length_squared() == 0.0 {
        return 0.0;
    }
    let wm = wm.normalize();
    // Half-vector → wi Jacobian: dωm/dωi = 1 / (4 |ωo·ωm|) (eq. 9.32).
    tr.d_visible(wo, wm) / (4.0 * wo.dot(wm).abs())
}

/// Samples wi by reflecting wo about a visible microfacet normal.
pub fn sample(eta: Vec3, k: Vec3, alpha: f32, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
    if wo.z == 0.0 {
        return None;
    }
    let flipped = wo.z < 0.0;
    let wo_up = if flipped { flip_z(wo) } else { wo };
    let unflip = |v: Vec3| if flipped { flip_z(v) } else { v };
    let tr = TrowbridgeReitz::new(alpha);
    if tr.effectively_smooth() {
        // Perfect mirror: f·|cosθi|/pdf = F (pbrt-v4 §9.4.2).
        let wi = Vec3::new(-wo_up.x, -wo_up.y, wo_up.z);
        let f = fr_complex_rgb(wi.z, eta, k) / wi.z;
        return Some(BsdfSample {
            wi: unflip(wi),
            f,
            pdf: 1.0,
            delta: true,
        });
    }
    let wm = tr.sample_wm(wo_up, u);
    let wi = reflect(wo_up, wm);
    if wi.z <= 0.0 {
        return None;
    }
    let pdf = tr.d_visible(wo_up, wm) / (4.0 * wo_up.dot(wm).abs());
    if pdf <= 0.0 || !pdf.is_finite() {
        return None;
    }
    let f = fr_complex_rgb(wo_up.dot(wm).abs(), eta, k)
        * (tr.d(wm) * tr.g(wo_up, wi) / (4.0 * wo_up.z * wi.z));
    Some(BsdfSample {
        wi: unflip(wi),
        f,
        pdf,
        delta: false,
    })
}
