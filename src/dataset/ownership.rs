//! Which files below a dataset root are the dataset's: the one rule behind
//! `verify` (extra or kept), `verify --repair` (what it may remove), the
//! resume sweep of temporaries and `dataset --force` (what it deletes).
//! A file is the dataset's iff it is named by a readable manifest line, or
//! is a native-layout file of a planned frame at exactly the path the
//! writers give it (`<town>/<config>_<weather>/<SSSS>/<native path>`), or a
//! file another configured layout writes for a planned frame
//! (`<layout>/…`, `output::layouts::frame_files`), or a temporary of the
//! atomic writers (`output::temp_base`) of any of these or of the bookkeeping.
//! Everything else is the user's and stays.

use std::collections::{BTreeSet, HashMap};
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::Path;
use std::sync::OnceLock;

use super::config::DatasetConfig;
use super::manifest::{ManifestLine, DATASET_JSON, FAILURES_DIR, MANIFEST_DIR};
use super::plan::{plan, Job};
use crate::output::layouts::{frame_files, LayoutKind};
use crate::output::temp_base;
use crate::output::{baseline_dir_name, native_path, NativePath};

/// The ownership rule of one dataset (see the module header).
pub struct Ownership {
    planned: BTreeSet<Job>,
    /// Each planned sequence directory (`town01/normal_clear/0000`) with a
    /// job of it (its frame is replaced by the file's).
    sequences: HashMap<String, Job>,
    /// The configured baselines' folders (`baseline_054`).
    baseline_dirs: BTreeSet<String>,
    /// Paths named by readable manifest lines.
    named: BTreeSet<String>,
    /// The configured layouts other than native.
    layouts: Vec<LayoutKind>,
    /// Planned frames, indexed by `layout_index`.
    jobs: Vec<Job>,
    /// (hash of a layout file's root-relative path, index into `jobs`),
    /// sorted: a compact index of every other layout's files, built on the
    /// first file met in a layout's folder; a hit is confirmed against the
    /// frame's paths, so a collision cannot mislead.
    layout_index: OnceLock<Vec<(u64, u32)>>,
    baselines_cm: Vec<f64>,
}

fn path_hash(rel: &str) -> u64 {
    let mut h = DefaultHasher::new();
    rel.hash(&mut h);
    h.finish()
}

impl Ownership {
    /// The ownership rule of `config`'s dataset whose manifests hold `lines`.
    pub fn new<'a>(
        config: &DatasetConfig,
        lines: impl IntoIterator<Item = &'a ManifestLine>,
    ) -> Ownership {
        let jobs = plan(config);
        let sequences = jobs
            .iter()
            .map(|j| (slash(&j.sequence_dir()), j.clone()))
            .collect();
        let layouts = super::layouts::extra_kinds(&config.layouts).collect();
        Ownership {
            planned: jobs.iter().cloned().collect(),
            sequences,
            baseline_dirs: config
                .baselines_cm
                .iter()
                .map(|&b| baseline_dir_name(b))
                .collect(),
            named: lines
                .into_iter()
                .flat_map(|l| l.files.iter().map(|f| f.path.clone()))
                .collect(),
            layouts,
            jobs,
            layout_index: OnceLock::new(),
            baselines_cm: config.baselines_cm.clone(),
        }
    }

    fn layout_index(&self) -> &[(u64, u32)] {
        self.layout_index.get_or_init(|| {
            let mut index = Vec::new();
            for (i, job) in self.jobs.iter().enumerate() {
                index.extend(
                    self.layout_files(job)
                        .iter()
                        .map(|f| (path_hash(f), i as u32)),
                );
            }
            index.sort_unstable();
            index
        })
    }

    /// Root-relative paths of `job`'s files in the other configured layouts.
    fn layout_files(&self, job: &Job) -> Vec<String> {
        let key = super::layouts::frame_key(job);
        self.layouts
            .iter()
            .flat_map(|&kind| {
                frame_files(kind, &key, &self.baselines_cm)
                    .into_iter()
                    .map(move |f| format!("{}/{f}", kind.name()))
            })
            .collect()
    }

    /// True when `rel` ('/'-separated, relative to the root) is the dataset's.
    pub fn owns(&self, rel: &str) -> bool {
        let (base, temp) = strip_temp(rel);
        self.named.contains(&base)
            || self.native_frame(&base).is_some()
            || self.layout_frame(&base).is_some()
            || (temp && is_bookkeeping(Path::new(&base)))
    }

    /// The planned frame whose native or other-layout file `rel` is (or is
    /// the temporary of); `None` for any other path.
    pub fn frame_of(&self, rel: &str) -> Option<Job> {
        let (base, _) = strip_temp(rel);
        self.native_frame(&base)
            .or_else(|| self.layout_frame(&base))
    }

    /// `<town>/<config>_<weather>/<SSSS>/<native path>` of a planned frame,
    /// in a configured baseline's folder.
    fn native_frame(&self, rel: &str) -> Option<Job> {
        let mut parts = rel.splitn(4, '/');
        let seq = [parts.next()?, parts.next()?, parts.next()?].join("/");
        let rest = parts.next()?;
        let job = self.sequences.get(&seq)?;
        let NativePath::File { frame, .. } = native_path(Path::new(rest))? else {
            return None;
        };
        let top = rest.split('/').next().unwrap_or("");
        if top.starts_with("baseline_") && !self.baseline_dirs.contains(top) {
            return None;
        }
        let job = Job {
            frame,
            ..job.clone()
        };
        self.planned.contains(&job).then_some(job)
    }

    /// A file another configured layout writes for a planned frame.
    fn layout_frame(&self, rel: &str) -> Option<Job> {
        let top = rel.split('/').next().unwrap_or("");
        if !self.layouts.iter().any(|k| k.name() == top) {
            return None;
        }
        let h = path_hash(rel);
        let index = self.layout_index();
        let from = index.partition_point(|e| e.0 < h);
        index[from..]
            .iter()
            .take_while(|e| e.0 == h)
            .map(|e| &self.jobs[e.1 as usize])
            .find(|job| self.layout_files(job).iter().any(|f| f == rel))
            .cloned()
    }
}

