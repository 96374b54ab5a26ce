//! Integrators: the exact ground-truth pass (`gt`), the path tracer
//! (`path`, and `volpath` in scenes with a medium) with the per-frame data
//! its paths share (`context`: [`Shading`], [`PathContext`]), the parts of
//! each sample the image-space denoiser needs (`denoise_parts`), and rain
//! streaks (`rain`).
//!
//! Both passes consume a `RenderCamera` — a camera re-expressed in render space — so
//! neither ever sees world coordinates; only `texture` turns a hit back into
//! a world position, so procedural albedo does not move with the rig.

mod aov;
mod context;
mod denoise_parts;
pub mod gt;
pub mod path;
pub mod rain;
pub mod volpath;

pub use aov::Aov;
pub use context::{PathContext, Shading};
pub use denoise_parts::{luminance, DenoiseSample, DenoiseSum, OPEN_RADIUS};

use glam::{DMat3, DVec3, Vec3};

use crate::accel::Ray;
use crate::camera::{Camera, Intrinsics};
use crate::sampler::SampleStream;

/// A camera placed in render space (world minus the scene's render origin).
#[derive(Clone, Copy, Debug)]
pub struct RenderCamera {
    /// Intrinsics.
    pub intrinsics: Intrinsics,
    /// Rotation camera → render (= world) orientation.
    pub render_from_camera: DMat3,
    /// Camera centre in render space, f64.
    pub center: DVec3,
}

impl RenderCamera {
    /// Expresses `camera` relative to `origin_world`.
    pub fn new(camera: &Camera, origin_world: DVec3) -> Self {
        RenderCamera {
            intrinsics: camera.intrinsics,
            render_from_camera: camera.world_from_camera,
            center: camera.center_world - origin_world,
        }
    }

    /// Render-space direction through image point (u, v), with camera z = 1.
    pub fn dir(&self, u: f64, v: f64) -> DVec3 {
        self.render_from_camera * self.intrinsics.dir_cam(u, v)
    }

    /// The direction through every pixel centre, tabulated (see [`CentreDirs`]).
    pub fn centre_dirs(&self) -> CentreDirs {
        let k = &self.intrinsics;
        let axis = |n: u32, c: f64| (0..n).map(|i| (i as f64 + 0.5 - c) / k.f_px).collect();
        CentreDirs {
            render_from_camera: self.render_from_camera,
            x: axis(k.width, k.cx_px),
            y: axis(k.height, k.cy_px),
        }
    }

    /// The cone of the camera ray of unit render-space direction `d`
    /// (`path::RayCone`): width 0 at the pinhole, spread cos^1.5 θ / f, the
    /// side of a square of its pixel's solid angle (θ off the optical axis).
    pub fn cone(&self, d: Vec3) -> path::RayCone {
        let cos = d
            .as_dvec3()
            .dot(self.render_from_camera.z_axis)
            .clamp(0.0, 1.0);
        path::RayCone::primary((cos * cos.sqrt() / self.intrinsics.f_px) as f32)
    }

    /// The camera centre rounded to f32, as ray origin for traversal.
    pub fn center_f32(&self) -> Vec3 {
        self.center.as_vec3()
    }

    /// The path pass's camera ray through pixel (i, j), jittered inside the
    /// pixel by the stream's next 2D sample (its first, for a new stream).
    pub fn jittered_ray(&self, i: u32, j: u32, stream: &mut SampleStream) -> Ray {
        let jitter = stream.next_2d();
        let d = self
            .dir(i as f64 + jitter.x as f64, j as f64 + jitter.y as f64)
            .as_vec3()
            .normalize();
        Ray::new(self.center_f32(), d)
    }
}

/// A camera's pixel-centre directions: the camera-frame coordinates
/// (u − cx)/f of every column and (v − cy)/f of every row, divided once per
/// column and row instead of twice per pixel. [`CentreDirs::dir`] gives the
/// bits of `RenderCamera::dir(i + 0.5, j + 0.5)`.
#[derive(Clone, Debug)]
pub struct CentreDirs {
    render_from_camera: DMat3,
    x: Vec<f64>,
    y: Vec<f64>,
}

