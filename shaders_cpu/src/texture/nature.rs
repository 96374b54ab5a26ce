//! Organic surfaces: wood planks, bark, leaves, foliage, grass and soil.
//! Albedo factors of mean 1 (leaves: veins make it ~3 % darker).

use glam::{DVec3, Vec3};

use super::noise::{cell_hash, hash_cell, rehash, rehash_signed, signed_unit, unit, value_noise};
use super::{plane, smoothstep, Footprint, Pat};

/// Wood: planks 14 cm wide (along the plane's v) and 1–3 m long, 3 mm
/// grooves between them; grain lines along u (rings every ~4 mm, wavy),
/// a knot in one plank-metre in six; per-plank tone ±12 %.
pub fn wood(base: Vec3, p: DVec3, n: Vec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    const W: f64 = 0.14;
    let (u, v, face) = plane::coords(p, n);
    let (row, in_v) = plane::cell(v, W, 0.0);
    let hr = hash_cell([row, face, 0xF0], seed);
    let len = 1.0 + 2.0 * unit(hr) as f64;
    let (col, in_u) = plane::cell(u, len, len * unit(rehash(hr, 8)) as f64);
    let d = plane::edge_dist(in_v, W).min(plane::edge_dist(in_u, len));
    let hp = hash_cell([col, row, face], seed ^ 0xF1);
    // Grain: rings of a log sawn along u, distorted by a slow noise.
    let q = DVec3::new(u / 40.0, v, face as f64);
    let warp = 0.01 * value_noise(q, 0.05, seed ^ 0xF2) as f64;
    let ring = ((in_v + warp + 0.3 * unit(hp) as f64) / 0.004).fract() as f32;
    let late = smoothstep(0.6, 0.9, ring) * (1.0 - smoothstep(0.9, 1.0, ring));
    let h = fp.keep(0.003) * plane::joint(d, 0.0015, 0.001, 0.002) - 0.0001 * fp.keep(0.004) * late;
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    let tone = 1.0 + 0.12 * fp.keep(W) * signed_unit(hp);
    // Late wood (a ~25 % band) darker, early wood lighter: mean 1.
    let grain = 1.0 + 0.25 * fp.keep(0.004) * (0.25 - late);
    // A knot: one in six planks, a dark ellipse ~3 cm.
    let kx = len * unit(rehash(hp, 4)) as f64;
    let ky = W * (0.2 + 0.6 * unit(rehash(hp, 12)) as f64);
    let kr = (((in_u - kx) / 0.03).powi(2) + ((in_v - ky) / 0.015).powi(2)).sqrt() as f32;
    let knot = if unit(rehash(hp, 20)) < 1.0 / 6.0 {
        1.0 - 0.5 * fp.keep(0.03) * (1.0 - smoothstep(0.6, 1.0, kr))
    } else {
        1.0
    };
    // Pores and fibres, 1.5 mm.
    let pores = 1.0 + 0.15 * fp.cell_noise(p, 0.0015, seed ^ 0xF3);
    // Grooves 4 mm wide: their box-filtered cover under a wider footprint.
    let groove = 1.0
        - (1.0 - fp.band_cover(plane::edge_dist(in_v, W), 0.002, W as f32))
            * (1.0 - fp.band_cover(plane::edge_dist(in_u, len), 0.002, len as f32));
    let groove = fp.fade(0.004, 1.0 - smoothstep(0.0015, 0.0025, d), groove);
    let c = base * (tone * grain * knot * pores * (1.0 - 0.4 * groove));
    Pat { c, r: 1.0, h }
}

/// Bark: vertical furrows (a ridged noise stretched 5× along z, 3 cm
/// across), 8 mm deep and darker, lichen-grey patches on the ridges.
pub fn bark(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let q = DVec3::new(p.x, p.y, p.z / 5.0);
    // Ridges 3 cm across: towards their mean (~0.68) under a wide footprint.
    let k_ridge = fp.keep(0.03);
    let ridge = if k_ridge > 0.0 {
        fp.fade(0.03, 1.0 - value_noise(q, 0.03, seed ^ 0xE1).abs(), 0.68)
    } else {
        0.68
    };
    let (fine_h, fine) = fp.relief_and_colour(0.005, |f| f.fbm(p, 0.01, 2, 0.6, seed ^ 0xE2));
    let h = 0.008 * (ridge - 0.5) + 0.001 * fine_h;
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    // Furrow floors darker, ridges lighter (1 − |noise| has mean ~0.68).
    let depth = 1.0 + 0.7 * (ridge - 0.68);
    let flakes = 1.0 + 0.15 * fp.cell_noise(p, 0.003, seed ^ 0xE4);
    let lichen = smoothstep(0.35, 0.6, fp.fbm(p, 0.15, 3, 0.5, seed ^ 0xE3)) * ridge;
    let c = (base * depth * flakes * (1.0 + 0.1 * fine)).lerp(
        Vec3::new(0.3, 0.32, 0.26) * base.max_element() / 0.25,
        0.25 * lichen,
    );
    Pat { c, r: 1.0, h }
}

