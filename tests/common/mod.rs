//! Shared set-up for integration tests: inline scenes, one-call frame renders.
#![allow(dead_code)]

pub mod boxes;
pub mod towns;

use std::path::Path;

use parallax::accel::{build_accel, AnyAccel, Backend};
use parallax::camera::StereoRig;
use parallax::render::{render_frame, FrameOutput, RenderSettings};
use parallax::scene::{build_scene, parse_scene_str, LoadedScene, Scene};

/// Parses an inline scene (OBJ paths resolve against `tests/`).
pub fn scene_from_toml(text: &str) -> LoadedScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    parse_scene_str(text, &path).unwrap_or_else(|e| panic!("inline scene: {e}"))
}

/// Everything of one rendered frame.
pub struct Rendered {
    pub rig: StereoRig,
    pub scene: Scene,
    pub accel: AnyAccel,
    pub out: FrameOutput,
}

/// The default baselines in metres (GROUND_TRUTH.md "Stereo rig"), rendered
/// by every scene that sets no `baselines_cm`.
pub const DEFAULT_BASELINES_M: [f64; 5] = [0.10, 0.54, 1.0, 2.0, 3.0];

/// Right camera centre of baseline `b` metres for a level rig looking along
/// +x: C_R = C_L + B·x_L, with the image x axis x_L = world −y (image right
/// is the world's −y when looking along +x with z up).
pub fn level_right_centre(c_left: glam::DVec3, b: f64) -> glam::DVec3 {
    c_left + glam::DVec3::new(0.0, -b, 0.0)
}

/// Builds and renders `loaded` with `spp` samples (0 = ground truth only).
pub fn render(loaded: &LoadedScene, backend: Backend, spp: u32) -> Rendered {
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let scene = build_scene(loaded, rig.left.center_world).expect("scene builds");
    let accel = build_accel(backend, &scene.accel_geometry()).expect("accel builds");
    let settings = RenderSettings {
        spp,
        max_depth: loaded.desc.render.max_depth,
        seed: loaded.desc.render.seed.unwrap_or(1),
        frame: 0,
    };
    let out = render_frame(&scene, &accel, &rig, &settings, &|_, _| {});
    // Every test scene must render without a NaN or infinite sample (the
    // renderer drops them from the pixel means, which would hide the bug).
    assert_eq!(out.stats.non_finite_samples, 0, "non-finite samples");
    Rendered {
        rig,
        scene,
        accel,
        out,
    }
}

/// A camera block for a level rig at `position` looking along +x.
pub fn camera_block(width: u32, height: u32, position: [f64; 3]) -> String {
    format!(
        "[camera]\nwidth = {width}\nheight = {height}\nhfov_deg = 60.0\nposition = [{:?}, {:?}, {:?}]\n",
        position[0], position[1], position[2]
    )
}

/// Mean and standard error of a sample.
pub fn mean_stderr(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// A grey diffuse material under a white constant sky.
pub const GREY_UNDER_SKY: &str = r#"
[sky]
kind = "constant"
le = [1.0, 1.0, 1.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
"#;
