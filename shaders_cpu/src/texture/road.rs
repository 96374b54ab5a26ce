//! Road surfaces: asphalt (aggregate, grit, wear, cracks, patches, tar
//! seams, tyre streaks, and the sparse decals of `decals`), worn road paint,
//! paving slabs and kerb stones. Heights in metres; albedo factors of mean 1
//! unless noted (road paint wears down to the asphalt). Every term fades to
//! its mean under a footprint wider than it (`Footprint`).

use glam::{DVec3, Vec3};

use super::noise::{cell_hash, hash_cell, rehash, rehash_signed, signed_unit, unit};
use super::{decals, plane, smoothstep, Footprint, Pat};

/// Albedo of the asphalt under worn paint.
const ASPHALT_UNDER_PAINT: f32 = 0.09;

/// The aggregate relief shared by asphalt and the paint on it: 4 mm stones
/// proud of the binder by up to ~0.6 mm (one noise: this runs three times
/// per seen road point).
fn aggregate_height(p: DVec3, seed: u32, f: Footprint) -> f32 {
    let k = f.keep(0.004);
    if k > 0.0 {
        0.0006 * k * super::noise::value_noise(p, 0.004, seed ^ 0x1A).max(-0.3)
    } else {
        0.0
    }
}

/// Asphalt. Decals (manholes, gratings, oil stains) and cracks, patches and
/// seams only on up-facing surfaces; walls of a road (its edge) keep the
/// aggregate.
pub fn asphalt(base: Vec3, p: DVec3, n: Vec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let mut h = aggregate_height(p, seed, fp);
    let up = n.z.abs() >= 0.7;
    let mut f = 1.0;
    if up {
        match decals::road(p, seed, fp) {
            Some(decals::Decal::Cover(pat)) => return pat,
            Some(decals::Decal::Stain(k)) => f = k,
            None => {}
        }
    }
    if color {
        // Aggregate: 4 mm cells; a fraction Q are light stones of brightness
        // LIGHT, the rest binder, darkened so that Q·LIGHT + (1−Q)·dark = 1.
        const Q: f32 = 0.2;
        const LIGHT: f32 = 2.1;
        const DARK: f32 = (1.0 - Q * LIGHT) / (1.0 - Q);
        // Two-valued, std √(Q(1−Q))·(LIGHT − DARK).
        const STD: f32 = 0.4 * (LIGHT - DARK);
        let stone = 1.0
            + fp.cells(
                || {
                    if unit(cell_hash(p, 0.004, seed)) < Q {
                        LIGHT - 1.0
                    } else {
                        DARK - 1.0
                    }
                },
                STD,
                p,
                0.004,
                seed ^ 0x10,
            );
        // Grit, 2 mm (a hash, not a noise: the colour pass runs per seen point).
        let grit = 1.0 + 0.15 * fp.cell_noise(p, 0.002, seed ^ 0x11);
        let surface = 1.0 + 0.12 * fp.fbm(p, 0.06, 2, 0.6, seed ^ 0x22);
        // Wear: 1.6 m and 80 cm.
        let wear = 1.0 + 0.2 * fp.fbm(p, 1.6, 2, 0.55, seed ^ 0x33);
        // Tyre streaks: 5 m long, 25 cm wide, along x and along y (town
        // grids), polished lighter or rubbed darker (mean 1).
        let sx = fp.value_noise(DVec3::new(p.x / 20.0, p.y, 0.0), 0.25, seed ^ 0x44);
        let sy = fp.value_noise(DVec3::new(p.x, p.y / 20.0, 0.0), 0.25, seed ^ 0x45);
        let tyre = 1.0 + 0.08 * (sx + sy);
        f *= stone * grit * surface * wear * tyre;
    }
    if up {
        // Patches: one in five 7 m cells holds a rectangle of newer (lighter)
        // or fresher (darker) asphalt, raised 2 mm, with a dark sealed edge.
        let (cx, ox) = plane::cell(p.x, 7.0, 0.0);
        let (cy, oy) = plane::cell(p.y, 7.0, 0.0);
        let hp = hash_cell([cx, cy, 0x7A7C], seed);
        if unit(hp) < 0.2 {
            let r2 = hash_cell([cx, cy, 0x7A7D], seed);
            let (w, l) = (
                1.0 + 3.0 * unit(r2) as f64,
                1.0 + 2.5 * unit(rehash(r2, 3)) as f64,
            );
            let (x0, y0) = (
                0.2 + (6.6 - w) * unit(rehash(hp, 5)) as f64,
                0.2 + (6.6 - l) * unit(rehash(hp, 11)) as f64,
            );
            let d = (ox - x0).min(x0 + w - ox).min(oy - y0).min(y0 + l - oy) as f32;
            if d > 0.0 {
                h += 0.002 * fp.keep(0.01) * smoothstep(0.0, 0.01, d);
                let lighter = signed_unit(hp) > -0.6;
                f *= if lighter { 1.25 } else { 0.75 };
                // The 2 cm sealed edge fades to its share of a footprint.
                let edge = 1.0 - smoothstep(0.01, 0.03, d);
                f *= 1.0 - 0.5 * fp.fade(0.02, edge, fp.band_cover(d, 0.02, 7.0));
            }
        }
        // Tar-sealed seams: 5 cm bands every 9.7 m along x and 13.3 m along
        // y, wandering ±3 cm; smooth (the aggregate filled) and dark.
        let seam = |wob: f64| {
            let sx = plane::edge_dist(plane::cell(p.x + wob, 9.7, 3.1).1, 9.7);
            let sy = plane::edge_dist(plane::cell(p.y + wob, 13.3, 5.3).1, 13.3);
            sx.min(sy) as f64
        };
        // The wobble's noise only near a seam (or a footprint's width).
        if seam(0.0) < 0.07 + fp.w as f64 {
            let tar_at = |wob: f64| {
                let sx = plane::edge_dist(plane::cell(p.x + wob, 9.7, 3.1).1, 9.7);
                let sy = plane::edge_dist(plane::cell(p.y + wob, 13.3, 5.3).1, 13.3);
                let band = |d: f32, period: f32| {
                    fp.band(1.0 - smoothstep(0.02, 0.03, d), d, 0.025, period)
                };
                1.0 - (1.0 - band(sx, 9.7)) * (1.0 - band(sy, 13.3))
            };
            // The relief's wobble has no residual grain (see `Pat::h`).
            let (wob_h, wob_c) =
                fp.relief_and_colour(0.7, |f| 0.03 * f.value_noise(p, 0.7, seed ^ 0x55) as f64);
            let tar = tar_at(wob_h);
            h = h * (1.0 - tar) + 0.0004 * tar;
            let tar = if wob_c == wob_h { tar } else { tar_at(wob_c) };
            f *= 1.0 - 0.55 * tar;
        }
        // Cracks: zero lines of a 90 cm noise, ~1 cm wide, 4 mm deep, in
        // the third of the road where an 8 m field says the surface is old.
        let old = super::noise::value_noise(p, 8.0, seed ^ 0x66);
        let k = fp.keep(0.01);
        if old > 0.2 && k > 0.0 {
            let c = super::noise::value_noise(p, 0.9, seed ^ 0x77).abs();
            let crack = (1.0 - smoothstep(0.004, 0.012, c)) * smoothstep(0.2, 0.3, old);
            // Cracks ~1 cm wide fade out (they cover a few % of old road).
            h -= 0.004 * k * crack;
            f *= 1.0 - 0.6 * k * crack;
        }
    }
    Pat {
        c: base * f,
        r: 1.0,
        h,
    }
}

