//! A dielectric coat (car clear coat, water film) over a Lambert or conductor
//! base, reflection only and two-sided (like the conductor: `wo` below the
//! surface mirrors both directions through z = 0).
//!
//! f = f_coat(wo, wi) + (1 − F(cosθo)) (1 − F(cosθi)) f_base(wo, wi), with
//! F the smooth-interface Fresnel reflectance at the macro normal (pbrt-v4
//! §9.3.5) and f_coat the Fresnel-weighted GGX reflection of the interface
//! (pbrt-v4 §9.7, reflection half) or a delta mirror when smooth. This is
//! Weidlich & Wilkie 2007 ("Arbitrarily layered micro-facet surfaces") without
//! refracting the base's directions and without absorption in the layer: it is
//! reciprocal and, for a base of albedo ≤ 1, never creates energy. Sampling
//! picks the coat with probability clamp(F(cosθo), 0.05, 0.95), else the base.

use super::fresnel::{fr_dielectric, reflect};
use super::microfacet::TrowbridgeReitz;
use super::{conductor, lambert, BsdfSample};
use glam::{Vec2, Vec3};

/// The layer under a coat.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CoatBase {
    /// Lambertian paint or wet asphalt.
    Lambert {
        /// Reflectance per channel in [0, 1].
        albedo: Vec3,
    },
    /// GGX conductor (metallic flakes), as `Bsdf::Conductor`.
    Conductor {
        /// Real part of the complex IOR per channel.
        eta: Vec3,
        /// Imaginary part per channel.
        k: Vec3,
        /// GGX roughness alpha (< 1e-3: mirror).
        alpha: f32,
    },
}

impl CoatBase {
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match *self {
            CoatBase::Lambert { albedo } => lambert::eval(albedo, wo, wi),
            CoatBase::Conductor { eta, k, alpha } => conductor::eval(eta, k, alpha, wo, wi),
        }
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match *self {
            CoatBase::Lambert { .. } => lambert::pdf(wo, wi),
            CoatBase::Conductor { alpha, .. } => conductor::pdf(alpha, wo, wi),
        }
    }
    fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        match *self {
            CoatBase::Lambert { albedo } => lambert::sample(albedo, wo, u),
            CoatBase::Conductor { eta, k, alpha } => conductor::sample(eta, k, alpha, wo, u),
        }
    }
    /// Whether the base is a perfect mirror.
    pub fn is_delta(&self) -> bool {
        match *self {
            CoatBase::Lambert { .. } => false,
            CoatBase::Conductor { alpha, .. } => TrowbridgeReitz::new(alpha).effectively_smooth(),
        }
    }
    /// Debug colour: the albedo or the conductor's normal-incidence F0.
    pub fn albedo_hint(&self) -> Vec3 {
        match *self {
            CoatBase::Lambert { albedo } => albedo,
            CoatBase::Conductor { eta, k, .. } => super::fresnel::fr_complex_rgb(1.0, eta, k),
        }
    }
}

/// Mirror through the tangent plane.
fn flip_z(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}

/// Brings (wo, wi) to the upper side; `None` if in opposite hemispheres.
fn to_upper(wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
    if wo.z * wi.z <= 0.0 {
        None
    } else if wo.z < 0.0 {
        Some((flip_z(wo), flip_z(wi)))
    } else {
        Some((wo, wi))
    }
}

/// Probability of sampling the coat lobe for an upper-side `wo`.
fn coat_pmf(eta: f32, wo: Vec3) -> f32 {
    fr_dielectric(wo.z, eta).clamp(0.05, 0.95)
}

/// Whether every lobe is a delta (smooth coat over a mirror).
pub fn is_delta(base: &CoatBase, alpha: f32) -> bool {
    TrowbridgeReitz::new(alpha).effectively_smooth() && base.is_delta()
}

/// Rough coat reflection f = D G F(wo·wm) / (4 cosθo cosθi), both upper.
fn coat_eval(eta: f32, tr: &TrowbridgeReitz, wo: Vec3, wi: Vec3) -> f32 {
    let wm = wo + wi;
    if wm.length_squared() == 0.0 {
        return 0.0;
    }
    let wm = wm.normalize();
    tr.d(wm) * tr.g(wo, wi) * fr_dielectric(wo.dot(wm), eta) / (4.0 * wo.z * wi.z)
}

