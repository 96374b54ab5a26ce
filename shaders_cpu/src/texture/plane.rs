//! Coordinates of patterns laid in a plane (bricks, slabs, planks): walls
//! (|n_z| < 0.7) use u = horizontal distance along the wall and v = height;
//! floors and roofs use (x, y). The normal's sign is canonicalised, so both
//! faces of a wall and either winding see one pattern; `face` separates the
//! wall and floor projections for hashing.

use glam::{DVec3, Vec3};

/// (u, v) in metres and a face id (0 wall, 1 floor).
#[inline]
pub fn coords(p: DVec3, n: Vec3) -> (f64, f64, i64) {
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

/// The running cell of `x` in rows of period `period` shifted by `shift`:
/// (cell index, offset inside the cell in [0, period)).
#[inline]
pub fn cell(x: f64, period: f64, shift: f64) -> (i64, f64) {
    let k = ((x - shift) / period).floor();
    (k as i64, x - shift - k * period)
}

/// Distance from `offset` (inside a cell of length `len`) to the nearer
/// cell edge, metres.
#[inline]
pub fn edge_dist(offset: f64, len: f64) -> f32 {
    offset.min(len - offset) as f32
}

/// A recessed joint's height profile: `-depth` within `half_width` of the
/// joint's centre line, rising smoothly to 0 over `bevel` (so the relief
/// gradient sees the edge). `d` is the distance to the centre line.
#[inline]
pub fn joint(d: f32, half_width: f32, bevel: f32, depth: f32) -> f32 {
    -depth * (1.0 - super::smoothstep(half_width, half_width + bevel, d))
}
