//! Material descriptions: `[[material]]` with a unique `name` and a `kind`.
//!
//! Colours are linear RGB. Roughness is perceptual, in [0, 1]; the GGX alpha
//! is roughness². Mask bits follow GROUND_TRUTH.md: dielectrics are
//! transparent, conductors with roughness < 0.1 are mirrors, unless `mask`
//! says otherwise. `coated` (car paint) sets no mask bit by default.

use serde::{Deserialize, Serialize};

/// A named material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MaterialDesc {
    /// Unique name, referenced by objects' `material`.
    pub name: String,
    /// Explicit GT mask flags, replacing the ones derived from the kind.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mask: Option<Vec<MaskFlag>>,
    /// Procedural albedo variation (diffuse materials only), e.g.
    /// `texture = { kind = "asphalt", scale = 1.0, seed = 3 }`. A function of
    /// world position, with mean over a large area equal to `albedo`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture: Option<TextureDesc>,
    /// The scattering model and its parameters.
    #[serde(flatten)]
    pub kind: MaterialKindDesc,
}

/// A procedural texture on a diffuse material's albedo.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureDesc {
    /// The pattern.
    pub kind: TextureKindDesc,
    /// Feature-size multiplier in [0.001, 1000] (default 1: real-world sizes, e.g.
    /// 4 mm asphalt aggregate, 215 × 65 mm bricks; 2 doubles every feature).
    #[serde(default = "default_scale")]
    pub scale: f64,
    /// Decorrelates materials sharing a kind (default 0).
    #[serde(default)]
    pub seed: u32,
}

/// The texture patterns (`shaders_cpu::texture::TextureKind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TextureKindDesc {
    /// Road asphalt: 4 mm aggregate speckle, grit, wear patches up to 1.6 m.
    Asphalt,
    /// Concrete: mottling (60 cm … 4 cm), aggregate texture, sand grain.
    Concrete,
    /// Running-bond brick, 215 × 65 mm with 10 mm mortar, in the wall plane
    /// (paving on surfaces facing up or down).
    Brick,
    /// Plaster: low-amplitude trowel mottling and grain.
    Plaster,
    /// Foliage: per-leaf (5 cm) brightness and hue, clumps, veins.
    Foliage,
}

impl TextureDesc {
    /// The shading-side texture.
    pub fn build(&self) -> shaders_cpu::texture::Texture {
        use shaders_cpu::texture::TextureKind as K;
        let kind = match self.kind {
            TextureKindDesc::Asphalt => K::Asphalt,
            TextureKindDesc::Concrete => K::Concrete,
            TextureKindDesc::Brick => K::Brick,
            TextureKindDesc::Plaster => K::Plaster,
            TextureKindDesc::Foliage => K::Foliage,
        };
        shaders_cpu::texture::Texture {
            kind,
            scale: self.scale,
            seed: self.seed,
        }
    }
}

/// A GT mask flag a material may set.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MaskFlag {
    /// Transparent surface (glass, water).
    Transparent,
    /// Mirror-like surface (puddle, chrome).
    Mirror,
}

/// The material family, selected by `kind`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum MaterialKindDesc {
    /// Lambertian diffuse.
    Diffuse {
        /// Reflectance per channel, in [0, 1].
        albedo: [f64; 3],
    },
    /// GGX conductor: either `preset` or both `eta` and `k`.
    Conductor {
        /// A named metal (approximate RGB optical constants).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        preset: Option<ConductorPreset>,
        /// Real part of the index of refraction per channel, > 0.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        eta: Option<[f64; 3]>,
        /// Absorption coefficient per channel, ≥ 0.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        k: Option<[f64; 3]>,
        /// Perceptual roughness in [0, 1] (default 0).
        #[serde(default)]
        roughness: f64,
    },
    /// GGX dielectric (glass, water) with reflection and transmission.
    Dielectric {
        /// Index of refraction inside/outside, > 0 (default 1.5).
        #[serde(default = "default_ior")]
        ior: f64,
        /// Perceptual roughness in [0, 1] (default 0).
        #[serde(default)]
        roughness: f64,
        /// Transmission tint per channel in [0, 1] (default white).
        #[serde(default = "default_tint")]
        tint: [f64; 3],
    },
    /// A dielectric clear coat over a diffuse or metallic base (car paint):
    /// give `albedo` for a diffuse base, or `preset` / `eta` + `k` for a
    /// conductor base.
    Coated {
        /// Diffuse base reflectance per channel, in [0, 1].
        #[serde(default, skip_serializing_if = "Option::is_none")]
        albedo: Option<[f64; 3]>,
        /// Conductor base: a named metal.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        preset: Option<ConductorPreset>,
        /// Conductor base: real part of the IOR per channel, > 0.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        eta: Option<[f64; 3]>,
        /// Conductor base: absorption per channel, ≥ 0.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        k: Option<[f64; 3]>,
        /// Conductor base perceptual roughness in [0, 1] (default 0.3).
        #[serde(default = "default_base_roughness")]
        base_roughness: f64,
        /// Index of refraction of the coat, in (1, 3] (default 1.5).
        #[serde(default = "default_ior")]
        coat_ior: f64,
        /// Perceptual roughness of the coat in [0, 1] (default 0: smooth).
        #[serde(default)]
        coat_roughness: f64,
    },
    /// An emitter (its surface scatters nothing: black Lambert).
    Emissive {
        /// Emitted radiance, W·m⁻²·sr⁻¹ per channel, each ≥ 0.
        radiance: [f64; 3],
        /// Whether both faces emit (default false: only the geometric front).
        #[serde(default)]
        two_sided: bool,
    },
}

/// Named metals for conductors.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ConductorPreset {
    /// Aluminium.
    Aluminium,
    /// Chromium.
    Chrome,
    /// Copper.
    Copper,
    /// Gold.
    Gold,
    /// Silver.
    Silver,
    /// Iron.
    Iron,
}

impl ConductorPreset {
    /// The preset's name in `shaders_cpu`'s table of measured metals.
    pub fn name(self) -> &'static str {
        match self {
            ConductorPreset::Aluminium => "aluminium",
            ConductorPreset::Chrome => "chrome",
            ConductorPreset::Copper => "copper",
            ConductorPreset::Gold => "gold",
            ConductorPreset::Silver => "silver",
            ConductorPreset::Iron => "iron",
        }
    }

    /// RGB (eta, k) from `shaders_cpu`'s measured-metal table (one source of truth).
    pub fn eta_k(self) -> ([f64; 3], [f64; 3]) {
        match shaders_cpu::bsdf::Bsdf::conductor_preset(self.name(), 0.0) {
            Some(shaders_cpu::bsdf::Bsdf::Conductor { eta, k, .. }) => {
                (eta.as_dvec3().to_array(), k.as_dvec3().to_array())
            }
            _ => unreachable!("every preset is in shaders_cpu's table"),
        }
    }
}

/// A conductor's (eta, k): the preset's when named, else the given values
/// (defaults: eta 1, k 0).
pub fn conductor_eta_k(
    preset: &Option<ConductorPreset>,
    eta: &Option<[f64; 3]>,
    k: &Option<[f64; 3]>,
) -> ([f64; 3], [f64; 3]) {
    match preset {
        Some(p) => p.eta_k(),
        None => (eta.unwrap_or([1.0; 3]), k.unwrap_or([0.0; 3])),
    }
}

fn default_scale() -> f64 {
    1.0
}
fn default_ior() -> f64 {
    1.5
}
fn default_base_roughness() -> f64 {
    0.3
}
fn default_tint() -> [f64; 3] {
    [1.0; 3]
}
