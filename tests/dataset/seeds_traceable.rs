//! Every dataset frame can be traced back to its geometry: its camera file
//! and manifest line record every seed (town, traffic, weather, samples),
//! the town frame and the town description; `render --town` with those
//! seeds gives the dataset's bytes, `town --export` writes the same cameras
//! beside the OBJ, and `town` draws and records its seed as `render --town`
//! does. The manifest's disparity figures count valid pixels as `stats`
//! does (finite, > 0), and `dataset.json` records `filter` and the towns.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::cli::parallax_ok;

fn json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap()
}

fn files(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p.strip_prefix(root).unwrap().to_path_buf());
            }
        }
    }
    out.sort();
    out
}

/// A two-frame storm dataset (rain streaks and sensor noise use the sample
/// seed and frame) whose frame 1 is town frame 5, at 32×18 and 1 spp.
const CONFIG: &str = "seed = 77\ntowns = [\"town01\"]\nconfigs = [\"roll05\"]\n\
weathers = [\"storm\"]\nbaselines_cm = [10.0, 54.0]\nframes_per_sequence = 2\nstride = 5\n\
width = 32\nheight = 18\nhfov_deg = 70\nspp = 1\nmax_depth = 2\n";

/// The dataset of `CONFIG`, rendered once for every test (they only read it).
fn dataset() -> &'static Path {
    static DIR: std::sync::OnceLock<tempfile::TempDir> = std::sync::OnceLock::new();
    let dir = DIR.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("c.toml"), CONFIG).unwrap();
        parallax_ok(
            dir.path(),
            &["dataset", "c.toml", "-o", "ds", "--threads", "2"],
        );
        dir
    });
    dir.path()
}

/// The manifest line of dataset frame `frame`.
fn manifest_line(root: &Path, frame: u64) -> Value {
    let text = std::fs::read_to_string(root.join("manifest/shard-1-of-1.jsonl")).unwrap();
    text.lines()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
        .find(|l| l["frame"].as_u64() == Some(frame))
        .expect("a manifest line of the frame")
}

fn seed(v: &Value, key: &str) -> String {
    v["seeds"][key]
        .as_u64()
        .unwrap_or_else(|| panic!("seeds.{key} in {v}"))
        .to_string()
}

#[test]
fn a_dataset_frame_re_renders_and_exports_from_its_recorded_seeds() {
    let dir = tempfile::tempdir().unwrap();
    let root = dataset().join("ds");
    let seq = root.join("town01/roll05_storm/0000");
    let line = manifest_line(&root, 1);
    let cam = json(&seq.join("cameras/000001.json"));
    // The camera file and the manifest line record the same seeds, and the
    // town frame of dataset frame 1 (stride 5).
    assert_eq!(cam["seeds"], line["seeds"], "{cam}\n{line}");
    assert_eq!(cam["town"]["frame"].as_u64(), Some(5));
    assert_eq!(line["town_frame"].as_u64(), Some(5));
    assert_eq!(cam["town"]["config"], "roll05");
    assert_eq!(cam["town"]["source"], "built-in");
    assert_eq!(seed(&cam, "samples"), cam["seed"].to_string());
    assert_eq!(seed(&cam, "traffic"), seed(&cam, "town"));
    // Three different streams (the traffic is the town's).
    let all: std::collections::BTreeSet<String> = ["town", "weather", "samples"]
        .iter()
        .map(|k| seed(&cam, k))
        .collect();
    assert_eq!(all.len(), 3, "{cam}");

    // Re-rendered from the record alone: the same bytes, file by file.
    let (town, weather, samples) = (
        seed(&cam, "town"),
        seed(&cam, "weather"),
        seed(&cam, "samples"),
    );
    // The sequence's drive (`drive_index`): roll05 is configuration 1,
    // storm weather 5 of 7, one sequence: (1 · 7 + 5) · 1 + 0.
    assert_eq!(cam["town"]["sequence"].as_u64(), Some(12));
    #[rustfmt::skip]
    parallax_ok(dir.path(), &[
        "render", "--town", "town01", "--seed", &town, "--sequence", "12", "--frame", "5", "--config", "roll05",
        "--weather", "storm", "--weather-seed", &weather, "--sample-seed", &samples,
        "--sample-frame", "1", "--width", "32", "--height", "18", "--hfov", "70",
        "--baselines", "10,54", "--spp", "1", "--max-depth", "2", "--threads", "1", "-o", "again",
    ]);
    let again = dir.path().join("again");
    let written = files(&again);
    let listed: Vec<PathBuf> = line["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            let p = PathBuf::from(f["path"].as_str().unwrap());
            p.strip_prefix("town01/roll05_storm/0000")
                .unwrap()
                .to_path_buf()
        })
        .collect();
    let mut listed_sorted = listed.clone();
    listed_sorted.sort();
    assert_eq!(
        written, listed_sorted,
        "the render writes the frame's files"
    );
    for rel in &written {
        let (a, b) = (
            std::fs::read(again.join(rel)).unwrap(),
            std::fs::read(seq.join(rel)).unwrap(),
        );
        assert!(a == b, "{} differs from the dataset's", rel.display());
    }

    // `town --export` of the same frame writes the frame's cameras beside the OBJ.
    #[rustfmt::skip]
    let o = parallax_ok(dir.path(), &[
        "town", "town01", "--seed", &town, "--sequence", "12", "--frame", "5", "--config", "roll05",
        "--width", "32", "--height", "18", "--hfov", "70", "--baselines", "10,54",
        "--threads", "1", "--export", "exp/frame.obj",
    ]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("frame.cameras.json"));
    let exported = json(&dir.path().join("exp/frame.cameras.json"));
    for key in ["width", "height", "k", "f_px", "left_pose", "right", "town"] {
        assert_eq!(exported[key], cam[key], "{key}");
    }
    assert_eq!(
        (seed(&exported, "town"), seed(&exported, "traffic")),
        (town.clone(), town)
    );
    assert!(exported["seeds"]["samples"].is_null() && exported["seeds"]["weather"].is_null());
    assert!(dir.path().join("exp/frame.obj").is_file());
}

