//! Masonry in the wall plane (`plane::coords`): brick in stretcher,
//! Flemish and English bond, and ashlar stone. Mortar joints are recessed
//! (brick 3 mm, stone 4 mm) with a pale mortar of the base's luminance;
//! the unit colour is solved so that the area-weighted mean equals the
//! nominal albedo. Under a footprint wider than a joint, a point's colour
//! is the mix of mortar and brick its footprint holds (the joints' box-
//! filtered cover), and fine grain and relief fade to their means.

use glam::{DVec3, Vec3};

use super::noise::{hash_cell, rehash, rehash_signed, signed_unit, unit};
use super::{plane, smoothstep, Footprint, Pat};

/// Brick length plus one mortar joint, metres (a stretcher's module).
pub const MODULE_U_M: f64 = 0.225;
/// Brick height plus one mortar joint, metres (the course height).
pub const MODULE_V_M: f64 = 0.075;
/// Mortar joint width, metres.
pub const MORTAR_M: f64 = 0.010;
/// A header's module (half a stretcher's).
const HEADER_U_M: f64 = MODULE_U_M / 2.0;

/// How courses are laid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bond {
    /// Stretchers only, every other course offset by half a brick.
    Stretcher,
    /// Stretcher and header alternating in each course, headers centred on
    /// the stretchers below.
    Flemish,
    /// A course of stretchers, then one of headers (offset a quarter brick).
    English,
}

impl Bond {
    /// The area fraction of brick faces (the rest is mortar).
    fn brick_fraction(self) -> f32 {
        let v = (MODULE_V_M - MORTAR_M) / MODULE_V_M;
        let s = (MODULE_U_M - MORTAR_M) / MODULE_U_M;
        let hd = (HEADER_U_M - MORTAR_M) / HEADER_U_M;
        let u = match self {
            Bond::Stretcher => s,
            Bond::Flemish => (MODULE_U_M + HEADER_U_M - 2.0 * MORTAR_M) / (MODULE_U_M + HEADER_U_M),
            Bond::English => 0.5 * (s + hd),
        };
        (u * v) as f32
    }

    /// The brick holding in-course position `u` of course `row`: (column id,
    /// offset in it, its length with joint, whether a header).
    fn locate(self, u: f64, row: i64) -> (i64, f64, f64, bool) {
        let odd = row.rem_euclid(2) == 1;
        match self {
            Bond::Stretcher => {
                let shift = if odd { 0.5 * MODULE_U_M } else { 0.0 };
                let (c, o) = plane::cell(u, MODULE_U_M, shift);
                (c, o, MODULE_U_M, false)
            }
            Bond::English if odd => {
                let (c, o) = plane::cell(u, HEADER_U_M, 0.25 * MODULE_U_M);
                (c, o, HEADER_U_M, true)
            }
            Bond::English => {
                let (c, o) = plane::cell(u, MODULE_U_M, 0.0);
                (c, o, MODULE_U_M, false)
            }
            Bond::Flemish => {
                // A period is a stretcher then a header; odd courses start
                // with the header, a quarter header further on.
                let period = MODULE_U_M + HEADER_U_M;
                let shift = if odd { 0.5 * HEADER_U_M } else { 0.0 };
                let (c, o) = plane::cell(u, period, shift);
                let (first, first_header) = if odd {
                    (HEADER_U_M, true)
                } else {
                    (MODULE_U_M, false)
                };
                if o < first {
                    (2 * c, o, first, first_header)
                } else {
                    (2 * c + 1, o - first, period - first, !first_header)
                }
            }
        }
    }
}

