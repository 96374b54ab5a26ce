//! `parallax verify ROOT`: proves a dataset (one shard's or the union of
//! many) whole against its own `dataset.json`: every planned frame has a
//! manifest line, every file of every line exists with its size and SHA-256,
//! no frame has two lines, no line names a file twice and none of the
//! dataset's files lies outside the manifests. Files that are not the
//! dataset's ([`Ownership`]) are listed as kept. `--repair` (module
//! `repair`) re-renders exactly the missing, corrupted and duplicated frames.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::io;
use std::path::Path;

use super::manifest::{read_manifests, ManifestLine, DATASET_JSON, FAILURES_DIR, MANIFEST_DIR};
use super::plan::{plan, Job};
use super::run::{job_of_path, temp_base, walk_files, DatasetError};

/// What `verify` found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VerifyReport {
    /// Planned frames in good order.
    pub frames_ok: usize,
    /// Files checked against their SHA-256.
    pub files_checked: usize,
    /// Planned frames without a manifest line.
    pub missing: Vec<String>,
    /// Frames whose files are absent, of the wrong size or checksum: (frame id, file, reason).
    pub corrupted: Vec<(String, String, String)>,
    /// Frames with more than one manifest line.
    pub duplicates: Vec<String>,
    /// The dataset's own files that no line of a planned frame lists (stale
    /// frame files, temporaries of the atomic writers, files of bad lines).
    pub extra: Vec<String>,
    /// Files below the root that are not the dataset's: listed, never
    /// removed, and no reason to call the dataset incomplete.
    pub kept: Vec<String>,
    /// Manifest lines that do not parse or name no planned frame: (file:line, reason).
    pub bad_lines: Vec<(String, String)>,
}

impl VerifyReport {
    /// True when nothing is missing, corrupted, duplicated, extra or
    /// unreadable (files that are not the dataset's do not count).
    pub fn is_whole(&self) -> bool {
        self.missing.is_empty()
            && self.corrupted.is_empty()
            && self.duplicates.is_empty()
            && self.extra.is_empty()
            && self.bad_lines.is_empty()
    }

    /// A readable report, one problem per line, then the counts.
    pub fn text(&self) -> String {
        let mut t = String::new();
        for m in &self.missing {
            t += &format!("missing    {m}\n");
        }
        for (id, f, why) in &self.corrupted {
            t += &format!("corrupted  {id}: {f}: {why}\n");
        }
        for d in &self.duplicates {
            t += &format!("duplicate  {d}\n");
        }
        for e in &self.extra {
            t += &format!("extra      {e}\n");
        }
        for k in &self.kept {
            t += &format!("extra, kept {k} (not the dataset's)\n");
        }
        for (at, why) in &self.bad_lines {
            t += &format!("bad line   {at}: {why}\n");
        }
        t += &format!(
            "{} frames ok, {} files checked; {} missing, {} corrupted, {} duplicate, {} extra files, {} bad manifest lines; {} files not the dataset's kept\n",
            self.frames_ok,
            self.files_checked,
            self.missing.len(),
            self.corrupted.iter().map(|c| &c.0).collect::<BTreeSet<_>>().len(),
            self.duplicates.len(),
            self.extra.len(),
            self.bad_lines.len(),
            self.kept.len()
        );
        t
    }

    /// The frames `--repair` re-renders: missing, corrupted and duplicated.
    pub fn frames_to_render(&self) -> BTreeSet<String> {
        let mut s: BTreeSet<String> = self.missing.iter().cloned().collect();
        s.extend(self.corrupted.iter().map(|c| c.0.clone()));
        s.extend(self.duplicates.iter().cloned());
        s
    }
}

/// The dataset's configuration, from `dataset.json`.
pub fn dataset_config(root: &Path) -> Result<super::config::DatasetConfig, DatasetError> {
    match super::manifest::read_meta(root)? {
        Some(m) => Ok(m.config),
        None => Err(DatasetError::input(format!(
            "{}: no {DATASET_JSON}; not a parallax dataset root",
            root.join(DATASET_JSON).display()
        ))),
    }
}

