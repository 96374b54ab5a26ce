//! Ray–primitive intersection routines shared by the pure-Rust BVH and the
//! brute-force reference, so both backends agree bit for bit per primitive.
//!
//! Triangles: the watertight test of Woop, Benthin and Wald, "Watertight
//! Ray/Triangle Intersection", JCGT 2(1), 2013 — shear into a ray-aligned frame,
//! 2D edge functions with an f64 fallback when one is exactly zero, so rays
//! through shared edges and vertices never fall through. Barycentrics follow
//! Embree (`u` weights vertex 1, `v` vertex 2). Spheres: the quadratic of Haines
//! et al., "Precision Improvements for Ray/Sphere Intersection", Ray Tracing
//! Gems ch. 7 (as in pbrt-v4's `Sphere::BasicIntersect`). Hits are accepted for
//! `tmin <= t <= tmax`; both faces count.

use glam::{Vec3, Vec4};

use super::Ray;
use crate::geometry::gamma;

/// A ray prepared for the watertight triangle test: the permutation that makes
/// `kz` the dominant direction axis and the shear constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightRay {
    /// Origin, render space.
    pub o: Vec3,
    /// Axis permutation (kx, ky, kz); `kz` is the largest |d| component.
    k: [usize; 3],
    /// Shear constants (Sx, Sy, Sz) of the paper.
    s: Vec3,
    /// Smallest accepted parameter.
    pub tmin: f32,
    /// Largest accepted parameter.
    pub tmax: f32,
}

impl WatertightRay {
    /// Precomputes the shear for `ray` (once per ray, not per triangle).
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        let d = ray.d;
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        // Swap kx and ky to preserve the winding (and thus the sign of det).
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let sz = 1.0 / d[kz];
        WatertightRay {
            o: ray.o,
            k: [kx, ky, kz],
            s: Vec3::new(d[kx] * sz, d[ky] * sz, sz),
            tmin: ray.tmin,
            tmax: ray.tmax,
        }
    }
}

/// A triangle hit: parameter and Embree-convention barycentrics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TriHit {
    /// Ray parameter.
    pub t: f32,
    /// Weight of vertex 1.
    pub u: f32,
    /// Weight of vertex 2.
    pub v: f32,
}

/// Watertight ray/triangle intersection (Woop et al. 2013, fig. 4/5) over the
/// closed interval `[ray.tmin, ray.tmax]`; either face is hit.
#[inline]
pub(crate) fn intersect_triangle(
    ray: &WatertightRay,
    p0: Vec3,
    p1: Vec3,
    p2: Vec3,
) -> Option<TriHit> {
    let [kx, ky, kz] = ray.k;
    let a = p0 - ray.o;
    let b = p1 - ray.o;
    let c = p2 - ray.o;
    // Shear and scale the vertices into the ray frame (ray along +z).
    let ax = a[kx] - ray.s.x * a[kz];
    let ay = a[ky] - ray.s.y * a[kz];
    let bx = b[kx] - ray.s.x * b[kz];
    let by = b[ky] - ray.s.y * b[kz];
    let cx = c[kx] - ray.s.x * c[kz];
    let cy = c[ky] - ray.s.y * c[kz];
    // Scaled barycentrics: e0 weights vertex 0 (edge p1 p2), e1 vertex 1, e2 vertex 2.
    let mut e0 = cx * by - cy * bx;
    let mut e1 = ax * cy - ay * cx;
    let mut e2 = bx * ay - by * ax;
    // An exactly-zero edge function is where f32 rounding could disagree between
    // neighbouring triangles: redo it in f64 so a shared edge is classified the
    // same way from both sides (section 3.2 of the paper).
    if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
        let (axd, ayd, bxd, byd, cxd, cyd) = (
            ax as f64, ay as f64, bx as f64, by as f64, cx as f64, cy as f64,
        );
        e0 = (cxd * byd - cyd * bxd) as f32;
        e1 = (axd * cyd - ayd * cxd) as f32;
        e2 = (bxd * ayd - byd * axd) as f32;
    }
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return None;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 {
        // Ray parallel to (or in the plane of) the triangle.
        return None;
    }
    let az = ray.s.z * a[kz];
    let bz = ray.s.z * b[kz];
    let cz = ray.s.z * c[kz];
    let t_scaled = e0 * az + e1 * bz + e2 * cz;
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    if !(t >= ray.tmin && t <= ray.tmax) {
        return None;
    }
    // Reject hits whose t is not conservatively positive (pbrt-v4 §6.5.3,
    // "Ensuring a conservative t"): a ray spawned at an error-bounded origin
    // must not re-hit the surface it leaves through rounding in this test.
    if t <= conservative_t_error(ax, ay, az, bx, by, bz, cx, cy, cz, [e0, e1, e2], inv_det) {
        return None;
    }
    Some(TriHit {
        t,
        u: e1 * inv_det,
        v: e2 * inv_det,
    })
}