/// Leaves: per-leaf (6 cm cells) brightness ±30 % and yellow–blue hue,
/// a darker vein network (zero lines of a 1.5 cm noise), 0.3 mm vein relief.
pub fn leaves(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    // Veins (~1 mm lines, a few % of the leaf) fade to their share.
    const VEIN_SHARE: f32 = 0.05;
    let k_vein = fp.keep(0.003);
    let vein = if k_vein > 0.0 {
        let vein_n = value_noise(p, 0.015, seed ^ 0xC1).abs();
        fp.fade(0.003, 1.0 - smoothstep(0.02, 0.06, vein_n), VEIN_SHARE)
    } else {
        VEIN_SHARE
    };
    let h = 0.0003 * k_vein * vein + 0.0001 * fp.relief().value_noise(p, 0.003, seed ^ 0xC2);
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    let hl = cell_hash(p, 0.06, seed ^ 0xC3);
    let k_leaf = fp.keep(0.06);
    let shade = 1.0 + fp.cells(|| 0.3 * signed_unit(hl), 0.173, p, 0.06, seed ^ 0xC4);
    let hue = 0.15 * k_leaf * rehash_signed(hl);
    let c = base * Vec3::new(1.0 + hue, 1.0, 1.0 - hue) * (shade * (1.0 - 0.35 * vein));
    Pat { c, r: 1.0, h }
}

/// Foliage from afar: per-leaf (5 cm cells) brightness and yellow–blue
/// hue, clumps (30 cm … 8 cm) and veins (8 mm … 2 mm); 2 mm leaf relief.
pub fn foliage(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let fr = fp.relief();
    let h = 0.002 * fr.value_noise(p, 0.05, seed ^ 0xAD)
        + 0.0003 * fr.value_noise(p, 0.008, seed ^ 0xAE);
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    let hl = cell_hash(p, 0.05, seed ^ 0xAA);
    let k_leaf = fp.keep(0.05);
    let shade = 1.0 + fp.cells(|| 0.4 * signed_unit(hl), 0.231, p, 0.05, seed ^ 0xAC);
    let hue = 0.15 * k_leaf * rehash_signed(hl);
    let clump = 1.0 + 0.25 * fp.fbm(p, 0.3, 3, 0.5, seed ^ 0xBB);
    let veins = 1.0 + 0.2 * fp.fbm(p, 0.008, 3, 0.7, seed ^ 0xCC);
    let c = base * Vec3::new(1.0 + hue, 1.0, 1.0 - hue) * (shade * clump * veins);
    Pat { c, r: 1.0, h }
}

/// Grass: blades (5 mm cells of ±35 % brightness, hue), tufts (4 cm
/// relief of 4 mm), clumps (25 cm) and dry yellow patches (1.5 m, ~15 %).
pub fn grass(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let fr = fp.relief();
    let h = 0.004 * fr.fbm(p, 0.04, 2, 0.5, seed ^ 0x61)
        + 0.001 * fr.value_noise(p, 0.005, seed ^ 0x62);
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    let hb = cell_hash(p, 0.005, seed ^ 0x63);
    let k_blade = fp.keep(0.005);
    let blade = 1.0 + fp.cells(|| 0.35 * signed_unit(hb), 0.202, p, 0.005, seed ^ 0x66);
    let hue = 0.12 * k_blade * rehash_signed(hb);
    let clump = 1.0 + 0.2 * fp.fbm(p, 0.25, 3, 0.5, seed ^ 0x64);
    let dry = smoothstep(0.3, 0.5, fp.fbm(p, 1.5, 3, 0.5, seed ^ 0x65));
    // Dry grass yellower, lush grass a little greener: the tint's mean
    // over the area (dry has mean DRY_MEAN) stays 1 per channel.
    const DRY_MEAN: f32 = 0.08;
    let tint = Vec3::ONE + (Vec3::new(1.5, 1.15, 0.7) - Vec3::ONE) * (dry - DRY_MEAN);
    let c = base * Vec3::new(1.0 + hue, 1.0, 1.0 - hue) * tint * (blade * clump);
    Pat { c, r: 1.0, h }
}

/// Soil: clods (3 cm, 5 mm relief), pebbles (1.5 cm cells, one in ten, raised
/// 3 mm and lighter), damp darker patches (1 m).
pub fn soil(base: Vec3, p: DVec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let hp = cell_hash(p, 0.015, seed ^ 0x51);
    let pebble = unit(hp) < 0.1;
    let k_pebble = fp.keep(0.015);
    let bump = if pebble && k_pebble > 0.0 {
        0.003 * k_pebble * smoothstep(0.0, 0.5, value_noise(p, 0.006, seed ^ 0x52) + 0.4)
    } else {
        0.0
    };
    let h = 0.005 * fp.relief().fbm(p, 0.03, 3, 0.5, seed ^ 0x53) + bump;
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    let stones = if pebble {
        1.6 + 0.3 * signed_unit(rehash(hp, 4))
    } else {
        (1.0 - 0.1 * 1.6) / 0.9
    };
    let stones = fp.fade(0.015, stones, 1.0);
    let damp = 1.0 + 0.2 * fp.fbm(p, 1.0, 3, 0.5, seed ^ 0x54);
    let grain = 1.0 + 0.15 * fp.cell_noise(p, 0.003, seed ^ 0x55);
    let c = base * (stones * damp * grain);
    Pat { c, r: 1.0, h }
}
