//! Bookkeeping files of a dataset root (DATASET.md, bookkeeping):
//! `dataset.json` (generator, full configuration, seed, intrinsics,
//! baselines, layouts) and `manifest/shard-i-of-N.jsonl`, one JSON line per
//! complete frame, appended and fsynced after every file of the frame has
//! been renamed into place. A line torn by a kill is ignored on reading and
//! cut off before the shard appends again.

use std::collections::BTreeMap;
use std::fs::{self, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::config::DatasetConfig;
use super::plan::Job;
use crate::output::frame::FrameSeeds;
use crate::output::layouts::LayoutKind;
use crate::output::{Access, FileRecord, OutputError};
use crate::town::TownSource;

/// Name of the dataset description at the root.
pub const DATASET_JSON: &str = "dataset.json";
/// Directory of the per-shard manifests.
pub const MANIFEST_DIR: &str = "manifest";
/// Directory of the per-shard failure lists.
pub const FAILURES_DIR: &str = "failures";

/// `dataset.json`: everything needed to recompute the job list.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DatasetMeta {
    /// `parallax <version>`.
    pub generator: String,
    /// The full resolved configuration.
    pub config: DatasetConfig,
    /// The master seed (also in `config`).
    pub seed: u64,
    /// Intrinsic matrix K (row-major), pixels.
    pub k: [[f64; 3]; 3],
    /// Image width and height, pixels.
    pub resolution: [u32; 2],
    /// Baselines in centimetres, in rig order.
    pub baselines_cm: Vec<f64>,
    /// Layouts written.
    pub layouts: Vec<LayoutKind>,
    /// The town descriptions the frames were generated from, in the
    /// configuration's order: source (`built-in` or path) and SHA-256 of
    /// the text. Absent in datasets of older versions.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub towns: Vec<TownSource>,
}

impl DatasetMeta {
    /// The description of a dataset rendered from `config` with `towns`.
    pub fn new(config: &DatasetConfig, towns: Vec<TownSource>) -> DatasetMeta {
        let intr = crate::camera::Intrinsics::from_hfov(
            config.width,
            config.height,
            config.hfov_deg.to_radians(),
        );
        DatasetMeta {
            generator: format!("parallax {}", env!("CARGO_PKG_VERSION")),
            config: config.clone(),
            seed: config.seed,
            k: intr.k_matrix(),
            resolution: [config.width, config.height],
            baselines_cm: config.baselines_cm.clone(),
            layouts: config.layouts.clone(),
            towns,
        }
    }

    /// Refuses town descriptions other than those recorded (a resumed or
    /// repaired dataset must not mix towns); an older `dataset.json` without
    /// the record accepts any.
    pub fn check_towns(&self, towns: &[TownSource]) -> Result<(), String> {
        for t in towns {
            let Some(old) = self.towns.iter().find(|o| o.name == t.name) else {
                continue;
            };
            if old.sha256 != t.sha256 {
                // The fix depends on where the recorded description lives.
                let hint = if t.source == crate::town::source::BUILT_IN {
                    "pass --scenes DIR holding that description".to_string()
                } else if old.source == crate::town::source::BUILT_IN {
                    "leave out --scenes to use the built-in description, or use the parallax \
                     version the dataset was made with if the built-in one has changed"
                        .to_string()
                } else {
                    format!(
                        "pass --scenes DIR holding that description (it was read from {})",
                        old.source
                    )
                };
                return Err(format!(
                    "town '{}': the description from {} (SHA-256 {}) is not the one this \
                     dataset was made from ({}, SHA-256 {}, recorded in {DATASET_JSON}); {hint}",
                    t.name, t.source, t.sha256, old.source, old.sha256
                ));
            }
        }
        Ok(())
    }
}

/// Reads `dataset.json` below `root`; `Ok(None)` when absent.
pub fn read_meta(root: &Path) -> io::Result<Option<DatasetMeta>> {
    let path = root.join(DATASET_JSON);
    if !path.exists() {
        return Ok(None);
    }
    let bytes = crate::output::read_file(&path)?;
    serde_json::from_slice(&bytes)
        .map(Some)
        .map_err(|e| OutputError::wrap(&path, Access::Read, io::Error::other(e)))
}

