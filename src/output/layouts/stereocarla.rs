//! The `stereocarla` layout: the published StereoCarla tree as OpenStereo's
//! `CarlaDataset` reads it (a split line `left right depth`, depth a 16-bit PNG
//! of the LEFT camera's depth_z in centimetres, disparity recovered as
//! d = B_cm·f / (depth_cm + 1e-6) in float32, valid where d < 512).
//!
//! Directories: clear weather under `<config>/<town>/`, other weathers under
//! `weather/<town>_<weather>/`. StereoCarla's weather subset has one camera
//! configuration; so that several cannot collide there, a frame of a
//! configuration other than `normal` gets the stem `<config>_SSSS_NNNNNN`.
//! Sky and anything beyond 655.35 m (or nearer than 5 mm) is written as 0, which
//! the loader turns into a huge disparity and masks out. The depth PNG is the
//! same for every baseline: written once, hard-linked (copied where links fail).

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::{flat_stem, rel_str, srgb_views, write_baseline_splits, write_split, FrameKey};
use crate::camera::StereoRig;
use crate::output::frame::CameraFile;
use crate::output::{
    baseline_dir_name, write_atomic, write_jpeg_rgb8, write_json, write_png_gray16, Access,
    OutputError,
};
use crate::render::FrameOutput;

/// OpenStereo's validity threshold on decoded StereoCarla disparity, px (`d < 512`).
pub const STEREOCARLA_VALID_MAX_PX: f32 = 512.0;

/// JPEG quality of the images (the format is lossy; 95 keeps artefacts small).
const JPEG_QUALITY: u8 = 95;

/// Encodes depth_z (metres, +inf for sky) as StereoCarla's 16-bit centimetres:
/// round to nearest; non-finite, ≥ 655.355 m or < 5 mm → 0 (invalid).
pub fn encode_stereocarla_depth(depth_z_m: &[f64]) -> Vec<u16> {
    depth_z_m
        .iter()
        .map(|&z| {
            let cm = (z * 100.0).round();
            if cm.is_finite() && (1.0..=65535.0).contains(&cm) {
                cm as u16
            } else {
                0
            }
        })
        .collect()
}

/// Decodes StereoCarla depth exactly as OpenStereo does, in float32:
/// d = baseline_cm · f_px / (depth_cm + 1e-6). A 0 (sky) gives ≈ 1e11 px, which
/// fails the validity test d < [`STEREOCARLA_VALID_MAX_PX`].
pub fn decode_stereocarla_depth(depth_cm: &[u16], baseline_cm: f64, f_px: f64) -> Vec<f32> {
    // numpy: a Python float times a float32 array stays float32.
    let bf = (baseline_cm * f_px) as f32;
    depth_cm.iter().map(|&v| bf / (v as f32 + 1e-6)).collect()
}

/// The pose file of one baseline (`baseline_XXX/pose/<stem>.json`).
#[derive(Serialize)]
struct PoseFile<'a> {
    baseline_m: f64,
    width: u32,
    height: u32,
    f_px: f64,
    k: [[f64; 3]; 3],
    left_pose: [[f64; 4]; 4],
    right_pose: [[f64; 4]; 4],
    conventions: &'a str,
}

/// The sample directory and stem of a frame.
fn dir_and_stem(key: &FrameKey) -> (Vec<String>, String) {
    if key.weather == "clear" {
        (vec![key.config.clone(), key.town.clone()], flat_stem(key))
    } else {
        let stem = if key.config == "normal" {
            flat_stem(key)
        } else {
            format!("{}_{}", key.config, flat_stem(key))
        };
        (
            vec!["weather".into(), format!("{}_{}", key.town, key.weather)],
            stem,
        )
    }
}

/// Root-relative `<dir>/<top>/<folder>/<stem>.<ext>` of a frame.
fn sample_path(key: &FrameKey, top: &str, folder: &str, ext: &str) -> String {
    let (dir, stem) = dir_and_stem(key);
    let d: Vec<&str> = dir.iter().map(String::as_str).collect();
    rel_str(&[d.as_slice(), &[top, folder, &format!("{stem}.{ext}")]].concat())
}

/// Root-relative `[left, right, depth]` of a frame at one baseline.
pub(super) fn sample_paths(key: &FrameKey, baseline_cm: f64) -> [String; 3] {
    let b = baseline_dir_name(baseline_cm);
    [
        sample_path(key, "left", "rgb", "jpg"),
        sample_path(key, &b, "rgb", "jpg"),
        sample_path(key, &b, "depth", "png"),
    ]
}

/// Root-relative pose file of a frame at one baseline, beside the baseline's
/// depth folder: `<dir>/baseline_XXX/pose/<stem>.json`.
pub(super) fn pose_path(key: &FrameKey, baseline_cm: f64) -> String {
    sample_path(key, &baseline_dir_name(baseline_cm), "pose", "json")
}

