//! Lattice noise on world coordinates: an integer hash, cell white noise,
//! trilinear-quintic value noise and fBm.
//!
//! Positions arrive in f64 metres; the lattice cell is found in f64 (so a
//! town kilometres from the origin keeps millimetre detail) and only the
//! in-cell fraction drops to f32. Every value is a pure function of
//! (seed, position): no tables, no allocation. The lattice is turned off the world axes
//! and shifted per seed, so its rows never line up with roads or walls.
//! Value noise: Perlin, "An image synthesizer" (SIGGRAPH 1985); fBm: Musgrave
//! in Ebert et al., *Texturing & Modeling* (3rd ed.), ch. 16.

use glam::{DMat3, DVec3, Vec3};

/// 32-bit avalanche hash of a lattice cell and a seed (lowbias32 mixing).
#[inline]
pub fn hash_cell(cell: [i64; 3], seed: u32) -> u32 {
    cell.into_iter().fold(hash_seed(seed), mix)
}

/// The hash state before any coordinate is mixed in.
#[inline]
fn hash_seed(seed: u32) -> u32 {
    seed.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B
}

/// Mixes one coordinate into a hash state; `hash_cell` folds x, y, z in
/// order, so value noise can share the x and xy prefixes of its 8 corners.
#[inline]
fn mix(mut h: u32, c: i64) -> u32 {
    // Fold the full i64 so cells 2³² apart still differ.
    let c = c as u64;
    h ^= (c as u32) ^ ((c >> 32) as u32).rotate_left(16);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^ (h >> 16)
}

/// The `k`-th further hash drawn from `h` (one mixing round): independent
/// draws from one cell hash, where shifting its bits would not be uniform.
#[inline]
pub fn rehash(h: u32, k: u32) -> u32 {
    mix(h, k as i64 + 0x2F)
}

/// A hash mapped to [-1, 1) (uniform, mean 0).
#[inline]
pub fn signed_unit(h: u32) -> f32 {
    (h >> 8) as f32 * (2.0 / 16_777_216.0) - 1.0
}

/// A hash mapped to [0, 1) (uniform).
#[inline]
pub fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Splits `p` (lattice units) into its integer cell and the in-cell fraction.
#[inline]
fn split(p: DVec3) -> ([i64; 3], Vec3) {
    let f = p.floor();
    ([f.x as i64, f.y as i64, f.z as i64], (p - f).as_vec3())
}

/// The hash of the `cell_m`-metre cell holding `p_world` (one draw per cell).
#[inline]
pub fn cell_hash(p_world: DVec3, cell_m: f64, seed: u32) -> u32 {
    let (c, _) = split(to_lattice(p_world, cell_m, seed));
    hash_cell(c, seed)
}

/// Uniform white noise in [-1, 1), constant over cells of `cell_m` metres.
#[inline]
pub fn cell_noise(p_world: DVec3, cell_m: f64, seed: u32) -> f32 {
    signed_unit(cell_hash(p_world, cell_m, seed))
}

/// A second, independent uniform draw in [-1, 1) from a hash already drawn.
#[inline]
pub fn rehash_signed(h: u32) -> f32 {
    signed_unit(hash_cell([h as i64, 0x51ED, 0], 0x2545_F491))
}

/// Value noise in [-1, 1] with features of `cell_m` metres; mean 0 (the
/// lattice values are symmetric about 0 and interpolation is linear in them).
pub fn value_noise(p_world: DVec3, cell_m: f64, seed: u32) -> f32 {
    let (c, f) = split(to_lattice(p_world, cell_m, seed));
    // Quintic fade 6t⁵ − 15t⁴ + 10t³: C² across cell faces.
    let w = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    // Corner hashes equal hash_cell(corner, seed); shared prefixes make
    // them 14 mixing rounds instead of 24.
    let h0 = hash_seed(seed);
    let hx = [mix(h0, c[0]), mix(h0, c[0] + 1)];
    let hxy = |dx: usize, dy: i64| mix(hx[dx], c[1] + dy);
    let (h00, h10, h01, h11) = (hxy(0, 0), hxy(1, 0), hxy(0, 1), hxy(1, 1));
    let v = |h: u32, dz: i64| signed_unit(mix(h, c[2] + dz));
    let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
    let x00 = lerp(v(h00, 0), v(h10, 0), w.x);
    let x10 = lerp(v(h01, 0), v(h11, 0), w.x);
    let x01 = lerp(v(h00, 1), v(h10, 1), w.x);
    let x11 = lerp(v(h01, 1), v(h11, 1), w.x);
    lerp(lerp(x00, x10, w.y), lerp(x01, x11, w.y), w.z)
}

/// Fractional Brownian motion in [-1, 1]: `octaves` value-noise octaves from
/// `largest_m` down by halves, amplitude × `gain` per octave, normalised by
/// the amplitude sum. Mean 0.
pub fn fbm(p_world: DVec3, largest_m: f64, octaves: u32, gain: f32, seed: u32) -> f32 {
    let (mut sum, mut norm, mut amp, mut cell) = (0.0f32, 0.0f32, 1.0f32, largest_m);
    for o in 0..octaves {
        sum += amp
            * value_noise(
                p_world,
                cell,
                seed.wrapping_add(o.wrapping_mul(0x68E3_1DA4)),
            );
        norm += amp;
        amp *= gain;
        cell *= 0.5;
    }
    sum / norm
}

/// Rotates world axes off the lattice's (an exactly orthonormal matrix with
/// rational entries) and shifts the lattice by a seed-dependent, non-integer
/// offset of up to ~3300 cells, so textures and octaves neither align with roads and walls
/// nor share lattice points.
#[inline]
fn to_lattice(p_world: DVec3, cell_m: f64, seed: u32) -> DVec3 {
    const R: DMat3 = DMat3::from_cols_array(&[0.0, 0.8, 0.6, -0.8, 0.36, -0.48, -0.6, -0.48, 0.64]);
    // Three 10–11-bit fields of one hash, times an irrational-ish step.
    let h = hash_cell([1, 2, 3], seed);
    let offset = DVec3::new(
        (h & 0x7FF) as f64,
        ((h >> 11) & 0x7FF) as f64,
        (h >> 22) as f64,
    ) * 1.618_034;
    R * p_world / cell_m + offset
}
