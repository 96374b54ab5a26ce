//! Pinhole cameras and the stereo rig (GROUND_TRUTH.md "Camera", "Stereo rig").
//!
//! Camera frame is OpenCV's: x right, y down, z forward; world is right-handed,
//! z up, metres. Pixel (i, j) has its centre at (i + 0.5, j + 0.5) and the ray
//! through image point (u, v) has camera-frame direction ((u−cx)/f, (v−cy)/f, 1),
//! so the ray parameter of a hit along that (unnormalised) direction IS depth_z.
//! Cameras are pure geometry: they own no film and read no description (the
//! scene description builds its rig from plain values). Also the rig's
//! baseline-folder rule (`baseline`).

mod baseline;
mod rig;

pub use baseline::{baseline_dir_name, check_baseline_dirs, SharedBaselineDir};
pub use rig::StereoRig;

use glam::{DMat3, DVec2, DVec3};

/// Pinhole intrinsics: square pixels, no skew, principal point at the centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intrinsics {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Focal length in pixels (fx = fy).
    pub f_px: f64,
    /// Principal point x, pixels (= width / 2).
    pub cx_px: f64,
    /// Principal point y, pixels (= height / 2).
    pub cy_px: f64,
}

impl Intrinsics {
    /// Intrinsics for a horizontal field of view in radians, in (0, π).
    pub fn from_hfov(width: u32, height: u32, hfov_rad: f64) -> Self {
        let f_px = (width as f64 / 2.0) / (hfov_rad / 2.0).tan();
        Intrinsics {
            width,
            height,
            f_px,
            cx_px: width as f64 / 2.0,
            cy_px: height as f64 / 2.0,
        }
    }

    /// Horizontal field of view in radians.
    pub fn hfov_rad(&self) -> f64 {
        2.0 * (self.width as f64 / 2.0 / self.f_px).atan()
    }

    /// The 3×3 matrix K, row-major.
    pub fn k_matrix(&self) -> [[f64; 3]; 3] {
        [
            [self.f_px, 0.0, self.cx_px],
            [0.0, self.f_px, self.cy_px],
            [0.0, 0.0, 1.0],
        ]
    }

    /// Camera-frame direction (z = 1) through image point (u, v) in pixels.
    pub fn dir_cam(&self, u: f64, v: f64) -> DVec3 {
        DVec3::new(
            (u - self.cx_px) / self.f_px,
            (v - self.cy_px) / self.f_px,
            1.0,
        )
    }

    /// Image point of a camera-frame point (z > 0 for points in front).
    pub fn project(&self, p_cam: DVec3) -> DVec2 {
        DVec2::new(
            self.f_px * p_cam.x / p_cam.z + self.cx_px,
            self.f_px * p_cam.y / p_cam.z + self.cy_px,
        )
    }
}

/// One posed pinhole camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Intrinsics shared by every camera of a rig.
    pub intrinsics: Intrinsics,
    /// Rotation taking camera-frame vectors to world vectors (columns: camera axes).
    pub world_from_camera: DMat3,
    /// Camera centre, world metres.
    pub center_world: DVec3,
}

impl Camera {
    /// World direction (unnormalised, camera z component 1) through pixel centre (i, j).
    pub fn pixel_center_dir_world(&self, i: u32, j: u32) -> DVec3 {
        self.dir_world(i as f64 + 0.5, j as f64 + 0.5)
    }

    /// World direction (camera z component 1) through image point (u, v).
    pub fn dir_world(&self, u: f64, v: f64) -> DVec3 {
        self.world_from_camera * self.intrinsics.dir_cam(u, v)
    }

    /// Camera-frame coordinates of a world point.
    pub fn cam_from_world(&self, p_world: DVec3) -> DVec3 {
        self.world_from_camera.transpose() * (p_world - self.center_world)
    }

    /// Image point of a world point (meaningful when it lies in front: z > 0).
    pub fn project_world(&self, p_world: DVec3) -> DVec2 {
        self.intrinsics.project(self.cam_from_world(p_world))
    }

    /// The optical axis (camera +z) in world coordinates.
    pub fn forward_world(&self) -> DVec3 {
        self.world_from_camera.z_axis
    }

    /// 4×4 world-from-camera pose, row-major (for metadata files).
    pub fn pose_matrix(&self) -> [[f64; 4]; 4] {
        let r = self.world_from_camera;
        let c = self.center_world;
        [
            [r.x_axis.x, r.y_axis.x, r.z_axis.x, c.x],
            [r.x_axis.y, r.y_axis.y, r.z_axis.y, c.y],
            [r.x_axis.z, r.y_axis.z, r.z_axis.z, c.z],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn focal_length_matches_stereocarla_for_60_degrees() {
        let k = Intrinsics::from_hfov(1600, 900, 60f64.to_radians());
        assert!((k.f_px - 1385.6406460551018).abs() < 1e-9);
        assert!((k.hfov_rad() - 60f64.to_radians()).abs() < 1e-12);
        assert_eq!((k.cx_px, k.cy_px), (800.0, 450.0));
    }

    #[test]
    fn projection_inverts_pixel_rays() {
        let k = Intrinsics::from_hfov(640, 480, 1.1);
        for &(u, v) in &[(0.5, 0.5), (320.0, 240.0), (639.5, 12.25)] {
            let p = k.dir_cam(u, v) * 7.3;
            let q = k.project(p);
            assert!((q.x - u).abs() < 1e-9 && (q.y - v).abs() < 1e-9);
        }
    }
}
