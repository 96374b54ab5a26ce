//! Writes one rendered frame in the native layout of DATASET.md: lossless
//! PNG images, EXR depth and normals, PFM disparities, PNG labels and masks, and
//! the camera JSON. Every file is written atomically (temporary name, rename).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::registry::{maps_in, Kind};
use super::{map_pixels, write_json, write_map, NativeLayout};
use crate::camera::StereoRig;
use crate::light::Light;
use crate::render::{FrameOutput, RenderSettings};
use crate::scene::Scene;
use crate::weather::WeatherParams;

/// A rig's cameras as every camera record writes them (a render's camera
/// file, a town export's `.cameras.json`): size, K, the left pose and one
/// entry per baseline.
#[derive(Clone, Debug, Serialize)]
pub struct RigCameras {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Intrinsic matrix K (row-major), pixels.
    pub k: [[f64; 3]; 3],
    /// Focal length, pixels.
    pub f_px: f64,
    /// World-from-camera pose of the left camera (row-major 4×4, OpenCV camera frame).
    pub left_pose: [[f64; 4]; 4],
    /// One entry per baseline.
    pub right: Vec<RightCamera>,
}

impl RigCameras {
    /// The cameras of `rig`.
    pub fn of(rig: &StereoRig) -> Self {
        RigCameras {
            width: rig.left.intrinsics.width,
            height: rig.left.intrinsics.height,
            k: rig.left.intrinsics.k_matrix(),
            f_px: rig.left.intrinsics.f_px,
            left_pose: rig.left.pose_matrix(),
            right: right_cameras(rig),
        }
    }
}

/// Per-frame metadata written to `cameras/NNNNNN.json`.
#[derive(Clone, Debug, Serialize)]
pub struct CameraFile {
    /// Size, K, left and right poses (flattened: the file's first keys).
    #[serde(flatten)]
    pub cameras: RigCameras,
    /// Exposure scale applied to linear radiance before the tone curve.
    pub exposure_scale: f32,
    /// Exposure in EV (log2 of the scale).
    pub exposure_ev: f32,
    /// Unit vector towards the (first) sun in world coordinates, if the scene
    /// has one; null under a weather preset's night sky, whose only
    /// directional light is the moon (recorded in `weather.moon`).
    pub sun_direction_world: Option<[f64; 3]>,
    /// Weather preset and its drawn parameters; null when the frame uses the
    /// scene's own sky and lights (no preset applied).
    pub weather: Option<WeatherParams>,
    /// Seed of every random stream of this frame (the sample streams,
    /// rain and sensor noise: `seeds.samples`).
    pub seed: u64,
    /// Frame index.
    pub frame: u32,
    /// Samples per pixel per view.
    pub spp: u32,
    /// Maximum path depth.
    pub max_depth: u32,
    /// Whether the images' smooth light was filtered in image space: sky
    /// and indirect light on diffuse surfaces (`[render] filter_indirect`)
    /// or fog light (`[medium] filter_inscatter`). Ground truth never is.
    pub image_filter: bool,
    /// The denoiser of the surfaces where `image_filter` is true: "parallax",
    /// "oidn" (Intel Open Image Denoise) or "blend" (the mean of the two);
    /// null when it is false.
    pub denoiser: Option<crate::denoise::Denoiser>,
    /// Semantic class table: (name, id).
    pub semantic_classes: Vec<(String, u8)>,
    /// Conventions, spelled out for readers of the file.
    pub conventions: &'static str,
    /// Every seed that determines the frame.
    pub seeds: FrameSeeds,
    /// The generated town and town frame rendered; null for a scene file.
    pub town: Option<TownFrameRecord>,
}

/// Every seed that determines a frame; with the town frame, camera
/// configuration, resolution and quality they re-render it exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameSeeds {
    /// Seed of the town's layout, buildings, furniture and terrain; null
    /// for a scene file.
    pub town: Option<u64>,
    /// Seed of the town's traffic (vehicles and pedestrians at every town
    /// frame): the town seed, as the traffic is part of the town; null for
    /// a scene file.
    pub traffic: Option<u64>,
    /// Seed of the weather preset's drawn parameters; null without a preset.
    pub weather: Option<u64>,
    /// Seed of the sample streams, rain streaks and sensor noise; null in a
    /// town export (nothing is sampled).
    pub samples: Option<u64>,
}

impl FrameSeeds {
    /// A town frame's geometry seeds: the town seed, which also drives its
    /// traffic.
    pub fn town(seed: u64) -> Self {
        FrameSeeds {
            town: Some(seed),
            traffic: Some(seed),
            ..FrameSeeds::default()
        }
    }
}