/// Bound on the rounding error of the watertight test's t (pbrt-v4 §6.8.4,
/// `Triangle::Intersect`), from the sheared vertex coordinates.
#[allow(clippy::too_many_arguments)]
#[inline]
fn conservative_t_error(
    ax: f32,
    ay: f32,
    az: f32,
    bx: f32,
    by: f32,
    bz: f32,
    cx: f32,
    cy: f32,
    cz: f32,
    e: [f32; 3],
    inv_det: f32,
) -> f32 {
    let max_zt = az.abs().max(bz.abs()).max(cz.abs());
    let delta_z = gamma(3) * max_zt;
    let max_xt = ax.abs().max(bx.abs()).max(cx.abs());
    let max_yt = ay.abs().max(by.abs()).max(cy.abs());
    let delta_x = gamma(5) * (max_xt + max_zt);
    let delta_y = gamma(5) * (max_yt + max_zt);
    let delta_e = 2.0 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    let max_e = e[0].abs().max(e[1].abs()).max(e[2].abs());
    3.0 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * inv_det.abs()
}

/// Geometric normal of a triangle as Embree reports it: `(p1 − p0) × (p2 − p0)`,
/// not normalised.
#[inline]
pub(crate) fn triangle_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
    (p1 - p0).cross(p2 - p0)
}

