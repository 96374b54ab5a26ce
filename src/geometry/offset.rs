//! Error-bounded ray origins, after pbrt-v4 (§6.8.4-6.8.6, "Robust spawned ray
//! origins"): the computed hit point carries a conservative per-axis error
//! bound; a spawned ray starts just outside that box along the geometric normal,
//! so it cannot re-hit the surface it leaves. No fixed epsilons.

use glam::Vec3;

/// gamma(n) = n·u / (1 − n·u) with u the f32 unit roundoff (pbrt eq. 6.28).
pub const fn gamma(n: i32) -> f32 {
    let u = f32::EPSILON * 0.5;
    (n as f32 * u) / (1.0 - n as f32 * u)
}

/// Conservative absolute error bound of a point interpolated from triangle
/// vertices with barycentrics (pbrt eq. 6.32): gamma(7)·Σ|b_i·p_i|.
pub fn position_error(b: [f32; 3], p: [Vec3; 3]) -> Vec3 {
    ((p[0] * b[0]).abs() + (p[1] * b[1]).abs() + (p[2] * b[2]).abs()) * gamma(7)
}

/// Origin for a ray leaving a surface at `p` (error bound `p_error`) with
/// geometric normal `n_geo`, heading along `w` (pbrt `OffsetRayOrigin`).
pub fn offset_ray_origin(p: Vec3, p_error: Vec3, n_geo: Vec3, w: Vec3) -> Vec3 {
    let d = n_geo.abs().dot(p_error);
    let mut offset = n_geo * d;
    if w.dot(n_geo) < 0.0 {
        offset = -offset;
    }
    let mut po = p + offset;
    // Round away from p so the offset survives the final rounding.
    for i in 0..3 {
        if offset[i] > 0.0 {
            po[i] = po[i].next_up();
        } else if offset[i] < 0.0 {
            po[i] = po[i].next_down();
        }
    }
    po
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_origin_lies_on_the_side_of_travel() {
        let p = Vec3::new(1000.0, 2.0, -3.0);
        let err = position_error([0.2, 0.3, 0.5], [p, p, p]);
        let n = Vec3::Z;
        let up = offset_ray_origin(p, err, n, Vec3::new(0.0, 0.3, 1.0));
        let down = offset_ray_origin(p, err, n, Vec3::new(0.0, 0.3, -1.0));
        assert!(up.z > p.z && down.z < p.z);
        assert!((up.z - p.z).abs() >= err.z);
    }
}
