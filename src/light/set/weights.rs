//! What the light set weighs its lights by: the light-BVH bounds of
//! explicit lights, the point-independent selection pmf, and the emitted
//! power of the distant lights (against which the local lights' share
//! decides how they are sampled).

use glam::Vec3;
use shaders_cpu::sampling::luminance;

use super::super::bvh::acos_clamped;
use super::super::{power, Light};
use super::LightBounds;
use crate::scene::Scene;

/// Emitted power proxy of the distant lights (suns, and the sky as the
/// irradiance π·L̄ it gives a disk of the scene's `radius`, `scene_radius`).
pub(super) fn distant_power(scene: &Scene, radius: f32) -> f32 {
    let suns: f32 = scene
        .lights
        .iter()
        .filter(|l| matches!(l, Light::Sun { .. }))
        .map(|l| power(l, radius))
        .sum();
    let pi = std::f32::consts::PI;
    suns + pi * radius * radius * pi * scene.sky.luminance_avg().max(0.0)
}

/// BVH bounds of an explicit local light; suns get none (phi 0: not in the tree).
pub(super) fn explicit_bounds(light: &Light) -> LightBounds {
    let point =
        |p: Vec3, w: Vec3, intensity: Vec3, cos_theta_o: f32, cos_theta_e: f32| LightBounds {
            p_min: p,
            p_max: p,
            w,
            phi: luminance(intensity),
            cos_theta_o,
            cos_theta_e,
            two_sided: false,
        };
    match *light {
        Light::Sun { dir_to_sun, .. } => LightBounds {
            phi: 0.0,
            ..point(Vec3::ZERO, dir_to_sun, Vec3::ZERO, -1.0, 0.0)
        },
        Light::Point { p, intensity } => point(p, Vec3::Z, intensity, -1.0, 0.0),
        Light::Spot {
            p,
            dir,
            intensity,
            cos_inner,
            cos_outer,
        } => {
            // Full intensity inside θ_o, falloff out to θ_outer = θ_o + θ_e
            // (a small θ_e keeps hard-edged spots inside their own bound).
            let theta_outer = acos_clamped(cos_outer);
            let theta_o = acos_clamped(cos_inner).min(theta_outer);
            let theta_e = (theta_outer - theta_o).max(1e-3);
            point(p, dir, intensity, theta_o.cos(), theta_e.cos())
        }
    }
}

/// Selection probabilities: half by power, half uniform. Power alone starves
/// the sky next to the sun (≈ 9% of picks) although it is the only light in
/// every shadow; the uniform half keeps each light's share ≥ 1/(2N).
pub(super) fn selection_pmf(weights: &[f32]) -> Vec<f32> {
    let n = weights.len().max(1) as f64;
    let total: f64 = weights.iter().map(|&w| w.max(0.0) as f64).sum();
    weights
        .iter()
        .map(|&w| {
            let by_power = if total > 0.0 {
                w.max(0.0) as f64 / total
            } else {
                1.0 / n
            };
            (0.5 * by_power + 0.5 / n) as f32
        })
        .collect()
}

/// Largest scene radius the light weights use, metres.
const MAX_SCENE_RADIUS: f32 = 100.0;

/// Radius of the scene's bounding sphere around the render origin, clamped to a
/// range that keeps distant lights from swamping or vanishing in selection.
/// The walk stops at the first point past the clamp: a town frame has one
/// within its first meshes, and would otherwise transform every instanced
/// vertex of the frame.
pub(super) fn scene_radius(scene: &Scene) -> f32 {
    let placed = scene.instances.iter().flat_map(|i| {
        let m = i.render_from_local_f32;
        let proto = &scene.prototypes[i.prototype as usize];
        proto.meshes.iter().flat_map(move |pm| {
            pm.p_f32
                .iter()
                .map(move |&p| m.transform_point3(p).length())
        })
    });
    let lengths = scene
        .meshes
        .iter()
        .flat_map(|m| m.p_f32.iter())
        .map(|p| p.length())
        .chain(placed)
        .chain(
            scene
                .spheres_f32
                .iter()
                .map(|s| s.truncate().length() + s.w),
        );
    let mut r = 0.0f32;
    for l in lengths {
        if l >= MAX_SCENE_RADIUS {
            return MAX_SCENE_RADIUS;
        }
        r = r.max(l);
    }
    r.clamp(1.0, MAX_SCENE_RADIUS)
}
