//! `parallax town NAME [--seed S] [--sequence N] --trajectory COUNT`: the
//! ego pose of the drive's first COUNT town frames as JSON lines; and
//! `--coverage DRIVES`: the lane length drives 0..DRIVES pass.

use super::CliError;
use crate::town::traffic::coverage::coverage;
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

/// Town frames of one `stereocarla` preset sequence: 59 frames at stride 10.
pub const SEQUENCE_FRAMES: u64 = 59 * 10;

/// One line on the lane coverage of drives 0..`drives` (the preset plans
/// 6 configurations × 7 weathers × 7 sequences = 294 per town), each
/// `SEQUENCE_FRAMES` long.
pub fn coverage_line(town: &NamedTown, seed: u64, drives: u64) -> Result<String, CliError> {
    if !(1..=10_000).contains(&drives) {
        return Err(CliError::input(format!(
            "--coverage {drives}: DRIVES must be a drive count from 1 to 10000"
        )));
    }
    let c = coverage(&town.desc, seed, 0..drives, SEQUENCE_FRAMES);
    Ok(format!(
        "{} seed {seed}: lane length {:.0} m, covered {:.0} m ({:.1} %) by {} drives of {} frames ({} distinct), {:.2} junction turns per sequence",
        town.desc.name,
        c.lane_m,
        c.covered_m,
        100.0 * c.fraction(),
        c.drives,
        SEQUENCE_FRAMES,
        c.distinct_drives,
        c.turns_per_drive
    ))
}
