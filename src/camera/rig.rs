//! The stereo rig: the left camera is the reference; each right camera has the
//! same rotation and intrinsics and its centre at C_L + B·x_L (GROUND_TRUTH.md).
//! Roll, pitch and yaw move the whole rig; baselines stay on the rig's own x axis.

use glam::{DMat3, DVec3};

use super::{Camera, Intrinsics};

/// A rectified stereo rig with one left camera and one right camera per baseline.
#[derive(Clone, Debug, PartialEq)]
pub struct StereoRig {
    /// The reference (left) camera.
    pub left: Camera,
    /// Baselines in metres, in the order of the description.
    pub baselines_m: Vec<f64>,
}

/// Rotation world_from_camera for a heading, downward pitch and roll (radians).
///
/// At zero angles the camera looks along world +x with image x to world −y and
/// image y to world −z. Pitch rotates about the camera's x axis (down for > 0),
/// roll about its optical axis (image x towards image y for > 0, i.e. clockwise
/// seen from behind), yaw about world z.
pub fn world_from_camera_rotation(yaw_rad: f64, pitch_rad: f64, roll_rad: f64) -> DMat3 {
    let level = DMat3::from_cols(DVec3::NEG_Y, DVec3::NEG_Z, DVec3::X);
    // Rotating about camera x by −pitch turns +z (forward) towards +y (down).
    DMat3::from_rotation_z(yaw_rad)
        * level
        * DMat3::from_rotation_x(-pitch_rad)
        * DMat3::from_rotation_z(roll_rad)
}

impl StereoRig {
    /// A rig whose left camera has `intrinsics`, sits at `center_world` and
    /// is turned by heading `yaw_rad`, downward pitch `pitch_rad` and roll
    /// `roll_rad` ([`world_from_camera_rotation`]); one right camera per
    /// baseline (metres, in order) along the left camera's x axis.
    pub fn new(
        intrinsics: Intrinsics,
        center_world: DVec3,
        [yaw_rad, pitch_rad, roll_rad]: [f64; 3],
        baselines_m: Vec<f64>,
    ) -> Self {
        let left = Camera {
            intrinsics,
            world_from_camera: world_from_camera_rotation(yaw_rad, pitch_rad, roll_rad),
            center_world,
        };
        StereoRig { left, baselines_m }
    }

    /// The right camera for baseline `index`.
    pub fn right(&self, index: usize) -> Camera {
        let x_left = self.left.world_from_camera.x_axis;
        Camera {
            center_world: self.left.center_world + x_left * self.baselines_m[index],
            ..self.left
        }
    }

    /// Every view of the frame: the left camera, then one right camera per baseline.
    pub fn views(&self) -> Vec<Camera> {
        std::iter::once(self.left)
            .chain((0..self.baselines_m.len()).map(|b| self.right(b)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rig of a 1600×900, 60° camera at (1, 2, 1.65) with baselines
    /// 10 and 54 cm, turned by the given angles in degrees.
    fn rig(yaw: f64, pitch: f64, roll: f64) -> StereoRig {
        StereoRig::new(
            Intrinsics::from_hfov(1600, 900, 60f64.to_radians()),
            DVec3::new(1.0, 2.0, 1.65),
            [yaw, pitch, roll].map(f64::to_radians),
            vec![0.10, 0.54],
        )
    }

    #[test]
    fn level_rig_looks_along_x_with_z_up() {
        let rig = rig(0.0, 0.0, 0.0);
        let r = rig.left.world_from_camera;
        assert!((r.z_axis - DVec3::X).length() < 1e-12);
        assert!((r.y_axis - DVec3::NEG_Z).length() < 1e-12);
        // Right camera sits to the right of the left one: world −y.
        let c = rig.right(1).center_world - rig.left.center_world;
        assert!((c - DVec3::new(0.0, -0.54, 0.0)).length() < 1e-12);
    }

    #[test]
    fn pitch_tilts_forward_down_and_roll_keeps_baseline_on_rig_x() {
        let rig = rig(30.0, 30.0, 15.0);
        let r = rig.left.world_from_camera;
        assert!((r.z_axis.z - (-0.5)).abs() < 1e-12, "30° down");
        assert!((r.determinant() - 1.0).abs() < 1e-12);
        let b = rig.right(0).center_world - rig.left.center_world;
        assert!((b.normalize() - r.x_axis).length() < 1e-12);
        // Same point seen by both cameras sits on the same image row.
        let p = rig.left.center_world + r * DVec3::new(0.3, -0.2, 12.0);
        let (ql, qr) = (rig.left.project_world(p), rig.right(0).project_world(p));
        assert!((ql.y - qr.y).abs() < 1e-9 && ql.x > qr.x);
    }

    #[test]
    fn positive_roll_turns_image_x_towards_image_down() {
        let rig = rig(0.0, 0.0, 10.0);
        // Image x axis tilts towards world −z (down) on the right side.
        assert!(rig.left.world_from_camera.x_axis.z < 0.0);
    }
}
