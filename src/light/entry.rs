//! One light the set can pick (`Entry`) and its sampling as seen from a
//! shading point (`LightSample`): explicit lights, the distant group's suns,
//! the sky and emissive triangles. Render-space directions (z up); pdfs per
//! solid angle times the selection pmf the caller passes, so they enter MIS
//! weights directly. Suns are dimmed by the sky's cloud deck at the point.

use glam::{Vec2, Vec3};
use shaders_cpu::sampling::sample_uniform_triangle;

use super::{sample_explicit, Light, SunSampler};
use crate::scene::Scene;

/// One entry the sampler can pick.
#[derive(Clone, Copy, Debug)]
pub(super) enum Entry {
    Explicit(Light),
    /// A sun of the distant group, prepared for sampling.
    Sun(SunSampler),
    Sky,
    /// An emissive triangle with what sampling it reads (not its mesh's
    /// records: at night a sample's chain of cache misses through the
    /// mesh, its indices, vertices and material cost as much as its draw).
    Triangle {
        /// Its vertices (render space), as the mesh stores them.
        v: [Vec3; 3],
        area: f32,
        /// Its material's emitted radiance.
        le: Vec3,
        two_sided: bool,
    },
}

/// A light sample as seen from a shading point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction towards the light.
    pub wi: Vec3,
    /// Incident radiance (for delta lights: intensity / distance²).
    pub li: Vec3,
    /// Pdf per solid angle including the selection pmf (delta lights: the pmf).
    pub pdf: f32,
    /// Distance to the light sample (infinite for the sun and sky).
    pub dist: f32,
    /// Whether the light is a delta distribution (no MIS possible).
    pub delta: bool,
}

/// Samples one entry with selection probability `pmf`.
pub(super) fn sample_entry(
    scene: &Scene,
    entry: &Entry,
    pmf: f32,
    p: Vec3,
    u: Vec2,
) -> Option<LightSample> {
    match *entry {
        Entry::Explicit(light) => {
            let (wi, mut li, pdf, dist, delta) = sample_explicit(&light, p, u)?;
            if matches!(light, Light::Sun { .. }) {
                li *= cloud_transmittance(scene, p, wi);
            }
            Some(LightSample {
                wi,
                li,
                pdf: pdf * pmf,
                dist,
                delta,
            })
        }
        Entry::Sun(ref sun) => {
            let (wi, li, pdf) = sun.sample(u);
            Some(LightSample {
                wi,
                li: li * cloud_transmittance(scene, p, wi),
                pdf: pdf * pmf,
                dist: f32::INFINITY,
                delta: false,
            })
        }
        Entry::Sky => {
            let (wi, li, pdf) = scene.sky.sample(u);
            (pdf > 0.0).then_some(LightSample {
                wi,
                li,
                pdf: pdf * pmf,
                dist: f32::INFINITY,
                delta: false,
            })
        }
        Entry::Triangle {
            v: [a, b, c],
            area,
            le,
            two_sided,
        } => {
            let bary = sample_uniform_triangle(u);
            let q = a * bary[0] + b * bary[1] + c * bary[2];
            let d = q - p;
            let dist2 = d.length_squared();
            if dist2 == 0.0 || area == 0.0 {
                return None;
            }
            let n = (b - a).cross(c - a).normalize();
            let dist = dist2.sqrt();
            let wi = d / dist;
            let cos_l = -n.dot(wi);
            if cos_l <= 0.0 && !two_sided || cos_l == 0.0 {
                return None;
            }
            Some(LightSample {
                wi,
                li: le,
                pdf: pmf * dist2 / (cos_l.abs() * area),
                dist,
                delta: false,
            })
        }
    }
}

/// Sun transmittance through the sky's cloud deck from render-space `p`
/// (a function of the world position only, so every view agrees).
pub(super) fn cloud_transmittance(scene: &Scene, p: Vec3, wi: Vec3) -> f32 {
    scene
        .sky
        .cloud_transmittance(scene.origin_world + p.as_dvec3(), wi)
}
