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
    /// Procedural albedo, roughness and relief, e.g.
    /// `texture = { kind = "asphalt", scale = 1.0, seed = 3 }`: a function of
    /// world position whose mean albedo over a large area is the material's
    /// (`albedo`, a coat's diffuse base, a dielectric's `tint`); emitters
    /// take none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture: Option<TextureDesc>,
    /// The scattering model and its parameters.
    #[serde(flatten)]
    pub kind: MaterialKindDesc,
}

/// A procedural texture: albedo, roughness and relief (bump) varying with
/// world position, e.g. `texture = { kind = "brick_flemish", seed = 3 }`.
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
    /// Relief multiplier in [0, 4] (default 1: the kind's own relief, e.g.
    /// recessed mortar joints; 0: flat, albedo and roughness only).
    #[serde(default = "default_bump")]
    pub bump: f64,
}

/// The texture kinds of the scene format (`shaders_cpu::texture::TextureKind`
/// documents each): the names other modules give materials by.
///
/// `asphalt`, `road_paint`, `paving`, `kerb`, `brick` (stretcher bond),
/// `brick_flemish`, `brick_english`, `plaster`, `stone`, `concrete`,
/// `glass`, `metal_painted`, `metal_brushed`, `wood`, `bark`, `leaves`,
/// `foliage`, `grass`, `soil`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TextureKindDesc {
    /// Road asphalt: aggregate, cracks, patches, tar seams, tyre wear,
    /// manhole covers, drain gratings and oil stains.
    Asphalt,
    /// Worn road-marking paint: wear, gaps showing the asphalt, aggregate relief.
    RoadPaint,
    /// Paving slabs (600 × 600 mm) with recessed joints.
    Paving,
    /// Kerb stones (915 mm long) with joints.
    Kerb,
    /// Stretcher-bond brick, 215 × 65 mm with 10 mm recessed mortar.
    Brick,
    /// Flemish-bond brick: stretchers and headers alternating in each course.
    BrickFlemish,
    /// English-bond brick: courses of stretchers and of headers alternating.
    BrickEnglish,
    /// Rendered plaster: trowel mottling, grain, fine relief.
    Plaster,
    /// Ashlar stone: courses of dressed blocks of varied length.
    Stone,
    /// Concrete: mottling, aggregate, sand, formwork pores.
    Concrete,
    /// Glass: faint tint variation and smudges (on the transmission tint).
    Glass,
    /// Painted metal: paint with chips and rust spots, orange-peel relief.
    MetalPainted,
    /// Brushed metal: roughness streaks along the horizontal.
    MetalBrushed,
    /// Wood: planks with grain along the horizontal, knots.
    Wood,
    /// Bark: vertical furrows and ridges with strong relief.
    Bark,
    /// Leaves: leaf-scale hue and brightness, midribs and veins.
    Leaves,
    /// Foliage seen from afar: per-leaf brightness and hue, clumps, veins.
    Foliage,
    /// Grass: blades, clumps and dry patches.
    Grass,
    /// Soil: clods, pebbles and damp patches.
    Soil,
}

impl TextureKindDesc {
    /// Every kind, in the order of the list above.
    pub const ALL: [TextureKindDesc; 19] = [
        TextureKindDesc::Asphalt,
        TextureKindDesc::RoadPaint,
        TextureKindDesc::Paving,
        TextureKindDesc::Kerb,
        TextureKindDesc::Brick,
        TextureKindDesc::BrickFlemish,
        TextureKindDesc::BrickEnglish,
        TextureKindDesc::Plaster,
        TextureKindDesc::Stone,
        TextureKindDesc::Concrete,
        TextureKindDesc::Glass,
        TextureKindDesc::MetalPainted,
        TextureKindDesc::MetalBrushed,
        TextureKindDesc::Wood,
        TextureKindDesc::Bark,
        TextureKindDesc::Leaves,
        TextureKindDesc::Foliage,
        TextureKindDesc::Grass,
        TextureKindDesc::Soil,
    ];
}

impl TextureDesc {
    /// A texture of `kind` at real-world size with its own relief.
    pub fn new(kind: TextureKindDesc, seed: u32) -> Self {
        TextureDesc {
            kind,
            scale: 1.0,
            seed,
            bump: 1.0,
        }
    }

    /// The shading-side texture.
    pub fn build(&self) -> shaders_cpu::texture::Texture {
        use shaders_cpu::texture::TextureKind as K;
        let kind = match self.kind {
            TextureKindDesc::Asphalt => K::Asphalt,
            TextureKindDesc::RoadPaint => K::RoadPaint,
            TextureKindDesc::Paving => K::Paving,
            TextureKindDesc::Kerb => K::Kerb,
            TextureKindDesc::Brick => K::Brick,
            TextureKindDesc::BrickFlemish => K::BrickFlemish,
            TextureKindDesc::BrickEnglish => K::BrickEnglish,
            TextureKindDesc::Plaster => K::Plaster,
            TextureKindDesc::Stone => K::Stone,
            TextureKindDesc::Concrete => K::Concrete,
            TextureKindDesc::Glass => K::Glass,
            TextureKindDesc::MetalPainted => K::MetalPainted,
            TextureKindDesc::MetalBrushed => K::MetalBrushed,
            TextureKindDesc::Wood => K::Wood,
            TextureKindDesc::Bark => K::Bark,
            TextureKindDesc::Leaves => K::Leaves,
            TextureKindDesc::Foliage => K::Foliage,
            TextureKindDesc::Grass => K::Grass,
            TextureKindDesc::Soil => K::Soil,
        };
        shaders_cpu::texture::Texture {
            kind,
            scale: self.scale,
            seed: self.seed,
            bump: self.bump as f32,
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
fn default_bump() -> f64 {
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
