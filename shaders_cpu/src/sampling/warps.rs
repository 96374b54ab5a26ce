//! Warps from the unit square to disks, spheres, hemispheres, cones, triangles.
//!
//! pbrt-v4 §A.5: concentric disk (Shirley–Chiu 1997), Malley's method for the
//! cosine hemisphere (§A.5.3), uniform sphere/hemisphere/cone (§A.5.2), and the
//! low-distortion triangle map of Heitz 2019 ("A Low-Distortion Map Between
//! Triangle and Square"). Directions are unit vectors around +z. Angles go
//! through `sin_cos_turns` (in turns, no libm call).

use super::trig::sin_cos_turns;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Uniform point on the unit disk by the polar map (r = √u₀, φ = 2πu₁).
pub fn sample_uniform_disk_polar(u: Vec2) -> Vec2 {
    let r = u.x.sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    Vec2::new(r * cos_phi, r * sin_phi)
}

/// Uniform point on the unit disk by Shirley–Chiu's concentric map (pbrt-v4
/// §A.5.1); area pdf 1/π. Preserves adjacency, so stratification survives.
#[inline]
pub fn sample_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    // Square wedges map to disk wedges: the larger |coordinate| is the
    // radius; the angle in turns is θ/2π (π/4 rad = 1/8 turn).
    // Written as selects around one division: the wedge is a coin flip per
    // sample, and a branch on it mispredicts half the time.
    let x_major = o.x.abs() > o.y.abs();
    let (r, other) = if x_major { (o.x, o.y) } else { (o.y, o.x) };
    let ratio = 0.125 * (other / r);
    let theta_turns = if x_major { ratio } else { 0.25 - ratio };
    let (sin_theta, cos_theta) = sin_cos_turns(theta_turns);
    r * Vec2::new(cos_theta, sin_theta)
}

