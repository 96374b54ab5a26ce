//! The `[camera]` description → `StereoRig` conversion: degrees and
//! centimetres of the file become the radians and metres the camera module
//! takes (camera reads no description; the description builds its rig).

use glam::DVec3;

use super::RigDesc;
use crate::camera::{Intrinsics, StereoRig};

impl StereoRig {
    /// Builds the rig of a description (validated upstream).
    pub fn from_desc(desc: &RigDesc) -> Self {
        StereoRig::new(
            Intrinsics::from_hfov(desc.width, desc.height, desc.hfov_deg.to_radians()),
            DVec3::from_array(desc.position),
            [desc.yaw_deg, desc.pitch_deg, desc.roll_deg].map(f64::to_radians),
            desc.baselines_cm.iter().map(|cm| cm / 100.0).collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn description_degrees_and_centimetres_become_radians_and_metres() {
        let desc = RigDesc {
            width: 160,
            height: 90,
            hfov_deg: 90.0,
            baselines_cm: vec![10.0, 54.0],
            position: [1.0, 2.0, 1.65],
            yaw_deg: 90.0,
            pitch_deg: 0.0,
            roll_deg: 0.0,
        };
        let rig = StereoRig::from_desc(&desc);
        assert_eq!(rig.baselines_m, vec![0.1, 0.54]);
        assert_eq!(rig.left.center_world, DVec3::new(1.0, 2.0, 1.65));
        // 90° field over 160 px: f = 80 / tan 45° = 80 px.
        assert!((rig.left.intrinsics.f_px - 80.0).abs() < 1e-9);
        // Heading 90°: looking along world +y, the right camera towards +x.
        let r = rig.left.world_from_camera;
        assert!((r.z_axis - DVec3::Y).length() < 1e-12, "{r}");
        let b = rig.right(1).center_world - rig.left.center_world;
        assert!((b - DVec3::new(0.54, 0.0, 0.0)).length() < 1e-12, "{b}");
    }
}
