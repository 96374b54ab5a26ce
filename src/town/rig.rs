//! Camera configurations on the ego vehicle (DATASET.md): `normal` (left
//! camera 1.65 m above the road, level), `roll05`/`roll15`/`roll30` (normal,
//! rolled 5/15/30°), `pitch00` (10 m above the road at the ego, level),
//! `pitch30` (10 m up, pitched 30° down). The left camera sits
//! `CAMERA_FORWARD_M` ahead of the centre of the ego's footprint, just in
//! front of the sedan's windscreen and 0.2 m above its roof height, and looks
//! along its heading: the bottom row (18° down) clears the bonnet, and the
//! right cameras of rolled rigs (up to 1.5 m lower) stay outside the cabin.

use std::fmt;
use std::str::FromStr;

use glam::{DMat3, DVec3, EulerRot};

use crate::scene::desc::RigDesc;

use super::traffic::VehiclePose;

/// How far ahead of the ego footprint's centre the cameras sit, metres.
pub const CAMERA_FORWARD_M: f64 = 1.1;

/// A camera configuration of the dataset.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraConfig {
    /// 1.65 m, level.
    Normal,
    /// 1.65 m, rolled 5°.
    Roll05,
    /// 1.65 m, rolled 15°.
    Roll15,
    /// 1.65 m, rolled 30°.
    Roll30,
    /// 10 m above the road, level.
    Pitch00,
    /// 10 m above the road, 30° down.
    Pitch30,
}

/// Every configuration, in DATASET.md order.
pub const CONFIGS: [CameraConfig; 6] = [
    CameraConfig::Normal,
    CameraConfig::Roll05,
    CameraConfig::Roll15,
    CameraConfig::Roll30,
    CameraConfig::Pitch00,
    CameraConfig::Pitch30,
];

impl CameraConfig {
    /// The name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            CameraConfig::Normal => "normal",
            CameraConfig::Roll05 => "roll05",
            CameraConfig::Roll15 => "roll15",
            CameraConfig::Roll30 => "roll30",
            CameraConfig::Pitch00 => "pitch00",
            CameraConfig::Pitch30 => "pitch30",
        }
    }

    /// (height above the road m, pitch down deg, roll deg).
    pub fn pose(self) -> (f64, f64, f64) {
        match self {
            CameraConfig::Normal => (1.65, 0.0, 0.0),
            CameraConfig::Roll05 => (1.65, 0.0, 5.0),
            CameraConfig::Roll15 => (1.65, 0.0, 15.0),
            CameraConfig::Roll30 => (1.65, 0.0, 30.0),
            CameraConfig::Pitch00 => (10.0, 0.0, 0.0),
            CameraConfig::Pitch30 => (10.0, 30.0, 0.0),
        }
    }
}

impl fmt::Display for CameraConfig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for CameraConfig {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        CONFIGS
            .iter()
            .copied()
            .find(|c| c.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = CONFIGS.iter().map(|c| c.name()).collect();
                format!(
                    "unknown camera configuration '{s}' (one of {})",
                    names.join(", ")
                )
            })
    }
}

/// The rig of `config` on the ego vehicle: 1600×900, 60° horizontal FOV and
/// the default baselines (the scene's `[camera]` defaults). On a grade the
/// rig rides the ego's body frame: its offset and its pitch and roll are
/// taken in the body frame Rz(heading)·Ry(−pitch)·Rx(roll) and turned back
/// into the rig's yaw, pitch and roll (the same Z-Y-X order).
pub fn rig_desc(config: CameraConfig, ego: &VehiclePose) -> RigDesc {
    if ego.pitch_deg != 0.0 || ego.roll_deg != 0.0 {
        return tilted_rig_desc(config, ego);
    }
    let (height_m, pitch_deg, roll_deg) = config.pose();
    let yaw = ego.heading_deg.to_radians();
    let (x, y) = (
        ego.position[0] + CAMERA_FORWARD_M * yaw.cos(),
        ego.position[1] + CAMERA_FORWARD_M * yaw.sin(),
    );
    RigDesc {
        width: 1600,
        height: 900,
        hfov_deg: 60.0,
        baselines_cm: vec![10.0, 54.0, 100.0, 200.0, 300.0],
        position: [x, y, ego.position[2] + height_m],
        yaw_deg: ego.heading_deg,
        pitch_deg,
        roll_deg,
    }
}

