//! The `sceneflow` layout (FlyingThings3D / Driving style): lossless PNG pairs
//! and PFM disparities for both views, positive disparity, 0 for sky.
//!
//! `frames_cleanpass/baseline_XXX/<town>_<config>_<weather>/SSSS/{left,right}/NNNNNN.png`
//! and `disparity/baseline_XXX/<town>_<config>_<weather>/SSSS/{left,right}/NNNNNN.pfm`
//! (SceneFlow's `<pass>/<subset>/<scene>/<camera>/<frame>` tree, the baseline
//! standing in for the subset).

use std::io;
use std::path::{Path, PathBuf};

use super::{rel_str, srgb_views, write_baseline_splits, FrameKey};
use crate::camera::StereoRig;
use crate::output::{baseline_dir_name, frame_stem, write_pfm_gray, write_png_rgb8};
use crate::render::FrameOutput;

/// Root-relative `[left png, right png, left pfm, right pfm]` of a frame.
pub(super) fn sample_paths(key: &FrameKey, baseline_cm: f64) -> [String; 4] {
    let b = baseline_dir_name(baseline_cm);
    let scene = format!("{}_{}_{}", key.town, key.config, key.weather);
    let seq = format!("{:04}", key.sequence);
    let stem = frame_stem(key.frame);
    let png = format!("{stem}.png");
    let pfm = format!("{stem}.pfm");
    [
        rel_str(&["frames_cleanpass", &b, &scene, &seq, "left", &png]),
        rel_str(&["frames_cleanpass", &b, &scene, &seq, "right", &png]),
        rel_str(&["disparity", &b, &scene, &seq, "left", &pfm]),
        rel_str(&["disparity", &b, &scene, &seq, "right", &pfm]),
    ]
}

/// Writes one frame; returns the files written. The left PNG is repeated per
/// baseline so that each baseline directory is a self-contained subset.
pub(super) fn write_frame(
    root: &Path,
    key: &FrameKey,
    rig: &StereoRig,
    out: &FrameOutput,
) -> io::Result<Vec<PathBuf>> {
    let (w, h) = (out.left.width as usize, out.left.height as usize);
    let srgb = srgb_views(out);
    let mut written = Vec::new();
    for (b, &baseline_m) in rig.baselines_m.iter().enumerate() {
        let gt = &out.baselines[b];
        let [l, r, dl, dr] = sample_paths(key, baseline_m * 100.0).map(|p| root.join(p));
        write_png_rgb8(&l, w, h, &srgb[0])?;
        write_png_rgb8(&r, w, h, &srgb[1 + b])?;
        write_pfm_gray(&dl, w, h, &gt.disparity_left)?;
        write_pfm_gray(&dr, w, h, &gt.disparity_right)?;
        written.extend([l, r, dl, dr]);
    }
    Ok(written)
}

/// Writes `splits/sceneflow_baseline_XXX.txt`: `left right disp_left` per line.
pub(super) fn write_index(
    root: &Path,
    keys: &[FrameKey],
    baselines_cm: &[f64],
) -> io::Result<Vec<PathBuf>> {
    let line = |k: &FrameKey, cm: f64| sample_paths(k, cm)[..3].join(" ");
    Ok(write_baseline_splits(root, "sceneflow", keys, baselines_cm, line)?.0)
}
