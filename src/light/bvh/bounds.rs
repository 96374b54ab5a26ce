//! The bounds a light-tree node keeps of its lights (positions' box,
//! cone of emission normals, spread, intensity) and their union (Conty
//! Estevez & Kulla 2018 §4.1; pbrt-v4's `LightBounds`, `DirectionCone`).
//! Render space; angles as cosines.

use glam::Vec3;

use super::node::Packed;

/// Bounds of one light or of a cluster of lights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    /// Minimum corner of the positions' box (render space, m).
    pub p_min: Vec3,
    /// Maximum corner of the positions' box.
    pub p_max: Vec3,
    /// Unit axis of the cone of emission normals.
    pub w: Vec3,
    /// Intensity bound (luminance, W·sr⁻¹): phi·cosθ/d² bounds the irradiance.
    pub phi: f32,
    /// Cosine of the normal cone's half-angle θ_o (−1: every direction).
    pub cos_theta_o: f32,
    /// Cosine of the emission spread θ_e about a normal (0 for a Lambert emitter).
    pub cos_theta_e: f32,
    /// Emission on both sides of each normal.
    pub two_sided: bool,
}

impl LightBounds {
    pub(super) fn centroid(&self) -> Vec3 {
        0.5 * (self.p_min + self.p_max)
    }

    /// Bound of the light's contribution at `p` (0: it cannot light `p`).
    pub fn importance(&self, p: Vec3) -> f32 {
        Packed::new(self, 0, true).at(p, Vec3::ZERO)
    }

    /// [`LightBounds::importance`] at a receiver that reflects only, whose
    /// unit normal `n` faces the side it reflects on (zero: no receiver
    /// bound): also times the largest cosine between `n` and a direction
    /// into the bounds.
    pub fn importance_facing(&self, p: Vec3, n: Vec3) -> f32 {
        Packed::new(self, 0, true).at(p, n)
    }

    /// The bounds of both `self` and `o`.
    pub fn union(&self, o: &LightBounds) -> LightBounds {
        if self.phi == 0.0 {
            return *o;
        }
        if o.phi == 0.0 {
            return *self;
        }
        let (w, cos_theta_o) = cone_union(self.w, self.cos_theta_o, o.w, o.cos_theta_o);
        LightBounds {
            p_min: self.p_min.min(o.p_min),
            p_max: self.p_max.max(o.p_max),
            w,
            phi: self.phi + o.phi,
            cos_theta_o,
            cos_theta_e: self.cos_theta_e.min(o.cos_theta_e),
            two_sided: self.two_sided || o.two_sided,
        }
    }
}

/// The smallest cone holding two cones (axis, cosine of half-angle).
pub(super) fn cone_union(wa: Vec3, cos_a: f32, wb: Vec3, cos_b: f32) -> (Vec3, f32) {
    if cos_a == -1.0 || cos_b == -1.0 {
        return (wa, -1.0);
    }
    let cos_d = wa.dot(wb).clamp(-1.0, 1.0);
    // Parallel axes and cone b no wider than a: the general path below
    // returns (wa, cos_a) too (θ_d = 0, θ_b ≤ θ_a), without its arc cosines.
    // Most unions in a town's light tree are of this kind (lamp and window
    // faces share their normals), and the build is a large part of a
    // frame's set-up.
    if cos_d == 1.0 && (cos_b == 1.0 || cos_b == cos_a) {
        return (wa, cos_a);
    }
    let theta_a = acos_clamped(cos_a);
    let theta_b = acos_clamped(cos_b);
    let theta_d = acos_clamped(cos_d);
    // One cone inside the other.
    if (theta_d + theta_b).min(std::f32::consts::PI) <= theta_a {
        return (wa, cos_a);
    }
    if (theta_d + theta_a).min(std::f32::consts::PI) <= theta_b {
        return (wb, cos_b);
    }
    let theta_o = 0.5 * (theta_a + theta_d + theta_b);
    if theta_o >= std::f32::consts::PI {
        return (wa, -1.0);
    }
    // Rotate wa towards wb by θ_o − θ_a about their common normal.
    let theta_r = theta_o - theta_a;
    let axis = wa.cross(wb);
    if axis.length_squared() < 1e-12 {
        // (Nearly) parallel axes: keep wa and widen it to cover cone b.
        let theta = (theta_d + theta_b).max(theta_a).min(std::f32::consts::PI);
        return (wa, theta.cos());
    }
    let w = glam::Quat::from_axis_angle(axis.normalize(), theta_r) * wa;
    (w.normalize(), theta_o.cos())
}

/// acos of `c` clamped to [−1, 1]; the cosines of single emitters (1 for a
/// face's normal cone, 0 for a Lambert spread) skip the libm call with the
/// bits it returns for them (acos 1 = +0, acos 0 = π/2 correctly rounded;
/// `tests::acos_shortcuts_are_the_libm_bits`).
#[inline]
pub(in crate::light) fn acos_clamped(c: f32) -> f32 {
    if c == 1.0 {
        0.0
    } else if c == 0.0 {
        std::f32::consts::FRAC_PI_2
    } else {
        c.clamp(-1.0, 1.0).acos()
    }
}
