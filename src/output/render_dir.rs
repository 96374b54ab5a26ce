//! The output directory of `parallax render`: checked before any render
//! work, written through a staging sibling, and swapped in whole.
//!
//! `-o DIR` may be new, empty, or an earlier render's output (nothing but
//! native-layout folders and files of one frame); anything else is refused
//! untouched. [`StagedDir::prepare`] creates the staging directory
//! `.NAME.partial-<pid>-<n>` beside DIR (which also proves DIR's parent
//! writable); the frame is written there, and [`StagedDir::commit`] then
//! renames an earlier render aside, renames the staging directory to DIR and
//! removes the earlier render. A failure, a panic or Ctrl-C before that
//! leaves DIR as it was; only the hidden staging directory may remain.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use super::layout::{is_preview_file, native_path, NativePath, PREVIEW_DIR};

/// A render's output directory being written: the staging directory and
/// where it goes. Dropped without [`StagedDir::commit`], it removes the
/// staging directory and any parent directories it created.
#[derive(Debug)]
pub struct StagedDir {
    target: PathBuf,
    staging: PathBuf,
    /// Ancestors of the target created by `prepare`, outermost first.
    created: Vec<PathBuf>,
    committed: bool,
}

impl StagedDir {
    /// Checks `target` (absent, empty or an earlier render's output) and
    /// creates the staging directory beside it. The error says what is wrong
    /// with `target` (the caller names the argument); nothing is left behind.
    pub fn prepare(target: &Path) -> Result<StagedDir, String> {
        let target = match fs::symlink_metadata(target) {
            Ok(_) => {
                let real =
                    fs::canonicalize(target).map_err(|e| format!("cannot resolve it: {e}"))?;
                if !real.is_dir() {
                    return Err("is a file, expected a directory".into());
                }
                check_replaceable(&real)?;
                real
            }
            // Absent, or below a file: creating the staging directory says which.
            Err(e)
                if matches!(
                    e.kind(),
                    io::ErrorKind::NotFound | io::ErrorKind::NotADirectory
                ) =>
            {
                target.to_path_buf()
            }
            Err(e) => return Err(format!("cannot use it: {e}")),
        };
        let name = target
            .file_name()
            .ok_or("names no directory (the file-system root or '..')")?
            .to_string_lossy()
            .into_owned();
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let mut staged = StagedDir {
            target: target.clone(),
            staging: PathBuf::new(),
            created: Vec::new(),
            committed: false,
        };
        staged.created = create_ancestors(&parent)
            .map_err(|(dir, e)| format!("cannot create {}: {e}", dir.display()))?;
        sweep_abandoned_stagings(&parent, &name);
        staged.staging = create_unique(&parent, &format!(".{name}.partial"))
            .map_err(|e| format!("cannot write in {}: {e}", parent.display()))?;
        Ok(staged)
    }

