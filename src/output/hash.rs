//! JSON writing and SHA-256 file records for manifests (DATASET.md,
//! bookkeeping: every file with its size and SHA-256).

use super::atomic::{read_file, write_atomic, Access, OutputError};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// Writes `value` as pretty-printed JSON with a trailing newline, atomically.
pub fn write_json<T: Serialize + ?Sized>(path: &Path, value: &T) -> io::Result<()> {
    let mut bytes = serde_json::to_vec_pretty(value)
        .map_err(|e| OutputError::wrap(path, Access::Write, io::Error::other(e)))?;
    bytes.push(b'\n');
    write_atomic(path, &bytes)
}

/// Lower-case hex SHA-256 of a byte slice.
pub fn sha256_bytes(bytes: &[u8]) -> String {
    hex(&Sha256::digest(bytes))
}

/// Lower-case hex SHA-256 of a file's contents, streamed. Errors name the path.
pub fn sha256_file(path: &Path) -> io::Result<String> {
    let hash = (|| {
        let mut file = File::open(path)?;
        let mut hasher = Sha256::new();
        let mut buf = vec![0u8; 1 << 16];
        loop {
            let n = file.read(&mut buf)?;
            if n == 0 {
                break;
            }
            hasher.update(&buf[..n]);
        }
        Ok(hasher.finalize())
    })()
    .map_err(|e| OutputError::wrap(path, Access::Read, e))?;
    Ok(hex(&hash))
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// One file of a frame in a manifest line: path relative to the dataset or
/// sequence root ('/'-separated), size in bytes, SHA-256 hex.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileRecord {
    /// Path relative to the root, '/'-separated.
    pub path: String,
    /// File size in bytes.
    pub bytes: u64,
    /// Lower-case hex SHA-256 of the contents.
    pub sha256: String,
}

impl FileRecord {
    /// Records the file at `path`, which must lie under `root`. Errors name the
    /// path (a path outside `root` is `InvalidInput`).
    pub fn of(root: &Path, path: &Path) -> io::Result<FileRecord> {
        let rel = path.strip_prefix(root).map_err(|_| {
            let msg = format!("not under root {}", root.display());
            OutputError::wrap(
                path,
                Access::Read,
                io::Error::new(io::ErrorKind::InvalidInput, msg),
            )
        })?;
        let rel: Vec<String> = rel
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        // Hash the bytes actually read, so size and hash describe the same contents.
        let contents = read_file(path)?;
        Ok(FileRecord {
            path: rel.join("/"),
            bytes: contents.len() as u64,
            sha256: sha256_bytes(&contents),
        })
    }

    /// Checks the file under `root` against this record: `Ok(true)` when size
    /// and hash match, `Ok(false)` when the contents differ, `Err` when the
    /// file cannot be read.
    pub fn verify(&self, root: &Path) -> io::Result<bool> {
        let path = root.join(&self.path);
        let contents = read_file(&path)?;
        Ok(contents.len() as u64 == self.bytes && sha256_bytes(&contents) == self.sha256)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_of_abc_matches_fips_180_2_vector() {
        assert_eq!(
            sha256_bytes(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