/// Road paint over asphalt: worn through in patches (a ~9.4 % area, wear
/// of 25 cm to 2 cm features) down to the asphalt, thin (0.3 mm) on the
/// aggregate's relief. Mean albedo ~10 % below nominal.
pub fn road_paint(base: Vec3, p: DVec3, _n: Vec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    // Worn patches are where the wear field peaks: under a footprint wider
    // than a patch, their area share (fading the field itself would lose
    // the peaks, and the paint would look new from afar).
    const WORN_SHARE: f32 = 0.094;
    let worn_at = |fp: Footprint| {
        if fp.keep(0.05) > 0.0 {
            let wear =
                fp.fbm(p, 0.25, 3, 0.55, seed ^ 0x88) + 0.4 * fp.fbm(p, 0.02, 2, 0.6, seed ^ 0x89);
            fp.fade(0.05, smoothstep(0.3, 0.45, wear), WORN_SHARE)
        } else {
            WORN_SHARE
        }
    };
    // The finest octave is 1 cm; the relief's wear has no residual grain.
    let (worn_h, worn) = fp.relief_and_colour(0.01, worn_at);
    let h = aggregate_height(p, seed, fp) + 0.0003 * fp.keep(0.03) * (1.0 - worn_h);
    let c = if color {
        let grain = 1.0 + 0.08 * fp.cell_noise(p, 0.003, seed ^ 0x8A);
        let dirt = 1.0 + 0.06 * fp.fbm(p, 0.5, 2, 0.5, seed ^ 0x8B);
        (base * (grain * dirt)).lerp(Vec3::splat(ASPHALT_UNDER_PAINT), worn)
    } else {
        base
    };
    Pat { c, r: 1.0, h }
}

