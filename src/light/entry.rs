//! One light the set can pick (`Entry`) and its sampling as seen from a
//! shading point (`LightSample`): explicit lights, the distant group's suns,
//! the sky and emitters (groups of emissive triangles, `emitter.rs`). Render-space directions (z up); pdfs per
//! solid angle times the selection pmf the caller passes, so they enter MIS
//! weights directly. Suns are dimmed by the sky's cloud deck at the point.

use glam::{Vec2, Vec3};

use super::emitter::{point_on, Emitters};
use super::{sample_explicit, Light, SunSampler};
use crate::scene::Scene;

/// One entry the sampler can pick.
#[derive(Clone, Copy, Debug)]
pub(super) enum Entry {
    Explicit(Light),
    /// A sun of the distant group, prepared for sampling.
    Sun(SunSampler),
    Sky,
    /// Emissive triangles of one mesh and material close together, with
    /// what sampling them reads (not their mesh's records: at night a
    /// sample's chain of cache misses through the mesh, its indices,
    /// vertices and material cost as much as its draw).
    Emitter {
        /// Its triangles' indices in the set's `Emitters`, `first..end`.
        first: u32,
        end: u32,
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

/// Samples one entry with selection probability `pmf` (an emitter's
/// triangles in `emitters`).
pub(super) fn sample_entry(
    scene: &Scene,
    emitters: &Emitters,
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
        Entry::Emitter {
            first,
            end,
            le,
            two_sided,
        } => {
            let drawn = emitters.draw(first..end, two_sided, p, u.x)?;
            let q = point_on(&drawn, u);
            let d = q - p;
            let dist2 = d.length_squared();
            let area = drawn.area;
            if dist2 == 0.0 || area == 0.0 {
                return None;
            }
            let [a, b, c] = drawn.v;
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
                pdf: pmf * drawn.pmf * dist2 / (cos_l.abs() * area),
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
