//! `parallax town NAME [--seed S] [--sequence N] --trajectory COUNT`: the
//! ego pose of the drive's first COUNT town frames as JSON lines.

use super::CliError;
use crate::town::traffic::{ego_pose, DRIVE_WINDOW_FRAMES};
use crate::town::NamedTown;

/// The most frames `--trajectory` prints (one drive's traffic window).
pub const MAX_FRAMES: u64 = DRIVE_WINDOW_FRAMES - 7;

/// Checks COUNT before any work.
pub fn check_count(count: u64) -> Result<(), CliError> {
    if (1..=MAX_FRAMES).contains(&count) {
        Ok(())
    } else {
        Err(CliError::input(format!(
            "--trajectory {count}: COUNT must be a frame count from 1 to {MAX_FRAMES}"
        )))
    }
}

/// One JSON line per frame k < `count` of drive `drive`: `frame` k,
/// `time` k / fps (seconds since the drive's start), `position` [x, y, z]
/// (world metres, the centre of the ego's footprint on the ground),
/// `rotation` [roll, pitch, yaw] degrees (yaw counter-clockwise from +x
/// about +z, pitch nose-up, roll > 0 with the left side higher), `speed`
/// (m/s over the last frame).
pub fn lines(town: &NamedTown, seed: u64, drive: u64, count: u64) -> Vec<String> {
    (0..count)
        .map(|k| {
            let (v, speed) = ego_pose(&town.desc, seed, drive, k);
            serde_json::json!({
                "frame": k,
                "time": k as f64 / town.desc.fps,
                "position": v.position,
                "rotation": [v.roll_deg, v.pitch_deg, v.heading_deg],
                "speed": speed,
            })
            .to_string()
        })
        .collect()
}
