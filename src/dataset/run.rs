//! The dataset loop: prepare the root (module `root`), sweep temporary files left by a killed run, skip complete frames, render
//! the rest with one retry, write each frame whole and append its manifest
//! line, and list failures. Resume is simply running the same command again.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::time::Instant;

use super::config::DatasetConfig;
use super::frame::{frame_complete, render_job, write_job, Quality, StaticCache, Towns};
use super::manifest::{
    append_line, cut_torn_tail, latest_lines, read_manifests, ManifestLine, ReadLine, RenderRecord,
    FAILURES_DIR, MANIFEST_DIR,
};
use super::ownership::{slash, Ownership};
use super::plan::{plan, Job};
use super::progress::{Progress, RunSummary};
use super::shard::Shard;
use super::signals::StopGuard;
use crate::accel::Backend;
use crate::output::{write_atomic, Access, OutputError};
use crate::render::RenderStats;

/// A dataset error: bad input (exit 2) or a failure while running (exit 1).
#[derive(Debug)]
pub struct DatasetError {
    /// Message naming the file, key or path.
    pub message: String,
    /// True for bad input (configuration, arguments, refused directory).
    pub input: bool,
}

impl DatasetError {
    /// A bad-input error.
    pub fn input(message: impl Into<String>) -> Self {
        DatasetError {
            message: message.into(),
            input: true,
        }
    }
    /// A runtime failure.
    pub fn failure(message: impl Into<String>) -> Self {
        DatasetError {
            message: message.into(),
            input: false,
        }
    }
}

impl From<io::Error> for DatasetError {
    fn from(e: io::Error) -> Self {
        DatasetError::failure(e.to_string())
    }
}

/// How to run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Dataset root.
    pub root: PathBuf,
    /// Which part of the job list.
    pub shard: Shard,
    /// Replace a different configuration in a non-empty root.
    pub force: bool,
    /// Check SHA-256 of complete frames before skipping them (else sizes only).
    pub check_hashes: bool,
    /// Traversal backend.
    pub backend: Backend,
    /// Directory holding the town files (`None`: the built-in towns).
    pub scenes: Option<PathBuf>,
    /// Render exactly these jobs, even those a manifest line calls complete
    /// (verify --repair); `None`: the whole shard, skipping complete frames.
    pub only: Option<BTreeSet<Job>>,
}

pub use crate::output::temp_base;

/// True for names written by the atomic writers before their rename.
pub fn is_temp_name(name: &str) -> bool {
    temp_base(name).is_some()
}

/// The ownership rule of the dataset of `config` below `root`, with the
/// files its readable manifest lines name.
pub(super) fn ownership_of(root: &Path, config: &DatasetConfig) -> io::Result<Ownership> {
    Ok(ownership_from(config, &read_manifests(root)?))
}

/// The ownership rule of `config`'s dataset whose manifests hold `lines`.
fn ownership_from(config: &DatasetConfig, lines: &[ReadLine]) -> Ownership {
    Ownership::new(config, lines.iter().filter_map(|l| l.parsed.as_ref().ok()))
}