/// Hard-links `src` to `dst` atomically (link to a temporary name, rename);
/// copies through `write_atomic` when the file system refuses links.
fn link_or_copy(src: &Path, dst: &Path) -> io::Result<()> {
    let mut tmp = dst.as_os_str().to_os_string();
    tmp.push(format!(".tmp-link-{}", std::process::id()));
    let tmp = PathBuf::from(tmp);
    let linked = (|| {
        if let Some(p) = dst.parent() {
            fs::create_dir_all(p)?;
        }
        let _ = fs::remove_file(&tmp);
        fs::hard_link(src, &tmp)?;
        let renamed = fs::rename(&tmp, dst);
        // POSIX rename is a no-op when tmp and dst already name the same
        // inode, leaving tmp behind: remove it in every case.
        let _ = fs::remove_file(&tmp);
        renamed
    })();
    match linked {
        Ok(()) => Ok(()),
        Err(_) => {
            let bytes = fs::read(src).map_err(|e| OutputError::wrap(src, Access::Read, e))?;
            write_atomic(dst, &bytes)
        }
    }
}

/// Writes one frame; returns the files written.
pub(super) fn write_frame(
    root: &Path,
    key: &FrameKey,
    rig: &StereoRig,
    out: &FrameOutput,
    meta: &CameraFile,
) -> io::Result<Vec<PathBuf>> {
    let (w, h) = (out.left.width as usize, out.left.height as usize);
    let srgb = srgb_views(out);
    let depth_cm = encode_stereocarla_depth(&out.left.depth_z);
    let mut written = Vec::new();
    let mut first_depth: Option<PathBuf> = None;
    for (b, &baseline_m) in rig.baselines_m.iter().enumerate() {
        let [left, right, depth] = sample_paths(key, baseline_m * 100.0).map(|p| root.join(p));
        if b == 0 {
            write_jpeg_rgb8(&left, w, h, &srgb[0], JPEG_QUALITY)?;
            written.push(left);
        }
        write_jpeg_rgb8(&right, w, h, &srgb[1 + b], JPEG_QUALITY)?;
        written.push(right.clone());
        match &first_depth {
            None => {
                write_png_gray16(&depth, w, h, &depth_cm)?;
                first_depth = Some(depth.clone());
            }
            Some(src) => link_or_copy(src, &depth)?,
        }
        written.push(depth.clone());
        let pose_path = root.join(pose_path(key, baseline_m * 100.0));
        let pose = PoseFile {
            baseline_m,
            width: meta.cameras.width,
            height: meta.cameras.height,
            f_px: meta.cameras.f_px,
            k: meta.cameras.k,
            left_pose: meta.cameras.left_pose,
            right_pose: meta
                .cameras
                .right
                .get(b)
                .map_or(meta.cameras.left_pose, |r| r.pose),
            conventions: meta.conventions,
        };
        write_json(&pose_path, &pose)?;
        written.push(pose_path);
    }
    Ok(written)
}

/// Writes `splits/stereocarla_all.txt` (every baseline) and
/// `splits/stereocarla_baseline_XXX.txt` (one per baseline).
pub(super) fn write_index(
    root: &Path,
    keys: &[FrameKey],
    baselines_cm: &[f64],
) -> io::Result<Vec<PathBuf>> {
    let line = |k: &FrameKey, cm: f64| sample_paths(k, cm).join(" ");
    let (mut written, all) = write_baseline_splits(root, "stereocarla", keys, baselines_cm, line)?;
    written.push(write_split(root, "stereocarla_all.txt", &all)?);
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(config: &str, weather: &str) -> FrameKey {
        FrameKey {
            town: "town02".into(),
            config: config.into(),
            weather: weather.into(),
            sequence: 1,
            frame: 7,
        }
    }

    #[test]
    fn paths_follow_the_published_tree() {
        let [l, r, d] = sample_paths(&key("roll15", "clear"), 54.0);
        assert_eq!(l, "roll15/town02/left/rgb/0001_000007.jpg");
        assert_eq!(r, "roll15/town02/baseline_054/rgb/0001_000007.jpg");
        assert_eq!(d, "roll15/town02/baseline_054/depth/0001_000007.png");
        let [_, r, _] = sample_paths(&key("normal", "foggy"), 10.0);
        assert_eq!(r, "weather/town02_foggy/baseline_010/rgb/0001_000007.jpg");
        let [l, _, _] = sample_paths(&key("pitch30", "night"), 10.0);
        assert_eq!(l, "weather/town02_night/left/rgb/pitch30_0001_000007.jpg");
    }

    #[test]
    fn depth_rounds_to_centimetres_and_zeroes_sky_and_far() {
        let z = [
            12.344,
            12.346,
            f64::INFINITY,
            655.35,
            655.36,
            0.004,
            f64::NAN,
        ];
        assert_eq!(
            encode_stereocarla_depth(&z),
            vec![1234, 1235, 0, 65535, 0, 0, 0]
        );
        let d = decode_stereocarla_depth(&[1000, 0], 54.0, 1385.64);
        assert!((d[0] - 74.82456).abs() < 1e-3);
        assert!(
            d[1] > 1e10,
            "sky decodes far above the {STEREOCARLA_VALID_MAX_PX} px limit"
        );
    }
}