/// The town description and town frame a frame was generated from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TownFrameRecord {
    /// Town name as given (`town01` or a file path).
    pub name: String,
    /// Where its description came from: `built-in` or the file path.
    pub source: String,
    /// SHA-256 of the description's text.
    pub sha256: String,
    /// Town frame (time step at the town's fps from the drive's start) of
    /// the vehicles and pedestrians.
    pub frame: u64,
    /// The drive (`render --sequence`): the ego's route and the traffic's
    /// time window.
    pub sequence: u64,
    /// Camera configuration on the ego vehicle.
    pub config: String,
}

/// One right camera in the metadata.
#[derive(Clone, Debug, Serialize)]
pub struct RightCamera {
    /// Baseline, metres.
    pub baseline_m: f64,
    /// Directory name (`baseline_XXX`).
    pub dir: String,
    /// World-from-camera pose (row-major 4×4).
    pub pose: [[f64; 4]; 4],
}

/// Conventions string stored in every camera file.
pub const CONVENTIONS: &str = "world: right-handed, z up, metres; camera: OpenCV (x right, y down, z forward); \
pixel (i,j) centre at (i+0.5, j+0.5); depth_z along the optical axis, +inf for sky; \
disparity = f*B/Z px (left pixel x lands at x-d in the right image; right pixel x at x+d in the left); \
occlusion 255 = occluded; mask bits: 1 sky, 2 rain, 4 transparent, 8 mirror-like";

/// Options for writing a frame.
#[derive(Clone, Copy, Debug, Default)]
pub struct WriteOptions {
    /// Also write linear HDR radiance EXRs for every view.
    pub hdr: bool,
}

/// Writes every file of `out` for frame `frame` below `root`; returns the
/// paths written. Walks the registry: every ground-truth map, then the
/// images, each first in `left/` then per baseline; HDR maps only with
/// `opts.hdr`, images only when the frame has them (spp ≥ 1).
pub fn write_native_frame(
    root: &Path,
    frame: u32,
    rig: &StereoRig,
    out: &FrameOutput,
    meta: CameraFile,
    opts: WriteOptions,
) -> std::io::Result<Vec<PathBuf>> {
    let layout = NativeLayout::new(root);
    let (w, h) = (
        rig.left.intrinsics.width as usize,
        rig.left.intrinsics.height as usize,
    );
    let mut written = Vec::new();
    for kind in [Kind::Truth, Kind::Image] {
        let folders = std::iter::once(None).chain((0..rig.baselines_m.len()).map(Some));
        for baseline in folders {
            let maps =
                maps_in(baseline.is_some()).filter(|m| m.kind == kind && (opts.hdr || !m.hdr_only));
            for spec in maps {
                let Some(pixels) = map_pixels(spec.map, out, baseline.unwrap_or(0)) else {
                    continue;
                };
                let cm = baseline.map(|b| rig.baselines_m[b] * 100.0);
                let p = layout.path(spec.map, frame, cm);
                write_map(&p, w, h, spec.format, &pixels)?;
                written.push(p);
            }
        }
    }
    let p = layout.camera_json(frame);
    write_json(&p, &meta)?;
    written.push(p);
    Ok(written)
}

/// Builds the camera metadata of a frame.
pub fn camera_file(
    scene: &Scene,
    rig: &StereoRig,
    out: &FrameOutput,
    settings: &RenderSettings,
    weather: Option<&WeatherParams>,
) -> CameraFile {
    CameraFile {
        cameras: RigCameras::of(rig),
        exposure_scale: out.exposure_scale,
        exposure_ev: out.exposure_scale.log2(),
        sun_direction_world: scene
            .lights
            .iter()
            .find_map(|l| match l {
                Light::Sun { dir_to_sun, .. } => Some(dir_to_sun.as_dvec3().to_array()),
                _ => None,
            })
            .filter(|_| weather.is_none_or(|w| w.moon.is_none())),
        weather: weather.cloned(),
        seed: settings.seed,
        frame: settings.frame,
        spp: settings.spp,
        max_depth: settings.max_depth,
        image_filter: scene.filter_indirect || scene.filter_inscatter,
        denoiser: (scene.filter_indirect || scene.filter_inscatter).then_some(scene.denoiser),
        semantic_classes: crate::scene::semantic::CLASSES
            .iter()
            .map(|c| (c.name.to_string(), c.id))
            .collect(),
        conventions: CONVENTIONS,
        // The caller fills in the town and weather seeds it used.
        seeds: FrameSeeds {
            samples: Some(settings.seed),
            ..FrameSeeds::default()
        },
        town: None,
    }
}

/// The right cameras of `rig` as camera files list them.
pub fn right_cameras(rig: &StereoRig) -> Vec<RightCamera> {
    (0..rig.baselines_m.len())
        .map(|b| RightCamera {
            baseline_m: rig.baselines_m[b],
            dir: super::baseline_dir_name(rig.baselines_m[b] * 100.0),
            pose: rig.right(b).pose_matrix(),
        })
        .collect()
}