/// `rig_desc` for an ego pitched or rolled on a grade.
fn tilted_rig_desc(config: CameraConfig, ego: &VehiclePose) -> RigDesc {
    let (height_m, pitch_deg, roll_deg) = config.pose();
    let rot = super::grade::body_rotation_deg(ego.heading_deg, ego.pitch_deg, ego.roll_deg)
        .map(f64::to_radians);
    let body = DMat3::from_euler(EulerRot::ZYX, rot[2], rot[1], rot[0]);
    let p = DVec3::from(ego.position) + body * DVec3::new(CAMERA_FORWARD_M, 0.0, height_m);
    // The rig's rotation is Rz(yaw)·Ry(pitch down)·Rx(roll) ahead of its
    // fixed camera axes (`camera::rig::world_from_camera_rotation`).
    let cam = body
        * DMat3::from_euler(
            EulerRot::ZYX,
            0.0,
            pitch_deg.to_radians(),
            roll_deg.to_radians(),
        );
    let (yaw, pitch, roll) = cam.to_euler(EulerRot::ZYX);
    RigDesc {
        width: 1600,
        height: 900,
        hfov_deg: 60.0,
        baselines_cm: vec![10.0, 54.0, 100.0, 200.0, 300.0],
        position: p.to_array(),
        yaw_deg: yaw.to_degrees(),
        pitch_deg: pitch.to_degrees(),
        roll_deg: roll.to_degrees(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::vehicles::BodyKind;

    fn ego_level() -> VehiclePose {
        VehiclePose {
            id: 1,
            body: BodyKind::Sedan,
            paint: "paint_red",
            position: [10.0, -1.75, 0.0],
            heading_deg: 90.0,
            pitch_deg: 0.0,
            roll_deg: 0.0,
            route: 0,
            lamps: Default::default(),
        }
    }

    #[test]
    fn names_round_trip_and_rigs_sit_on_the_ego() {
        let ego = ego_level();
        for c in CONFIGS {
            assert_eq!(c.name().parse::<CameraConfig>(), Ok(c));
            let r = rig_desc(c, &ego);
            let (h, pitch, roll) = c.pose();
            // Heading 90°: the cameras sit 1.1 m further along +y.
            let p = r.position;
            assert!((p[0] - 10.0).abs() < 1e-12 && (p[1] + 0.65).abs() < 1e-12);
            assert_eq!(p[2], h);
            assert_eq!((r.yaw_deg, r.pitch_deg, r.roll_deg), (90.0, pitch, roll));
        }
        assert_eq!(CameraConfig::Roll30.pose(), (1.65, 0.0, 30.0));
        assert_eq!(CameraConfig::Pitch30.pose(), (10.0, 30.0, 0.0));
    }

    #[test]
    fn rig_on_a_tilted_ego_is_the_level_rig_turned_by_the_body() {
        use crate::camera::StereoRig;
        let turn = |yaw: f64, pitch: f64, roll: f64| {
            let mut d = rig_desc(CameraConfig::Normal, &ego_level());
            (d.yaw_deg, d.pitch_deg, d.roll_deg) = (yaw, pitch, roll);
            StereoRig::from_desc(&d).left.world_from_camera
        };
        let ego = VehiclePose {
            id: 1,
            body: BodyKind::Sedan,
            paint: "paint_red",
            position: [10.0, -1.75, 3.0],
            heading_deg: 120.0,
            pitch_deg: 2.5,
            roll_deg: -1.5,
            route: 0,
            lamps: Default::default(),
        };
        let r = crate::town::grade::body_rotation_deg(120.0, 2.5, -1.5).map(f64::to_radians);
        let body = DMat3::from_rotation_z(r[2])
            * DMat3::from_rotation_y(r[1])
            * DMat3::from_rotation_x(r[0]);
        for c in CONFIGS {
            let (h, pitch, roll) = c.pose();
            let rd = rig_desc(c, &ego);
            let got = turn(rd.yaw_deg, rd.pitch_deg, rd.roll_deg);
            let level = turn(0.0, pitch, roll);
            let want = body * level;
            assert!((got - want).abs_diff_eq(DMat3::ZERO, 1e-12), "{c}");
            let p = DVec3::from(rd.position) - DVec3::from(ego.position);
            assert!((p - body * DVec3::new(CAMERA_FORWARD_M, 0.0, h)).length() < 1e-12);
            // The nose-up ego lifts the camera's forward axis by its pitch.
            if c == CameraConfig::Normal {
                let f = got.z_axis;
                let up = f.z.asin().to_degrees();
                assert!((up - 2.5).abs() < 1e-9, "{up}");
            }
        }
    }
}
