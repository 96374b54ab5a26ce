//! Atomic file writes (temporary file in the same directory, fsync, rename)
//! and the path-carrying error every writer and reader returns.

use std::fmt;
use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Whether a failed operation was reading or writing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// Reading an existing file.
    Read,
    /// Creating or replacing a file.
    Write,
}

/// An I/O or format error tied to the file it concerns. Displayed as
/// "cannot write <path>: <reason>" (or "cannot read …"). Writers and readers
/// return it inside an `io::Error` of the source's kind.
#[derive(Debug)]
pub struct OutputError {
    /// The file being read or written.
    pub path: PathBuf,
    /// Read or write.
    pub access: Access,
    /// The underlying cause.
    pub source: io::Error,
}

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let verb = match self.access {
            Access::Read => "read",
            Access::Write => "write",
        };
        write!(f, "cannot {verb} {}: {}", self.path.display(), self.source)
    }
}

impl std::error::Error for OutputError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.source)
    }
}

impl OutputError {
    /// Wraps `source` as an `io::Error` (same kind) naming `path`.
    pub fn wrap(path: &Path, access: Access, source: io::Error) -> io::Error {
        io::Error::new(
            source.kind(),
            OutputError {
                path: path.to_path_buf(),
                access,
                source,
            },
        )
    }
}

/// An `InvalidData` error with a message (bad or unsupported file content).
pub(crate) fn invalid_data(msg: impl Into<String>) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, msg.into())
}

/// An `InvalidInput` error with a message (bad arguments to a writer).
pub(crate) fn invalid_input(msg: impl Into<String>) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, msg.into())
}

/// Checks that a buffer of `len` items holds `w × h × channels` samples.
pub(crate) fn check_len(len: usize, w: usize, h: usize, channels: usize) -> io::Result<()> {
    match w.checked_mul(h).and_then(|n| n.checked_mul(channels)) {
        Some(n) if n == len => Ok(()),
        _ => Err(invalid_input(format!(
            "buffer holds {len} samples, expected {w}×{h}×{channels}"
        ))),
    }
}

/// Distinguishes temporary files of concurrent writes within one process.
static TMP_SEQ: AtomicU64 = AtomicU64::new(0);

/// Writes `bytes` to `path` atomically: parent directories are created, the
/// data goes to `<name>.tmp-<pid>-<seq>` beside `path`, is fsynced and renamed
/// over `path`. On failure the temporary file is removed and the error names
/// `path`. An existing file is replaced whole.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_inner(path, bytes).map_err(|e| OutputError::wrap(path, Access::Write, e))
}

fn write_atomic_inner(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let name = path
        .file_name()
        .ok_or_else(|| invalid_input("path has no file name"))?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    fs::create_dir_all(dir)?;
    let seq = TMP_SEQ.fetch_add(1, Ordering::Relaxed);
    let mut tmp_name = name.to_os_string();
    tmp_name.push(format!(".tmp-{}-{seq}", std::process::id()));
    let tmp = dir.join(tmp_name);
    let result = (|| {
        let mut file = File::create(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result?;
    // Make the rename itself durable; not every platform can fsync a directory,
    // and the file is already complete, so a failure here is not an error.
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

/// Reads a whole file; the error names the path.
pub fn read_file(path: &Path) -> io::Result<Vec<u8>> {
    fs::read(path).map_err(|e| OutputError::wrap(path, Access::Read, e))
}

/// The name a temporary file of the atomic writers will be renamed to:
/// `<name>.tmp-<pid>-<seq>` (`write_atomic`) or `<name>.tmp-link-<pid>`
/// (a layout's hard link) give `<name>`; any other name gives `None`.
pub fn temp_base(name: &str) -> Option<&str> {
    let (base, tail) = name.rsplit_once(".tmp-")?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    let ok = match tail.split_once('-') {
        Some(("link", pid)) => digits(pid),
        Some((pid, seq)) => digits(pid) && digits(seq),
        None => false,
    };
    (ok && !base.is_empty()).then_some(base)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_len_rejects_mismatch_and_overflow() {
        assert!(check_len(12, 2, 2, 3).is_ok());
        assert!(check_len(11, 2, 2, 3).is_err());
        assert!(check_len(0, usize::MAX, 2, 1).is_err());
    }

    #[test]
    fn error_display_names_path_and_reason() {
        let e = OutputError::wrap(Path::new("/x/y.png"), Access::Write, invalid_data("broken"));
        assert_eq!(e.to_string(), "cannot write /x/y.png: broken");
        assert_eq!(e.kind(), io::ErrorKind::InvalidData);
    }
}
