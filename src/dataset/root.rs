//! The start of a run at its root: create it, refuse a different
//! configuration or other town descriptions (or foreign files) unless
//! `--force`, which first removes the old dataset's own files; then write
//! `dataset.json`.

use std::collections::BTreeSet;
use std::fs;
use std::io;
use std::path::Path;

use super::config::DatasetConfig;
use super::manifest::{DatasetMeta, DATASET_JSON, FAILURES_DIR, MANIFEST_DIR};
use super::ownership::{is_bookkeeping, slash};
use super::run::{is_temp_name, ownership_of, walk_files, DatasetError};
use crate::output::{write_json, Access, OutputError};

/// Creates the root, refuses a different configuration or town descriptions
/// (or foreign files) in a non-empty root unless `force`, and writes
/// `dataset.json`.
pub fn prepare_root(
    root: &Path,
    config: &DatasetConfig,
    towns: &[crate::town::TownSource],
    force: bool,
) -> Result<(), DatasetError> {
    if root.is_file() {
        return Err(DatasetError::input(format!(
            "{}: is a file, expected a directory",
            root.display()
        )));
    }
    fs::create_dir_all(root).map_err(|e| OutputError::wrap(root, Access::Write, e))?;
    let meta = DatasetMeta::new(config, towns.to_vec());
    let existing = super::manifest::read_meta(root);
    let towns_differ = match &existing {
        Ok(Some(m)) if m.config == meta.config => m.check_towns(towns).err(),
        _ => None,
    };
    let nonempty = fs::read_dir(root)
        .map_err(|e| OutputError::wrap(root, Access::Read, e))?
        .filter_map(|e| e.ok())
        .any(|e| !is_temp_name(&e.file_name().to_string_lossy()));
    let same =
        matches!(&existing, Ok(Some(m)) if m.config == meta.config) && towns_differ.is_none();
    if nonempty && !same {
        let why = match (&existing, towns_differ) {
            (_, Some(towns)) => format!("holds a dataset of other town descriptions: {towns}"),
            (Ok(Some(old)), _) => format!(
                "holds a dataset of a different configuration ({})",
                config_differences(&old.config, config).join("; ")
            ),
            (Ok(None), _) => "is not empty and holds no dataset.json".into(),
            (Err(_), _) => "holds an unreadable dataset.json".into(),
        };
        if !force {
            return Err(DatasetError::input(format!(
                "{}: {why}; choose another directory or pass --force to start over \
                 (the old dataset's frames and manifests are removed)",
                root.display()
            )));
        }
        if let Ok(Some(old)) = &existing {
            remove_old_frames(root, &old.config)?;
        }
        for dir in [MANIFEST_DIR, FAILURES_DIR] {
            let p = root.join(dir);
            if p.exists() {
                fs::remove_dir_all(&p).map_err(|e| OutputError::wrap(&p, Access::Write, e))?;
            }
        }
    }
    // A resume leaves an identical dataset.json as it is (bytes and mtime).
    if !matches!(&existing, Ok(Some(m)) if *m == meta) {
        write_json(&root.join(DATASET_JSON), &meta)?;
    }
    Ok(())
}

/// The configuration keys whose values differ, each as
/// `key = <old> in dataset.json, <new> in the new configuration` (compact JSON).
fn config_differences(old: &DatasetConfig, new: &DatasetConfig) -> Vec<String> {
    use serde_json::{Map, Value};
    let object = |c: &DatasetConfig| match serde_json::to_value(c) {
        Ok(Value::Object(m)) => m,
        _ => Map::new(),
    };
    let (a, b) = (object(old), object(new));
    // A key left out when serialized holds its default.
    let show = |v: Option<&Value>| v.map_or_else(|| "its default".to_string(), Value::to_string);
    let keys: BTreeSet<&String> = a.keys().chain(b.keys()).collect();
    keys.into_iter()
        .filter(|k| a.get(*k) != b.get(*k))
        .map(|k| {
            format!(
                "{k} = {} in {DATASET_JSON}, {} in the new configuration",
                show(a.get(k)),
                show(b.get(k))
            )
        })
        .collect()
}

/// Removes the files of the dataset of `old` being replaced: those its
/// manifests list and every other file the `ownership` rule calls its own
/// (also of frames whose line was never written), then the directories that
/// leaves empty. Files parallax did not write stay.
fn remove_old_frames(root: &Path, old: &DatasetConfig) -> Result<(), DatasetError> {
    let read = |e| OutputError::wrap(root, Access::Read, e);
    let owner = ownership_of(root, old).map_err(read)?;
    let mut dirs = BTreeSet::new();
    for rel in walk_files(root).map_err(read)? {
        if is_bookkeeping(&rel) || !owner.owns(&slash(&rel)) {
            continue;
        }
        let p = root.join(&rel);
        match fs::remove_file(&p) {
            Ok(()) => {}
            Err(e) if e.kind() == io::ErrorKind::NotFound => continue,
            Err(e) => return Err(OutputError::wrap(&p, Access::Write, e).into()),
        }
        let parents = rel
            .ancestors()
            .skip(1)
            .filter(|a| !a.as_os_str().is_empty());
        dirs.extend(parents.map(Path::to_path_buf));
    }
    // Deepest first; a directory still holding anything stays.
    for dir in dirs.iter().rev() {
        let _ = fs::remove_dir(root.join(dir));
    }
    Ok(())
}
