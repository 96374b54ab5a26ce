//! Sky direction sampling: a mixture of a cosine lobe about +z (weight `p_cos`)
//! and the uniform sphere (weight 1 − `p_cos`), one-sample MIS-style mixture
//! (pbrt-v4 §2.2.3): pdf = p_cos·cosθ/π·[z > 0] + (1 − p_cos)/(4π).

use crate::sampling::{
    cosine_hemisphere_pdf, sample_cosine_hemisphere, sample_uniform_sphere, uniform_sphere_pdf,
};
use glam::{Vec2, Vec3};

/// Draws a direction; `u.x` both selects the component and is re-stretched.
#[inline]
pub(super) fn sample_dir(p_cos: f32, u: Vec2) -> Vec3 {
    if u.x < p_cos {
        let ux = (u.x / p_cos).min(1.0 - f32::EPSILON / 2.0);
        sample_cosine_hemisphere(Vec2::new(ux, u.y))
    } else {
        let ux = ((u.x - p_cos) / (1.0 - p_cos)).min(1.0 - f32::EPSILON / 2.0);
        sample_uniform_sphere(Vec2::new(ux, u.y))
    }
}

/// Mixture pdf per solid angle of [`sample_dir`].
#[inline]
pub(super) fn dir_pdf(p_cos: f32, dir: Vec3) -> f32 {
    p_cos * cosine_hemisphere_pdf(dir.z) + (1.0 - p_cos) * uniform_sphere_pdf()
}
