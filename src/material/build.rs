//! Material description → `Material`: the BSDF parameters `shaders_cpu`
//! evaluates, emission, and the GT mask bits of GROUND_TRUTH.md (from the
//! kind, or the description's explicit `mask` list).

use glam::{DVec3, Vec3};
use shaders_cpu::bsdf::{Bsdf, CoatBase};

use super::{mask_bits, Material};
use crate::scene::desc::{
    conductor_eta_k, ConductorPreset, MaskFlag, MaterialDesc, MaterialKindDesc,
};

/// Perceptual roughness below which a conductor counts as a mirror in the mask.
pub const MIRROR_ROUGHNESS: f64 = 0.1;

/// What a material kind resolves to before the mask override.
struct Resolved {
    bsdf: Bsdf,
    le: Vec3,
    two_sided_emission: bool,
    mask: u8,
}

impl Resolved {
    /// A non-emissive surface scattering by `bsdf`.
    fn surface(bsdf: Bsdf, mask: u8) -> Self {
        Resolved {
            bsdf,
            le: Vec3::ZERO,
            two_sided_emission: false,
            mask,
        }
    }
}

/// Resolves one material description (mask bits per GROUND_TRUTH.md).
pub fn build_material(m: &MaterialDesc) -> Material {
    let r = resolve_kind(&m.kind);
    Material {
        name: m.name.clone(),
        bsdf: r.bsdf,
        le: r.le,
        two_sided_emission: r.two_sided_emission,
        mask: m.mask.as_deref().map_or(r.mask, explicit_mask),
        texture: m.texture.map(|t| t.build()),
    }
}

/// The BSDF, emission and kind-implied mask bits of a material kind.
fn resolve_kind(kind: &MaterialKindDesc) -> Resolved {
    match kind {
        MaterialKindDesc::Diffuse { albedo } => Resolved::surface(
            Bsdf::Lambert {
                albedo: v3(*albedo),
            },
            0,
        ),
        MaterialKindDesc::Conductor {
            preset,
            eta,
            k,
            roughness,
        } => conductor(preset, eta, k, *roughness),
        MaterialKindDesc::Dielectric {
            ior,
            roughness,
            tint,
        } => Resolved::surface(
            Bsdf::Dielectric {
                eta: *ior as f32,
                alpha: (roughness * roughness) as f32,
                tint: v3(*tint),
            },
            mask_bits::TRANSPARENT,
        ),
        MaterialKindDesc::Coated {
            albedo,
            preset,
            eta,
            k,
            base_roughness,
            coat_ior,
            coat_roughness,
        } => {
            let base = match albedo {
                Some(a) => CoatBase::Lambert { albedo: v3(*a) },
                None => {
                    let (eta, k) = conductor_eta_k(preset, eta, k);
                    CoatBase::Conductor {
                        eta: v3(eta),
                        k: v3(k),
                        alpha: (base_roughness * base_roughness) as f32,
                    }
                }
            };
            let bsdf = Bsdf::Coated {
                base,
                eta: *coat_ior as f32,
                alpha: (coat_roughness * coat_roughness) as f32,
            };
            Resolved::surface(bsdf, 0)
        }
        MaterialKindDesc::Emissive {
            radiance,
            two_sided,
        } => Resolved {
            bsdf: Bsdf::Lambert { albedo: Vec3::ZERO },
            le: v3(*radiance),
            two_sided_emission: *two_sided,
            mask: 0,
        },
    }
}

/// A metal from a preset or explicit η, k; a mirror in the mask below
/// [`MIRROR_ROUGHNESS`].
fn conductor(
    preset: &Option<ConductorPreset>,
    eta: &Option<[f64; 3]>,
    k: &Option<[f64; 3]>,
    roughness: f64,
) -> Resolved {
    let (eta, k) = conductor_eta_k(preset, eta, k);
    let mask = if roughness < MIRROR_ROUGHNESS {
        mask_bits::MIRROR
    } else {
        0
    };
    let bsdf = Bsdf::Conductor {
        eta: v3(eta),
        k: v3(k),
        alpha: (roughness * roughness) as f32,
    };
    Resolved::surface(bsdf, mask)
}

/// The mask bits of an explicit `mask = [...]` list (replaces the kind's).
fn explicit_mask(flags: &[MaskFlag]) -> u8 {
    flags.iter().fold(0, |bits, f| {
        bits | match f {
            MaskFlag::Transparent => mask_bits::TRANSPARENT,
            MaskFlag::Mirror => mask_bits::MIRROR,
        }
    })
}

/// A description's colour or vector as f32.
pub(crate) fn v3(c: [f64; 3]) -> Vec3 {
    DVec3::from(c).as_vec3()
}
