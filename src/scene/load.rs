//! Loading and validating scene files (placeholder).
use std::path::Path;

use super::desc::SceneDesc;

/// A scene-file error naming the file and the offending key or line.
#[derive(Debug)]
pub struct SceneError(pub String);

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}
impl std::error::Error for SceneError {}

/// Reads and validates a scene file.
pub fn load_scene(path: &Path) -> Result<SceneDesc, SceneError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError(format!("{}: {e}", path.display())))?;
    toml::from_str(&text).map_err(|e| SceneError(format!("{}: {e}", path.display())))
}
