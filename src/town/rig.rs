//! Camera configurations on the ego vehicle (DATASET.md): `normal` (left
//! camera 1.65 m above the road, level), `roll05`/`roll15`/`roll30` (normal,
//! rolled 5/15/30°), `pitch00` (10 m above the road at the ego, level),
//! `pitch30` (10 m up, pitched 30° down). The left camera sits above the
//! centre of the ego's footprint and looks along its heading.

use std::fmt;
use std::str::FromStr;

use crate::scene::desc::RigDesc;

use super::traffic::VehiclePose;

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
/// the default baselines (the scene's `[camera]` defaults).
pub fn rig_desc(config: CameraConfig, ego: &VehiclePose) -> RigDesc {
    let (height_m, pitch_deg, roll_deg) = config.pose();
    RigDesc {
        width: 1600,
        height: 900,
        hfov_deg: 60.0,
        baselines_cm: vec![10.0, 54.0, 100.0, 200.0, 300.0],
        position: [ego.position[0], ego.position[1], ego.position[2] + height_m],
        yaw_deg: ego.heading_deg,
        pitch_deg,
        roll_deg,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::vehicles::BodyKind;

    #[test]
    fn names_round_trip_and_rigs_sit_on_the_ego() {
        let ego = VehiclePose {
            id: 1,
            body: BodyKind::Sedan,
            paint: "paint_red",
            position: [10.0, -1.75, 0.0],
            heading_deg: 90.0,
            lane: 0,
        };
        for c in CONFIGS {
            assert_eq!(c.name().parse::<CameraConfig>(), Ok(c));
            let r = rig_desc(c, &ego);
            let (h, pitch, roll) = c.pose();
            assert_eq!(r.position, [10.0, -1.75, h]);
            assert_eq!((r.yaw_deg, r.pitch_deg, r.roll_deg), (90.0, pitch, roll));
        }
        assert_eq!(CameraConfig::Roll30.pose(), (1.65, 0.0, 30.0));
        assert_eq!(CameraConfig::Pitch30.pose(), (10.0, 30.0, 0.0));
    }
}
