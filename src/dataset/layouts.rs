//! The one place the dataset loop calls the layout writers. `native` is
//! written by the run itself (`output::frame::write_native_frame`); the other
//! layouts (stereocarla, kitti, sceneflow) are written from the same render
//! by `output::layouts` once that module exists.

use std::io;
use std::path::{Path, PathBuf};

use crate::camera::StereoRig;
use crate::output::frame::CameraFile;
use crate::render::FrameOutput;

/// Writes frame `frame` of (town, config, weather, sequence) in every layout
/// of `kinds` other than `native` below the dataset root `root`; returns the
/// paths written (all below `root`).
#[allow(clippy::too_many_arguments)]
pub fn write_extra_layouts(
    kinds: &[String],
    root: &Path,
    town: &str,
    config: &str,
    weather: &str,
    sequence: u32,
    frame: u32,
    rig: &StereoRig,
    out: &FrameOutput,
    meta: &CameraFile,
) -> io::Result<Vec<PathBuf>> {
    let _ = (root, town, config, weather, sequence, frame, rig, out, meta);
    if let Some(kind) = kinds.iter().find(|k| k.as_str() != "native") {
        return Err(io::Error::new(
            io::ErrorKind::Unsupported,
            format!("layout {kind} is not built yet (only native is)"),
        ));
    }
    Ok(Vec::new())
}
