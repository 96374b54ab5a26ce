//! Where town descriptions come from: the repository's `scenes/town*.toml`
//! built into the binary (so every command works from any directory and
//! after `cargo install`), a `--scenes DIR` overriding them, or a `.toml`
//! path given as the town name. Every loaded town carries its source and
//! the SHA-256 of its text, recorded in `dataset.json` and camera files.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::desc::{parse_town_str, TownDesc};
use super::CameraConfig;
use crate::output::frame::TownFrameRecord;

/// The built-in town descriptions: (name, text of `scenes/<name>.toml`).
pub const BUILTIN_TOWNS: &[(&str, &str)] = &[
    ("town01", include_str!("../../scenes/town01.toml")),
    ("town02", include_str!("../../scenes/town02.toml")),
    ("town03", include_str!("../../scenes/town03.toml")),
    ("town04", include_str!("../../scenes/town04.toml")),
    ("town05", include_str!("../../scenes/town05.toml")),
    ("town06", include_str!("../../scenes/town06.toml")),
    ("town07", include_str!("../../scenes/town07.toml")),
    ("town10", include_str!("../../scenes/town10.toml")),
];

/// Text of `scenes/street.toml`, `bench`'s default scene.
pub const STREET_SCENE: &str = include_str!("../../scenes/street.toml");

/// The `source` of a built-in description.
pub const BUILT_IN: &str = "built-in";

/// Where one town description came from, with the hash of its text.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TownSource {
    /// Town name as the configuration or command line gave it.
    pub name: String,
    /// `built-in` or the path of the file read.
    pub source: String,
    /// SHA-256 (hex) of the description's text.
    pub sha256: String,
}

impl TownSource {
    /// The camera-file record of town frame `frame` of drive `sequence`
    /// seen from `config`.
    pub fn frame_record(
        &self,
        (sequence, frame): (u64, u64),
        config: CameraConfig,
    ) -> TownFrameRecord {
        TownFrameRecord {
            sequence,
            name: self.name.clone(),
            source: self.source.clone(),
            sha256: self.sha256.clone(),
            frame,
            config: config.name().to_string(),
        }
    }
}

/// A loaded town description.
#[derive(Clone, Debug)]
pub struct NamedTown {
    /// The validated description.
    pub desc: TownDesc,
    /// The path naming it in messages (`<built-in>/NAME.toml` when built in).
    pub path: PathBuf,
    /// Where it came from.
    pub source: TownSource,
}

/// `scenes_dir/NAME.toml` for a bare town name; a path ending in `.toml` as is.
pub fn town_path(name: &str, scenes_dir: &Path) -> PathBuf {
    if name.ends_with(".toml") {
        PathBuf::from(name)
    } else {
        scenes_dir.join(format!("{name}.toml"))
    }
}

/// Reads and validates the town `name`: a path ending in `.toml` as is, a
/// bare name from `scenes_dir` when given (`--scenes DIR`, which must
/// exist), else the built-in description of that name.
pub fn load_named_town(name: &str, scenes_dir: Option<&Path>) -> Result<NamedTown, String> {
    if name.ends_with(".toml") {
        return load_file(name, Path::new(name));
    }
    match scenes_dir {
        Some(dir) => {
            if !dir.is_dir() {
                return Err(format!(
                    "--scenes {}: no such directory; town '{name}' is looked up in the \
                     --scenes directory ('{}')",
                    dir.display(),
                    dir.display()
                ));
            }
            let path = town_path(name, dir);
            if !path.is_file() {
                return Err(format!(
                    "{}: no such town file; town '{name}' is looked up in the --scenes \
                     directory ('{}')",
                    path.display(),
                    dir.display()
                ));
            }
            load_file(name, &path)
        }
        None => builtin(name),
    }
}

/// The built-in description `name`.
fn builtin(name: &str) -> Result<NamedTown, String> {
    let Some((_, text)) = BUILTIN_TOWNS.iter().find(|(n, _)| *n == name) else {
        let names: Vec<&str> = BUILTIN_TOWNS.iter().map(|(n, _)| *n).collect();
        return Err(format!(
            "town '{name}': no such built-in town (built in: {}); give --scenes DIR \
             holding {name}.toml, or a path ending in .toml",
            names.join(", ")
        ));
    };
    let path = PathBuf::from(format!("<built-in>/{name}.toml"));
    named(name, text, path, BUILT_IN.to_string())
}

fn load_file(name: &str, path: &Path) -> Result<NamedTown, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read town file: {e}", path.display()))?;
    named(name, &text, path.to_path_buf(), path.display().to_string())
}

fn named(name: &str, text: &str, path: PathBuf, source: String) -> Result<NamedTown, String> {
    let desc = parse_town_str(text, &path)?;
    Ok(NamedTown {
        desc,
        path,
        source: TownSource {
            name: name.to_string(),
            source,
            sha256: crate::output::sha256_bytes(text.as_bytes()),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_repository_town_is_built_in_and_parses() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| n.starts_with("town") && n.ends_with(".toml"))
            .map(|n| n.trim_end_matches(".toml").to_string())
            .collect();
        on_disk.sort();
        let built: Vec<&str> = BUILTIN_TOWNS.iter().map(|(n, _)| *n).collect();
        assert_eq!(on_disk, built);
        for (name, _) in BUILTIN_TOWNS {
            let b = load_named_town(name, None).unwrap_or_else(|e| panic!("{e}"));
            let f = load_named_town(name, Some(&dir)).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(b.desc, f.desc, "{name}");
            assert_eq!(
                (b.source.source.as_str(), &b.source.sha256),
                (BUILT_IN, &f.source.sha256)
            );
            assert_eq!(
                f.source.source,
                dir.join(format!("{name}.toml")).display().to_string()
            );
        }
    }
}