/// Paving slabs 600 × 600 mm in a grid (plane coordinates), 6 mm joints
/// recessed 4 mm and darker, each slab tinted ±8 % and tilted up to 3 mm/m.
pub fn paving(base: Vec3, p: DVec3, n: Vec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    const SLAB: f64 = 0.6;
    let (u, v, face) = plane::coords(p, n);
    let (cu, ou) = plane::cell(u, SLAB, 0.0);
    let (cv, ov) = plane::cell(v, SLAB, 0.0);
    let d = plane::edge_dist(ou, SLAB).min(plane::edge_dist(ov, SLAB));
    let hs = hash_cell([cu, cv, face], seed ^ 0x9A);
    let tilt =
        0.003 * (signed_unit(hs) * (ou - 0.3) as f32 + rehash_signed(hs) * (ov - 0.3) as f32);
    let h = fp.keep(SLAB) * tilt
        + fp.keep(0.008) * plane::joint(d, 0.003, 0.002, 0.004)
        + 0.0002 * fp.relief().value_noise(p, 0.003, seed ^ 0x9B);
    let c = if color {
        let slab = 1.0 + 0.08 * fp.keep(SLAB) * signed_unit(rehash(hs, 1));
        let grain = (1.0 + 0.1 * fp.fbm(p, 0.02, 2, 0.6, seed ^ 0x9C))
            * (1.0 + 0.08 * fp.cell_noise(p, 0.003, seed ^ 0x9D));
        let stain = 1.0 + 0.1 * fp.fbm(p, 1.2, 2, 0.5, seed ^ 0x9E);
        // Joints (a ~2 % area: 7 mm of each 600 mm, two ways) darker; slabs
        // brightened to keep the mean.
        let band = |o: f64| fp.band_cover(plane::edge_dist(o, SLAB), 0.0035, SLAB as f32);
        let joint = fp.fade(
            0.007,
            1.0 - smoothstep(0.003, 0.004, d),
            1.0 - (1.0 - band(ou)) * (1.0 - band(ov)),
        );
        base * (slab * grain * stain * (1.01 - 0.5 * joint))
    } else {
        base
    };
    Pat { c, r: 1.0, h }
}

/// Kerb stones 915 mm long (joints across the kerb on its faces; on its top
/// a 915 mm grid, of which a narrow kerb shows the cross joints), 5 mm
/// joints recessed 3 mm, per-stone tint ±6 %.
pub fn kerb(base: Vec3, p: DVec3, n: Vec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    const STONE: f64 = 0.915;
    let (u, v, face) = plane::coords(p, n);
    let (cu, ou) = plane::cell(u, STONE, 0.0);
    let (cv, ov) = plane::cell(v, STONE, 0.0);
    let d = if face == 0 {
        plane::edge_dist(ou, STONE)
    } else {
        plane::edge_dist(ou, STONE).min(plane::edge_dist(ov, STONE))
    };
    let cv = if face == 0 { 0 } else { cv };
    let hs = hash_cell([cu, cv, 0x4B], seed);
    let h = fp.keep(0.006) * plane::joint(d, 0.0025, 0.002, 0.003)
        + 0.0004 * fp.relief().fbm(p, 0.01, 2, 0.6, seed ^ 0xAB);
    let c = if color {
        let stone = 1.0 + 0.06 * fp.keep(STONE) * signed_unit(hs);
        let grain = (1.0 + 0.1 * fp.fbm(p, 0.03, 3, 0.6, seed ^ 0xAC))
            * (1.0 + 0.1 * fp.cell_noise(p, 0.003, seed ^ 0xAD));
        let band = |o: f64| fp.band_cover(plane::edge_dist(o, STONE), 0.003, STONE as f32);
        let cover = if face == 0 {
            band(ou)
        } else {
            1.0 - (1.0 - band(ou)) * (1.0 - band(ov))
        };
        let joint = fp.fade(0.006, 1.0 - smoothstep(0.0025, 0.0035, d), cover);
        base * (stone * grain * (1.0 - 0.5 * joint))
    } else {
        base
    };
    Pat { c, r: 1.0, h }
}
