//! Procedural surface textures: pure functions of world position (and, for
//! patterns laid in a plane, the geometric normal) that give a material's
//! albedo, a roughness factor and a height field (relief), with detail from
//! ~1 mm to ~20 m — the scales a stereo matcher sees at 1600×900 (~3 mm per
//! pixel at 5 m) up to patches across a lane and sparse road decals.
//!
//! Positions are world metres in f64 (never render space, so both views and
//! successive frames see one texture). Albedo patterns are built from
//! factors of mean 1, so the mean over a large area is the material's
//! nominal albedo (`TextureKind::MEAN_PRESERVING`; road paint's wear and
//! leaves' veins are the exceptions, documented on the kind); albedos are
//! clamped to [0, 0.99]. Relief is a height in metres along the normal
//! whose tangential gradient, by forward differences 0.4 mm
//! apart in the tangent frame of the geometric normal, tilts the shading
//! normal ([`Texture::bump_normal`]); the BSDF side (`bsdf::normal_map`)
//! keeps that energy-conserving.
//!
//! Kinds, by scene name: `asphalt`, `road_paint`, `paving`, `kerb`, `brick`,
//! `brick_flemish`, `brick_english`, `plaster`, `stone`, `concrete`, `glass`,
//! `metal_painted`, `metal_brushed`, `wood`, `bark`, `leaves`, `foliage`,
//! `grass`, `soil`.

mod decals;
mod filter;
mod masonry;
mod nature;
pub mod noise;
mod plane;
mod road;
mod surfaces;

use glam::{DVec3, Vec3};

pub use filter::Footprint;

use crate::sampling::Frame;

/// The pattern family of a texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureKind {
    /// Road asphalt: 4 mm aggregate, grit, wear, cracks, patches, tar
    /// seams, tyre streaks, and sparse manhole covers, drain gratings and
    /// oil stains (up-facing surfaces).
    Asphalt,
    /// Worn road-marking paint: patches worn down to the asphalt (mean
    /// albedo ~10 % below nominal) over aggregate relief.
    RoadPaint,
    /// Paving slabs 600 × 600 mm, 6 mm recessed joints, per-slab tint and tilt.
    Paving,
    /// Kerb stones 915 mm long with recessed joints.
    Kerb,
    /// Stretcher-bond brick (215 × 65 mm, 10 mm recessed mortar).
    Brick,
    /// Flemish-bond brick: header and stretcher alternating in each course.
    BrickFlemish,
    /// English-bond brick: stretcher and header courses alternating.
    BrickEnglish,
    /// Rendered plaster: trowel mottling, grain and fine relief.
    Plaster,
    /// Ashlar stone: courses 28–40 cm high of blocks 40–90 cm long.
    Stone,
    /// Cast concrete: mottling, aggregate, sand grain and pores.
    Concrete,
    /// Glass: a faint tint variation and smudges; no relief.
    Glass,
    /// Painted metal: paint chipped to rust, orange-peel relief.
    MetalPainted,
    /// Brushed metal: roughness streaks along the horizontal.
    MetalBrushed,
    /// Wood planks (14 cm) with grain along the horizontal and knots.
    Wood,
    /// Bark: vertical furrows and ridges, strong relief.
    Bark,
    /// Leaves: per-leaf hue and brightness, veins (mean ~3 % below nominal).
    Leaves,
    /// Foliage from afar: per-leaf (5 cm) brightness and hue, clumps, veins.
    Foliage,
    /// Grass: blades, clumps and dry patches.
    Grass,
    /// Soil: clods, pebbles, damp patches.
    Soil,
}

impl TextureKind {
    /// Every kind, for tests and tables.
    pub const ALL: [TextureKind; 19] = [
        TextureKind::Asphalt,
        TextureKind::RoadPaint,
        TextureKind::Paving,
        TextureKind::Kerb,
        TextureKind::Brick,
        TextureKind::BrickFlemish,
        TextureKind::BrickEnglish,
        TextureKind::Plaster,
        TextureKind::Stone,
        TextureKind::Concrete,
        TextureKind::Glass,
        TextureKind::MetalPainted,
        TextureKind::MetalBrushed,
        TextureKind::Wood,
        TextureKind::Bark,
        TextureKind::Leaves,
        TextureKind::Foliage,
        TextureKind::Grass,
        TextureKind::Soil,
    ];