#[test]
fn manifest_disparity_counts_valid_pixels_and_dataset_json_is_complete() {
    let root = dataset().join("ds");
    for frame in 0..2 {
        let line = manifest_line(&root, frame);
        for rec in line["disparity"].as_array().unwrap() {
            let cm = rec["baseline_cm"].as_f64().unwrap();
            let pfm = root.join(format!(
                "town01/roll05_storm/0000/baseline_{:03}/disp/{:06}.pfm",
                cm.round() as u32,
                frame
            ));
            let (w, h, d) = parallax::output::read_pfm_gray(&pfm).unwrap();
            let valid: Vec<f64> = d
                .iter()
                .filter(|v| v.is_finite() && **v > 0.0)
                .map(|&v| v as f64)
                .collect();
            assert!(valid.len() < w * h, "the frame shows sky (0): {pfm:?}");
            assert_eq!(rec["valid_px"].as_u64(), Some(valid.len() as u64), "{rec}");
            let mean = valid.iter().sum::<f64>() / valid.len() as f64;
            let min = valid.iter().copied().fold(f64::INFINITY, f64::min);
            assert!((rec["mean_px"].as_f64().unwrap() - mean).abs() < 1e-9 * mean);
            assert_eq!(rec["min_px"].as_f64(), Some(min));
        }
    }
    let meta = json(&root.join("dataset.json"));
    assert_eq!(meta["config"]["filter"], Value::Bool(true), "{meta}");
    let town01 = std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/town01.toml"));
    let sha = parallax::output::sha256_bytes(&town01.unwrap());
    assert_eq!(
        meta["towns"],
        serde_json::json!([{"name": "town01", "source": "built-in", "sha256": sha}])
    );
}

#[test]
fn town_draws_its_seed_and_records_it_like_render_town() {
    let dir = tempfile::tempdir().unwrap();
    let export = |name: &str, seed: Option<&str>| {
        let obj = format!("{name}.obj");
        let mut args = vec![
            "town",
            "town02",
            "--frame",
            "4",
            "--width",
            "32",
            "--height",
            "18",
            "--threads",
            "1",
            "--export",
            &obj,
        ];
        if let Some(s) = seed {
            args.extend(["--seed", s]);
        }
        let o = parallax_ok(dir.path(), &args);
        let path = dir.path().join(format!("{name}.cameras.json"));
        (
            String::from_utf8_lossy(&o.stdout).into_owned(),
            json(&path),
            path,
        )
    };
    let (out_a, a, path_a) = export("a", None);
    let (_, b, _) = export("b", None);
    let drawn = seed(&a, "town");
    assert_ne!(drawn, seed(&b, "town"), "a seed is drawn per run");
    assert!(out_a.contains(&format!("seed {drawn} ")), "{out_a}");
    // The recorded seed gives the same frame: the same cameras, byte for byte.
    let (_, _, path_c) = export("c", Some(&drawn));
    assert_eq!(
        std::fs::read(path_a).unwrap(),
        std::fs::read(path_c).unwrap()
    );
}

#[test]
fn a_dataset_without_a_sample_count_renders_fog_at_three_quarters_and_records_it() {
    let dir = tempfile::tempdir().unwrap();
    let config = "seed = 5\ntowns = [\"town01\"]\nconfigs = [\"normal\"]\n\
weathers = [\"clear\", \"foggy\"]\nbaselines_cm = [10.0]\nframes_per_sequence = 1\n\
width = 16\nheight = 9\nmax_depth = 2\n";
    std::fs::write(dir.path().join("c.toml"), config).unwrap();
    parallax_ok(
        dir.path(),
        &["dataset", "c.toml", "-o", "ds", "--threads", "2"],
    );
    let root = dir.path().join("ds");
    let text = std::fs::read_to_string(root.join("manifest/shard-1-of-1.jsonl")).unwrap();
    let mut seen = Vec::new();
    for line in text
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
    {
        let weather = line["weather"].as_str().unwrap().to_string();
        let cam = json(&root.join(format!("town01/normal_{weather}/0000/cameras/000000.json")));
        let want = if weather == "foggy" { 48 } else { 64 };
        assert_eq!(
            line["render"]["spp"].as_u64(),
            Some(want),
            "{weather}: {line}"
        );
        assert_eq!(cam["spp"].as_u64(), Some(want), "{weather}");
        seen.push(weather);
    }
    seen.sort();
    assert_eq!(seen, ["clear", "foggy"]);
    // dataset.json keeps the count absent, as the configuration gave it.
    let meta = json(&root.join("dataset.json"));
    assert!(meta["config"].get("spp").is_none(), "{}", meta["config"]);
}
