//! Lambertian reflection (pbrt-v4 §9.2, `DiffuseBxDF`).
//!
//! f = albedo/π for `wi` in the hemisphere of `wo`, zero otherwise (two-sided:
//! works for `wo` on either side of the local z axis). Sampling is cosine-
//! weighted (Malley's method) mirrored into `wo`'s hemisphere.

use super::BsdfSample;
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// f(wo, wi) of a Lambertian reflector.
#[inline]
pub fn eval(albedo: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    if wo.z * wi.z > 0.0 {
        albedo * FRAC_1_PI
    } else {
        Vec3::ZERO
    }
}

/// Pdf of [`sample`]: |cos θi|/π in `wo`'s hemisphere.
#[inline]
pub fn pdf(wo: Vec3, wi: Vec3) -> f32 {
    if wo.z * wi.z > 0.0 {
        cosine_hemisphere_pdf(wi.z.abs())
    } else {
        0.0
    }
}

/// Cosine-weighted sample in `wo`'s hemisphere; `None` for grazing `wo`.
#[inline]
pub fn sample(albedo: Vec3, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
    if wo.z == 0.0 {
        return None;
    }
    let mut wi = sample_cosine_hemisphere(u);
    if wo.z < 0.0 {
        wi.z = -wi.z;
    }
    let pdf = cosine_hemisphere_pdf(wi.z.abs());
    if pdf == 0.0 {
        return None;
    }
    Some(BsdfSample {
        wi,
        f: albedo * FRAC_1_PI,
        pdf,
        delta: false,
    })
}