    /// Whether the mean albedo over a large area is the nominal one.
    pub fn mean_preserving(self) -> bool {
        !matches!(self, TextureKind::RoadPaint | TextureKind::Leaves)
    }
}

/// A placed texture: pattern, feature scale, seed and relief strength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texture {
    /// The pattern.
    pub kind: TextureKind,
    /// Feature-size multiplier (1 = real-world sizes, 2 = everything twice as big), > 0.
    pub scale: f64,
    /// Decorrelates materials sharing a kind.
    pub seed: u32,
    /// Relief multiplier (0: flat; 1: the kind's own relief).
    pub bump: f32,
}

/// What a texture gives at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexSample {
    /// Albedo, each channel in [0, 0.99].
    pub albedo: Vec3,
    /// Factor on the material's perceptual roughness (mean ~1).
    pub roughness: f32,
}

/// One pattern's answer before clamping: albedo, roughness factor, height (m).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pat {
    pub c: Vec3,
    pub r: f32,
    /// The height under the footprint's relief version
    /// ([`Footprint::relief`]: faded terms leave no residual grain),
    /// whichever footprint the colour is filtered by, so the colour pass
    /// gives the relief's height at its point.
    pub h: f32,
}

/// Forward-difference step of the relief gradient, metres (texture space).
const BUMP_STEP_M: f64 = 4e-4;
/// Largest relief slope after `bump` (a tilt of ~63°), so the shading
/// normal stays well inside the geometric hemisphere.
const MAX_SLOPE: f32 = 2.0;

impl Texture {
    /// A texture of `kind` at real-world size with its own relief.
    pub fn new(kind: TextureKind, seed: u32) -> Self {
        Texture {
            kind,
            scale: 1.0,
            seed,
            bump: 1.0,
        }
    }

    /// The pattern at texture-space `p` (world / scale) filtered by the
    /// footprint `f` (texture space); `color` false asks for the height
    /// only (the albedo may then be anything).
    fn pat(&self, base: Vec3, p: DVec3, n: Vec3, f: Footprint, color: bool) -> Pat {
        use TextureKind as K;
        let s = self.seed;
        match self.kind {
            K::Asphalt => road::asphalt(base, p, n, s, f, color),
            K::RoadPaint => road::road_paint(base, p, n, s, f, color),
            K::Paving => road::paving(base, p, n, s, f, color),
            K::Kerb => road::kerb(base, p, n, s, f, color),
            K::Brick => masonry::brick(masonry::Bond::Stretcher, base, p, n, s, f, color),
            K::BrickFlemish => masonry::brick(masonry::Bond::Flemish, base, p, n, s, f, color),
            K::BrickEnglish => masonry::brick(masonry::Bond::English, base, p, n, s, f, color),
            K::Stone => masonry::stone(base, p, n, s, f, color),
            K::Plaster => surfaces::plaster(base, p, s, f, color),
            K::Concrete => surfaces::concrete(base, p, s, f, color),
            K::Glass => surfaces::glass(base, p, s, f),
            K::MetalPainted => surfaces::metal_painted(base, p, s, f, color),
            K::MetalBrushed => surfaces::metal_brushed(base, p, n, s, f, color),
            K::Wood => nature::wood(base, p, n, s, f, color),
            K::Bark => nature::bark(base, p, s, f, color),
            K::Leaves => nature::leaves(base, p, s, f, color),
            K::Foliage => nature::foliage(base, p, s, f, color),
            K::Grass => nature::grass(base, p, s, f, color),
            K::Soil => nature::soil(base, p, s, f, color),
        }
    }

    /// The texture-space footprint of a world footprint of `footprint_m`.
    fn footprint(&self, footprint_m: f32) -> Footprint {
        Footprint::new(footprint_m / self.scale as f32)
    }

    /// Albedo and roughness factor at `p_world` (metres) for a material of
    /// nominal albedo `base`; `n` is the unit geometric normal (either
    /// orientation; patterns laid in a plane use it to find the plane).
    pub fn sample(&self, base: Vec3, p_world: DVec3, n: Vec3) -> TexSample {
        self.sample_filtered(base, p_world, n, 0.0)
    }

