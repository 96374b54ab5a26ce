//! BSDFs in the local shading frame (z = shading normal). API contract only;
//! implementations live in the per-family files.

use glam::{Vec2, Vec3};

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Sampled incident direction, local frame, unit length.
    pub wi: Vec3,
    /// BSDF value f(wo, wi) (without the cosine).
    pub f: Vec3,
    /// Pdf per solid angle (for delta lobes: the discrete lobe probability).
    pub pdf: f32,
    /// Whether the sample came from a delta (perfectly specular) lobe.
    pub delta: bool,
}

/// The closed set of scattering models.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bsdf {
    /// Lambertian diffuse reflection.
    Lambert {
        /// Reflectance in [0, 1] per channel.
        albedo: Vec3,
    },
    /// GGX microfacet conductor (alpha below ~1e-3 is a perfect mirror).
    Conductor {
        /// Real part of the complex index of refraction, per channel.
        eta: Vec3,
        /// Imaginary part (absorption), per channel.
        k: Vec3,
        /// GGX roughness alpha (= perceptual roughness squared).
        alpha: f32,
    },
    /// GGX microfacet dielectric with reflection and transmission
    /// (alpha below ~1e-3 is smooth glass).
    Dielectric {
        /// Relative index of refraction inside/outside (e.g. 1.5 for glass).
        eta: f32,
        /// GGX roughness alpha.
        alpha: f32,
        /// Transmission tint per channel in [0, 1].
        tint: Vec3,
    },
}

impl Bsdf {
    /// f(wo, wi), local frame (zero for delta lobes).
    pub fn eval(&self, _wo: Vec3, _wi: Vec3) -> Vec3 {
        unimplemented!("shaders helper")
    }
    /// Pdf per solid angle of sampling `wi` given `wo` (zero for delta lobes).
    pub fn pdf(&self, _wo: Vec3, _wi: Vec3) -> f32 {
        unimplemented!("shaders helper")
    }
    /// Samples `wi` given `wo`, a lobe-selection number and a 2D sample.
    pub fn sample(&self, _wo: Vec3, _u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        unimplemented!("shaders helper")
    }
    /// Whether every lobe is a delta (eval and pdf are then always zero).
    pub fn is_delta(&self) -> bool {
        unimplemented!("shaders helper")
    }
}
