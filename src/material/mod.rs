//! Materials: what a surface is made of and what that makes of light at a
//! hit. Owns the resolved `Material` (built from its description by
//! `build`), the GT mask bits a material carries, procedural texturing
//! (`texture`), wet surfaces and puddles (`wet`), and `Shading`, the one
//! place where a hit's material becomes the BSDF and mask bits the
//! integrators use.
//!
//! Materials sit below the scene: nothing here reads a `Scene`; a scene
//! lends its materials, wetness and render origin as a `Shading`.

pub mod build;
pub mod texture;
pub mod wet;

pub use build::{build_material, MIRROR_ROUGHNESS};
pub use texture::{textured_albedo, textured_bsdf};
pub use wet::{mask_at, wet_bsdf, Wetness};

use glam::{DVec3, Vec3};
use shaders_cpu::bsdf::Bsdf;

use crate::geometry::SurfaceInteraction;

/// Mask bits of GROUND_TRUTH.md carried by a material.
pub mod mask_bits {
    /// Bit 0: sky (no surface hit).
    pub const SKY: u8 = 1;
    /// Bit 1: covered by rain particles.
    pub const RAIN: u8 = 2;
    /// Bit 2: transparent surface (glass, water).
    pub const TRANSPARENT: u8 = 4;
    /// Bit 3: mirror-like surface (puddle, chrome).
    pub const MIRROR: u8 = 8;
}

/// A resolved material: how a surface scatters and emits.
#[derive(Clone, Debug)]
pub struct Material {
    /// Name from the description (unique).
    pub name: String,
    /// Scattering model, evaluated in the local shading frame.
    pub bsdf: Bsdf,
    /// Emitted radiance (W·m⁻²·sr⁻¹ per RGB channel), zero if not emissive.
    pub le: Vec3,
    /// Whether emission leaves both faces (otherwise only the geometric front).
    pub two_sided_emission: bool,
    /// GT mask bits this surface sets (`mask_bits::TRANSPARENT`, `MIRROR`).
    pub mask: u8,
    /// Procedural albedo variation of a Lambertian `bsdf` (world position).
    pub texture: Option<shaders_cpu::texture::Texture>,
}

/// What shading reads of one frame: its materials (indexed by
/// `SurfaceInteraction::material`), its wetness and the world position of
/// its render origin (textures are functions of world position).
#[derive(Clone, Copy, Debug)]
pub struct Shading<'a> {
    /// The frame's materials.
    pub materials: &'a [Material],
    /// Wet surfaces and puddles (None: dry).
    pub wetness: Option<&'a Wetness>,
    /// World position of the render-space origin (metres).
    pub origin_world: DVec3,
}

impl Shading<'_> {
    /// The BSDF at `si` seen from `wo` (pointing away from the surface): the
    /// material's, textured when `seen` ([`textured_bsdf`]), then wetted
    /// ([`wet_bsdf`]).
    #[inline]
    pub fn bsdf(&self, si: &SurfaceInteraction, wo: Vec3, seen: bool) -> Bsdf {
        let material = &self.materials[si.material as usize];
        let textured = textured_bsdf(material, self.origin_world, si.p, si.n_geo, seen);
        wet_bsdf(self.wetness, si, wo, textured)
    }

    /// The GT mask bits at `si` for a camera ray of direction `ray_d`
    /// ([`mask_at`]).
    #[inline]
    pub fn mask(&self, si: &SurfaceInteraction, ray_d: Vec3) -> u8 {
        mask_at(
            &self.materials[si.material as usize],
            self.wetness,
            si,
            ray_d,
        )
    }
}
