//! The one place the dataset loop calls the layout writers. `native` is
//! written by the run itself (`output::frame::write_native_frame`); every other
//! layout (stereocarla, kitti, sceneflow) is written from the same render by
//! `output::layouts`, each below its own directory `<root>/<layout>/`.
//!
//! Split lists name the PLANNED frames (a pure function of the configuration),
//! so every shard writes the same bytes and the union of shards equals a
//! one-shard run; `verify` checks the frames, not the lists.

use std::io;
use std::path::{Path, PathBuf};

use super::config::DatasetConfig;
use super::plan::{plan, Job};
use crate::camera::StereoRig;
use crate::output::frame::CameraFile;
use crate::output::layouts::{write_layout_frame, write_layout_index, FrameKey, LayoutKind};
use crate::render::FrameOutput;

/// Directory holding a layout's split lists, below the layout's own root.
const SPLITS_DIR: &str = "splits";

/// The layouts of `kinds` other than `native`.
pub(super) fn extra_kinds(kinds: &[LayoutKind]) -> impl Iterator<Item = LayoutKind> + '_ {
    kinds.iter().copied().filter(|k| *k != LayoutKind::Native)
}

/// The layouts' key of a planned frame.
pub(super) fn frame_key(job: &Job) -> FrameKey {
    FrameKey {
        town: job.town.clone(),
        config: job.config.name().to_string(),
        weather: job.weather.name().to_string(),
        sequence: job.sequence,
        frame: job.frame,
    }
}

/// Writes `job`'s frame in every layout of `kinds` other than `native` below
/// `root/<layout>/`; returns the paths written (all below `root`).
pub fn write_extra_layouts(
    kinds: &[LayoutKind],
    root: &Path,
    job: &Job,
    rig: &StereoRig,
    out: &FrameOutput,
    meta: &CameraFile,
) -> io::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for kind in extra_kinds(kinds) {
        let layout_root = root.join(kind.name());
        written.extend(write_layout_frame(
            kind,
            &layout_root,
            &frame_key(job),
            rig,
            out,
            meta,
        )?);
    }
    Ok(written)
}

/// Writes the split lists of every non-native layout for the whole plan.
pub fn write_layout_indexes(root: &Path, config: &DatasetConfig) -> io::Result<()> {
    let kinds: Vec<LayoutKind> = extra_kinds(&config.layouts).collect();
    if kinds.is_empty() {
        return Ok(());
    }
    let keys: Vec<FrameKey> = plan(config).iter().map(frame_key).collect();
    for kind in kinds {
        write_layout_index(kind, &root.join(kind.name()), &keys, &config.baselines_cm)?;
    }
    Ok(())
}

/// True for a root-relative path that is a layout's split list (not a frame file).
pub fn is_layout_index(rel: &Path) -> bool {
    let mut parts = rel.components().map(|c| c.as_os_str().to_string_lossy());
    match (parts.next(), parts.next()) {
        (Some(layout), Some(dir)) => {
            let extra = layout
                .parse()
                .is_ok_and(|k: LayoutKind| k != LayoutKind::Native);
            extra && dir == SPLITS_DIR
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_lists_are_recognised_and_frames_are_not() {
        assert!(is_layout_index(Path::new(
            "stereocarla/splits/stereocarla_all.txt"
        )));
        assert!(is_layout_index(Path::new(
            "kitti/splits/kitti_baseline_010.txt"
        )));
        assert!(!is_layout_index(Path::new(
            "stereocarla/normal/town02/left/rgb/0000_000000.jpg"
        )));
        assert!(!is_layout_index(Path::new(
            "town02/normal_clear/0000/left/rgb/000000.png"
        )));
        assert!(!is_layout_index(Path::new("splits/x.txt")));
    }
}