/// Every file below `root` (relative paths), depth first, sorted.
pub fn walk_files(root: &Path) -> io::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        let dir = root.join(&rel);
        for e in fs::read_dir(&dir).map_err(|e| OutputError::wrap(&dir, Access::Read, e))? {
            let e = e.map_err(|e| OutputError::wrap(&dir, Access::Read, e))?;
            let r = rel.join(e.file_name());
            if e.file_type().is_ok_and(|t| t.is_dir()) {
                stack.push(r);
            } else {
                out.push(r);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Removes temporary files of the dataset's (`ownership`) a killed run left
/// behind: those of this shard's jobs, and (for a one-shard run) every
/// other one. Returns how many.
fn sweep_temp_files(
    root: &Path,
    config: &DatasetConfig,
    lines: &[ReadLine],
    jobs: &BTreeSet<Job>,
    shard: Shard,
) -> io::Result<usize> {
    let temps: Vec<PathBuf> = walk_files(root)?
        .into_iter()
        .filter(|rel| {
            let name = rel.file_name().map(|s| s.to_string_lossy().into_owned());
            name.is_some_and(|n| is_temp_name(&n))
        })
        .collect();
    if temps.is_empty() {
        return Ok(0);
    }
    let owner = ownership_from(config, lines);
    let mut n = 0;
    for rel in temps {
        let path = slash(&rel);
        if !owner.owns(&path) {
            continue;
        }
        let ours = match owner.frame_of(&path) {
            Some(job) => jobs.contains(&job),
            None => shard.count == 1,
        };
        if ours {
            let p = root.join(&rel);
            fs::remove_file(&p).map_err(|e| OutputError::wrap(&p, Access::Write, e))?;
            n += 1;
        }
    }
    Ok(n)
}

/// Errors after which further frames cannot succeed either.
fn is_fatal(e: &io::Error) -> bool {
    use io::ErrorKind::*;
    matches!(
        e.kind(),
        StorageFull | ReadOnlyFilesystem | PermissionDenied | QuotaExceeded
    )
}

/// Runs (or resumes) the configuration's jobs of `opts.shard` below `opts.root`.
pub fn run_dataset(
    config: &DatasetConfig,
    opts: &RunOptions,
    stop: &StopGuard,
) -> Result<RunSummary, DatasetError> {
    let started = Instant::now();
    let towns = Towns::load(config, opts.scenes.as_deref()).map_err(DatasetError::input)?;
    super::root::prepare_root(&opts.root, config, &towns.sources(config), opts.force)?;
    let jobs = shard_jobs(config, opts);
    let start = start_run(config, opts, &jobs)?;
    let views = 1 + config.baselines_cm.len();
    let run = Run {
        config,
        towns: &towns,
        opts,
        stop,
        manifest: start.manifest,
        progress: Progress::new(jobs.len() as u64, views as u64),
        cache: StaticCache::default(),
    };
    if start.swept > 0 {
        run.progress.note(&format!(
            "removed {} temporary files of an interrupted run",
            start.swept
        ));
    }
    let mut s = RunSummary::default();
    // Frames written again over a line of theirs (damaged on disk).
    let mut superseded = BTreeSet::new();
    for (k, job) in jobs.iter().enumerate() {
        if stop.stopped() {
            break;
        }
        // A repair renders its frames whatever their old lines say.
        if let Some(line) = start.existing.get(job).filter(|_| opts.only.is_none()) {
            if frame_complete(&opts.root, line, opts.check_hashes) {
                s.skipped += 1;
                run.progress
                    .frame(k as u64 + 1, job, "complete, skipped", &s);
                continue;
            }
        }
        match run.frame(k, job, &mut s) {
            Ok(true) if start.existing.contains_key(job) => {
                superseded.insert(job.clone());
            }
            Ok(_) => {}
            Err((e, fatal)) => {
                run.progress.note(&format!("FAILED {}: {e}", job.id()));
                s.failed.push((job.id(), e));
                if fatal {
                    run.progress.note("stopping: the output cannot be written");
                    break;
                }
            }
        }
    }
    run.progress.finish();
    // A repair drops old lines itself (module `repair`), after every frame.
    if opts.only.is_none() {
        drop_superseded_lines(&run.manifest, &superseded)?;
    }
    write_failures(&opts.root, opts.shard, &s)?;
    eprintln!(
        "shard {}: {}",
        opts.shard,
        s.line(started.elapsed().as_secs_f64())
    );
    Ok(s)
}

/// The jobs of `opts.shard` (only those of `opts.only`, if given), in plan order.
fn shard_jobs(config: &DatasetConfig, opts: &RunOptions) -> Vec<Job> {
    plan(config)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| opts.shard.owns(*i))
        .map(|(_, j)| j)
        .filter(|j| opts.only.as_ref().is_none_or(|o| o.contains(j)))
        .collect()
}

/// What a run finds at its start.
struct RunStart {
    /// This shard's manifest.
    manifest: PathBuf,
    /// The last manifest line of every frame (any shard's).
    existing: BTreeMap<Job, ManifestLine>,
    /// Temporary files of an interrupted run removed.
    swept: usize,
}

/// Cuts a torn line off this shard's manifest, reads the manifests (once),
/// sweeps the temporaries of `jobs` and writes the layouts' split lists.
fn start_run(
    config: &DatasetConfig,
    opts: &RunOptions,
    jobs: &[Job],
) -> Result<RunStart, DatasetError> {
    let root = opts.root.as_path();
    let manifest = root.join(MANIFEST_DIR).join(opts.shard.manifest_name());
    cut_torn_tail(&manifest)?;
    let lines = read_manifests(root)?;
    let job_set: BTreeSet<Job> = jobs.iter().cloned().collect();
    let swept = sweep_temp_files(root, config, &lines, &job_set, opts.shard)?;
    super::layouts::write_layout_indexes(root, config)
        .map_err(|e| DatasetError::failure(e.to_string()))?;
    Ok(RunStart {
        manifest,
        existing: latest_lines(&lines),
        swept,
    })
}

/// What one attempt at a frame came to.
enum Attempt {
    /// Rendered and written: its manifest line's render record and the
    /// render's statistics.
    Written(RenderRecord, RenderStats),
    /// The render failed.
    RenderFailed(String),
    /// Writing the files or the line failed.
    WriteFailed(io::Error),
    /// A stop came during the render: nothing of the frame was written.
    Stopped,
}

/// One shard's run over its jobs.
struct Run<'a> {
    config: &'a DatasetConfig,
    towns: &'a Towns,
    opts: &'a RunOptions,
    stop: &'a StopGuard,
    manifest: PathBuf,
    progress: Progress,
    /// The static world of the town being rendered (jobs come town by town).
    cache: StaticCache,
}

