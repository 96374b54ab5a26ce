//! Man-made surfaces without joints: plaster, concrete, glass, painted and
//! brushed metal. Albedo factors of mean 1; roughness factors of mean ~1
//! (they scale a GGX material's roughness; Lambertian ones have none).

use glam::{DVec3, Vec3};

use super::noise::{cell_hash, fbm, unit, value_noise};
use super::{plane, smoothstep, Footprint, Pat};

/// Plaster: trowel mottling (40 cm … 10 cm), grain (1 cm … 2 mm), relief
/// of trowel ridges (0.5 mm at 5 cm) and sand (0.15 mm).
pub fn plaster(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let fr = fp.relief();
    let h = 0.0005 * fr.value_noise(p, 0.05, seed ^ 0x71)
        + 0.00015 * fr.value_noise(p, 0.002, seed ^ 0x72);
    let c = if color {
        let trowel = 1.0 + 0.07 * fp.fbm(p, 0.4, 3, 0.5, seed ^ 0x77);
        let grain = 1.0 + 0.06 * fp.fbm(p, 0.01, 3, 0.7, seed ^ 0x88);
        let sand = 1.0 + 0.04 * fp.cell_noise(p, 0.002, seed ^ 0x99);
        base * (trowel * grain * sand)
    } else {
        base
    };
    Pat { c, r: 1.0, h }
}

/// Concrete: mottling (60 cm … 8 cm), aggregate (2 cm … 5 mm), sand,
/// and pores (1.5 cm cells, one in twelve a 1 mm pit, darker).
pub fn concrete(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let pore = unit(cell_hash(p, 0.015, seed ^ 0x4F)) < 1.0 / 12.0;
    let k_pit = fp.keep(0.004);
    let pit = if pore && k_pit > 0.0 {
        let n = value_noise(p, 0.004, seed ^ 0x4E).abs();
        -0.001 * k_pit * (1.0 - smoothstep(0.2, 0.6, n))
    } else {
        0.0
    };
    let h = pit + 0.0004 * fp.relief().fbm(p, 0.02, 2, 0.6, seed ^ 0x4D);
    let c = if color {
        let mottle = 1.0 + 0.14 * fp.fbm(p, 0.6, 4, 0.55, seed ^ 0x44);
        let aggregate = 1.0 + 0.1 * fp.fbm(p, 0.02, 3, 0.7, seed ^ 0x55);
        let sand = 1.0 + 0.1 * fp.cell_noise(p, 0.003, seed ^ 0x66);
        let pores = fp.fade(0.015, if pore { 0.85 } else { 1.0 + 0.15 / 11.0 }, 1.0);
        base * (mottle * aggregate * sand * pores)
    } else {
        base
    };
    Pat { c, r: 1.0, h }
}

/// Glass: the tint varies ±3 % over 50 cm, smudges (20 cm) raise the
/// roughness factor to up to 2.5 where they lie. No relief.
pub fn glass(base: Vec3, p: DVec3, seed: u32, fp: Footprint) -> Pat {
    let tint = 1.0 + 0.03 * fp.fbm(p, 0.5, 2, 0.5, seed ^ 0x61);
    let smudge = smoothstep(0.25, 0.6, fp.fbm(p, 0.2, 3, 0.5, seed ^ 0x62));
    Pat {
        c: base * tint,
        r: 1.0 + 1.5 * smudge,
        h: 0.0,
    }
}

/// Painted metal: paint (orange peel, 0.05 mm at 3 mm) chipped to rust
/// where a 30 cm … 2 cm field peaks (~4 % of the area), the chips 0.1 mm
/// down; rust is rougher. The paint is brightened to keep the mean.
pub fn metal_painted(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    // Chips 2–30 cm: under a wider footprint, their area share.
    const CHIP_SHARE: f32 = 0.04;
    let k_chip = fp.keep(0.05);
    let chip = if k_chip > 0.0 {
        let sharp = smoothstep(0.42, 0.48, fbm(p, 0.3, 4, 0.6, seed ^ 0x91));
        fp.fade(0.05, sharp, CHIP_SHARE)
    } else {
        CHIP_SHARE
    };
    let h = 0.00005 * fp.relief().value_noise(p, 0.003, seed ^ 0x92) - 0.0001 * chip;
    let c = if color {
        let rust = Vec3::new(0.22, 0.1, 0.05) * (1.0 + 0.2 * fp.cell_noise(p, 0.002, seed ^ 0x93));
        let paint = base * (1.0 + 0.04 * fp.fbm(p, 0.5, 2, 0.5, seed ^ 0x94));
        paint.lerp(rust, chip)
    } else {
        base
    };
    Pat {
        c,
        r: 1.0 + chip,
        h,
    }
}

/// Brushed metal: streaks along the horizontal in the plane (50 cm long,
/// 0.2 mm wide) vary the roughness factor 0.6 … 1.4 and give 2 µm of
/// relief; the albedo varies ±3 %.
pub fn metal_brushed(base: Vec3, p: DVec3, n: Vec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let (u, v, face) = plane::coords(p, n);
    let q = DVec3::new(u / 2500.0, v, face as f64);
    let (streak_h, streak) =
        fp.relief_and_colour(0.0002, |f| f.value_noise(q, 0.0002, seed ^ 0xB1));
    let c = if color {
        base * (1.0 + 0.03 * fp.fbm(p, 0.3, 2, 0.5, seed ^ 0xB2))
    } else {
        base
    };
    Pat {
        c,
        r: 1.0 + 0.4 * streak,
        h: 0.000002 * streak_h,
    }
}