/// Which files below a root are the dataset's, hence removable by
/// `--repair`: every path a parseable manifest line names (also lines that
/// are dropped), every native-layout file of a planned frame
/// (`<town>/<config>_<weather>/<seq>/…/NNNNNN.*`), and the temporary files of
/// the atomic writers (`<name>.tmp-<pid>-<n>`, `<name>.tmp-link-<pid>`) of
/// these, at the root or in a layout's directory. Everything else is the
/// user's.
pub struct Ownership {
    planned: BTreeSet<Job>,
    named: BTreeSet<String>,
    layout_dirs: BTreeSet<String>,
}

impl Ownership {
    /// The ownership rule of `config`'s dataset whose manifests hold `lines`.
    pub fn new<'a>(
        config: &super::config::DatasetConfig,
        lines: impl IntoIterator<Item = &'a ManifestLine>,
    ) -> Ownership {
        Ownership {
            planned: plan(config).into_iter().collect(),
            named: lines
                .into_iter()
                .flat_map(|l| l.files.iter().map(|f| f.path.clone()))
                .collect(),
            layout_dirs: config.layouts.iter().cloned().collect(),
        }
    }

    /// True when `rel` ('/'-separated, relative to the root) is the dataset's.
    pub fn owns(&self, rel: &str) -> bool {
        let (dir, name) = rel.rsplit_once('/').unwrap_or(("", rel));
        let temp = temp_base(name);
        let path = match (temp, dir) {
            (Some(base), "") => base.to_string(),
            (Some(base), _) => format!("{dir}/{base}"),
            (None, _) => rel.to_string(),
        };
        if self.named.contains(&path) || self.planned_frame_file(&path).is_some() {
            return true;
        }
        let top = rel.split('/').next().unwrap_or("");
        temp.is_some() && (dir.is_empty() || self.layout_dirs.contains(top))
    }

    /// The planned frame a native-layout file `…/NNNNNN.ext` (temporary
    /// suffix stripped) belongs to; a name with more (`000001.png.bak`) or
    /// other stems is not a frame file.
    pub fn planned_frame_file(&self, rel: &str) -> Option<Job> {
        let (dir, name) = rel.rsplit_once('/')?;
        let name = temp_base(name).unwrap_or(name);
        let (stem, ext) = name.split_once('.')?;
        if ext.contains('.') || !stem.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        job_of_path(Path::new(&format!("{dir}/{name}"))).filter(|j| self.planned.contains(j))
    }
}

/// Why a parsed manifest line describes no frame of the plan, if it does not.
pub fn line_problem(line: &ManifestLine, planned: &BTreeSet<Job>) -> Option<String> {
    if !line.job().is_some_and(|j| planned.contains(&j)) {
        return Some("names no frame of this dataset's plan".into());
    }
    let mut seen = BTreeSet::new();
    line.files
        .iter()
        .find(|f| !seen.insert(f.path.as_str()))
        .map(|f| format!("names {} twice", f.path))
}

/// True for the bookkeeping below a root (`dataset.json`, manifests, failure
/// lists, layouts' split lists): never a frame's file.
pub fn is_bookkeeping(rel: &Path) -> bool {
    let first = rel.components().next().map(|c| c.as_os_str().to_owned());
    let top = first.as_deref().and_then(|s| s.to_str()).unwrap_or("");
    rel == Path::new(DATASET_JSON)
        || top == MANIFEST_DIR
        || top == FAILURES_DIR
        || super::layouts::is_layout_index(rel)
}

/// A relative path '/'-separated, as manifests write it.
pub fn slash_path(rel: &Path) -> String {
    let parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    parts.join("/")
}