/// The path a temporary file will be renamed to, and whether `rel` is one.
fn strip_temp(rel: &str) -> (String, bool) {
    let (dir, name) = match rel.rsplit_once('/') {
        Some((d, n)) => (Some(d), n),
        None => (None, rel),
    };
    match (temp_base(name), dir) {
        (Some(base), Some(d)) => (format!("{d}/{base}"), true),
        (Some(base), None) => (base.to_string(), true),
        (None, _) => (rel.to_string(), false),
    }
}

/// A relative path '/'-separated, as manifests write it.
pub fn slash(rel: &Path) -> String {
    let parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    parts.join("/")
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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::output::FileRecord;

    /// A manifest line of `job` listing `file`.
    pub(crate) fn line_of(job: &Job, file: FileRecord) -> ManifestLine {
        ManifestLine {
            town: job.town.clone(),
            config: job.config.name().into(),
            weather: job.weather.name().into(),
            sequence: job.sequence,
            frame: job.frame,
            town_frame: 0,
            seed: 0,
            files: vec![file],
            render: super::super::manifest::RenderRecord {
                spp: 1,
                rays: 0,
                seconds: 0.0,
            },
            disparity: Vec::new(),
            seeds: None,
        }
    }

    #[test]
    fn ownership_covers_named_frame_and_temporary_files_only() {
        let text = "seed = 1\ntowns = [\"town01\"]\nconfigs = [\"normal\"]\n\
                    weathers = [\"clear\"]\nframes_per_sequence = 2\n\
                    baselines_cm = [10.0, 54.0]\nlayouts = [\"native\", \"kitti\"]\n";
        let config = super::super::parse_config(text, "t.toml").unwrap();
        let listed = FileRecord {
            path: "old/listed.bin".into(),
            bytes: 1,
            sha256: String::new(),
        };
        let line = line_of(&plan(&config)[0], listed);
        let owner = Ownership::new(&config, [&line]);
        let seq = "town01/normal_clear/0000";
        let kitti = "kitti/baseline_054/image_2/town01_normal_clear_0000_000001.png";
        for rel in [
            "old/listed.bin",
            "old/listed.bin.tmp-7-0",
            &format!("{seq}/left/rgb/000001.png"),
            &format!("{seq}/left/rgb_hdr/000001.exr"),
            &format!("{seq}/cameras/000000.json"),
            &format!("{seq}/baseline_054/disp/000000.pfm.tmp-12-3"),
            "dataset.json.tmp-5-1",
            kitti,
            &format!("{kitti}.tmp-link-9"),
            "kitti/baseline_010/disp_noc_0/town01_normal_clear_0000_000000.png",
        ] {
            assert!(owner.owns(rel), "{rel} is the dataset's");
        }
        for rel in [
            "notes.txt",
            "notes.txt.tmp-1-1",
            "old/other.bin",
            "old/notes.tmp-old",
            &format!("{seq}/left/rgb/stray.png"),
            &format!("{seq}/left/rgb/000001.png.bak"),
            &format!("{seq}/left/rgb/000001.png.tmp-1-1.tmp-2-2"),
            // A frame's number in a folder or with an extension the layout
            // does not write, or in a sequence folder not spelled `SSSS`.
            &format!("{seq}/mystuff/000000.txt"),
            &format!("{seq}/mystuff/000000.txt.tmp-1-1"),
            &format!("{seq}/left/rgb/000000.txt"),
            &format!("{seq}/left/disp/000000.pfm"),
            &format!("{seq}/baseline_300/rgb/000000.png"),
            &format!("{seq}/000000.png"),
            "town01/normal_clear/0/left/rgb/000000.png",
            "town01/normal_clear/00000/left/rgb/000000.png",
            // Frame 2 and sequence 1 are not planned; sceneflow is not written.
            &format!("{seq}/left/rgb/000002.png"),
            "town01/normal_clear/0001/left/rgb/000000.png",
            "kitti/baseline_054/image_2/town01_normal_clear_0000_000002.png",
            "kitti/baseline_054/image_2/x.png.tmp-link-9",
            "kitti/baseline_054/mine/town01_normal_clear_0000_000001.png",
            "sceneflow/disparity/a.pfm.tmp-1-1",
        ] {
            assert!(!owner.owns(rel), "{rel} is not the dataset's");
        }
        let job = owner.frame_of(&format!("{kitti}.tmp-1-2")).unwrap();
        assert_eq!(job.id(), "town01/normal_clear/0000/000001");
        let job = owner.frame_of(&format!("{seq}/cameras/000001.json.tmp-4-0"));
        assert_eq!(
            job.map(|j| j.id()).as_deref(),
            Some("town01/normal_clear/0000/000001")
        );
        assert_eq!(owner.frame_of("old/listed.bin"), None);
    }
}