impl CentreDirs {
    /// Render-space direction (camera z = 1) through the centre of pixel (i, j).
    #[inline]
    pub fn dir(&self, i: usize, j: usize) -> DVec3 {
        self.render_from_camera * DVec3::new(self.x[i], self.y[j], 1.0)
    }
}

/// The scene's rain field seeded for one frame: streak positions are a pure
/// function of (seed, frame, world cell), the same in every view; streaks
/// are pre-filtered to pixels of `f_px` pixels per unit focal length.
pub fn frame_rain(
    scene: &crate::scene::Scene,
    seed: u64,
    frame: u32,
    f_px: f64,
) -> Option<shaders_cpu::medium::Rain> {
    let seed = crate::sampler::hash_words(&[seed, frame as u64, 0x7261_696e]);
    scene.rain.map(|r| r.for_frame(seed, 1.0 / f_px))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Intrinsics;

    #[test]
    fn centre_dirs_give_the_bits_of_dir_through_every_pixel_centre() {
        // An odd size (principal point on a pixel centre) and a yawed,
        // pitched, rolled camera, so every matrix entry takes part.
        let (yaw, pitch, roll) = (0.3f64, -0.2f64, 0.1f64);
        let camera = Camera {
            intrinsics: Intrinsics::from_hfov(37, 21, 1.1),
            world_from_camera: DMat3::from_rotation_z(yaw)
                * DMat3::from_rotation_y(pitch)
                * DMat3::from_rotation_x(roll),
            center_world: DVec3::new(1.0e5, -2.0e5, 12.0),
        };
        let cam = RenderCamera::new(&camera, DVec3::new(1.0e5, -2.0e5, 0.0));
        let table = cam.centre_dirs();
        for j in 0..21 {
            for i in 0..37 {
                let expect = cam.dir(i as f64 + 0.5, j as f64 + 0.5);
                assert_eq!(
                    table.dir(i, j).to_array().map(f64::to_bits),
                    expect.to_array().map(f64::to_bits),
                    "pixel ({i}, {j})"
                );
            }
        }
    }

    #[test]
    fn a_camera_rays_footprint_on_a_facing_wall_is_its_pixels_projection() {
        // A wall parallel to the image plane at depth D: every pixel
        // projects onto it as a square of side D / f, whatever the ray's
        // angle off the axis (the slant lengthens the ray by 1/cos θ and
        // the patch by 1/cos θ in area). A yawed, pitched, rolled left
        // camera and a right camera 0.54 m along its x axis.
        let rot = DMat3::from_rotation_z(0.7)
            * DMat3::from_rotation_y(-0.25)
            * DMat3::from_rotation_x(0.15);
        let k = Intrinsics::from_hfov(64, 36, 1.6);
        let left = Camera {
            intrinsics: k,
            world_from_camera: rot,
            center_world: DVec3::new(300.0, -20.0, 1.6),
        };
        let right = Camera {
            center_world: left.center_world + rot.x_axis * 0.54,
            ..left
        };
        let origin = DVec3::new(290.0, -25.0, 0.0);
        for camera in [left, right] {
            let cam = RenderCamera::new(&camera, origin);
            let fwd = cam.render_from_camera.z_axis.as_vec3();
            for depth in [2.0f32, 17.0, 140.0] {
                let expect = depth / k.f_px as f32;
                for (u, v) in [
                    (0.5, 0.5),
                    (32.0, 18.0),
                    (63.9, 0.2),
                    (10.3, 35.0),
                    (50.0, 30.0),
                ] {
                    let d = cam.dir(u, v).as_vec3().normalize();
                    let cos = d.dot(fwd);
                    let t = depth / cos;
                    let got = cam.cone(d).footprint(t, -cos);
                    assert!(
                        (got / expect - 1.0).abs() < 1e-4,
                        "({u}, {v}) at depth {depth}: {got} vs {expect}"
                    );
                }
            }
        }
    }
}