/// Checks the dataset below `root` (every checksum).
pub fn verify_dataset(root: &Path) -> Result<VerifyReport, DatasetError> {
    let config = dataset_config(root)?;
    let planned: BTreeSet<Job> = plan(&config).into_iter().collect();
    let mut report = VerifyReport::default();
    let mut lines: BTreeMap<Job, Vec<ManifestLine>> = BTreeMap::new();
    let mut parsed = Vec::new();
    for l in read_manifests(root)? {
        let at = format!("{}:{}", l.file.display(), l.line_no);
        match l.parsed {
            Err(e) => report.bad_lines.push((at, e)),
            Ok(line) => {
                match (line_problem(&line, &planned), line.job()) {
                    (None, Some(job)) => lines.entry(job).or_default().push(line.clone()),
                    (why, _) => report.bad_lines.push((at, why.unwrap_or_default())),
                }
                parsed.push(line);
            }
        }
    }
    let owner = Ownership::new(&config, &parsed);
    let mut listed = BTreeSet::new();
    for job in &planned {
        let Some(ls) = lines.get(job) else {
            report.missing.push(job.id());
            continue;
        };
        if ls.len() > 1 {
            report.duplicates.push(job.id());
        }
        let mut ok = true;
        for line in ls {
            for f in &line.files {
                listed.insert(f.path.clone());
                report.files_checked += 1;
                let why = match f.verify(root) {
                    Ok(true) => continue,
                    Ok(false) => match fs::metadata(root.join(&f.path)) {
                        Ok(m) if m.len() != f.bytes => {
                            format!("{} bytes, expected {}", m.len(), f.bytes)
                        }
                        _ => "SHA-256 differs".to_string(),
                    },
                    Err(e) if e.kind() == io::ErrorKind::NotFound => "file is missing".into(),
                    Err(e) => e.to_string(),
                };
                ok = false;
                report.corrupted.push((job.id(), f.path.clone(), why));
            }
        }
        if ok && ls.len() == 1 {
            report.frames_ok += 1;
        }
    }
    for rel in walk_files(root)? {
        let slash = slash_path(&rel);
        if is_bookkeeping(&rel) || listed.contains(&slash) {
            continue;
        }
        if owner.owns(&slash) {
            report.extra.push(slash);
        } else {
            report.kept.push(slash);
        }
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::FileRecord;

    #[test]
    fn ownership_covers_named_frame_and_temporary_files_only() {
        let text = "seed = 1\ntowns = [\"town01\"]\nconfigs = [\"normal\"]\n\
                    weathers = [\"clear\"]\nframes_per_sequence = 2\n\
                    layouts = [\"native\", \"kitti\"]\n";
        let config = super::super::parse_config(text, "t.toml").unwrap();
        let job = plan(&config)[0].clone();
        let line = ManifestLine {
            town: job.town.clone(),
            config: job.config.name().into(),
            weather: job.weather.name().into(),
            sequence: 0,
            frame: 0,
            town_frame: 0,
            seed: 0,
            files: vec![FileRecord {
                path: "old/listed.bin".into(),
                bytes: 1,
                sha256: String::new(),
            }],
            render: super::super::manifest::RenderRecord {
                spp: 1,
                rays: 0,
                seconds: 0.0,
            },
            disparity: Vec::new(),
            seeds: None,
        };
        let owner = Ownership::new(&config, [&line]);
        let seq = "town01/normal_clear/0000";
        for rel in [
            "old/listed.bin",
            "old/listed.bin.tmp-7-0",
            &format!("{seq}/left/rgb/000001.png"),
            &format!("{seq}/baseline_054/disp/000000.pfm.tmp-12-3"),
            "dataset.json.tmp-5-1",
            "kitti/baseline_054/image_2/x.png.tmp-link-9",
        ] {
            assert!(owner.owns(rel), "{rel} is the dataset's");
        }
        for rel in [
            "notes.txt",
            "old/other.bin",
            "old/notes.tmp-old",
            &format!("{seq}/left/rgb/stray.png"),
            &format!("{seq}/left/rgb/000001.png.bak"),
            // Frame 2 and sequence 1 are not planned; sceneflow is not written.
            &format!("{seq}/left/rgb/000002.png"),
            "town01/normal_clear/0001/left/rgb/000000.png",
            "sceneflow/disparity/a.pfm.tmp-1-1",
        ] {
            assert!(!owner.owns(rel), "{rel} is not the dataset's");
        }
        let twice = ManifestLine {
            files: vec![line.files[0].clone(), line.files[0].clone()],
            ..line.clone()
        };
        let planned = plan(&config).into_iter().collect();
        assert_eq!(line_problem(&line, &planned), None);
        assert_eq!(
            line_problem(&twice, &planned).as_deref(),
            Some("names old/listed.bin twice")
        );
    }
}
