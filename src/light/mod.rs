//! Lights: the sun (a directional light with the sun's angular size), point and
//! spot lights, and emissive triangles found from materials; light selection
//! for next-event estimation. This module owns the light types and their
//! emission (here), the frame's sky and its sun or moon (`sky.rs`), the set
//! next-event estimation samples and how it picks a light (`set.rs`, with
//! `entry.rs` per light, `bvh.rs` for many local lights and `fog_sky.rs`
//! for the sky seen through fog), and the sun's cone, exact for any
//! angular size (`sun_cone.rs`).
//!
//! Directions are render space (= world orientation, z up). Sampling returns
//! radiance arriving at the shading point and a pdf per solid angle.

use glam::Vec3;

pub mod bvh;
mod emitter;
mod entry;
mod fog_sky;
mod set;

pub use set::{LightSample, LightSelection, LightSet, LOCAL_CANDIDATES, MAX_DISTANT};
// The light and sky data a `Scene` stores are built below the scene;
// sampling them is this module's job.
pub use crate::scene::emitters::{moon_phase_factor, Light};

mod sun_cone;

pub use sun_cone::SunCone;

use shaders_cpu::sampling::Frame;

/// A sun disk prepared for sampling: everything but the draw itself (the
/// cone, its radiance, pdf and a frame) computed once per frame instead
/// of at every vertex. Samples are bit-identical to sampling the `Light`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SunSampler {
    /// Frame whose z axis points at the sun's centre.
    frame: Frame,
    /// The sampled cone.
    cone: SunCone,
    /// Radiance of the disk.
    le: Vec3,
    /// Solid-angle pdf of a uniform cone sample.
    pdf: f32,
}

impl SunSampler {
    /// The sampler of a sun towards unit `dir_to_sun` (see [`Light::Sun`]).
    pub(crate) fn new(dir_to_sun: Vec3, angular_radius_rad: f32, irradiance: Vec3) -> Self {
        let cone = SunCone::new(angular_radius_rad);
        SunSampler {
            frame: Frame::from_z(dir_to_sun),
            cone,
            le: cone.radiance(irradiance),
            pdf: cone.pdf(),
        }
    }

    /// Radiance of the disk.
    #[inline]
    pub(crate) fn le(&self) -> Vec3 {
        self.le
    }

    /// A direction uniform in the disk's cone: (wi, radiance, pdf per solid angle).
    #[inline]
    pub(crate) fn sample(&self, u: glam::Vec2) -> (Vec3, Vec3, f32) {
        let wi = self.frame.from_local(self.cone.sample_local(u));
        (wi, self.le, self.pdf)
    }
}

/// Direction and radiance of a sample of one explicit light seen from `p`:
/// (wi, radiance or intensity/d², pdf per solid angle or 1 for delta, distance).
fn sample_explicit(light: &Light, p: Vec3, u: glam::Vec2) -> Option<(Vec3, Vec3, f32, f32, bool)> {
    match *light {
        Light::Sun {
            dir_to_sun,
            angular_radius_rad,
            irradiance,
        } => {
            let (wi, le, pdf) =
                SunSampler::new(dir_to_sun, angular_radius_rad, irradiance).sample(u);
            Some((wi, le, pdf, f32::INFINITY, false))
        }
        Light::Point { p: pl, intensity } => {
            let d = pl - p;
            let dist2 = d.length_squared();
            if dist2 == 0.0 {
                return None;
            }
            let dist = dist2.sqrt();
            Some((d / dist, intensity / dist2, 1.0, dist, true))
        }
        Light::Spot {
            p: pl,
            dir,
            intensity,
            cos_inner,
            cos_outer,
        } => {
            let d = pl - p;
            let dist2 = d.length_squared();
            if dist2 == 0.0 {
                return None;
            }
            let dist = dist2.sqrt();
            let wi = d / dist;
            let falloff = spot_falloff(-wi.dot(dir), cos_inner, cos_outer);
            if falloff == 0.0 {
                return None;
            }
            Some((wi, intensity * falloff / dist2, 1.0, dist, true))
        }
    }
}

/// Smoothstep falloff between the outer (0) and inner (1) cone cosines (pbrt-v4 §12.2.2).
pub fn spot_falloff(cos_theta: f32, cos_inner: f32, cos_outer: f32) -> f32 {
    if cos_inner <= cos_outer {
        return if cos_theta >= cos_outer { 1.0 } else { 0.0 };
    }
    let t = ((cos_theta - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Emitted power proxy (luminance-weighted) of an explicit light, for selection.
/// Distant lights use `scene_radius` for the disk they illuminate (pbrt-v4's
/// `DistantLight::Phi`).
fn power(light: &Light, scene_radius: f32) -> f32 {
    use shaders_cpu::sampling::luminance;
    let pi = std::f32::consts::PI;
    match *light {
        Light::Sun { irradiance, .. } => pi * scene_radius * scene_radius * luminance(irradiance),
        Light::Point { intensity, .. } => 4.0 * pi * luminance(intensity),
        Light::Spot {
            intensity,
            cos_inner,
            cos_outer,
            ..
        } => 2.0 * pi * (1.0 - 0.5 * (cos_inner + cos_outer)) * luminance(intensity),
    }
}
