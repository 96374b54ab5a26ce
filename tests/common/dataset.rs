//! Shared set-up of the dataset tests: a tiny configuration (64×36 px, 1 spp,
//! one town, two baselines), the real binary, and a hash map of a root's files.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

// The dataset tests reach the binary through this module.
pub use super::cli::parallax;

/// A tiny configuration: town01, `configs`, clear, `frames` frames, 64×36, 1 spp.
pub fn tiny_config(configs: &[&str], frames: u32) -> String {
    let list: Vec<String> = configs.iter().map(|c| format!("\"{c}\"")).collect();
    format!(
        "seed = 11\ntowns = [\"town01\"]\nconfigs = [{}]\nweathers = [\"clear\"]\n\
         baselines_cm = [10.0, 54.0]\nframes_per_sequence = {frames}\nstride = 7\n\
         width = 64\nheight = 36\nspp = 1\nmax_depth = 2\n",
        list.join(", ")
    )
}

/// Writes `text` as `name` in `dir` and returns its path.
pub fn write_config(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Scenes directory argument.
pub fn scenes() -> String {
    format!("{}/scenes", env!("CARGO_MANIFEST_DIR"))
}

/// Runs `parallax dataset CONFIG -o OUT [extra…] --threads 2`.
pub fn dataset(config: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "dataset",
        config.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let s = scenes();
    args.extend_from_slice(&["--scenes", &s, "--threads", "2"]);
    parallax(&args).output().unwrap()
}

/// Runs `parallax verify OUT [extra…]`.
pub fn verify(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["verify", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let s = scenes();
    args.extend_from_slice(&["--scenes", &s, "--threads", "2"]);
    parallax(&args).output().unwrap()
}

/// Panics with the output unless the command succeeded.
pub fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "exit {:?}\nstdout:\n{}\nstderr:\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// stdout + stderr as text.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Every entry below `root`: (path relative to it, full path, is a directory).
pub fn walk(root: &Path) -> Vec<(String, PathBuf, bool)> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
            let is_dir = p.is_dir();
            if is_dir {
                stack.push(p.clone());
            }
            out.push((rel, p, is_dir));
        }
    }
    out
}

/// SHA-256 of every data file below `root` (manifests and failure lists left out).
pub fn data_files(root: &Path) -> BTreeMap<String, String> {
    walk(root)
        .into_iter()
        .filter(|(rel, _, is_dir)| {
            !is_dir && !rel.starts_with("manifest") && !rel.starts_with("failures")
        })
        .map(|(rel, p, _)| (rel, parallax::output::sha256_file(&p).unwrap()))
        .collect()
}

/// Manifest lines of every shard below `root`.
pub fn manifest_lines(root: &Path) -> usize {
    let dir = root.join("manifest");
    let Ok(rd) = std::fs::read_dir(dir) else {
        return 0;
    };
    rd.map(|e| std::fs::read_to_string(e.unwrap().path()).unwrap())
        .map(|t| t.lines().filter(|l| l.ends_with('}')).count())
        .sum()
}

/// Every entry below `root` (directories with `None`, files with their bytes),
/// manifests and hidden files included.
pub fn tree(root: &Path) -> BTreeMap<String, Option<Vec<u8>>> {
    walk(root)
        .into_iter()
        .map(|(rel, p, is_dir)| (rel, (!is_dir).then(|| std::fs::read(&p).unwrap())))
        .collect()
}

/// Modification time of every data file below `root` (as `data_files`).
pub fn mtimes(root: &Path) -> BTreeMap<String, std::time::SystemTime> {
    data_files(root)
        .into_keys()
        .map(|rel| {
            let t = std::fs::metadata(root.join(&rel))
                .unwrap()
                .modified()
                .unwrap();
            (rel, t)
        })
        .collect()
}

/// The manifest lines of every shard below `root`, by frame id
/// (`town01/normal_clear/0000/000001`), in file and line order.
pub fn lines_by_frame(root: &Path) -> BTreeMap<String, Vec<String>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("manifest"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for f in files {
        for l in std::fs::read_to_string(f).unwrap().lines() {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            let id = format!(
                "{}/{}_{}/{:04}/{:06}",
                v["town"].as_str().unwrap(),
                v["config"].as_str().unwrap(),
                v["weather"].as_str().unwrap(),
                v["sequence"].as_u64().unwrap(),
                v["frame"].as_u64().unwrap()
            );
            out.entry(id).or_default().push(l.to_string());
        }
    }
    out
}

/// Flips one bit in the middle of `path` (same size, other SHA-256).
pub fn flip_byte(path: &Path) {
    let mut bytes = std::fs::read(path).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x40;
    std::fs::write(path, &bytes).unwrap();
}

/// Cuts `path` to half its size; returns the old size.
pub fn truncate_half(path: &Path) -> u64 {
    let len = std::fs::metadata(path).unwrap().len();
    std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .unwrap()
        .set_len(len / 2)
        .unwrap();
    len
}

/// The data files (relative paths) of one frame: those whose path holds its
/// sequence directory and whose name starts with its 6-digit number.
pub fn frame_files<'a>(files: impl IntoIterator<Item = &'a String>, id: &str) -> Vec<String> {
    let (seq, frame) = id.rsplit_once('/').unwrap();
    files
        .into_iter()
        .filter(|rel| rel.starts_with(seq) && rel.rsplit('/').next().unwrap().starts_with(frame))
        .cloned()
        .collect()
}
