//! A bench scene from a plain OBJ and the shared camera file
//! (`../shared/bench/camera.json`): the OBJ is Y-up looking down −Z, so it is
//! rotated +90° about x into parallax's z-up world, lit by a sun and a sky.

use std::path::Path;

use glam::DVec3;
use serde::Deserialize;

use crate::scene::load::SceneErrorKind;
use crate::scene::{parse_scene_str, LoadedScene, SceneError};

/// The camera file format of the shared benchmark (OBJ frame: Y up).
#[derive(Clone, Debug, Deserialize)]
pub struct ObjCamera {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Horizontal field of view, degrees.
    pub hfov_deg: f64,
    /// Viewing direction, OBJ frame.
    pub forward: [f64; 3],
    /// Stereo baseline, metres.
    pub baseline_m: f64,
    /// Named camera positions; `left` is the reference.
    pub cameras: std::collections::BTreeMap<String, ObjCameraPosition>,
}

/// A camera position in the OBJ frame.
#[derive(Clone, Debug, Deserialize)]
pub struct ObjCameraPosition {
    /// Centre, OBJ frame.
    pub position: [f64; 3],
}

/// OBJ (y up) → parallax world (z up): a +90° rotation about x.
fn z_up(v: [f64; 3]) -> DVec3 {
    DVec3::new(v[0], -v[2], v[1])
}

/// The default camera when an OBJ comes without a camera file: the shared
/// benchmark's driver view.
fn default_camera() -> ObjCamera {
    serde_json::from_str(
        r#"{"width":1600,"height":900,"hfov_deg":60.0,"forward":[0,0,-1],"baseline_m":0.54,
            "cameras":{"left":{"position":[1.5,1.6,0.0]}}}"#,
    )
    .expect("built-in camera parses")
}

/// Reads a camera file, naming it in errors.
pub fn read_obj_camera(path: &Path) -> Result<ObjCamera, SceneError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError::at(path, SceneErrorKind::Io, "", e.to_string()))?;
    serde_json::from_str(&text)
        .map_err(|e| SceneError::at(path, SceneErrorKind::Io, "", e.to_string()))
}

/// Builds a scene description around `obj` seen from `camera` (default: the
/// shared benchmark's driver view), with a sun and a gradient sky.
pub fn bench_scene_from_obj(
    obj: &Path,
    camera: Option<&ObjCamera>,
) -> Result<LoadedScene, SceneError> {
    let default = default_camera();
    let cam = camera.unwrap_or(&default);
    let left = cam.cameras.get("left").ok_or_else(|| {
        SceneError::at(
            obj,
            SceneErrorKind::Invalid,
            "cameras.left",
            "the camera file has no left camera",
        )
    })?;
    let p = z_up(left.position);
    let f = z_up(cam.forward).normalize();
    let yaw = f.y.atan2(f.x).to_degrees();
    let pitch = (-f.z).asin().to_degrees();
    let obj_abs = std::fs::canonicalize(obj)
        .map_err(|e| SceneError::at(obj, SceneErrorKind::Io, "", e.to_string()))?;
    let text = format!(
        r#"
[camera]
width = {w}
height = {h}
hfov_deg = {fov}
baselines_cm = [{b}]
position = [{px}, {py}, {pz}]
yaw_deg = {yaw}
pitch_deg = {pitch}

[render]
spp = 1
max_depth = 5
seed = 1

[sky]
kind = "gradient"
zenith = [9.0, 16.0, 38.0]
horizon = [30.0, 33.0, 37.0]
ground = [6.0, 5.6, 5.2]

[[light]]
kind = "sun"
elevation_deg = 40.0
azimuth_deg = 120.0
irradiance = [900.0, 850.0, 780.0]

[[object]]
kind = "obj"
file = {file:?}
semantic = "unlabeled"
transform = {{ rotate_deg = [90.0, 0.0, 0.0] }}
"#,
        w = cam.width,
        h = cam.height,
        fov = cam.hfov_deg,
        b = cam.baseline_m * 100.0,
        px = p.x,
        py = p.y,
        pz = p.z,
        file = obj_abs.display().to_string(),
    );
    parse_scene_str(&text, &obj_abs)
}