/// Pdf of the rough coat lobe: visible normals and the reflection Jacobian.
fn coat_pdf(tr: &TrowbridgeReitz, wo: Vec3, wi: Vec3) -> f32 {
    let wm = wo + wi;
    if wm.length_squared() == 0.0 {
        return 0.0;
    }
    let wm = wm.normalize();
    tr.d_visible(wo, wm) / (4.0 * wo.dot(wm).abs())
}

/// f(wo, wi) of the non-delta lobes.
pub fn eval(base: &CoatBase, eta: f32, alpha: f32, wo: Vec3, wi: Vec3) -> Vec3 {
    let Some((wo, wi)) = to_upper(wo, wi) else {
        return Vec3::ZERO;
    };
    let tr = TrowbridgeReitz::new(alpha);
    let coat = if tr.effectively_smooth() {
        0.0
    } else {
        coat_eval(eta, &tr, wo, wi)
    };
    // Light enters and leaves through the interface once each.
    let t = (1.0 - fr_dielectric(wo.z, eta)) * (1.0 - fr_dielectric(wi.z, eta));
    Vec3::splat(coat) + base.eval(wo, wi) * t
}

/// Pdf per solid angle of the non-delta lobes of [`sample`].
pub fn pdf(base: &CoatBase, eta: f32, alpha: f32, wo: Vec3, wi: Vec3) -> f32 {
    let Some((wo, wi)) = to_upper(wo, wi) else {
        return 0.0;
    };
    let tr = TrowbridgeReitz::new(alpha);
    let p = coat_pmf(eta, wo);
    let coat = if tr.effectively_smooth() {
        0.0
    } else {
        coat_pdf(&tr, wo, wi)
    };
    p * coat + (1.0 - p) * base.pdf(wo, wi)
}

/// Samples the coat with probability clamp(F(cosθo)), else the base.
pub fn sample(
    base: &CoatBase,
    eta: f32,
    alpha: f32,
    wo: Vec3,
    u_lobe: f32,
    u: Vec2,
) -> Option<BsdfSample> {
    if wo.z == 0.0 {
        return None;
    }
    let flipped = wo.z < 0.0;
    let wo_up = if flipped { flip_z(wo) } else { wo };
    let unflip = |v: Vec3| if flipped { flip_z(v) } else { v };
    let tr = TrowbridgeReitz::new(alpha);
    let p = coat_pmf(eta, wo_up);
    let wi_up = if u_lobe < p {
        if tr.effectively_smooth() {
            // Delta mirror of the coat: weight F/p.
            let wi = Vec3::new(-wo_up.x, -wo_up.y, wo_up.z);
            return Some(BsdfSample {
                wi: unflip(wi),
                f: Vec3::splat(fr_dielectric(wi.z, eta) / wi.z),
                pdf: p,
                delta: true,
            });
        }
        let wi = reflect(wo_up, tr.sample_wm(wo_up, u));
        if wi.z <= 0.0 {
            return None;
        }
        wi
    } else {
        let bs = base.sample(wo_up, u)?;
        if bs.delta {
            // Mirror base under the coat: attenuated by the interface twice.
            let t = (1.0 - fr_dielectric(wo_up.z, eta)) * (1.0 - fr_dielectric(bs.wi.z, eta));
            return Some(BsdfSample {
                wi: unflip(bs.wi),
                f: bs.f * t,
                pdf: (1.0 - p) * bs.pdf,
                delta: true,
            });
        }
        bs.wi
    };
    let pdf = pdf(base, eta, alpha, wo_up, wi_up);
    let f = eval(base, eta, alpha, wo_up, wi_up);
    if !(pdf > 0.0 && pdf.is_finite() && f.is_finite()) {
        return None;
    }
    Some(BsdfSample {
        wi: unflip(wi_up),
        f,
        pdf,
        delta: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_coat_mirror_weight_is_fresnel() {
        let base = CoatBase::Lambert {
            albedo: Vec3::splat(0.5),
        };
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let s = sample(&base, 1.33, 0.0, wo, 0.0, Vec2::splat(0.5)).unwrap();
        assert!(s.delta && (s.wi - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
        let f = fr_dielectric(0.8, 1.33);
        let p = f.clamp(0.05, 0.95);
        assert!((s.weight().x - f / p).abs() < 1e-5);
        // The diffuse part under the film: albedo/π · (1−F)².
        let wi = Vec3::new(0.0, 0.6, 0.8);
        let e = eval(&base, 1.33, 0.0, wo, wi).x;
        let expect = 0.5 / std::f32::consts::PI * (1.0 - f) * (1.0 - f);
        assert!((e - expect).abs() < 1e-6);
    }
}