    /// [`Texture::sample`] filtered by a footprint `footprint_m` metres
    /// wide (world): detail smaller than it fades to its mean
    /// ([`Footprint`]); 0 gives [`Texture::sample`]'s bits.
    pub fn sample_filtered(
        &self,
        base: Vec3,
        p_world: DVec3,
        n: Vec3,
        footprint_m: f32,
    ) -> TexSample {
        let f = self.footprint(footprint_m);
        let pat = self.pat(base, p_world / self.scale, n, f, true);
        TexSample {
            albedo: pat.c.clamp(Vec3::ZERO, Vec3::splat(0.99)),
            roughness: pat.r.max(0.0),
        }
    }

    /// The albedo alone ([`Texture::sample`]).
    pub fn albedo(&self, base: Vec3, p_world: DVec3, n: Vec3) -> Vec3 {
        self.sample(base, p_world, n).albedo
    }

    /// The relief height at `p_world` along `n`, metres (world).
    pub fn height(&self, p_world: DVec3, n: Vec3) -> f32 {
        self.height_filtered(p_world, n, 0.0)
    }

    /// [`Texture::height`] filtered by a footprint `footprint_m` metres wide.
    pub fn height_filtered(&self, p_world: DVec3, n: Vec3, footprint_m: f32) -> f32 {
        let f = self.footprint(footprint_m).relief();
        self.pat(Vec3::ONE, p_world / self.scale, n, f, false).h * self.scale as f32
    }

    /// Whether the texture has relief.
    pub fn has_relief(&self) -> bool {
        self.bump > 0.0 && self.kind != TextureKind::Glass
    }

    /// Albedo, roughness factor and the relief's shading normal
    /// ([`Texture::bump_normal`]) at once, filtered by a footprint
    /// `footprint_m` metres wide ([`Texture::sample_filtered`]; relief
    /// finer than the footprint flattens the same way): the pattern's
    /// colour pass gives the relief's height at `p_world` (`Pat::h`), so
    /// the gradient needs two more height passes.
    pub fn shade(
        &self,
        base: Vec3,
        p_world: DVec3,
        n_geo: Vec3,
        n_shading: Vec3,
        footprint_m: f32,
    ) -> (TexSample, Vec3) {
        let p = p_world / self.scale;
        let f = self.footprint(footprint_m);
        let pat = self.pat(base, p, n_geo, f, true);
        let sample = TexSample {
            albedo: pat.c.clamp(Vec3::ZERO, Vec3::splat(0.99)),
            roughness: pat.r.max(0.0),
        };
        let normal = if self.has_relief() {
            self.tilt(p, n_geo, n_shading, f.relief(), pat.h)
        } else {
            n_shading
        };
        (sample, normal)
    }

    /// The shading normal the relief gives at `p_world`: `n_shading` (unit,
    /// on the side of `n_geo`) tilted by `bump` × the height's tangential
    /// gradient (forward differences along the tangents of `n_geo`'s
    /// frame; the gradient does not depend on which tangents), slope
    /// clamped to `MAX_SLOPE`. `n_shading` itself when there is no relief.
    pub fn bump_normal(&self, p_world: DVec3, n_geo: Vec3, n_shading: Vec3) -> Vec3 {
        if !self.has_relief() {
            return n_shading;
        }
        let p = p_world / self.scale;
        let h0 = self.pat(Vec3::ONE, p, n_geo, Footprint::SHARP, false).h;
        self.tilt(p, n_geo, n_shading, Footprint::SHARP, h0)
    }

    /// [`Texture::bump_normal`] at texture-space `p` of height `h0`, the
    /// height filtered by `f`.
    fn tilt(&self, p: DVec3, n_geo: Vec3, n_shading: Vec3, f: Footprint, h0: f32) -> Vec3 {
        let frame = Frame::from_z(n_geo);
        let dh = |t: Vec3| {
            let q = p + t.as_dvec3() * BUMP_STEP_M;
            (self.pat(Vec3::ONE, q, n_geo, f, false).h - h0) / BUMP_STEP_M as f32
        };
        let mut g = (frame.x * dh(frame.x) + frame.y * dh(frame.y)) * self.bump;
        let slope = g.length();
        if slope > MAX_SLOPE {
            g *= MAX_SLOPE / slope;
        }
        // The gradient is tangent to the geometric surface; a height rising
        // along g tilts the normal away from g.
        (n_shading - g).normalize()
    }
}

/// Hermite smoothstep of `x` from `e0` to `e1` (0 below, 1 above).
#[inline]
pub(crate) fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests;
