//! Applies a material's procedural texture at a surface hit: the one place
//! where render-space hits become world positions for texturing.
//!
//! Textures are functions of world position (`origin_world + p_render`, in
//! f64), so both views of a frame and successive frames see the same
//! pattern, however the render origin moves. A texture sets a Lambertian
//! albedo, a coat's diffuse base or a dielectric's tint, scales every GGX
//! roughness by its roughness factor, and — where the model has no delta
//! lobe — tilts the normal by its relief, through the energy-conserving
//! microfacet normal map of `shaders_cpu::bsdf::normal_map`. Geometry and
//! the ground truth never see any of it.

use glam::{DVec3, Vec3};
use shaders_cpu::bsdf::{Bsdf, CoatBase};
use shaders_cpu::texture::Texture;

use super::Material;
use crate::geometry::SurfaceInteraction;

/// The albedo of `material` at world position `p_world` (metres) with unit
/// geometric normal `n_geo`; the untextured albedo when it has no texture,
/// zero for non-Lambertian BSDFs.
pub fn textured_albedo(material: &Material, p_world: DVec3, n_geo: Vec3) -> Vec3 {
    match (material.bsdf, material.texture) {
        (Bsdf::Lambert { albedo }, Some(t)) => t.albedo(albedo, p_world, n_geo),
        (Bsdf::Lambert { albedo }, None) => albedo,
        _ => Vec3::ZERO,
    }
}

/// A GGX alpha (roughness²) with its perceptual roughness scaled by `f`,
/// at most 1.
fn scale_alpha(alpha: f32, f: f32) -> f32 {
    (alpha * f * f).min(1.0)
}

/// `bsdf` with the texture's albedo (tint) and roughness at `p` (world).
fn textured(bsdf: Bsdf, t: &Texture, p: DVec3, n: Vec3) -> Bsdf {
    match bsdf {
        Bsdf::Lambert { albedo } => Bsdf::Lambert {
            albedo: t.albedo(albedo, p, n),
        },
        Bsdf::Conductor { eta, k, alpha } => Bsdf::Conductor {
            eta,
            k,
            alpha: scale_alpha(alpha, t.sample(Vec3::ONE, p, n).roughness),
        },
        Bsdf::Dielectric { eta, alpha, tint } => {
            let s = t.sample(tint, p, n);
            Bsdf::Dielectric {
                eta,
                alpha: scale_alpha(alpha, s.roughness),
                tint: s.albedo,
            }
        }
        Bsdf::Coated { base, eta, alpha } => {
            let s = t.sample(base.albedo_hint(), p, n);
            let base = match base {
                CoatBase::Lambert { .. } => CoatBase::Lambert { albedo: s.albedo },
                CoatBase::Conductor { eta, k, alpha } => CoatBase::Conductor {
                    eta,
                    k,
                    alpha: scale_alpha(alpha, s.roughness),
                },
            };
            Bsdf::Coated {
                base,
                eta,
                alpha: scale_alpha(alpha, s.roughness),
            }
        }
        other => other,
    }
}

/// The BSDF of `material` at the hit `si` of a frame whose render origin
/// is `origin_world`: its own, textured (albedo, roughness, relief) when it
/// has a texture and `seen` (the hit is seen by the camera directly or
/// through specular bounces only). After a diffuse bounce the nominal
/// material — the texture's area mean, flat — stands in: diffuse transport
/// blurs millimetre detail away, and this keeps the texture's cost to the
/// vertices whose detail reaches the image.
#[inline]
pub fn textured_bsdf(
    material: &Material,
    origin_world: DVec3,
    si: &SurfaceInteraction,
    seen: bool,
) -> Bsdf {
    match material.texture {
        Some(t) if seen && material.le == Vec3::ZERO => {
            let p = origin_world + si.p.as_dvec3();
            let bsdf = textured(material.bsdf, &t, p, si.n_geo);
            if t.has_relief() {
                bsdf.normal_mapped(t.bump_normal(p, si.n_geo, si.n_shading))
            } else {
                bsdf
            }
        }
        _ => material.bsdf,
    }
}