/// Render statistics of a frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderRecord {
    /// Samples per pixel per view.
    pub spp: u32,
    /// Rays traced (ground truth + paths).
    pub rays: u64,
    /// Wall-clock seconds for the frame (build, render, write).
    pub seconds: f64,
}

/// Left-view disparity statistics of one baseline over valid pixels
/// (finite and > 0, as `stats` counts them: sky is 0).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DisparityRecord {
    /// Baseline, centimetres.
    pub baseline_cm: f64,
    /// Pixels with valid disparity (finite and > 0; not sky).
    pub valid_px: u64,
    /// Minimum disparity, px (0 when no pixel is valid).
    pub min_px: f64,
    /// Maximum disparity, px.
    pub max_px: f64,
    /// Mean disparity, px.
    pub mean_px: f64,
}

impl DisparityRecord {
    /// Statistics of the valid values of `disparity` (`stats`' rule, in
    /// one pass: no histogram is needed for these figures); zeros when none
    /// is valid.
    pub fn of(baseline_cm: f64, disparity: &[f32]) -> DisparityRecord {
        let (mut n, mut sum) = (0u64, 0.0f64);
        let (mut min_px, mut max_px) = (f64::INFINITY, f64::NEG_INFINITY);
        for d in disparity.iter().filter(|&&d| crate::eval::gt_valid(d)) {
            let d = *d as f64;
            n += 1;
            sum += d;
            min_px = min_px.min(d);
            max_px = max_px.max(d);
        }
        if n == 0 {
            (min_px, max_px) = (0.0, 0.0);
        }
        DisparityRecord {
            baseline_cm,
            valid_px: n,
            min_px,
            max_px,
            mean_px: if n == 0 { 0.0 } else { sum / n as f64 },
        }
    }
}

/// One manifest line: a complete frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestLine {
    /// Town name.
    pub town: String,
    /// Camera configuration name.
    pub config: String,
    /// Weather name.
    pub weather: String,
    /// Sequence index.
    pub sequence: u32,
    /// Frame index within the sequence.
    pub frame: u32,
    /// Town frame (time step) rendered.
    pub town_frame: u64,
    /// Seed of the frame's sample streams.
    pub seed: u64,
    /// Every seed of the frame (town, traffic, weather, samples); absent in
    /// manifests of older versions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seeds: Option<FrameSeeds>,
    /// Every file of the frame, paths relative to the dataset root.
    pub files: Vec<FileRecord>,
    /// Render statistics.
    pub render: RenderRecord,
    /// Left-view disparity statistics per baseline.
    pub disparity: Vec<DisparityRecord>,
}

impl ManifestLine {
    /// The job this line completes; `None` when a name does not parse.
    pub fn job(&self) -> Option<Job> {
        Some(Job {
            town: self.town.clone(),
            config: self.config.parse().ok()?,
            weather: self.weather.parse().ok()?,
            sequence: self.sequence,
            frame: self.frame,
        })
    }
}

/// One line read back from a manifest file.
#[derive(Clone, Debug)]
pub struct ReadLine {
    /// The manifest file.
    pub file: PathBuf,
    /// 1-based line number.
    pub line_no: usize,
    /// The line as written (without its newline).
    pub text: String,
    /// The parsed line, or why it does not parse (torn or edited).
    pub parsed: Result<ManifestLine, String>,
}

/// The manifest files below `root`, sorted by name.
pub fn manifest_files(root: &Path) -> io::Result<Vec<PathBuf>> {
    let dir = root.join(MANIFEST_DIR);
    if !dir.is_dir() {
        return Ok(Vec::new());
    }
    let mut files: Vec<PathBuf> = fs::read_dir(&dir)
        .map_err(|e| OutputError::wrap(&dir, Access::Read, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "jsonl"))
        .collect();
    files.sort();
    Ok(files)
}

/// Every line of every manifest below `root`, in file and line order.
pub fn read_manifests(root: &Path) -> io::Result<Vec<ReadLine>> {
    let mut out = Vec::new();
    for file in manifest_files(root)? {
        let bytes = crate::output::read_file(&file)?;
        let text = String::from_utf8_lossy(&bytes);
        for (i, line) in text.lines().enumerate() {
            if line.trim().is_empty() {
                continue;
            }
            out.push(ReadLine {
                file: file.clone(),
                line_no: i + 1,
                text: line.to_string(),
                parsed: serde_json::from_str(line).map_err(|e| e.to_string()),
            });
        }
    }
    Ok(out)
}

