//! Exact (f64) re-intersection for the ground-truth pass.
//!
//! Traversal runs in f32; the GT pass takes the primitive it found and solves
//! the ray–plane or ray–sphere equation again in f64 from the f64 render-space
//! vertices, so depth_z is exact to f64 rounding even at grazing angles where an
//! f32 hit distance would be off by far more than the 1e-5 contract.

use glam::DVec3;

/// Parameter t of ray o + t·d against the plane of triangle (p0, p1, p2);
/// `None` if the ray is parallel to the plane.
pub fn ray_plane_t(o: DVec3, d: DVec3, p: [DVec3; 3]) -> Option<f64> {
    let n = (p[1] - p[0]).cross(p[2] - p[0]);
    let denom = n.dot(d);
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    // Average the vertices so no single far vertex dominates the rounding.
    let centroid = (p[0] + p[1] + p[2]) / 3.0;
    Some(n.dot(centroid - o) / denom)
}

/// Nearest parameter t ≥ `t_min` of ray o + t·d against a sphere, using the
/// cancellation-free form of Ray Tracing Gems ch. 7 (Haines et al. 2019).
pub fn ray_sphere_t(o: DVec3, d: DVec3, center: DVec3, radius: f64, t_min: f64) -> Option<f64> {
    let f = o - center;
    let a = d.dot(d);
    let b = -f.dot(d);
    // Discriminant via |f − (f·d̂)d̂|², stable for distant spheres.
    let l = f + d * (b / a);
    let disc = radius * radius - l.dot(l);
    if disc < 0.0 {
        return None;
    }
    let q = b + b.signum() * (a * disc).sqrt();
    let (t0, t1) = if q == 0.0 {
        (0.0, 0.0)
    } else {
        let c = f.dot(f) - radius * radius;
        let (x, y) = (c / q, q / a);
        (x.min(y), x.max(y))
    };
    [t0, t1].into_iter().find(|&t| t >= t_min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_hit_is_exact_at_grazing_angles() {
        // A road plane z = −1.65 seen almost edge-on, 20 km wide.
        let p = [
            DVec3::new(-2e4, -2e4, -1.65),
            DVec3::new(2e4, -2e4, -1.65),
            DVec3::new(0.0, 2e4, -1.65),
        ];
        let d = DVec3::new(1.0, 0.01, -1e-3);
        let t = ray_plane_t(DVec3::ZERO, d, p).unwrap();
        assert!((t - 1650.0).abs() < 1e-9 * 1650.0);
    }

    #[test]
    fn sphere_hits_near_and_far_sides() {
        let c = DVec3::new(0.0, 0.0, 10.0);
        let t = ray_sphere_t(DVec3::ZERO, DVec3::Z, c, 2.0, 0.0).unwrap();
        assert!((t - 8.0).abs() < 1e-12);
        let t_in = ray_sphere_t(c, DVec3::Z, c, 2.0, 0.0).unwrap();
        assert!((t_in - 2.0).abs() < 1e-12);
        assert!(ray_sphere_t(DVec3::ZERO, DVec3::X, c, 2.0, 0.0).is_none());
        // Far away sphere, small radius: no catastrophic cancellation.
        let far = DVec3::new(0.0, 0.0, 1e6);
        let t_far = ray_sphere_t(DVec3::ZERO, DVec3::Z * 2.0, far, 0.5, 0.0).unwrap();
        assert!((t_far - (1e6 - 0.5) / 2.0).abs() < 1e-9 * t_far);
    }
}
