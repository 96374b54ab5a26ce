//! Running-bond brick in wall-plane coordinates.
//!
//! Walls (|n_z| < 0.7) use u = horizontal distance along the wall and
//! v = height; floors and roofs use (x, y) (paving). The normal's sign is
//! canonicalised, so both faces of a wall and either winding see one
//! pattern. Bricks are 215 × 65 mm with 10 mm mortar (UK/EU format), every
//! other course offset by half a brick. The mortar is a pale grey of the
//! base's luminance; the brick colour is solved so that the area-weighted
//! mean over a module equals the nominal albedo.

use glam::{DVec3, Vec3};

use super::noise::{cell_noise, fbm, hash_cell, rehash_signed, signed_unit};

/// Brick length plus one mortar joint, metres (the horizontal period).
pub const MODULE_U_M: f64 = 0.225;
/// Brick height plus one mortar joint, metres (the course height).
pub const MODULE_V_M: f64 = 0.075;
/// Mortar joint width, metres.
pub const MORTAR_M: f64 = 0.010;

/// Wall-plane coordinates (u, v) in metres and a face id separating the
/// wall and floor projections.
fn plane_coords(p: DVec3, n: Vec3) -> (f64, f64, i64) {
    if n.z.abs() < 0.7 {
        // Horizontal tangent of the wall, sign fixed by the normal's line.
        let (nx, ny) = (n.x as f64, n.y as f64);
        let (nx, ny) = if nx < 0.0 || (nx == 0.0 && ny < 0.0) {
            (-nx, -ny)
        } else {
            (nx, ny)
        };
        let len = (nx * nx + ny * ny).sqrt().max(1e-12);
        ((p.x * -ny + p.y * nx) / len, p.z, 0)
    } else {
        (p.x, p.y, 1)
    }
}

/// The albedo of a brick wall of nominal albedo `base` at `p` (metres).
pub fn albedo(base: Vec3, p: DVec3, n: Vec3, seed: u32) -> Vec3 {
    let (u, v, face) = plane_coords(p, n);
    let row = (v / MODULE_V_M).floor();
    let shift = if (row as i64).rem_euclid(2) == 1 {
        0.5 * MODULE_U_M
    } else {
        0.0
    };
    let col = ((u + shift) / MODULE_U_M).floor();
    let in_u = u + shift - col * MODULE_U_M;
    let in_v = v - row * MODULE_V_M;
    // The joint sits at the low edge of each module in u and v.
    let mortar = in_u < MORTAR_M || in_v < MORTAR_M;

    let lum = base.dot(Vec3::new(0.2126, 0.7152, 0.0722));
    let mortar_rgb = Vec3::new(1.0, 0.97, 0.92) * (1.3 * lum).min(0.9);
    let f_brick =
        ((MODULE_U_M - MORTAR_M) * (MODULE_V_M - MORTAR_M) / (MODULE_U_M * MODULE_V_M)) as f32;
    if mortar {
        let sand = 1.0 + 0.15 * cell_noise(p, 0.002, seed ^ 0xD1);
        return mortar_rgb * sand;
    }
    // Brick colour so that f_brick·brick + (1 − f_brick)·mortar = base.
    let brick_rgb = ((base - (1.0 - f_brick) * mortar_rgb) / f_brick).max(Vec3::ZERO);
    let h = hash_cell([col as i64, row as i64, face], seed);
    let shade = 1.0 + 0.22 * signed_unit(h);
    let hue = 0.08 * rehash_signed(h);
    let surface = 1.0 + 0.1 * fbm(p, 0.03, 3, 0.6, seed ^ 0xD2);
    // Sand-faced grain, 3 mm.
    let grain = 1.0 + 0.12 * cell_noise(p, 0.003, seed ^ 0xD3);
    brick_rgb * Vec3::new(1.0 + hue, 1.0, 1.0 - hue) * (shade * surface * grain)
}
