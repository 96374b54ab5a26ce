//! The `[camera]` checks: image size, field of view, baselines and their
//! folders (`camera::check_baseline_dirs`), pose ranges, and the resource
//! guards on pixels and frame memory, all before anything is allocated.

use std::path::Path;

use crate::scene::desc::{num, RigDesc};
use crate::scene::load::{SceneError, SceneErrorKind as K};
use crate::scene::mesh::MAX_COORD_M;
use crate::scene::ranges::V;

/// Largest accepted image, pixels (64 megapixels).
pub const MAX_PIXELS: u64 = 64_000_000;
/// Bytes of film and ground-truth buffers of one frame: per view (left and
/// one right per baseline) f64 RGB accumulation 24, f32 RGB 12, depth 4,
/// normal 12, semantic 1, instance 2, mask 1 (56 with padding); per baseline
/// a left and a right disparity (4) and occlusion (1) (8 each with padding).
pub fn frame_bytes(rig: &RigDesc) -> u64 {
    let baselines = rig.baselines_cm.len() as u64;
    let per_pixel = (1 + baselines) * 56 + 2 * baselines * 8;
    rig.width as u64 * rig.height as u64 * per_pixel
}

/// Validates a rig on its own (e.g. after command-line overrides), naming `file`.
pub fn check_rig(rig: &RigDesc, file: &Path) -> Result<(), SceneError> {
    V { file }.rig(rig)
}

impl V<'_> {
    /// The `[camera]` table: image size, field of view, baselines (and
    /// their folders), pose, and the frame's pixel and memory budget.
    pub(super) fn rig(&self, rig: &RigDesc) -> Result<(), SceneError> {
        if rig.width == 0 || rig.height == 0 {
            let key = if rig.width == 0 {
                "camera.width"
            } else {
                "camera.height"
            };
            return Err(self.err(key, "image size must be at least 1 pixel"));
        }
        self.finite("camera.hfov_deg", &[rig.hfov_deg])?;
        if !(rig.hfov_deg > 0.0 && rig.hfov_deg < 180.0) {
            return Err(self.err(
                "camera.hfov_deg",
                format!("must be in (0, 180), got {}", num(rig.hfov_deg)),
            ));
        }
        if rig.baselines_cm.is_empty() {
            return Err(self.err("camera.baselines_cm", "at least one baseline is needed"));
        }
        self.positive("camera.baselines_cm", &rig.baselines_cm)?;
        // Centimetres: the right camera stays within the coordinate limit.
        self.range(
            "camera.baselines_cm",
            &rig.baselines_cm,
            0.0,
            MAX_COORD_M * 100.0,
        )?;
        crate::camera::check_baseline_dirs(&rig.baselines_cm)
            .map_err(|e| self.err(format!("camera.baselines_cm[{}]", e.index), e.to_string()))?;
        self.coord("camera.position", &rig.position)?;
        self.finite("camera.yaw_deg", &[rig.yaw_deg])?;
        self.range("camera.pitch_deg", &[rig.pitch_deg], -90.0, 90.0)?;
        self.range("camera.roll_deg", &[rig.roll_deg], -180.0, 180.0)?;
        let pixels = rig.width as u64 * rig.height as u64;
        if pixels > MAX_PIXELS {
            return Err(SceneError::at(
                self.file,
                K::Resource,
                "camera.width",
                format!(
                    "{}×{} = {pixels} pixels exceeds the limit of {MAX_PIXELS} pixels",
                    rig.width, rig.height
                ),
            ));
        }
        let need = frame_bytes(rig);
        if let Some(avail) = available_memory_bytes() {
            if need > avail {
                return Err(SceneError::at(
                    self.file,
                    K::Resource,
                    "camera.width",
                    format!(
                        "film and ground-truth buffers for {}×{} with {} baselines need {:.1} GiB, only {:.1} GiB of memory is available",
                        rig.width,
                        rig.height,
                        rig.baselines_cm.len(),
                        need as f64 / (1u64 << 30) as f64,
                        avail as f64 / (1u64 << 30) as f64
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// `MemAvailable` from /proc/meminfo, if readable.
fn available_memory_bytes() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}
