//! The non-native layouts of DATASET.md (`stereocarla`, `kitti`, `sceneflow`),
//! written from one rendered frame beside (or instead of) the native one.
//!
//! Flat layouts put frames of every sequence of a town and configuration in one
//! directory, so their file stem carries both indices: [`flat_stem`] gives
//! `SSSS_NNNNNN` (sequence, frame; e.g. sequence 3 frame 12 → `0003_000012`).
//! Every file is written atomically (`write_atomic`); each writer returns the
//! paths it wrote, for the manifest. The caller picks `root`; give each layout
//! its own root when several are written from one render.

mod kitti;
mod sceneflow;
mod stereocarla;

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::atomic::invalid_input;
use super::baseline_dir_name;
use super::frame::CameraFile;
use crate::camera::StereoRig;
use crate::render::FrameOutput;

pub use kitti::{decode_kitti_disparity, encode_kitti_disparity};
pub use stereocarla::{
    decode_stereocarla_depth, encode_stereocarla_depth, STEREOCARLA_VALID_MAX_PX,
};

/// A file layout of a dataset (DATASET.md, layouts). Names are lowercase,
/// also in TOML and JSON.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LayoutKind {
    /// Lossless PNG/EXR/PFM, every ground-truth map (`output::frame`).
    Native,
    /// The published StereoCarla layout as OpenStereo's loader reads it.
    Stereocarla,
    /// KITTI 2015 style: `image_2`, `image_3`, 16-bit disparity × 256.
    Kitti,
    /// SceneFlow style: PNG left/right, PFM disparity left/right.
    Sceneflow,
}

impl LayoutKind {
    /// Every layout, in a fixed order.
    pub const ALL: [LayoutKind; 4] = [
        LayoutKind::Native,
        LayoutKind::Stereocarla,
        LayoutKind::Kitti,
        LayoutKind::Sceneflow,
    ];

    /// The lowercase name (`native`, `stereocarla`, `kitti`, `sceneflow`).
    pub fn name(self) -> &'static str {
        match self {
            LayoutKind::Native => "native",
            LayoutKind::Stereocarla => "stereocarla",
            LayoutKind::Kitti => "kitti",
            LayoutKind::Sceneflow => "sceneflow",
        }
    }
}

impl fmt::Display for LayoutKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A configuration's layout name: the name, or an error listing the names.
impl<'de> Deserialize<'de> for LayoutKind {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        LayoutKind::ALL
            .into_iter()
            .find(|k| k.name() == name)
            .ok_or_else(|| {
                let names: Vec<&str> = LayoutKind::ALL.iter().map(|k| k.name()).collect();
                serde::de::Error::custom(format!(
                    "unknown layout '{name}' (one of {})",
                    names.join(", ")
                ))
            })
    }
}

impl FromStr for LayoutKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        LayoutKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = LayoutKind::ALL.iter().map(|k| k.name()).collect();
                let (last, rest) = names.split_last().expect("layouts exist");
                format!(
                    "unknown layout '{s}' (expected {} or {last})",
                    rest.join(", ")
                )
            })
    }
}

/// Identifies one frame of a dataset.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct FrameKey {
    /// Town name (`town01`, …).
    pub town: String,
    /// Camera configuration (`normal`, `roll05`, …).
    pub config: String,
    /// Weather name (`clear`, `foggy`, …).
    pub weather: String,
    /// Sequence index within the town/configuration/weather.
    pub sequence: u32,
    /// Frame index within the sequence.
    pub frame: u32,
}

/// The stem of a frame in a flat layout: `SSSS_NNNNNN` (sequence zero-padded to
/// 4 digits, frame to 6), unique across the sequences of one directory.
pub fn flat_stem(key: &FrameKey) -> String {
    format!("{:04}_{:06}", key.sequence, key.frame)
}

/// Writes one rendered frame in a non-native layout under `root`; returns every
/// file written (for the manifest). `Native` is written by
/// `output::frame::write_native_frame` and is an `InvalidInput` error here, as
/// is a frame without images (spp 0).
pub fn write_layout_frame(
    kind: LayoutKind,
    root: &Path,
    key: &FrameKey,
    rig: &StereoRig,
    out: &FrameOutput,
    meta: &CameraFile,
) -> io::Result<Vec<PathBuf>> {
    if out.images.len() != 1 + rig.baselines_m.len() {
        return Err(invalid_input(format!(
            "layout {kind}: frame has {} images, expected {} (render with spp ≥ 1)",
            out.images.len(),
            1 + rig.baselines_m.len()
        )));
    }
    match kind {
        LayoutKind::Native => Err(invalid_input(
            "the native layout is written by write_native_frame",
        )),
        LayoutKind::Stereocarla => stereocarla::write_frame(root, key, rig, out, meta),
        LayoutKind::Kitti => kitti::write_frame(root, key, rig, out),
        LayoutKind::Sceneflow => sceneflow::write_frame(root, key, rig, out),
    }
}

