//! Shared fixtures for the sampling tests: directions and BSDF line-ups.

#![allow(dead_code)]

use glam::Vec3;
use shaders_cpu::bsdf::Bsdf;

/// Unit direction from polar angle θ and azimuth φ in degrees (z up).
pub fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// Outgoing directions: near-normal, oblique, grazing and from below.
pub fn wos() -> [Vec3; 4] {
    [
        dir(5.0, 10.0),
        dir(45.0, 120.0),
        dir(87.0, -30.0),
        dir(130.0, 200.0),
    ]
}

/// Gold-like complex IOR.
pub fn gold(alpha: f32) -> Bsdf {
    Bsdf::conductor_preset("gold", alpha).expect("gold preset")
}

/// Glass with relative IOR `eta`, roughness `alpha`, white tint.
pub fn glass(eta: f32, alpha: f32) -> Bsdf {
    Bsdf::Dielectric {
        eta,
        alpha,
        tint: Vec3::ONE,
    }
}

/// Every rough BSDF under test.
pub fn rough_bsdfs() -> Vec<(String, Bsdf)> {
    vec![
        (
            "lambert".into(),
            Bsdf::Lambert {
                albedo: Vec3::new(0.8, 0.5, 0.2),
            },
        ),
        ("conductor a=0.2".into(), gold(0.2)),
        ("conductor a=0.5".into(), gold(0.5)),
        ("dielectric 1.5 a=0.3".into(), glass(1.5, 0.3)),
        ("dielectric 1/1.5 a=0.3".into(), glass(1.0 / 1.5, 0.3)),
    ]
}

/// Every smooth (delta) BSDF under test.
pub fn smooth_bsdfs() -> Vec<(String, Bsdf)> {
    vec![
        ("mirror".into(), gold(0.0)),
        ("glass 1.5".into(), glass(1.5, 0.0)),
        ("glass 1/1.5".into(), glass(1.0 / 1.5, 0.0)),
    ]
}
