//! The multiplicative patterns: each returns a per-channel factor of mean 1
//! at a point (world metres, already divided by the texture's scale).
//!
//! Each factor is a product of independent terms `1 + a·noise` with noise of
//! mean 0, or a two-valued draw whose values are weighted to mean 1, so the
//! product has mean 1. Feature sizes are in the comments of each term.

use glam::{DVec3, Vec3};

use super::noise::{cell_hash, cell_noise, fbm, rehash_signed, unit, value_noise};

/// Asphalt: light aggregate in dark binder, grit, and wear patches.
pub fn asphalt(p: DVec3, seed: u32) -> Vec3 {
    // Aggregate: 4 mm cells; a fraction Q are light stones of brightness
    // LIGHT, the rest binder, darkened so that Q·LIGHT + (1−Q)·dark = 1.
    const Q: f32 = 0.2;
    const LIGHT: f32 = 2.1;
    const DARK: f32 = (1.0 - Q * LIGHT) / (1.0 - Q);
    let stone = if unit(cell_hash(p, 0.004, seed)) < Q {
        LIGHT
    } else {
        DARK
    };
    let grit = 1.0 + 0.15 * value_noise(p, 0.0025, seed ^ 0x11);
    let surface = 1.0 + 0.12 * fbm(p, 0.06, 3, 0.6, seed ^ 0x22);
    // Wear and patching: 1.6 m down to 40 cm.
    let wear = 1.0 + 0.22 * fbm(p, 1.6, 3, 0.55, seed ^ 0x33);
    Vec3::splat(stone * grit * surface * wear)
}

/// Concrete: mottling (60 cm … 8 cm), aggregate texture (2 cm … 5 mm), sand.
pub fn concrete(p: DVec3, seed: u32) -> Vec3 {
    let mottle = 1.0 + 0.14 * fbm(p, 0.6, 4, 0.55, seed ^ 0x44);
    let aggregate = 1.0 + 0.1 * fbm(p, 0.02, 3, 0.7, seed ^ 0x55);
    let sand = 1.0 + 0.1 * cell_noise(p, 0.003, seed ^ 0x66);
    Vec3::splat(mottle * aggregate * sand)
}

/// Plaster: low-amplitude trowel mottling (40 cm … 10 cm) and grain (1 cm … 2 mm).
pub fn plaster(p: DVec3, seed: u32) -> Vec3 {
    let trowel = 1.0 + 0.07 * fbm(p, 0.4, 3, 0.5, seed ^ 0x77);
    let grain = 1.0 + 0.06 * fbm(p, 0.01, 3, 0.7, seed ^ 0x88);
    let sand = 1.0 + 0.04 * cell_noise(p, 0.002, seed ^ 0x99);
    Vec3::splat(trowel * grain * sand)
}

/// Foliage: per-leaf (5 cm cells) brightness and yellow–blue hue, clumps
/// (30 cm … 8 cm) and veins (8 mm … 2 mm).
pub fn foliage(p: DVec3, seed: u32) -> Vec3 {
    let h = cell_hash(p, 0.05, seed ^ 0xAA);
    let shade = 1.0 + 0.4 * super::noise::signed_unit(h);
    let hue = 0.15 * rehash_signed(h);
    let clump = 1.0 + 0.25 * fbm(p, 0.3, 3, 0.5, seed ^ 0xBB);
    let veins = 1.0 + 0.2 * fbm(p, 0.008, 3, 0.7, seed ^ 0xCC);
    Vec3::new(1.0 + hue, 1.0, 1.0 - hue) * (shade * clump * veins)
}