/// Writes the index files (split lists) of a layout for a set of complete
/// frames; returns the files written. Paths inside are relative to `root`,
/// separated by one space, one sample per line, in the order of `keys` then
/// `baselines_cm`. `Native` writes nothing.
pub fn write_layout_index(
    kind: LayoutKind,
    root: &Path,
    keys: &[FrameKey],
    baselines_cm: &[f64],
) -> io::Result<Vec<PathBuf>> {
    match kind {
        LayoutKind::Native => Ok(Vec::new()),
        LayoutKind::Stereocarla => stereocarla::write_index(root, keys, baselines_cm),
        LayoutKind::Kitti => kitti::write_index(root, keys, baselines_cm),
        LayoutKind::Sceneflow => sceneflow::write_index(root, keys, baselines_cm),
    }
}

/// Root-relative path of the left-view ground truth a layout writes for one
/// frame and baseline: kitti `disp_occ_0` PNG, sceneflow `disparity/…/left`
/// PFM, stereocarla depth PNG; `None` for native (`NativeLayout` names it).
/// `parallax eval` mirrors these names for predictions.
pub fn left_truth_rel(kind: LayoutKind, key: &FrameKey, baseline_cm: f64) -> Option<String> {
    match kind {
        LayoutKind::Native => None,
        LayoutKind::Kitti => Some(kitti::sample_paths(key, baseline_cm)[2].clone()),
        LayoutKind::Sceneflow => Some(sceneflow::sample_paths(key, baseline_cm)[2].clone()),
        LayoutKind::Stereocarla => Some(stereocarla::sample_paths(key, baseline_cm)[2].clone()),
    }
}

/// Root-relative paths of every file [`write_layout_frame`] writes for one
/// frame at `baselines_cm` (split lists aside; a path shared by baselines
/// once); empty for native. Tells a layout's own files from others'.
pub fn frame_files(kind: LayoutKind, key: &FrameKey, baselines_cm: &[f64]) -> Vec<String> {
    let mut files = Vec::new();
    for &cm in baselines_cm {
        match kind {
            LayoutKind::Native => {}
            LayoutKind::Kitti => files.extend(kitti::sample_paths(key, cm)),
            LayoutKind::Sceneflow => files.extend(sceneflow::sample_paths(key, cm)),
            LayoutKind::Stereocarla => {
                files.extend(stereocarla::sample_paths(key, cm));
                files.push(stereocarla::pose_path(key, cm));
            }
        }
    }
    let mut seen = std::collections::BTreeSet::new();
    files.retain(|f| seen.insert(f.clone()));
    files
}

/// A root-relative path as a split-list entry (always `/`-separated).
fn rel_str(parts: &[&str]) -> String {
    parts.join("/")
}

/// Writes `splits/<prefix>_baseline_XXX.txt` per baseline, one line per key
/// from `line(key, baseline_cm)`; returns the lists and all their lines.
fn write_baseline_splits(
    root: &Path,
    prefix: &str,
    keys: &[FrameKey],
    baselines_cm: &[f64],
    line: impl Fn(&FrameKey, f64) -> String,
) -> io::Result<(Vec<PathBuf>, Vec<String>)> {
    let mut written = Vec::new();
    let mut all = Vec::new();
    for &cm in baselines_cm {
        let lines: Vec<String> = keys.iter().map(|k| line(k, cm)).collect();
        let name = format!("{prefix}_{}.txt", baseline_dir_name(cm));
        written.push(write_split(root, &name, &lines)?);
        all.extend(lines);
    }
    Ok((written, all))
}

/// Writes a split list: one line per sample, entries separated by one space.
fn write_split(root: &Path, name: &str, lines: &[String]) -> io::Result<PathBuf> {
    let path = root.join("splits").join(name);
    let mut text = lines.join("\n");
    if !text.is_empty() {
        text.push('\n');
    }
    super::write_atomic(&path, text.as_bytes())?;
    Ok(path)
}

/// The frame's images tone-mapped to sRGB8: index 0 left, 1 + b right of baseline b.
fn srgb_views(out: &FrameOutput) -> Vec<Vec<u8>> {
    out.images
        .iter()
        .map(|film| crate::film::tonemap_to_srgb8(film, out.exposure_scale))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_names_round_trip_and_reject_unknown() {
        for k in LayoutKind::ALL {
            assert_eq!(k.to_string().parse::<LayoutKind>().unwrap(), k);
            let json = serde_json::to_string(&k).unwrap();
            assert_eq!(json, format!("\"{k}\""));
            assert_eq!(serde_json::from_str::<LayoutKind>(&json).unwrap(), k);
        }
        let e = serde_json::from_str::<LayoutKind>("\"coco\"").unwrap_err();
        assert!(
            e.to_string().starts_with(
                "unknown layout 'coco' (one of native, stereocarla, kitti, sceneflow)"
            ),
            "{e}"
        );
        assert!("KITTI".parse::<LayoutKind>().is_err());
    }

    #[test]
    fn flat_stem_carries_sequence_and_frame() {
        let key = FrameKey {
            town: "town01".into(),
            config: "normal".into(),
            weather: "clear".into(),
            sequence: 3,
            frame: 12,
        };
        assert_eq!(flat_stem(&key), "0003_000012");
    }
}