impl Run<'_> {
    /// Renders and writes frame `k` (`job`) with one retry: `Ok(true)` when
    /// written, `Ok(false)` when abandoned for a stop, else the last error
    /// and whether it is fatal for the run.
    fn frame(&self, k: usize, job: &Job, s: &mut RunSummary) -> Result<bool, (String, bool)> {
        let mut last_err = (String::new(), false);
        for attempt in 0..2 {
            let retry = |e: &dyn std::fmt::Display| {
                if attempt == 0 {
                    self.progress
                        .note(&format!("{}: {e}; retrying once", job.id()));
                }
            };
            match self.attempt(k, job) {
                Attempt::Written(record, stats) => {
                    s.done += 1;
                    s.rays += record.rays;
                    s.frame_seconds += record.seconds;
                    s.trace_seconds += stats.gt_seconds + stats.path_seconds;
                    self.progress.frame(k as u64 + 1, job, "written", s);
                    if let Some(warning) = stats.non_finite_warning() {
                        self.progress.note(&format!("{}: {warning}", job.id()));
                    }
                    return Ok(true);
                }
                Attempt::Stopped => return Ok(false),
                Attempt::RenderFailed(e) => {
                    retry(&e);
                    last_err = (e, false);
                }
                Attempt::WriteFailed(e) => {
                    let fatal = is_fatal(&e);
                    last_err = (e.to_string(), fatal);
                    retry(&e);
                }
            }
        }
        Err(last_err)
    }

    /// Renders frame `k` (`job`) once and, unless stopped, writes its files
    /// and appends its manifest line (holding off a stop meanwhile).
    fn attempt(&self, k: usize, job: &Job) -> Attempt {
        let t0 = Instant::now();
        let cb = |done: usize, _: usize| self.progress.views(k as u64, done);
        let config = self.config;
        let r = render_job(
            config,
            self.towns,
            job,
            Quality::of(config),
            self.opts.backend,
            &self.cache,
            &cb,
        );
        let r = match r {
            Ok(r) => r,
            Err(e) => return Attempt::RenderFailed(e),
        };
        if self.stop.stopped() {
            return Attempt::Stopped;
        }
        let _held = self.stop.write_lock();
        let root = self.opts.root.as_path();
        let written =
            write_job(root, config, job, &r, t0.elapsed().as_secs_f64()).and_then(|mut line| {
                line.render.seconds = t0.elapsed().as_secs_f64();
                append_line(&self.manifest, &line).map(|_| line)
            });
        match written {
            Ok(line) => Attempt::Written(line.render, r.out.stats),
            Err(e) => Attempt::WriteFailed(e),
        }
    }
}

