//! Applies a material's procedural texture at a surface hit: the one place
//! where render-space hits become world positions for texturing.
//!
//! Textures are functions of world position (`origin_world + p_render`, in
//! f64), so both views of a frame and successive frames see the same
//! pattern, however the render origin moves. Only Lambertian albedo is
//! textured; other BSDFs pass through unchanged.

use glam::{DVec3, Vec3};
use shaders_cpu::bsdf::Bsdf;

use super::Material;

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

/// The BSDF of `material` at a hit at render-space `p_render` of a frame
/// whose render origin is `origin_world`: its own, with the textured albedo
/// when it has a texture and `seen` (the hit is seen by the camera directly
/// or through specular bounces only). After a diffuse bounce the nominal
/// albedo — the texture's area mean — stands in: diffuse transport blurs
/// millimetre detail away, and this keeps the texture's cost to the vertices
/// whose detail reaches the image.
#[inline]
pub fn textured_bsdf(
    material: &Material,
    origin_world: DVec3,
    p_render: Vec3,
    n_geo: Vec3,
    seen: bool,
) -> Bsdf {
    match (material.bsdf, material.texture) {
        (Bsdf::Lambert { albedo }, Some(t)) if seen => Bsdf::Lambert {
            albedo: t.albedo(albedo, origin_world + p_render.as_dvec3(), n_geo),
        },
        (bsdf, _) => bsdf,
    }
}