/// Ray/sphere intersection over `[ray.tmin, ray.tmax]`: the nearer root if it is
/// in range, else the farther one (a ray starting inside hits the far side).
/// `sphere` is (centre xyz, radius w). Returns `t`.
#[inline]
pub(crate) fn intersect_sphere(ray: &Ray, sphere: Vec4) -> Option<f32> {
    let centre = sphere.truncate();
    let radius = sphere.w;
    let f = ray.o - centre;
    let a = ray.d.length_squared();
    if a == 0.0 {
        return None;
    }
    let beta = f.dot(ray.d);
    // Discriminant as a·(r² − |l|²), with l the closest-approach vector: this
    // avoids the cancellation in β² − a·c for far-away, small spheres (RTG ch. 7,
    // eq. 7.5); (r − |l|)(r + |l|) keeps r² − |l|² accurate near tangency.
    let l = f - (beta / a) * ray.d;
    let l_len = l.length();
    let disc = a * ((radius - l_len) * (radius + l_len));
    if disc < 0.0 {
        return None;
    }
    let c = f.length_squared() - radius * radius;
    // q has the sign of −β so the sum never cancels (RTG ch. 7, eq. 7.7).
    let q = -(beta + beta.signum() * disc.sqrt());
    let (mut t0, mut t1) = if q == 0.0 { (0.0, 0.0) } else { (c / q, q / a) };
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
    }
    if t0 >= ray.tmin && t0 <= ray.tmax {
        Some(t0)
    } else if t1 >= ray.tmin && t1 <= ray.tmax {
        Some(t1)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> [Vec3; 3] {
        [
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(1.0, 0.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0),
        ]
    }

    fn hit_tri(ray: Ray) -> Option<TriHit> {
        let [p0, p1, p2] = tri();
        intersect_triangle(&WatertightRay::new(&ray), p0, p1, p2)
    }

    #[test]
    fn triangle_hit_has_analytic_t_and_barycentrics() {
        let ray = Ray::new(Vec3::new(0.25, 0.5, 0.0), Vec3::new(0.0, 0.0, 1.0));
        let h = hit_tri(ray).unwrap();
        assert_eq!(h.t, 2.0);
        assert!((h.u - 0.25).abs() < 1e-7 && (h.v - 0.5).abs() < 1e-7);
        // Unnormalised direction: t scales inversely; from behind (−z) it still hits.
        let h2 = hit_tri(Ray::new(
            Vec3::new(0.25, 0.5, 6.0),
            Vec3::new(0.0, 0.0, -4.0),
        ))
        .unwrap();
        assert_eq!(h2.t, 1.0);
        assert!((h2.u - 0.25).abs() < 1e-7 && (h2.v - 0.5).abs() < 1e-7);
    }

    #[test]
    fn triangle_hit_point_reconstructs_from_barycentrics() {
        let [p0, p1, p2] = tri();
        let ray = Ray::new(Vec3::new(-1.0, -2.0, -3.0), Vec3::new(1.2, 2.3, 5.0));
        let h = hit_tri(ray).unwrap();
        let p_bary = (1.0 - h.u - h.v) * p0 + h.u * p1 + h.v * p2;
        assert!((ray.at(h.t) - p_bary).length() < 1e-5);
    }

    #[test]
    fn triangle_misses_outside_and_parallel() {
        assert!(hit_tri(Ray::new(Vec3::new(0.8, 0.8, 0.0), Vec3::Z)).is_none());
        // In the plane of the triangle, and parallel above it.
        assert!(hit_tri(Ray::new(Vec3::new(-1.0, 0.2, 2.0), Vec3::X)).is_none());
        assert!(hit_tri(Ray::new(
            Vec3::new(-1.0, 0.2, 1.0),
            Vec3::new(1.0, 0.1, 0.0)
        ))
        .is_none());
    }

    #[test]
    fn triangle_honours_tmin_and_tmax_inclusively() {
        let o = Vec3::new(0.2, 0.2, 0.0);
        assert!(hit_tri(Ray::segment(o, Vec3::Z, 1.999)).is_none());
        assert_eq!(hit_tri(Ray::segment(o, Vec3::Z, 2.0)).unwrap().t, 2.0);
        let mut ray = Ray::new(o, Vec3::Z);
        ray.tmin = 2.001;
        assert!(hit_tri(ray).is_none());
        ray.tmin = 2.0;
        assert_eq!(hit_tri(ray).unwrap().t, 2.0);
    }

    #[test]
    fn triangle_normal_follows_winding() {
        let [p0, p1, p2] = tri();
        assert_eq!(triangle_normal(p0, p1, p2), Vec3::Z);
        assert_eq!(triangle_normal(p0, p2, p1), -Vec3::Z);
    }

    #[test]
    fn sphere_hit_has_analytic_t_from_outside_and_inside() {
        let s = Vec4::new(0.0, 0.0, 10.0, 2.0);
        assert_eq!(
            intersect_sphere(&Ray::new(Vec3::ZERO, Vec3::Z), s),
            Some(8.0)
        );
        // Direction of length 2 halves t.
        assert_eq!(
            intersect_sphere(&Ray::new(Vec3::ZERO, 2.0 * Vec3::Z), s),
            Some(4.0)
        );
        // From the centre the far (only forward) root is returned.
        assert_eq!(
            intersect_sphere(&Ray::new(Vec3::new(0.0, 0.0, 10.0), Vec3::X), s),
            Some(2.0)
        );
        // Off-axis: hit at z where x² + (z−10)² = 4 with x = 1 → z = 10 − √3.
        let t = intersect_sphere(&Ray::new(Vec3::new(1.0, 0.0, 0.0), Vec3::Z), s).unwrap();
        assert!((t - (10.0 - 3f32.sqrt())).abs() < 1e-5);
    }

    #[test]
    fn sphere_misses_behind_beside_and_outside_segment() {
        let s = Vec4::new(0.0, 0.0, 10.0, 2.0);
        assert_eq!(intersect_sphere(&Ray::new(Vec3::ZERO, -Vec3::Z), s), None);
        assert_eq!(
            intersect_sphere(&Ray::new(Vec3::new(2.001, 0.0, 0.0), Vec3::Z), s),
            None
        );
        assert_eq!(
            intersect_sphere(&Ray::segment(Vec3::ZERO, Vec3::Z, 7.99), s),
            None
        );
        let mut ray = Ray::new(Vec3::ZERO, Vec3::Z);
        ray.tmin = 8.5;
        assert_eq!(intersect_sphere(&ray, s), Some(12.0));
        ray.tmin = 12.5;
        assert_eq!(intersect_sphere(&ray, s), None);
    }

    #[test]
    fn sphere_small_and_far_is_precise() {
        // A 1 cm sphere 1 km away: the naive β² − ac loses every digit.
        let s = Vec4::new(0.0, 0.0, 1000.0, 0.01);
        let t = intersect_sphere(&Ray::new(Vec3::new(0.005, 0.0, 0.0), Vec3::Z), s).unwrap();
        let expected = 1000.0 - (0.01f64 * 0.01 - 0.005 * 0.005).sqrt();
        assert!(((t as f64) - expected).abs() < 1e-4, "t = {t}");
    }
}