/// Drops from this shard's manifest every line of `jobs` but the last, so a
/// frame written again over a damaged one keeps one line. Other shards'
/// manifests are theirs to append to and stay as they are (a line of the
/// frame there remains, and `verify` reports the frame as duplicate).
fn drop_superseded_lines(manifest: &Path, jobs: &BTreeSet<Job>) -> io::Result<()> {
    if jobs.is_empty() {
        return Ok(());
    }
    let bytes = crate::output::read_file(manifest)?;
    let text = String::from_utf8_lossy(&bytes);
    let lines: Vec<(&str, Option<Job>)> = text
        .lines()
        .map(|l| {
            let job = serde_json::from_str::<super::manifest::ManifestLine>(l)
                .ok()
                .and_then(|p| p.job())
                .filter(|j| jobs.contains(j));
            (l, job)
        })
        .collect();
    let last: std::collections::BTreeMap<&Job, usize> = lines
        .iter()
        .enumerate()
        .filter_map(|(i, (_, j))| Some((j.as_ref()?, i)))
        .collect();
    let mut kept = String::new();
    for (i, (l, job)) in lines.iter().enumerate() {
        if job.as_ref().is_none_or(|j| last[j] == i) {
            kept.push_str(l);
            kept.push('\n');
        }
    }
    if kept.lines().count() != lines.len() {
        write_atomic(manifest, kept.as_bytes())?;
    }
    Ok(())
}

/// Writes `failures/shard-i-of-N.txt` (one `id<TAB>error` per line), or
/// removes it when nothing failed.
fn write_failures(root: &Path, shard: Shard, s: &RunSummary) -> Result<(), DatasetError> {
    let path = root
        .join(FAILURES_DIR)
        .join(format!("shard-{}-of-{}.txt", shard.index, shard.count));
    if s.failed.is_empty() {
        if path.exists() {
            fs::remove_file(&path).map_err(|e| OutputError::wrap(&path, Access::Write, e))?;
        }
        return Ok(());
    }
    let text: String = s
        .failed
        .iter()
        .map(|(id, e)| format!("{id}\t{}\n", e.replace('\n', " ")))
        .collect();
    if let Err(e) = write_atomic(&path, text.as_bytes()) {
        eprintln!("parallax: cannot write the failure list: {e}");
    } else {
        eprintln!("failures listed in {}", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_atomic_writers_names_are_temporary() {
        assert_eq!(temp_base("000007.png.tmp-9-1"), Some("000007.png"));
        assert_eq!(
            temp_base("0000_000001.jpg.tmp-link-42"),
            Some("0000_000001.jpg")
        );
        assert_eq!(temp_base("dataset.json.tmp-123-45"), Some("dataset.json"));
        for name in [
            "notes.tmp-old",
            "a.tmp-1",
            "a.tmp-1-",
            "a.tmp-x-2",
            ".tmp-1-2",
            "a.png",
        ] {
            assert_eq!(temp_base(name), None, "{name}");
        }
    }
}
