//! Scene fixtures: the analytic scenes of `scenes/analytic/` (each documents
//! its ground-truth answer), sized for a test.

use std::path::Path;

/// The text of `scenes/analytic/NAME.toml` at `width`×`height` pixels with
/// `baselines_cm`: for [`super::scene_from_toml`] or a scene file the binary
/// renders.
pub fn analytic_text(name: &str, (width, height): (u32, u32), baselines_cm: &[f64]) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/analytic/{name}.toml"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut doc: toml::Table = text
        .parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let camera = doc
        .get_mut("camera")
        .and_then(toml::Value::as_table_mut)
        .unwrap_or_else(|| panic!("{}: no [camera] table", path.display()));
    camera.insert("width".into(), i64::from(width).into());
    camera.insert("height".into(), i64::from(height).into());
    camera.insert("baselines_cm".into(), baselines_cm.to_vec().into());
    toml::to_string(&doc).unwrap()
}
