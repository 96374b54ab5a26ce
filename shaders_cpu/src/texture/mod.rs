//! Procedural albedo textures: pure functions of world position (and, for
//! brick, the geometric normal) that vary a diffuse material's albedo with
//! detail from ~2 mm to ~2 m — the scales a stereo matcher sees at 1600×900
//! (~3 mm per pixel at 5 m) up to wear patches across a lane.
//!
//! Positions are world metres in f64 (never render space, so both views and
//! successive frames see one texture). Every pattern is built from factors
//! of mean 1, so its mean over a large area is the material's nominal albedo
//! and a scene's energy stays calibrated; results are clamped to [0, 0.99].

mod brick;
pub mod noise;
mod patterns;

use glam::{DVec3, Vec3};

/// The pattern family of a texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureKind {
    /// Road asphalt: aggregate speckle (4 mm stones), grit, and wear patches.
    Asphalt,
    /// Cast concrete: mottling from 60 cm to 2 cm plus sand grain.
    Concrete,
    /// Running-bond brick (215 × 65 mm, 10 mm mortar) in the wall plane.
    Brick,
    /// Rendered plaster: low-amplitude trowel mottling and grain.
    Plaster,
    /// Foliage: per-leaf (5 cm) brightness and hue, clumps and veins.
    Foliage,
}

impl TextureKind {
    /// Every kind, for tests and tables.
    pub const ALL: [TextureKind; 5] = [
        TextureKind::Asphalt,
        TextureKind::Concrete,
        TextureKind::Brick,
        TextureKind::Plaster,
        TextureKind::Foliage,
    ];
}

/// A placed texture: pattern, feature scale and seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texture {
    /// The pattern.
    pub kind: TextureKind,
    /// Feature-size multiplier (1 = real-world sizes, 2 = everything twice as big), > 0.
    pub scale: f64,
    /// Decorrelates materials sharing a kind.
    pub seed: u32,
}

impl Texture {
    /// The albedo at `p_world` (metres) for a material of nominal albedo
    /// `base`; `n` is the unit geometric normal (either orientation; only
    /// brick uses it, to find the wall plane). Each channel in [0, 0.99].
    pub fn albedo(&self, base: Vec3, p_world: DVec3, n: Vec3) -> Vec3 {
        let p = p_world / self.scale;
        let s = self.seed;
        let a = match self.kind {
            TextureKind::Asphalt => base * patterns::asphalt(p, s),
            TextureKind::Concrete => base * patterns::concrete(p, s),
            TextureKind::Plaster => base * patterns::plaster(p, s),
            TextureKind::Foliage => base * patterns::foliage(p, s),
            TextureKind::Brick => brick::albedo(base, p, n, s),
        };
        a.clamp(Vec3::ZERO, Vec3::splat(0.99))
    }
}
