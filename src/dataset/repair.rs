//! `verify --repair` in two steps around the re-render, so that a repair
//! that cannot render changes nothing: [`stage`] only reads (the frames to
//! render and the manifest lines each has now); the caller renders them with
//! `run_dataset`, which overwrites a frame's files atomically and appends its
//! new line; [`finish`] then drops the lines the new ones replace and the
//! unreadable and unplanned lines, and removes the dataset's files that no
//! kept line lists. A frame that was not rendered keeps its lines and files;
//! files that are not the dataset's ([`Ownership`]) are never removed.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

use super::manifest::{read_manifests, ManifestLine};
use super::ownership::{is_bookkeeping, slash, Ownership};
use super::plan::{plan, Job};
use super::run::{walk_files, DatasetError};
use super::verify::{dataset_config, line_problem, VerifyReport};
use crate::output::{write_atomic, Access, OutputError};

/// A repair planned but not begun.
#[derive(Clone, Debug)]
pub struct Staged {
    /// Frames to render again: missing, corrupted and duplicated.
    pub redo: BTreeSet<Job>,
    /// The texts of those frames' manifest lines before the render.
    old: BTreeMap<Job, BTreeSet<String>>,
}

/// What [`finish`] changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Finished {
    /// Frames whose new line replaced their old ones.
    pub replaced: usize,
    /// Frames to redo that have no new line (failed or stopped): untouched.
    pub not_rendered: usize,
    /// Manifest lines dropped.
    pub lines_dropped: usize,
    /// The dataset's files removed (root-relative).
    pub removed: Vec<String>,
}

/// Plans the repair of what `report` found; reads only.
pub fn stage(root: &Path, report: &VerifyReport) -> Result<Staged, DatasetError> {
    let config = dataset_config(root)?;
    let ids = report.frames_to_render();
    let redo: BTreeSet<Job> = plan(&config)
        .into_iter()
        .filter(|j| ids.contains(&j.id()))
        .collect();
    let mut old: BTreeMap<Job, BTreeSet<String>> = BTreeMap::new();
    for l in read_manifests(root)? {
        if let Some(job) = l.parsed.ok().and_then(|p| p.job()) {
            if redo.contains(&job) {
                old.entry(job).or_default().insert(l.text);
            }
        }
    }
    Ok(Staged { redo, old })
}

/// Completes a repair after the render: every frame of `staged` with a new
/// line keeps only that line, unreadable and unplanned lines go, and the
/// dataset's files no kept line lists are removed (except those of frames
/// that were not rendered).
pub fn finish(root: &Path, staged: &Staged) -> Result<Finished, DatasetError> {
    let config = dataset_config(root)?;
    let planned: BTreeSet<Job> = plan(&config).into_iter().collect();
    let manifests = read_manifests(root)?;
    // The newest line of each frame to redo that was not there before.
    let mut new: BTreeMap<Job, &str> = BTreeMap::new();
    for l in &manifests {
        let job = l.parsed.as_ref().ok().and_then(ManifestLine::job);
        if let Some(job) = job.filter(|j| staged.redo.contains(j)) {
            if !staged.old.get(&job).is_some_and(|o| o.contains(&l.text)) {
                new.insert(job, &l.text);
            }
        }
    }
    let owner = Ownership::new(
        &config,
        manifests.iter().filter_map(|l| l.parsed.as_ref().ok()),
    );
    let mut done = Finished {
        replaced: new.len(),
        not_rendered: staged.redo.len() - new.len(),
        ..Finished::default()
    };
    let mut listed = BTreeSet::new();
    for lines in manifests.chunk_by(|a, b| a.file == b.file) {
        let mut kept = String::new();
        for l in lines {
            // A line verify calls bad goes, by verify's own rule.
            let keep = l
                .parsed
                .as_ref()
                .ok()
                .filter(|p| line_problem(p, &planned).is_none())
                .and_then(|p| Some((p.job()?, p)))
                .filter(|(job, _)| new.get(job).is_none_or(|n| *n == l.text));
            match keep {
                Some((_, line)) => {
                    listed.extend(line.files.iter().map(|f| f.path.clone()));
                    kept.push_str(&l.text);
                    kept.push('\n');
                }
                None => done.lines_dropped += 1,
            }
        }
        if kept.lines().count() != lines.len() {
            write_atomic(&lines[0].file, kept.as_bytes())?;
        }
    }
    let unrendered: BTreeSet<&Job> = staged
        .redo
        .iter()
        .filter(|j| !new.contains_key(*j))
        .collect();
    for rel in walk_files(root)? {
        let path = slash(&rel);
        if is_bookkeeping(&rel) || listed.contains(&path) || !owner.owns(&path) {
            continue;
        }
        // A frame that was not rendered again keeps whatever it has.
        if owner
            .frame_of(&path)
            .is_some_and(|j| unrendered.contains(&j))
        {
            continue;
        }
        let p = root.join(&rel);
        fs::remove_file(&p).map_err(|e| OutputError::wrap(&p, Access::Write, e))?;
        done.removed.push(path);
    }
    Ok(done)
}