/// Cosine-weighted direction on the +z hemisphere (Malley's method: a uniform
/// disk point lifted to the hemisphere); pdf `cos θ / π`.
#[inline]
pub fn sample_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = sample_uniform_disk_concentric(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// Pdf per solid angle of [`sample_cosine_hemisphere`]; zero below the horizon.
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// Uniform direction on the unit sphere (z = 1 − 2u₀, pbrt-v4 §A.5.2).
#[inline]
pub fn sample_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// Pdf per solid angle of [`sample_uniform_sphere`]: 1/(4π).
#[inline]
pub fn uniform_sphere_pdf() -> f32 {
    0.25 * FRAC_1_PI
}

/// Uniform direction on the +z hemisphere (z = u₀).
pub fn sample_uniform_hemisphere(u: Vec2) -> Vec3 {
    let z = u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// Pdf per solid angle of [`sample_uniform_hemisphere`]: 1/(2π).
pub fn uniform_hemisphere_pdf() -> f32 {
    0.5 * FRAC_1_PI
}

/// Uniform direction in the cone of half-angle θmax around +z, given
/// `cos_theta_max` in [-1, 1] (cos θ uniform in [cos θmax, 1]).
#[inline]
pub fn sample_uniform_cone(u: Vec2, cos_theta_max: f32) -> Vec3 {
    let cos_theta = (1.0 - u.x) + u.x * cos_theta_max;
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta)
}

/// Pdf per solid angle of [`sample_uniform_cone`]: 1 / (2π (1 − cos θmax)).
#[inline]
pub fn uniform_cone_pdf(cos_theta_max: f32) -> f32 {
    1.0 / (2.0 * PI * (1.0 - cos_theta_max))
}

/// Area-uniform barycentrics (b0, b1, b2) on a triangle, Heitz 2019's
/// low-distortion map (pbrt-v4 `SampleUniformTriangle`, §6.5.4).
pub fn sample_uniform_triangle(u: Vec2) -> [f32; 3] {
    let (b0, b1);
    if u.x < u.y {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    [b0, b1, 1.0 - b0 - b1]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Midpoint grid over the unit square (deterministic, stratified).
    fn grid(n: usize) -> impl Iterator<Item = Vec2> {
        (0..n * n).map(move |i| {
            Vec2::new(
                ((i % n) as f32 + 0.5) / n as f32,
                ((i / n) as f32 + 0.5) / n as f32,
            )
        })
    }

    /// ∫ pdf dω over the sphere by midpoint quadrature in (cos θ, φ).
    fn sphere_integral(pdf: impl Fn(Vec3) -> f32) -> f32 {
        let n = 400;
        let mut sum = 0.0f64;
        for u in grid(n) {
            let z = 2.0 * u.x - 1.0;
            let r = (1.0 - z * z).sqrt();
            let phi = 2.0 * PI * u.y;
            sum += pdf(Vec3::new(r * phi.cos(), r * phi.sin(), z)) as f64;
        }
        (sum * 4.0 * std::f64::consts::PI / (n * n) as f64) as f32
    }

    #[test]
    fn warps_land_on_their_domains() {
        let cos_max = 0.8f32;
        for u in grid(64) {
            assert!(sample_uniform_disk_concentric(u).length() <= 1.0 + 1e-6);
            assert!(sample_uniform_disk_polar(u).length() <= 1.0 + 1e-6);
            let w = sample_cosine_hemisphere(u);
            assert!((w.length() - 1.0).abs() < 1e-5 && w.z >= 0.0);
            let w = sample_uniform_sphere(u);
            assert!((w.length() - 1.0).abs() < 1e-5);
            let w = sample_uniform_hemisphere(u);
            assert!((w.length() - 1.0).abs() < 1e-5 && w.z >= 0.0);
            let w = sample_uniform_cone(u, cos_max);
            assert!((w.length() - 1.0).abs() < 1e-5 && w.z >= cos_max - 1e-6);
            let b = sample_uniform_triangle(u);
            assert!(b.iter().all(|&x| (-1e-6..=1.0 + 1e-6).contains(&x)));
            assert!((b.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn warp_pdfs_integrate_to_one() {
        let cos = sphere_integral(|w| cosine_hemisphere_pdf(w.z));
        let hemi = sphere_integral(|w| {
            if w.z > 0.0 {
                uniform_hemisphere_pdf()
            } else {
                0.0
            }
        });
        let sph = sphere_integral(|_| uniform_sphere_pdf());
        let cone = sphere_integral(|w| {
            if w.z > 0.5 {
                uniform_cone_pdf(0.5)
            } else {
                0.0
            }
        });
        for (name, v) in [
            ("cos", cos),
            ("hemi", hemi),
            ("sphere", sph),
            ("cone", cone),
        ] {
            assert!((v - 1.0).abs() < 2e-3, "{name}: {v}");
        }
    }

    #[test]
    fn cosine_warp_matches_its_pdf_in_moments() {
        // E[cos θ] under pdf cos θ/π is 2/3; E[z] for the uniform sphere is 0,
        // for the uniform cone (1 + cos θmax)/2.
        let n = 256;
        let mean = |f: &dyn Fn(Vec2) -> f32| grid(n).map(f).sum::<f32>() / (n * n) as f32;
        assert!((mean(&|u| sample_cosine_hemisphere(u).z) - 2.0 / 3.0).abs() < 1e-3);
        assert!(mean(&|u| sample_uniform_sphere(u).z).abs() < 1e-3);
        assert!((mean(&|u| sample_uniform_cone(u, 0.2).z) - 0.6).abs() < 1e-3);
        // Uniform disk: E[r²] = 1/2.
        assert!((mean(&|u| sample_uniform_disk_concentric(u).length_squared()) - 0.5).abs() < 1e-3);
    }

    #[test]
    fn triangle_warp_is_area_uniform() {
        // Every one of the 4 midpoint sub-triangles gets 1/4 of the samples.
        let n = 200;
        let mut counts = [0usize; 4];
        for u in grid(n) {
            let [b0, b1, b2] = sample_uniform_triangle(u);
            let k = if b0 > 0.5 {
                0
            } else if b1 > 0.5 {
                1
            } else if b2 > 0.5 {
                2
            } else {
                3
            };
            counts[k] += 1;
        }
        for c in counts {
            let frac = c as f32 / (n * n) as f32;
            assert!((frac - 0.25).abs() < 0.01, "{counts:?}");
        }
    }
}