/// Brick of `bond` with nominal albedo `base`.
pub fn brick(
    bond: Bond,
    base: Vec3,
    p: DVec3,
    n: Vec3,
    seed: u32,
    fp: Footprint,
    color: bool,
) -> Pat {
    let (u, v, face) = plane::coords(p, n);
    let (row, in_v) = plane::cell(v, MODULE_V_M, 0.0);
    let (col, in_u, len, header) = bond.locate(u, row);
    // The joint sits at the low edge of each module in u and v; distance
    // from the joint's centre line.
    let half = 0.5 * MORTAR_M;
    let du = ((in_u - half).abs()).min((in_u - len - half).abs()) as f32;
    let dv = ((in_v - half).abs()).min((in_v - MODULE_V_M - half).abs()) as f32;
    let d = du.min(dv);
    let hb = hash_cell([col, row, face], seed);
    let h = fp.keep(2.0 * MORTAR_M) * plane::joint(d, half as f32 - 0.001, 0.002, 0.003)
        + 0.0005
            * fp.keep(MODULE_V_M)
            * signed_unit(rehash(hb, 2))
            * smoothstep(half as f32, half as f32 + 0.002, d)
        + 0.0003 * fp.relief().value_noise(p, 0.004, seed ^ 0xD4);
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    let lum = base.dot(Vec3::new(0.2126, 0.7152, 0.0722));
    let mortar_rgb = Vec3::new(1.0, 0.97, 0.92) * (1.3 * lum).min(0.9);
    let f_brick = bond.brick_fraction();
    // The mortar's share of the footprint: the joints' cover across the
    // course (v) and along it (u, this course's module).
    let cover = if fp.keep(MORTAR_M) >= 1.0 {
        f32::from(u8::from(d < half as f32))
    } else {
        let w = fp.band_cover(dv, half as f32, MODULE_V_M as f32);
        let u = fp.band_cover(du, half as f32, len as f32);
        let cover = 1.0 - (1.0 - w) * (1.0 - u);
        fp.fade(MORTAR_M, f32::from(u8::from(d < half as f32)), cover)
    };
    let mortar = if cover > 0.0 {
        mortar_rgb * (1.0 + 0.15 * fp.cell_noise(p, 0.002, seed ^ 0xD1))
    } else {
        Vec3::ZERO
    };
    if cover >= 1.0 {
        return Pat {
            c: mortar,
            r: 1.0,
            h,
        };
    }
    // Brick colour so that f_brick·brick + (1 − f_brick)·mortar = base.
    let brick_rgb = ((base - (1.0 - f_brick) * mortar_rgb) / f_brick).max(Vec3::ZERO);
    let k_brick = fp.keep(MODULE_V_M);
    // Uniform ±0.22: std 0.22/√3.
    let shade = 1.0 + fp.cells(|| 0.22 * signed_unit(hb), 0.127, p, MODULE_V_M, seed ^ 0xD5);
    let hue = 0.08 * k_brick * rehash_signed(hb);
    // Flemish headers are often burnt darker; shift stretchers up to keep the mean.
    let burnt = match (bond, header) {
        (Bond::Flemish, true) => 0.8,
        (Bond::Flemish, false) => 1.1,
        _ => 1.0,
    };
    let burnt = fp.fade(MODULE_V_M, burnt, 1.0);
    let surface = 1.0 + 0.1 * fp.fbm(p, 0.03, 3, 0.6, seed ^ 0xD2);
    // Sand-faced grain, 3 mm.
    let grain = 1.0 + 0.12 * fp.cell_noise(p, 0.003, seed ^ 0xD3);
    let c = brick_rgb * Vec3::new(1.0 + hue, 1.0, 1.0 - hue) * (shade * surface * grain * burnt);
    Pat {
        c: c.lerp(mortar, cover),
        r: 1.0,
        h,
    }
}

/// Ashlar: courses 28–40 cm high (per course), blocks 40–90 cm long (per
/// course, offset per course), 8 mm joints recessed 4 mm, rock-faced
/// blocks (3 mm relief), each block tinted ±10 %.
pub fn stone(base: Vec3, p: DVec3, n: Vec3, seed: u32, fp: Footprint, color: bool) -> Pat {
    let (u, v, face) = plane::coords(p, n);
    // Course heights vary: cells of 34 cm with their boundaries jittered ±5 cm.
    let (row0, _) = plane::cell(v, 0.34, 0.0);
    let edge =
        |r: i64| r as f64 * 0.34 + 0.05 * signed_unit(hash_cell([r, 0x57, face], seed)) as f64;
    let row = if v < edge(row0) {
        row0 - 1
    } else if v >= edge(row0 + 1) {
        row0 + 1
    } else {
        row0
    };
    let (lo, hi) = (edge(row), edge(row + 1));
    let hr = hash_cell([row, 0x58, face], seed);
    let len = 0.4 + 0.5 * unit(hr) as f64;
    let (col, in_u) = plane::cell(u, len, len * unit(rehash(hr, 8)) as f64);
    let d = plane::edge_dist(in_u, len).min(((v - lo).min(hi - v)) as f32);
    let hb = hash_cell([col, row, face], seed ^ 0x59);
    let h = fp.keep(0.01) * plane::joint(d, 0.004, 0.003, 0.004)
        + 0.0015 * fp.relief().fbm(p, 0.06, 3, 0.55, seed ^ 0x5A) * smoothstep(0.004, 0.01, d);
    if !color {
        return Pat { c: base, r: 1.0, h };
    }
    let k_block = fp.keep(0.34);
    let block = 1.0 + 0.1 * k_block * signed_unit(hb);
    let hue = 0.04 * k_block * rehash_signed(hb);
    let grain = (1.0 + 0.08 * fp.fbm(p, 0.02, 3, 0.6, seed ^ 0x5B))
        * (1.0 + 0.08 * fp.cell_noise(p, 0.002, seed ^ 0x5C));
    // Joints: the box-filtered cover of the course's joints (v, its own
    // height) and of the blocks' (u, its length) under a wide footprint.
    let cover = 1.0
        - (1.0 - fp.band_cover(((v - lo).min(hi - v)) as f32, 0.0045, (hi - lo) as f32))
            * (1.0 - fp.band_cover(plane::edge_dist(in_u, len), 0.0045, len as f32));
    let joint = fp.fade(0.009, 1.0 - smoothstep(0.004, 0.005, d), cover);
    let c = base * Vec3::new(1.0 + hue, 1.0, 1.0 - hue) * (block * grain * (1.02 - 0.25 * joint));
    Pat { c, r: 1.0, h }
}
