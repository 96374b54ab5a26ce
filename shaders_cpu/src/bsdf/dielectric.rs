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

/// Least probability of sampling a smooth interface's reflection where it
/// also transmits. Fresnel's R (about 0.04 for glass seen head-on) would give
/// a window's reflection of the bright sky to 0 or 1 of 16 samples, a salt-
/// and-pepper pattern over the dark room behind; a quarter of the samples
/// estimate it smoothly, and the weights R/q, T/(1 − q) keep it unbiased.
const REFLECT_MIN: f32 = 0.25;

/// Probability of sampling the reflection of a smooth interface of
/// reflectance `r`: at least `REFLECT_MIN`, and 1 under total internal
/// reflection.
fn reflect_probability(r: f32) -> f32 {
    if r >= 1.0 {
        1.0
    } else {
        r.max(REFLECT_MIN)
    }
}

/// Smooth interface: specular reflection with probability q =
/// [`reflect_probability`], refraction with 1 − q (pbrt-v4 §9.5.2 with q =
/// R); f carries 1/|cosθi| so that f·|cosθi|/pdf = R/q (reflect) or
/// tint·T/((1 − q)·η'²) (transmit).
fn sample_smooth(eta: f32, tint: Vec3, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
    let r = fr_dielectric(wo.z, eta);
    let t = 1.0 - r;
    let q = reflect_probability(r);
    if u_lobe < q {
        let wi = Vec3::new(-wo.x, -wo.y, wo.z);
        Some(BsdfSample {
            wi,
            f: Vec3::splat(r / wi.z.abs()),
            pdf: q,
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
            pdf: 1.0 - q,
            delta: true,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The means over a uniform grid of lobe numbers, for `wo`: (fraction
    /// of reflection samples, mean reflected weight f·|cosθi|/pdf, mean
    /// transmitted weight, red channel).
    fn smooth_lobe_means(eta: f32, tint: Vec3, wo: Vec3) -> (f64, f64, f64) {
        const N: usize = 100_000;
        let (mut n_refl, mut w_refl, mut w_tran) = (0usize, 0.0f64, 0.0f64);
        for k in 0..N {
            let u_lobe = (k as f32 + 0.5) / N as f32;
            let s = sample(eta, 0.0, tint, wo, u_lobe, Vec2::ZERO).expect("a smooth sample");
            assert!(s.delta);
            let weight = (s.f.x * s.wi.z.abs() / s.pdf) as f64;
            if s.wi.z * wo.z > 0.0 {
                n_refl += 1;
                w_refl += weight;
            } else {
                w_tran += weight;
            }
        }
        (
            n_refl as f64 / N as f64,
            w_refl / N as f64,
            w_tran / N as f64,
        )
    }

    #[test]
    fn smooth_glass_reflects_a_quarter_of_samples_or_more_with_unbiased_weights() {
        let (eta, tint) = (1.5, Vec3::new(0.9, 0.95, 0.95));
        // Outside head-on (R = 0.04), outside grazing (R ≈ 0.5), and inside
        // below the critical angle (etap = 1/1.5).
        for (cos_o, side) in [(1.0f32, 1.0f32), (0.7, 1.0), (0.06, 1.0), (0.9, -1.0)] {
            let wo = Vec3::new((1.0 - cos_o * cos_o).sqrt(), 0.0, side * cos_o);
            let r = fr_dielectric(wo.z, eta);
            let etap = if side > 0.0 { eta } else { 1.0 / eta };
            let (frac, refl, tran) = smooth_lobe_means(eta, tint, wo);
            let q = r.max(REFLECT_MIN) as f64;
            assert!(
                (frac - q).abs() < 1e-4,
                "cos {cos_o} side {side}: {frac} vs {q}"
            );
            // The weights average to R and tint·T/η'², whatever q is.
            assert!((refl - r as f64).abs() < 1e-4, "R {r}: {refl}");
            let t_expect = (tint.x * (1.0 - r) / (etap * etap)) as f64;
            assert!((tran - t_expect).abs() < 1e-4, "T {t_expect}: {tran}");
        }
    }

    #[test]
    fn smooth_glass_reflects_every_sample_under_total_internal_reflection() {
        // Inside glass at 60° from the normal, past the 41.8° critical angle.
        let wo = Vec3::new(60f32.to_radians().sin(), 0.0, -60f32.to_radians().cos());
        assert_eq!(fr_dielectric(wo.z, 1.5), 1.0);
        let (frac, refl, tran) = smooth_lobe_means(1.5, Vec3::ONE, wo);
        assert_eq!((frac, tran), (1.0, 0.0));
        assert!((refl - 1.0).abs() < 1e-6, "{refl}");
    }
}
