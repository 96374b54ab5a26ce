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
use shaders_cpu::texture::TexSample;

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

/// The nominal colour a texture modulates in `bsdf`: a Lambertian albedo,
/// a coat's base, a dielectric's tint (a conductor: white, roughness only).
fn nominal(bsdf: &Bsdf) -> Vec3 {
    match bsdf {
        Bsdf::Lambert { albedo } => *albedo,
        Bsdf::Dielectric { tint, .. } => *tint,
        Bsdf::Coated { base, .. } => base.albedo_hint(),
        _ => Vec3::ONE,
    }
}

/// `bsdf` with the texture's albedo (tint) and roughness `s`.
fn textured(bsdf: Bsdf, s: TexSample) -> Bsdf {
    match bsdf {
        Bsdf::Lambert { .. } => Bsdf::Lambert { albedo: s.albedo },
        Bsdf::Conductor { eta, k, alpha } => Bsdf::Conductor {
            eta,
            k,
            alpha: scale_alpha(alpha, s.roughness),
        },
        Bsdf::Dielectric { eta, alpha, .. } => Bsdf::Dielectric {
            eta,
            alpha: scale_alpha(alpha, s.roughness),
            tint: s.albedo,
        },
        Bsdf::Coated { base, eta, alpha } => {
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
    textured_bsdf_filtered(material, origin_world, si, seen, 0.0)
}

/// [`textured_bsdf`] with the texture filtered by the footprint of the
/// pixel at the hit, `footprint_m` metres wide (`Texture::shade`): detail
/// finer than a pixel fades to its mean instead of adding noise.
#[inline]
pub fn textured_bsdf_filtered(
    material: &Material,
    origin_world: DVec3,
    si: &SurfaceInteraction,
    seen: bool,
    footprint_m: f32,
) -> Bsdf {
    match material.texture {
        Some(t) if seen && material.le == Vec3::ZERO => {
            let p = origin_world + si.p.as_dvec3();
            let bsdf = material.bsdf;
            let (s, normal) = t.shade(nominal(&bsdf), p, si.n_geo, si.n_shading, footprint_m);
            let bsdf = textured(bsdf, s);
            if t.has_relief() {
                bsdf.normal_mapped(normal)
            } else {
                bsdf
            }
        }
        _ => material.bsdf,
    }
}
