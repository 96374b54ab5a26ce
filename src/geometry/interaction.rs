//! `SurfaceInteraction`: a surface point as shading sees it (Mitsuba's
//! `SurfaceInteraction3f`): position with its f32 error bound, geometric and
//! shading normals, material index and labels, and the rays leaving it
//! without self-intersection. The scene builds it from an accelerator hit
//! (`scene::surface_interaction`).
//!
//! Normals are render-space (= world orientation) unit vectors; `n_geo` follows
//! the triangle winding (or points out of a sphere) and is not flipped here.

use glam::{Vec2, Vec3};

use super::offset::offset_ray_origin;
use super::Ray;

/// Everything shading needs to know about a surface point.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceInteraction {
    /// Hit point, render space.
    pub p: Vec3,
    /// Conservative absolute error bound of `p` per axis.
    pub p_error: Vec3,
    /// Unit geometric normal (winding order / outward for spheres).
    pub n_geo: Vec3,
    /// Unit shading normal, on the same side as `n_geo`.
    pub n_shading: Vec3,
    /// Texture coordinates (zero when the mesh has none).
    pub uv: Vec2,
    /// Material index into `Scene::materials`.
    pub material: u32,
    /// Semantic class id.
    pub semantic: u8,
    /// Instance id.
    pub instance: u16,
}

impl SurfaceInteraction {
    /// Origin for a ray leaving this point towards `w` (no self-intersection).
    pub fn spawn_origin(&self, w: Vec3) -> Vec3 {
        offset_ray_origin(self.p, self.p_error, self.n_geo, w)
    }

    /// A ray leaving this point towards direction `w`.
    pub fn spawn_ray(&self, w: Vec3) -> Ray {
        Ray::new(self.spawn_origin(w), w)
    }

    /// A shadow ray from this point to `target` (exclusive, by a relative margin).
    pub fn spawn_ray_to(&self, target: Vec3) -> Ray {
        segment_to(self.spawn_origin(target - self.p), target)
    }

    /// The origin of every ray leaving the side `n_geo` points to: `w` enters
    /// [`offset_ray_origin`] only through the sign of w·n_geo, so this is
    /// `spawn_origin(w)` for every w with w·n_geo ≥ 0. A vertex that spawns
    /// several rays computes it once ([`FrontOrigin`]).
    pub fn front_origin(&self) -> FrontOrigin {
        FrontOrigin(self.spawn_origin(self.n_geo))
    }
}

/// A surface point's front-side ray origin ([`SurfaceInteraction::front_origin`]):
/// its spawn methods give the bits of the `SurfaceInteraction` ones, with
/// the offset computed once for every ray that leaves the front side.
#[derive(Clone, Copy, Debug)]
pub struct FrontOrigin(Vec3);

impl FrontOrigin {
    /// [`SurfaceInteraction::spawn_origin`] of `si` (whose front origin this is).
    #[inline]
    pub fn spawn_origin(self, si: &SurfaceInteraction, w: Vec3) -> Vec3 {
        if w.dot(si.n_geo) < 0.0 {
            si.spawn_origin(w)
        } else {
            self.0
        }
    }

    /// [`SurfaceInteraction::spawn_ray`] of `si`.
    #[inline]
    pub fn spawn_ray(self, si: &SurfaceInteraction, w: Vec3) -> Ray {
        Ray::new(self.spawn_origin(si, w), w)
    }

    /// [`SurfaceInteraction::spawn_ray_to`] of `si`.
    #[inline]
    pub fn spawn_ray_to(self, si: &SurfaceInteraction, target: Vec3) -> Ray {
        segment_to(self.spawn_origin(si, target - si.p), target)
    }
}

/// The shadow segment from `o` to `target`, stopping a relative 1e-4 short
/// so the target's own surface does not count as a blocker.
fn segment_to(o: Vec3, target: Vec3) -> Ray {
    Ray::segment(o, target - o, 1.0 - 1e-4)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::position_error;

    /// A point far from the origin on a tilted triangle, so the offset is
    /// large enough that every rounding of it shows.
    fn interaction() -> SurfaceInteraction {
        let p = [
            Vec3::new(812.25, -40.5, 3.0),
            Vec3::new(813.0, -39.75, 3.5),
            Vec3::new(812.5, -40.0, 4.25),
        ];
        let b = [0.2f32, 0.3, 0.5];
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        SurfaceInteraction {
            p: p[0] * b[0] + p[1] * b[1] + p[2] * b[2],
            p_error: position_error(b, p),
            n_geo: n,
            n_shading: n,
            uv: Vec2::ZERO,
            material: 0,
            semantic: 0,
            instance: 0,
        }
    }

    #[test]
    fn front_origin_gives_the_bits_of_every_spawn_method_on_both_sides() {
        let si = interaction();
        let front = si.front_origin();
        // Directions on both sides, grazing ones and the plane's own tangent.
        let tangent = si.n_geo.any_orthonormal_vector();
        let mut dirs = vec![si.n_geo, -si.n_geo, tangent, -tangent];
        for k in 0..64 {
            let a = k as f32 * 0.7;
            let w = Vec3::new(a.cos(), a.sin(), (a * 1.3).sin() - 0.2).normalize();
            dirs.push(w);
            dirs.push(tangent + si.n_geo * (1e-6 * (k as f32 - 32.0)));
        }
        let (mut front_side, mut back_side) = (0, 0);
        for w in dirs {
            if w.dot(si.n_geo) < 0.0 {
                back_side += 1;
            } else {
                front_side += 1;
            }
            let o = si.spawn_origin(w);
            assert_eq!(
                front.spawn_origin(&si, w).to_array().map(f32::to_bits),
                o.to_array().map(f32::to_bits),
                "w {w}"
            );
            assert_eq!(front.spawn_ray(&si, w), si.spawn_ray(w));
            let target = si.p + w * 7.5;
            assert_eq!(front.spawn_ray_to(&si, target), si.spawn_ray_to(target));
        }
        assert!(
            front_side > 10 && back_side > 10,
            "{front_side} / {back_side}"
        );
        // The two sides' origins differ: the cache must not serve the back side.
        assert_ne!(si.spawn_origin(si.n_geo), si.spawn_origin(-si.n_geo));
    }
}
