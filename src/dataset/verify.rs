//! `parallax verify ROOT`: proves a dataset (one shard's or the union of
//! many) whole against its own `dataset.json`: every planned frame has a
//! manifest line, every file of every line exists with its size and SHA-256,
//! no frame has two lines and no file lies outside the manifests. `--repair`
//! drops the bad lines, removes extra files and re-renders exactly the
//! missing, corrupted and duplicated frames.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::io;
use std::path::Path;

use super::manifest::{read_manifests, ManifestLine, DATASET_JSON, FAILURES_DIR, MANIFEST_DIR};
use super::plan::{plan, Job};
use super::run::{walk_files, DatasetError};
use crate::output::{write_atomic, Access, OutputError};

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
    /// Files below the root that no manifest line lists.
    pub extra: Vec<String>,
    /// Manifest lines that do not parse or name no planned frame: (file:line, reason).
    pub bad_lines: Vec<(String, String)>,
}

impl VerifyReport {
    /// True when nothing is missing, corrupted, duplicated, extra or unreadable.
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
        for (at, why) in &self.bad_lines {
            t += &format!("bad line   {at}: {why}\n");
        }
        t += &format!(
            "{} frames ok, {} files checked; {} missing, {} corrupted, {} duplicate, {} extra files, {} bad manifest lines\n",
            self.frames_ok,
            self.files_checked,
            self.missing.len(),
            self.corrupted.iter().map(|c| &c.0).collect::<BTreeSet<_>>().len(),
            self.duplicates.len(),
            self.extra.len(),
            self.bad_lines.len()
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

/// Checks the dataset below `root` (every checksum).
pub fn verify_dataset(root: &Path) -> Result<VerifyReport, DatasetError> {
    let config = dataset_config(root)?;
    let planned: BTreeSet<Job> = plan(&config).into_iter().collect();
    let mut report = VerifyReport::default();
    let mut lines: BTreeMap<Job, Vec<ManifestLine>> = BTreeMap::new();
    for l in read_manifests(root)? {
        let at = format!("{}:{}", l.file.display(), l.line_no);
        match l.parsed {
            Err(e) => report.bad_lines.push((at, e)),
            Ok(line) => match line.job().filter(|j| planned.contains(j)) {
                Some(job) => lines.entry(job).or_default().push(line),
                None => report
                    .bad_lines
                    .push((at, "names no frame of this dataset's plan".into())),
            },
        }
    }
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
        let first = rel.components().next().map(|c| c.as_os_str().to_owned());
        let top = first.as_deref().and_then(|s| s.to_str()).unwrap_or("");
        if rel == Path::new(DATASET_JSON)
            || top == MANIFEST_DIR
            || top == FAILURES_DIR
            || super::layouts::is_layout_index(&rel)
        {
            continue;
        }
        let slash: Vec<String> = rel
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        let slash = slash.join("/");
        if !listed.contains(&slash) {
            report.extra.push(slash);
        }
    }
    Ok(report)
}

/// Repairs what `report` found: rewrites every manifest without unreadable
/// lines, unplanned lines and every line of a frame to re-render, removes
/// extra files and returns the jobs to render again.
pub fn prepare_repair(root: &Path, report: &VerifyReport) -> Result<BTreeSet<Job>, DatasetError> {
    let config = dataset_config(root)?;
    let redo_ids = report.frames_to_render();
    let planned: BTreeMap<String, Job> = plan(&config).into_iter().map(|j| (j.id(), j)).collect();
    let redo: BTreeSet<Job> = redo_ids
        .iter()
        .filter_map(|id| planned.get(id).cloned())
        .collect();
    for file in super::manifest::manifest_files(root)? {
        let text = String::from_utf8_lossy(&crate::output::read_file(&file)?).into_owned();
        let mut kept = String::new();
        for line in text.lines() {
            let keep = serde_json::from_str::<ManifestLine>(line)
                .ok()
                .and_then(|l| l.job())
                .is_some_and(|j| planned.contains_key(&j.id()) && !redo_ids.contains(&j.id()));
            if keep {
                kept.push_str(line);
                kept.push('\n');
            }
        }
        if kept != text {
            write_atomic(&file, kept.as_bytes())?;
        }
    }
    for e in &report.extra {
        let p = root.join(e);
        fs::remove_file(&p).map_err(|err| OutputError::wrap(&p, Access::Write, err))?;
    }
    Ok(redo)
}
