//! Sparse road decals in the asphalt texture, at seeded positions of world
//! (x, y): manhole covers (one in three 16 m cells), drain gratings (one in
//! three 22 m cells) and oil stains (one in three 6 m cells). Each lies
//! wholly inside its cell, so a point looks up one cell per decal kind.
//! Shading only: the geometry (and the ground truth) stays the flat road.
//! Heights are relative to the road surface; iron and slots override the
//! asphalt's albedo, stains darken it. Grooves, slots and ragged edges
//! finer than the footprint fade to the share of it they cover.

use glam::{DVec3, Vec3};

use super::noise::{hash_cell, rehash, unit};
use super::{plane, smoothstep, Footprint, Pat};

/// A decal at a point.
pub enum Decal {
    /// Iron (cover, grating): replaces the asphalt.
    Cover(Pat),
    /// An oil stain: a factor on the asphalt's albedo (its relief kept).
    Stain(f32),
}

/// The decal at `p` (texture-space metres, up-facing asphalt), if any.
pub fn road(p: DVec3, seed: u32, fp: Footprint) -> Option<Decal> {
    manhole(p, seed, fp)
        .or_else(|| grating(p, seed, fp))
        .map(Decal::Cover)
        .or_else(|| oil(p, seed, fp).map(Decal::Stain))
}

/// The cell of side `size` holding (x, y), its hash, and the offset in it.
fn cell(p: DVec3, size: f64, tag: i64, seed: u32) -> (u32, f64, f64) {
    let (cx, ox) = plane::cell(p.x, size, 0.0);
    let (cy, oy) = plane::cell(p.y, size, 0.0);
    (hash_cell([cx, cy, tag], seed), ox, oy)
}

/// A cast-iron manhole cover, 60 cm across in a 68 cm frame: a raised
/// 4 cm checker of 2 mm grooves, a 6 mm gap ring between cover and frame.
fn manhole(p: DVec3, seed: u32, fp: Footprint) -> Option<Pat> {
    const R: f64 = 0.3;
    let (h, ox, oy) = cell(p, 16.0, 0x3A4E, seed);
    if unit(h) >= 1.0 / 3.0 {
        return None;
    }
    let (x0, y0) = (
        1.0 + 14.0 * unit(rehash(h, 4)) as f64,
        1.0 + 14.0 * unit(rehash(h, 12)) as f64,
    );
    let (dx, dy) = (ox - x0, oy - y0);
    let r = (dx * dx + dy * dy).sqrt();
    if r > R + 0.04 {
        return None;
    }
    let iron = Vec3::new(0.075, 0.07, 0.065) * (1.0 + 0.15 * fp.value_noise(p, 0.05, seed ^ 0x3B));
    let ring = (r - R).abs() as f32;
    let gap = fp.keep(0.01) * plane::joint(ring, 0.003, 0.002, 0.008);
    let k_groove = fp.keep(0.006);
    let height = if r < R - 0.006 && k_groove > 0.0 {
        let gx = plane::edge_dist(plane::cell(dx, 0.04, 0.0).1, 0.04);
        let gy = plane::edge_dist(plane::cell(dy, 0.04, 0.0).1, 0.04);
        k_groove * plane::joint(gx.min(gy), 0.003, 0.002, 0.002)
    } else {
        0.0
    };
    // The 6 mm gap ring: its box-filtered cover across the ring.
    let dark = fp.fade(
        0.006,
        1.0 - smoothstep(0.003, 0.006, ring),
        fp.band_cover(ring, 0.0045, 1.0),
    );
    let c = iron * (1.0 - 0.65 * dark);
    Some(Pat {
        c,
        r: 0.8,
        h: height + gap,
    })
}

/// A drain grating 50 × 35 cm in a 3 cm frame, its 2.5 cm slots (3 cm
/// deep, nearly black) across the long side; long side along x or y.
fn grating(p: DVec3, seed: u32, fp: Footprint) -> Option<Pat> {
    const HALF: (f64, f64) = (0.25, 0.175);
    let (h, ox, oy) = cell(p, 22.0, 0x6A7E, seed);
    if unit(h) >= 1.0 / 3.0 {
        return None;
    }
    let (x0, y0) = (
        1.0 + 20.0 * unit(rehash(h, 4)) as f64,
        1.0 + 20.0 * unit(rehash(h, 12)) as f64,
    );
    let (mut a, mut b) = (ox - x0, oy - y0);
    if h & 1 == 1 {
        (a, b) = (b, a);
    }
    if a.abs() > HALF.0 || b.abs() > HALF.1 {
        return None;
    }
    let iron = Vec3::new(0.07, 0.065, 0.06);
    let inner = a.abs() < HALF.0 - 0.03 && b.abs() < HALF.1 - 0.03;
    // Bars 1.5 cm, slots 2.5 cm along a.
    let slot = inner && plane::cell(a, 0.04, 0.0).1 > 0.015;
    let edge = plane::edge_dist(plane::cell(a, 0.04, 0.0).1 - 0.015, 0.025);
    let k = fp.keep(0.015);
    if inner && k < 1.0 {
        // Bars and slots finer than the footprint: their mix, flat.
        let in_slot = f32::from(u8::from(slot));
        let centre = (plane::cell(a, 0.04, 0.0).1 - 0.0275).abs();
        let share = fp.fade(0.015, in_slot, fp.band_cover(centre as f32, 0.0125, 0.04));
        return Some(Pat {
            c: iron.lerp(Vec3::splat(0.012), share),
            r: 1.0 - 0.2 * (1.0 - share),
            h: -0.03 * k * in_slot * smoothstep(0.0, 0.003, edge),
        });
    }
    if slot {
        // Full depth inside the slot, 0 at its edges.
        let depth = -0.03 * smoothstep(0.0, 0.003, edge);
        return Some(Pat {
            c: Vec3::splat(0.012),
            r: 1.0,
            h: depth,
        });
    }
    Some(Pat {
        c: iron,
        r: 0.8,
        h: 0.0,
    })
}

/// An oil stain 25–90 cm across with a ragged edge: the asphalt darkened
/// to 55 %, its rim a little lighter.
fn oil(p: DVec3, seed: u32, fp: Footprint) -> Option<f32> {
    let (h, ox, oy) = cell(p, 6.0, 0x0111, seed);
    if unit(h) >= 1.0 / 3.0 {
        return None;
    }
    let radius = 0.25 + 0.65 * unit(rehash(h, 3)) as f64;
    let (x0, y0) = (
        1.2 + 3.6 * unit(rehash(h, 9)) as f64,
        1.2 + 3.6 * unit(rehash(h, 15)) as f64,
    );
    let r = ((ox - x0).powi(2) + (oy - y0).powi(2)).sqrt() / radius;
    if r > 1.4 {
        return None;
    }
    let d = r as f32 + 0.3 * fp.value_noise(p, 0.12 * radius, seed ^ 0x0112);
    (d < 1.0).then(|| 0.55 + 0.25 * smoothstep(0.6, 1.0, d))
}