    /// Where the frame is written until [`StagedDir::commit`].
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Makes the staged frame the target directory, replacing an earlier
    /// render there. Returns a warning when that earlier render could not be
    /// removed afterwards (the new frame is in place; the warning names where
    /// the old one was left). If the target changed since `prepare` so that
    /// it no longer holds only a render, nothing is replaced and the error
    /// names where the new frame was kept.
    pub fn commit(mut self) -> io::Result<Option<String>> {
        // From here on the staged frame is complete: never removed on drop.
        self.committed = true;
        let keep = |why: String| {
            io::Error::other(format!(
                "{why}; the new frame is kept in {}",
                self.staging.display()
            ))
        };
        let old = match fs::symlink_metadata(&self.target) {
            Ok(_) => {
                check_replaceable(&self.target)
                    .map_err(|e| keep(format!("{} changed: {e}", self.target.display())))?;
                let parent = self.staging.parent().unwrap_or(Path::new("."));
                let name = self
                    .target
                    .file_name()
                    .unwrap_or_default()
                    .to_string_lossy();
                let aside = create_unique(parent, &format!(".{name}.old"))
                    .map_err(|e| keep(format!("cannot move the earlier render aside: {e}")))?;
                // `aside` is an empty directory: rename replaces it.
                fs::rename(&self.target, &aside)
                    .map_err(|e| keep(format!("cannot move the earlier render aside: {e}")))?;
                Some(aside)
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => None,
            Err(e) => return Err(keep(e.to_string())),
        };
        if let Err(e) = fs::rename(&self.staging, &self.target) {
            if let Some(aside) = &old {
                let _ = fs::rename(aside, &self.target);
            }
            return Err(keep(format!(
                "cannot rename it to {}: {e}",
                self.target.display()
            )));
        }
        Ok(old.and_then(|aside| {
            fs::remove_dir_all(&aside).err().map(|e| {
                format!(
                    "the earlier render was replaced but could not be removed from {}: {e}",
                    aside.display()
                )
            })
        }))
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if self.committed {
            return;
        }
        if !self.staging.as_os_str().is_empty() {
            let _ = fs::remove_dir_all(&self.staging);
        }
        for dir in self.created.iter().rev() {
            let _ = fs::remove_dir(dir);
        }
    }
}

/// Whether `dir` may be replaced by a render: empty, or only native-layout
/// folders and files, all of one frame. The error names an offending entry.
fn check_replaceable(dir: &Path) -> Result<(), String> {
    let mut frames = Vec::new();
    walk(dir, Path::new(""), &mut frames)?;
    frames.sort_unstable();
    frames.dedup();
    if frames.len() > 1 {
        return Err(format!(
            "holds {} frames ({}), a sequence rather than one render's output; \
             give a new or empty directory",
            frames.len(),
            frames
                .iter()
                .map(|f| super::frame_stem(*f))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    Ok(())
}

/// Checks every entry below `dir/rel`, collecting the frames of its files.
fn walk(dir: &Path, rel: &Path, frames: &mut Vec<u32>) -> Result<(), String> {
    let here = dir.join(rel);
    let entries =
        fs::read_dir(&here).map_err(|e| format!("cannot read {}: {e}", here.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("cannot read {}: {e}", here.display()))?;
        let rel = rel.join(entry.file_name());
        // Symbolic links are never written by a render: refused like any
        // other foreign entry (replacing would not remove what they point to).
        let kind = entry.file_type().map_err(|e| e.to_string())?;
        // An interrupted atomic write's temporary file counts as the file it
        // was for.
        let name = entry.file_name();
        let as_written = match name.to_str().and_then(crate::output::temp_base) {
            Some(base) if kind.is_file() => rel.with_file_name(base),
            _ => rel.clone(),
        };
        match native_path(&as_written) {
            Some(NativePath::Folder) if kind.is_dir() => walk(dir, &rel, frames)?,
            Some(NativePath::File { frame, .. }) if kind.is_file() => frames.push(frame),
            // `parallax preview DIR`'s pictures of this render: stale once it
            // is replaced, so they go with it.
            _ if rel == Path::new(PREVIEW_DIR) && kind.is_dir() => walk(dir, &rel, frames)?,
            _ if rel.parent() == Some(Path::new(PREVIEW_DIR))
                && kind.is_file()
                && rel
                    .file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(is_preview_file) => {}
            _ => {
                return Err(format!(
                    "holds {}, which is not part of a parallax render; give a new or empty \
                     directory, or an earlier render's output (it is replaced whole)",
                    rel.display()
                ))
            }
        }
    }
    Ok(())
}

/// Creates the missing directories down to `dir`; returns those created,
/// outermost first. On failure removes them again and names the one that
/// could not be created.
fn create_ancestors(dir: &Path) -> Result<Vec<PathBuf>, (PathBuf, io::Error)> {
    let missing: Vec<&Path> = dir
        .ancestors()
        .filter(|a| !a.as_os_str().is_empty())
        .take_while(|a| fs::symlink_metadata(a).is_err())
        .collect();
    let mut created = Vec::new();
    for a in missing.into_iter().rev() {
        match fs::create_dir(a) {
            Ok(()) => created.push(a.to_path_buf()),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {}
            Err(e) => {
                for c in created.iter().rev() {
                    let _ = fs::remove_dir(c);
                }
                return Err((a.to_path_buf(), e));
            }
        }
    }
    Ok(created)
}

/// Removes `.NAME.partial-<pid>-<n>` directories of renders that were killed
/// (their process is gone) before their frame was complete (no camera file,
/// which is written last). A complete frame that a failed swap kept there is
/// left for the user, as its message said.
fn sweep_abandoned_stagings(parent: &Path, name: &str) {
    let prefix = format!(".{name}.partial-");
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name
            .to_str()
            .and_then(|n| n.strip_prefix(&prefix))
            .and_then(|rest| rest.split_once('-'))
            .and_then(|(pid, n)| n.parse::<u32>().ok().and(pid.parse::<i32>().ok()))
        else {
            continue;
        };
        let dir = entry.path();
        if process_alive(pid) || dir.join(super::CAMERAS_DIR).exists() {
            continue;
        }
        let _ = fs::remove_dir_all(&dir);
    }
}

/// Whether process `pid` exists (signal 0 probes without sending anything).
fn process_alive(pid: i32) -> bool {
    if pid <= 0 {
        return true; // not a process id of ours: leave it
    }
    // SAFETY: kill with signal 0 only checks that `pid` exists.
    let r = unsafe { libc::kill(pid, 0) };
    r == 0 || io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
}

/// Creates a new directory `<parent>/<prefix>-<pid>-<n>` (first free `n`).
fn create_unique(parent: &Path, prefix: &str) -> io::Result<PathBuf> {
    let pid = std::process::id();
    for n in 0..1000 {
        let p = parent.join(format!("{prefix}-{pid}-{n}"));
        match fs::create_dir(&p) {
            Ok(()) => return Ok(p),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::new(
        io::ErrorKind::AlreadyExists,
        format!("{prefix}-{pid}-0 … 999 all exist"),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn put(p: &Path) {
        fs::create_dir_all(p.parent().unwrap()).unwrap();
        fs::write(p, b"x").unwrap();
    }

    #[test]
    fn a_killed_renders_incomplete_staging_is_swept_and_a_kept_frame_is_not() {
        let dir = tempfile::tempdir().unwrap();
        // Beyond any pid_max: no such process.
        let dead = dir.path().join(".out.partial-2147483646-0");
        put(&dead.join("left/rgb/000000.png"));
        let kept = dir.path().join(".out.partial-2147483646-1");
        put(&kept.join("cameras/000000.json"));
        let live = dir
            .path()
            .join(format!(".out.partial-{}-7", std::process::id()));
        put(&live.join("left/rgb/000000.png"));
        let other = dir.path().join(".other.partial-2147483646-0");
        put(&other.join("x"));
        let staged = StagedDir::prepare(&dir.path().join("out")).unwrap();
        assert!(!dead.exists());
        assert!(kept.exists() && live.exists() && other.exists());
        drop(staged);
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn new_directory_appears_only_on_commit_with_its_parents() {
        let t = tempfile::tempdir().unwrap();
        let target = t.path().join("a/b/out");
        let s = StagedDir::prepare(&target).unwrap();
        assert!(!target.exists());
        put(&s.path().join("cameras/000000.json"));
        assert_eq!(s.commit().unwrap(), None);
        assert!(target.join("cameras/000000.json").is_file());
        assert_eq!(names(&t.path().join("a/b")), ["out"]);
    }

    #[test]
    fn dropping_uncommitted_removes_staging_and_created_parents() {
        let t = tempfile::tempdir().unwrap();
        let s = StagedDir::prepare(&t.path().join("a/b/out")).unwrap();
        put(&s.path().join("left/rgb/000000.png"));
        drop(s);
        assert!(names(t.path()).is_empty());
    }

    #[test]
    fn earlier_render_is_replaced_whole() {
        let t = tempfile::tempdir().unwrap();
        let target = t.path().join("out");
        put(&target.join("baseline_054/rgb/000000.png"));
        put(&target.join("cameras/000000.json"));
        let s = StagedDir::prepare(&target).unwrap();
        put(&s.path().join("baseline_010/rgb/000000.png"));
        assert_eq!(s.commit().unwrap(), None);
        assert_eq!(names(&target), ["baseline_010"]);
        assert_eq!(names(t.path()), ["out"]);
    }

    #[test]
    fn foreign_or_multi_frame_directories_are_refused() {
        let t = tempfile::tempdir().unwrap();
        let target = t.path().join("out");
        put(&target.join("left/rgb/000000.png"));
        put(&target.join("left/rgb/notes.txt"));
        let e = StagedDir::prepare(&target).unwrap_err();
        assert!(e.contains("left/rgb/notes.txt"), "{e}");
        fs::remove_file(target.join("left/rgb/notes.txt")).unwrap();
        put(&target.join("cameras/000001.json"));
        let e = StagedDir::prepare(&target).unwrap_err();
        assert!(e.contains("2 frames (000000, 000001)"), "{e}");
        assert_eq!(names(t.path()), ["out"]);
    }

    #[test]
    fn target_changed_during_render_is_left_alone() {
        let t = tempfile::tempdir().unwrap();
        let target = t.path().join("out");
        let s = StagedDir::prepare(&target).unwrap();
        let staging = s.path().to_path_buf();
        put(&staging.join("cameras/000000.json"));
        put(&target.join("mine.txt"));
        let e = s.commit().unwrap_err().to_string();
        assert!(e.contains("mine.txt") && e.contains("kept in"), "{e}");
        assert!(target.join("mine.txt").is_file());
        assert!(staging.join("cameras/000000.json").is_file());
    }
}
