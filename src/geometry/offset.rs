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
    let po = p + offset;
    // Round away from p so the offset survives the final rounding.
    Vec3::new(
        step_away(po.x, offset.x),
        step_away(po.y, offset.y),
        step_away(po.z, offset.z),
    )
}

/// `x.next_up()` for `dir` > 0, `x.next_down()` for `dir` < 0, else `x`.
///
/// For finite non-zero `x` this is ±1 on the bit pattern (the sign of `x`
/// decides which way is up), done without branching on `dir`: the offset's
/// signs follow the surface normal, a coin flip from vertex to vertex.
#[inline(always)]
fn step_away(x: f32, dir: f32) -> f32 {
    if !x.is_finite() || x == 0.0 {
        // ±0 steps to a subnormal of either sign, infinities and NaN stay.
        return if dir > 0.0 {
            x.next_up()
        } else if dir < 0.0 {
            x.next_down()
        } else {
            x
        };
    }
    let up = (dir > 0.0) as i32 - (dir < 0.0) as i32;
    // Magnitude grows with the bits: up is +1 for positive x, −1 for negative.
    let delta = if x.is_sign_negative() { -up } else { up };
    f32::from_bits(x.to_bits().wrapping_add_signed(delta))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_away_equals_next_up_and_next_down() {
        let xs = [
            1.0f32,
            -1.0,
            0.0,
            -0.0,
            1e-45,
            -1e-45,
            f32::MAX,
            -f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            123.456,
            -7.5e-20,
            f32::MIN_POSITIVE,
        ];
        for x in xs {
            for dir in [1.0f32, -2.0, 0.0, -0.0, f32::NAN] {
                let expect = if dir > 0.0 {
                    x.next_up()
                } else if dir < 0.0 {
                    x.next_down()
                } else {
                    x
                };
                assert_eq!(
                    step_away(x, dir).to_bits(),
                    expect.to_bits(),
                    "x {x:e} dir {dir}"
                );
            }
        }
    }

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
