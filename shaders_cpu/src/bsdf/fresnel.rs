//! Fresnel equations and the reflect/refract helpers (pbrt-v4 §9.3).
//!
//! Local-frame conventions: `n` is the (micro)normal, `wo` points away from the
//! surface. `eta` is the relative IOR inside/outside (η_t/η_i for light
//! arriving from the side `n` points to). Conductors use the complex IOR
//! η + iκ (pbrt-v4 §9.3.6), evaluated per RGB channel.

use glam::Vec3;

/// Mirror `wo` about `n` (pbrt-v4 eq. 9.1): `-wo + 2 (wo·n) n`.
pub fn reflect(wo: Vec3, n: Vec3) -> Vec3 {
    -wo + 2.0 * wo.dot(n) * n
}

/// Refracts `wi` through the interface with normal `n` and relative IOR `eta`
/// (pbrt-v4 §9.3.2, `Refract`). Handles `wi` on either side of `n` by flipping
/// to the incident side. Returns the transmitted direction and the relative IOR
/// `etap` actually crossed, or `None` on total internal reflection.
pub fn refract(wi: Vec3, n: Vec3, eta: f32) -> Option<(Vec3, f32)> {
    let mut cos_i = n.dot(wi);
    let (mut eta, mut n) = (eta, n);
    if cos_i < 0.0 {
        // Arriving from inside: invert the interface.
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
    // Snell's law in vector form (pbrt-v4 eq. 9.4).
    let wt = -wi / eta + (cos_i / eta - cos_t) * n;
    Some((wt, eta))
}

/// Unpolarised Fresnel reflectance of a dielectric interface (pbrt-v4 §9.3.5,
/// `FrDielectric`). `cos_theta_i` may be negative (incidence from inside);
/// returns 1 under total internal reflection.
pub fn fr_dielectric(cos_theta_i: f32, eta: f32) -> f32 {
    let mut cos_i = cos_theta_i.clamp(-1.0, 1.0);
    let mut eta = eta;
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    (r_parl * r_parl + r_perp * r_perp) / 2.0
}

/// Minimal complex number for the conductor Fresnel term.
#[derive(Clone, Copy, Debug)]
struct Complex {
    re: f32,
    im: f32,
}

impl Complex {
    fn new(re: f32, im: f32) -> Self {
        Complex { re, im }
    }
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    fn div(self, o: Complex) -> Complex {
        let d = o.re * o.re + o.im * o.im;
        Complex::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
    /// |z|².
    fn norm(self) -> f32 {
        self.re * self.re + self.im * self.im
    }
    /// Principal square root (non-negative real part).
    fn sqrt(self) -> Complex {
        let r = self.norm().sqrt();
        let re = ((r + self.re) * 0.5).max(0.0).sqrt();
        let im = ((r - self.re) * 0.5).max(0.0).sqrt();
        Complex::new(re, im.copysign(self.im))
    }
}

/// Fresnel reflectance of a conductor with complex IOR `eta + i k` at incidence
/// cosine `cos_theta_i` (clamped to [0, 1]); pbrt-v4 §9.3.6 `FrComplex`.
pub fn fr_complex(cos_theta_i: f32, eta: f32, k: f32) -> f32 {
    let cos_i = cos_theta_i.clamp(0.0, 1.0);
    let eta = Complex::new(eta, k);
    let sin2_i = 1.0 - cos_i * cos_i;
    // Snell's law with a complex eta: sin²θt = sin²θi / η².
    let sin2_t = Complex::new(sin2_i, 0.0).div(eta.mul(eta));
    let cos_t = Complex::new(1.0, 0.0).sub(sin2_t).sqrt();
    let ci = Complex::new(cos_i, 0.0);
    let eci = eta.mul(ci);
    let ect = eta.mul(cos_t);
    let r_parl = eci.sub(cos_t).div(eci.add(cos_t));
    let r_perp = ci.sub(ect).div(ci.add(ect));
    (r_parl.norm() + r_perp.norm()) / 2.0
}

/// [`fr_complex`] per RGB channel.
pub fn fr_complex_rgb(cos_theta_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    Vec3::new(
        fr_complex(cos_theta_i, eta.x, k.x),
        fr_complex(cos_theta_i, eta.y, k.y),
        fr_complex(cos_theta_i, eta.z, k.z),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dielectric_fresnel_limits() {
        // Normal incidence: ((n-1)/(n+1))².
        assert!((fr_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        assert!((fr_dielectric(-1.0, 1.5) - 0.04).abs() < 1e-6);
        // Grazing incidence reflects everything.
        assert!(fr_dielectric(1e-4, 1.5) > 0.99);
        // Total internal reflection beyond the critical angle asin(1/1.5).
        let cos_crit = (1.0f32 - 1.0 / 2.25).sqrt();
        assert_eq!(fr_dielectric(-(cos_crit - 1e-3), 1.5), 1.0);
        assert!(fr_dielectric(-(cos_crit + 1e-3), 1.5) < 1.0);
        // eta = 1: no interface.
        assert!(fr_dielectric(0.3, 1.0).abs() < 1e-7);
    }

    #[test]
    fn conductor_fresnel_reduces_to_closed_forms() {
        // Normal incidence: ((η-1)² + κ²) / ((η+1)² + κ²).
        let (eta, k) = (0.2f32, 3.9f32);
        let f0 = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        assert!((fr_complex(1.0, eta, k) - f0).abs() < 1e-5);
        // κ = 0 matches the dielectric formula.
        for c in [0.1f32, 0.5, 0.9] {
            assert!((fr_complex(c, 1.5, 0.0) - fr_dielectric(c, 1.5)).abs() < 1e-5);
        }
        assert!(fr_complex(0.0, eta, k) > 0.999);
    }

    #[test]
    fn refract_obeys_snell_and_round_trips() {
        let n = Vec3::Z;
        let wi = Vec3::new(0.6, 0.0, 0.8);
        let (wt, etap) = refract(wi, n, 1.5).unwrap();
        assert_eq!(etap, 1.5);
        let sin_t = (1.0 - wt.z * wt.z).sqrt();
        assert!((0.6 - 1.5 * sin_t).abs() < 1e-5);
        assert!((wt.length() - 1.0).abs() < 1e-5 && wt.z < 0.0);
        // Back through the interface from inside recovers wi.
        let (back, etap2) = refract(wt, n, 1.5).unwrap();
        assert!((back - wi).length() < 1e-5 && (etap2 - 1.0 / 1.5).abs() < 1e-6);
        // Total internal reflection from inside at grazing angles.
        assert!(refract(Vec3::new(0.9, 0.0, -0.436).normalize(), n, 1.5).is_none());
        assert!((reflect(wi, n) - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
    }
}
