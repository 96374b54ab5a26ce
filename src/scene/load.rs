//! Loading a scene file: TOML → `SceneDesc` (with key paths on type errors),
//! full validation (`validate`), OBJ loading (`obj`), so that every error
//! surfaces before any rendering or large allocation.
//!
//! Every `SceneError` names the scene file and the offending key path
//! (`object[3].material`) or, for TOML syntax, the line and column.

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

use super::desc::SceneDesc;
use super::obj::ObjAsset;
use super::validate;

/// What class of problem a `SceneError` reports (for callers that branch).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneErrorKind {
    /// The scene file (or a file it names) is missing or unreadable.
    Io,
    /// TOML syntax, unknown key or wrong type.
    Syntax,
    /// A value out of range or a dangling/duplicate reference.
    Invalid,
    /// A bad OBJ/MTL file.
    Obj,
    /// The frame would exceed a resource limit (pixels, memory, triangles).
    Resource,
    /// Nothing in the scene emits light.
    NoLight,
}

/// A scene-file error naming the file and the offending key or line.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// The scene file.
    pub file: PathBuf,
    /// What went wrong, by class.
    pub kind: SceneErrorKind,
    /// Key path such as `object[3].material` (empty when unknown).
    pub key: String,
    /// 1-based (line, column) in the scene file, when known.
    pub line_col: Option<(usize, usize)>,
    /// Human-readable description.
    pub message: String,
}

impl SceneError {
    /// An error at a key path.
    pub fn at(
        file: &Path,
        kind: SceneErrorKind,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        SceneError {
            file: file.to_path_buf(),
            kind,
            key: key.into(),
            line_col: None,
            message: message.into(),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some((line, col)) = self.line_col {
            write!(f, ":{line}:{col}")?;
        }
        if !self.key.is_empty() {
            write!(f, ": {}", self.key)?;
        }
        write!(f, ": {}", self.message)
    }
}
impl std::error::Error for SceneError {}

/// A parsed, fully validated scene with its OBJ assets loaded.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The scene file (OBJ paths are relative to its parent directory).
    pub path: PathBuf,
    /// The description as written.
    pub desc: SceneDesc,
    /// Loaded OBJ files, keyed by the `file` value as written.
    pub objs: BTreeMap<String, ObjAsset>,
    /// Triangle count of the built scene (exact, computed before tessellating).
    pub triangle_estimate: u64,
    /// Top-level objects (index ranges into `desc.objects`) that do not
    /// move within a sequence: their flat meshes are built into static
    /// tiles (`scene::anchored`). Empty for a scene file.
    pub static_objects: Vec<std::ops::Range<usize>>,
}

impl LoadedScene {
    /// Whether top-level object `i` is one of `static_objects`.
    pub fn is_static(&self, i: usize) -> bool {
        self.static_objects.iter().any(|r| r.contains(&i))
    }

    /// Whether top-level object `i` moves within a sequence: the scene
    /// names its static objects and `i` is not one of them.
    pub fn moves(&self, i: usize) -> bool {
        !self.static_objects.is_empty() && !self.is_static(i)
    }
}

/// Reads, parses and fully validates a scene file.
pub fn load_scene(path: &Path) -> Result<LoadedScene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        SceneError::at(
            path,
            SceneErrorKind::Io,
            "",
            format!("cannot read scene file: {e}"),
        )
    })?;
    parse_scene_str(&text, path)
}

/// Parses and fully validates scene text; `path` names the file in messages
/// and OBJ paths are resolved relative to its parent directory.
pub fn parse_scene_str(text: &str, path: &Path) -> Result<LoadedScene, SceneError> {
    let desc = parse_desc(text, path)?;
    let (objs, triangle_estimate) = validate::validate(&desc, path)?;
    Ok(LoadedScene {
        path: path.to_path_buf(),
        desc,
        objs,
        triangle_estimate,
        static_objects: Vec::new(),
    })
}

/// TOML → `SceneDesc` only (no validation), with key path and line/column on error.
pub fn parse_desc(text: &str, path: &Path) -> Result<SceneDesc, SceneError> {
    let de = toml::Deserializer::new(text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let mut key = e.path().to_string();
        let inner = e.into_inner();
        if key == "." {
            key.clear();
        }
        // Inside flattened shapes the path stops at the object: name the field.
        if let Some(field) = inner
            .message()
            .strip_prefix("unknown field `")
            .and_then(|rest| rest.split('`').next())
        {
            if !key.ends_with(field) {
                key = if key.is_empty() {
                    field.to_string()
                } else {
                    format!("{key}.{field}")
                };
            }
        }
        let (message, line_col) = toml_error(text, &inner);
        SceneError {
            file: path.to_path_buf(),
            kind: SceneErrorKind::Syntax,
            key,
            line_col,
            message,
        }
    })
}

/// A TOML error's description on one line, never empty (toml gives none for
/// a value missing at the end of the file), and its 1-based line and column.
/// Scene, town and dataset-configuration files all report through this.
pub fn toml_error(text: &str, e: &toml::de::Error) -> (String, Option<(usize, usize)>) {
    let pos = e.span().map(|s| line_col(text, s.start));
    let message = e.message().trim().replace('\n', "; ");
    if !message.is_empty() {
        return (message, pos);
    }
    let at = e.span().map_or(text.len(), |s| s.start.min(text.len()));
    let (before, after) = text.split_at(text.floor_char_boundary(at));
    let line = before.rsplit('\n').next().unwrap_or("").to_string()
        + after.split('\n').next().unwrap_or("");
    let line = line.trim();
    let message = if after.trim().is_empty() {
        format!("the file ends inside \"{line}\": a value is missing (a number, \"string\", true/false, [array] or {{ inline table }})")
    } else {
        format!("cannot parse \"{line}\"")
    };
    (message, pos)
}

/// 1-based line and column (in characters) of a byte offset.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}
