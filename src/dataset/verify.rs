//! `parallax verify ROOT`: proves a dataset (one shard's or the union of
//! many) whole against its own `dataset.json`: every planned frame has a
//! manifest line, every file of every line exists with its size and SHA-256,
//! no frame has two lines, no line names a file twice and none of the
//! dataset's files lies outside the manifests. Files that are not the
//! dataset's (module `ownership`) are listed as kept. `--repair` (module
//! `repair`) re-renders exactly the missing, corrupted and duplicated frames.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::io;
use std::path::Path;

use super::manifest::{read_manifests, ManifestLine, DATASET_JSON};
use super::ownership::{is_bookkeeping, slash, Ownership};
use super::plan::{plan, Job};
use super::run::{walk_files, DatasetError};

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
        let path = slash(&rel);
        if is_bookkeeping(&rel) || listed.contains(&path) {
            continue;
        }
        if owner.owns(&path) {
            report.extra.push(path);
        } else {
            report.kept.push(path);
        }
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::FileRecord;

    #[test]
    fn a_line_must_name_a_planned_frame_and_each_file_once() {
        let text = "seed = 1\ntowns = [\"town01\"]\nconfigs = [\"normal\"]\n\
                    weathers = [\"clear\"]\nframes_per_sequence = 2\n";
        let config = super::super::parse_config(text, "t.toml").unwrap();
        let file = FileRecord {
            path: "town01/normal_clear/0000/left/rgb/000000.png".into(),
            bytes: 1,
            sha256: String::new(),
        };
        let mut line = crate::dataset::ownership::tests::line_of(&plan(&config)[0], file.clone());
        let planned = plan(&config).into_iter().collect();
        assert_eq!(line_problem(&line, &planned), None);
        let twice = ManifestLine {
            files: vec![file.clone(), file],
            ..line.clone()
        };
        assert_eq!(
            line_problem(&twice, &planned).as_deref(),
            Some("names town01/normal_clear/0000/left/rgb/000000.png twice")
        );
        line.frame = 2;
        assert_eq!(
            line_problem(&line, &planned).as_deref(),
            Some("names no frame of this dataset's plan")
        );
    }
}