/// The last parsed line of every job (later lines win).
pub fn latest_lines(lines: &[ReadLine]) -> BTreeMap<Job, ManifestLine> {
    let mut map = BTreeMap::new();
    for l in lines {
        if let Some((job, line)) = l.parsed.as_ref().ok().and_then(|p| Some((p.job()?, p))) {
            map.insert(job, line.clone());
        }
    }
    map
}

/// Cuts a torn last line (no trailing newline, left by a kill) off `path`.
pub fn cut_torn_tail(path: &Path) -> io::Result<()> {
    let Ok(bytes) = fs::read(path) else {
        return Ok(());
    };
    if bytes.is_empty() || bytes.ends_with(b"\n") {
        return Ok(());
    }
    let keep = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let f = OpenOptions::new()
        .write(true)
        .open(path)
        .map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    f.set_len(keep as u64)
        .and_then(|_| f.sync_all())
        .map_err(|e| OutputError::wrap(path, Access::Write, e))
}

/// Appends `line` as one JSON line to `path` and fsyncs it.
pub fn append_line(path: &Path, line: &ManifestLine) -> io::Result<()> {
    let mut text = serde_json::to_string(line)
        .map_err(|e| OutputError::wrap(path, Access::Write, io::Error::other(e)))?;
    text.push('\n');
    (|| {
        if let Some(dir) = path.parent() {
            fs::create_dir_all(dir)?;
        }
        let mut f = OpenOptions::new().create(true).append(true).open(path)?;
        // One write call: a concurrent reader sees the line whole or not at all.
        f.write_all(text.as_bytes())?;
        f.sync_data()
    })()
    .map_err(|e| OutputError::wrap(path, Access::Write, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disparity_stats_skip_sky() {
        // Sky is 0 in the disparity maps: it counts no more than ∞ or NaN.
        let r = DisparityRecord::of(54.0, &[1.0, 0.0, f32::INFINITY, 3.0, 0.0, 8.0, f32::NAN]);
        assert_eq!(
            (r.valid_px, r.min_px, r.max_px, r.mean_px),
            (3, 1.0, 8.0, 4.0)
        );
        for sky in [[f32::INFINITY], [0.0]] {
            let s = DisparityRecord::of(54.0, &sky);
            assert_eq!(
                (s.valid_px, s.min_px, s.max_px, s.mean_px),
                (0, 0.0, 0.0, 0.0)
            );
        }
    }

    #[test]
    fn other_town_descriptions_are_refused_with_the_fix_for_their_source() {
        let text = "seed = 1\ntowns = [\"town01\"]\nframes_per_sequence = 1\n";
        let config = super::super::parse_config(text, "t.toml").unwrap();
        let town = |source: &str, sha: &str| TownSource {
            name: "town01".into(),
            source: source.into(),
            sha256: sha.into(),
        };
        let built_in = crate::town::source::BUILT_IN;
        let meta = DatasetMeta::new(&config, vec![town(built_in, "aa")]);
        assert!(meta.check_towns(&[town(built_in, "aa")]).is_ok());
        let e = meta
            .check_towns(&[town("/x/town01.toml", "bb")])
            .unwrap_err();
        assert!(e.contains("leave out --scenes") && !e.contains("  "), "{e}");
        let from_dir = DatasetMeta::new(&config, vec![town("/d/town01.toml", "aa")]);
        let e = from_dir.check_towns(&[town(built_in, "bb")]).unwrap_err();
        assert!(e.contains("pass --scenes DIR") && !e.contains("  "), "{e}");
    }

    #[test]
    fn torn_tail_is_cut_and_whole_lines_kept() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("m.jsonl");
        fs::write(&p, b"{\"a\":1}\n{\"a\":2}\n{\"a\"").unwrap();
        cut_torn_tail(&p).unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"{\"a\":1}\n{\"a\":2}\n");
        cut_torn_tail(&p).unwrap();
        assert_eq!(fs::read(&p).unwrap().len(), 16);
    }
}
