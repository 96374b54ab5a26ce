//! Equiangular distance sampling toward a point light (Kulla & Fajardo 2012,
//! "Importance Sampling Techniques for Path Tracing in Participating Media",
//! §4.1): along the ray o + t·d, t ∈ [a, b], pick t with density ∝ 1/r²(t),
//! which cancels the inverse-square falloff of the light at `q`.
//!
//! With Δ the ray parameter closest to q and D the distance of q from the
//! line, t = Δ + D·tan θ with θ uniform in [θa, θb]; pdf(t) = D / ((θb − θa)
//! (D² + (t − Δ)²)). `b` may be +∞ (θb = π/2). Positions in metres, d unit.

use glam::Vec3;

/// Smallest distance of the light from the ray line used (metres): keeps the
/// pdf finite when the light sits on the ray.
const MIN_LINE_DISTANCE_M: f32 = 1e-4;

/// Geometry of one equiangular set-up, reusable for sampling and pdf queries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equiangular {
    delta: f32,
    dist: f32,
    theta_a: f32,
    theta_b: f32,
}

impl Equiangular {
    /// Set-up for the ray `o + t·d` (unit d) over [t_a, t_b] and a light at `q`.
    pub fn new(o: Vec3, d: Vec3, t_a: f32, t_b: f32, q: Vec3) -> Self {
        let delta = (q - o).dot(d);
        let dist = (q - (o + d * delta)).length().max(MIN_LINE_DISTANCE_M);
        Equiangular {
            delta,
            dist,
            theta_a: ((t_a - delta) / dist).atan(),
            theta_b: ((t_b - delta) / dist).atan(),
        }
    }

    /// Samples t ∈ [t_a, t_b] from `u` ∈ [0, 1); returns (t, pdf per metre).
    pub fn sample(&self, u: f32) -> (f32, f32) {
        let theta = self.theta_a + u * (self.theta_b - self.theta_a);
        let t = self.delta + self.dist * theta.tan();
        (t, self.pdf(t))
    }

    /// Density per metre of choosing `t` (0 outside [t_a, t_b] is not checked).
    pub fn pdf(&self, t: f32) -> f32 {
        let x = t - self.delta;
        let span = self.theta_b - self.theta_a;
        if span <= 0.0 {
            return 0.0;
        }
        self.dist / (span * (self.dist * self.dist + x * x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equiangular_sample_inverts_within_range() {
        let e = Equiangular::new(Vec3::ZERO, Vec3::X, 0.5, 20.0, Vec3::new(4.0, 1.0, 0.0));
        let (t0, _) = e.sample(0.0);
        let (t1, _) = e.sample(0.999_999);
        assert!(
            (t0 - 0.5).abs() < 1e-4 && (t1 - 20.0).abs() < 1e-2,
            "{t0} {t1}"
        );
        let (tm, _) = e.sample(0.5);
        assert!(tm > 0.5 && tm < 20.0);
    }
}
