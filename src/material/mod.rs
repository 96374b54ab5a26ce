//! Materials: what a surface is made of and what that makes of light at a
//! hit. Owns the resolved `Material` (built from its description by
//! `build`), the GT mask bits a material carries, procedural texturing
//! (`texture`), wet surfaces and puddles (`wet`), and `MaterialView`, the one
//! place where a hit's material becomes the BSDF and mask bits the
//! integrators use.
//!
//! Materials sit below the scene: nothing here reads a `Scene`; a scene
//! lends its materials, wetness and render origin as a `MaterialView`.

pub mod build;
pub mod texture;
pub mod wet;

pub use build::{build_material, MIRROR_ROUGHNESS};
pub use texture::{textured_albedo, textured_bsdf, textured_bsdf_filtered};
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
    /// Procedural albedo, roughness and relief (world position).
    pub texture: Option<shaders_cpu::texture::Texture>,
}

/// What shading reads of one frame: its materials (indexed by
/// `SurfaceInteraction::material`), its wetness and the world position of
/// its render origin (textures are functions of world position).
#[derive(Clone, Copy, Debug)]
pub struct MaterialView<'a> {
    /// The frame's materials.
    pub materials: &'a [Material],
    /// Wet surfaces and puddles (None: dry).
    pub wetness: Option<&'a Wetness>,
    /// World position of the render-space origin (metres).
    pub origin_world: DVec3,
}

impl MaterialView<'_> {
    /// The BSDF at `si` seen from `wo` (pointing away from the surface): the
    /// material's, textured when `seen` ([`textured_bsdf`]), then wetted
    /// ([`wet_bsdf`]).
    #[inline]
    pub fn bsdf(&self, si: &SurfaceInteraction, wo: Vec3, seen: bool) -> Bsdf {
        self.bsdf_filtered(si, wo, seen, 0.0)
    }

    /// [`MaterialView::bsdf`] with the texture filtered by a footprint
    /// `footprint_m` metres wide ([`textured_bsdf_filtered`]).
    #[inline]
    pub fn bsdf_filtered(
        &self,
        si: &SurfaceInteraction,
        wo: Vec3,
        seen: bool,
        footprint_m: f32,
    ) -> Bsdf {
        let material = &self.materials[si.material as usize];
        let textured = textured_bsdf_filtered(material, self.origin_world, si, seen, footprint_m);
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

#[cfg(test)]
mod tests {
    use super::wet::WATER_IOR;
    use super::*;
    use crate::scene::desc::{TextureDesc, TextureKindDesc, WetnessDesc};

    /// A textured asphalt road material (nominal albedo 0.2).
    fn road() -> Material {
        let texture = TextureDesc {
            bump: 0.0,
            ..TextureDesc::new(TextureKindDesc::Asphalt, 3)
        };
        Material {
            name: "road".into(),
            bsdf: Bsdf::Lambert {
                albedo: Vec3::splat(0.2),
            },
            le: Vec3::ZERO,
            two_sided_emission: false,
            mask: 0,
            texture: Some(texture.build()),
        }
    }

    /// An up-facing hit at render-space `p` on material 0 of class `semantic`.
    fn hit(p: Vec3, semantic: u8) -> SurfaceInteraction {
        SurfaceInteraction {
            p,
            p_error: Vec3::ZERO,
            n_geo: Vec3::Z,
            n_shading: Vec3::Z,
            uv: glam::Vec2::ZERO,
            material: 0,
            semantic,
            instance: 0,
        }
    }

    #[test]
    fn shading_textures_seen_hits_at_their_world_point_then_wets_them() {
        let materials = [road()];
        let origin = DVec3::new(1000.0, -20.0, 0.5);
        let dry = MaterialView {
            materials: &materials,
            wetness: None,
            origin_world: origin,
        };
        let wo = Vec3::new(0.3, 0.0, 1.0).normalize();
        let mut textured = 0;
        for k in 0..32 {
            let si = hit(Vec3::new(0.37 * k as f32, 0.11 * k as f32, 0.0), 1);
            let p_world = origin + si.p.as_dvec3();
            let albedo = textured_albedo(&materials[0], p_world, si.n_geo);
            // Seen: the texture at the world point; after a diffuse bounce
            // the nominal albedo.
            assert_eq!(dry.bsdf(&si, wo, true), Bsdf::Lambert { albedo });
            assert_eq!(dry.bsdf(&si, wo, false), materials[0].bsdf);
            assert_eq!(dry.mask(&si, -wo), 0);
            textured += usize::from(albedo != Vec3::splat(0.2));
        }
        assert!(textured > 16, "texture changed {textured} of 32 albedos");

        // Soaked with puddles everywhere: a road hit becomes smooth water
        // over the soaked textured base and carries the mirror bit; a class
        // that does not get wet (0) keeps its textured BSDF.
        let desc = WetnessDesc {
            wetness: 1.0,
            puddle_cover: 1.0,
            puddle_scale_m: 4.0,
            seed: 1,
        };
        let w = Wetness::new(&desc, origin);
        let wet = MaterialView {
            wetness: Some(&w),
            ..dry
        };
        let si = hit(Vec3::new(2.5, -1.25, 0.0), 1);
        assert!(
            matches!(wet.bsdf(&si, wo, true), Bsdf::Coated { eta, alpha, .. } if eta == WATER_IOR && alpha == 0.0)
        );
        assert_eq!(wet.mask(&si, -wo), mask_bits::MIRROR);
        let dry_class = hit(si.p, 0);
        assert_eq!(
            wet.bsdf(&dry_class, wo, true),
            dry.bsdf(&dry_class, wo, true)
        );
        assert_eq!(wet.mask(&dry_class, -wo), 0);
    }
}
