//! Scene descriptions: the TOML scene format, as serde structs that reject
//! unknown keys. The field docs here are the scene-format manual.
//!
//! Units: metres, degrees in files (radians inside), world frame right-handed
//! with z up. Positions are f64 so a scene may sit far from the origin.
//! Families live in `object.rs`, `material.rs` and `light.rs` (lights and sky).
//!
//! Descriptions sit below the built scene (and below camera users, weather,
//! accel and material): besides the format they own only what a description
//! turns into on its own — the rig (`rig`: `StereoRig::from_desc`), the
//! sensor-noise parameters (`SensorNoise`), media and rain (`medium`) — and
//! `num`, the compact numbers of their messages.

mod denoiser;
mod light;
mod material;
mod medium;
mod num;
mod object;
mod rig;
pub mod semantic;
mod sensor;
mod wetness;

pub use denoiser::Denoiser;
pub use light::{LightDesc, SkyDesc};
pub use material::{
    conductor_eta_k, ConductorPreset, MaskFlag, MaterialDesc, MaterialKindDesc, TextureDesc,
    TextureKindDesc,
};
pub use medium::{build_medium, build_rain, MediumDesc, MediumKindDesc, RainDesc};
pub use num::num;
pub use object::{ObjectDesc, PrefabDesc, RepeatDesc, ScaleDesc, ShapeDesc, TransformDesc};
pub use sensor::{SensorNoise, SensorNoiseDesc};
pub use wetness::WetnessDesc;

use serde::{Deserialize, Serialize};

/// A whole scene file: `[camera]`, `[render]`, `[sky]`, `[[light]]`,
/// `[[material]]`, `[[object]]` and `[[prefab]]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// The stereo rig.
    pub camera: RigDesc,
    /// Render settings.
    #[serde(default)]
    pub render: RenderDesc,
    /// Environment radiance for rays leaving the scene (absent: black).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky: Option<SkyDesc>,
    /// Participating medium (fog, haze) filling the world (absent: clear air).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub medium: Option<MediumDesc>,
    /// Falling rain drawn as streaks (absent: no rain).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rain: Option<RainDesc>,
    /// Wet surfaces and puddles (absent: dry).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wetness: Option<WetnessDesc>,
    /// Explicit lights: sun, point, spot.
    #[serde(default, rename = "light", skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<LightDesc>,
    /// Named materials, referenced by objects.
    #[serde(default, rename = "material", skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<MaterialDesc>,
    /// Objects placed in the world.
    #[serde(default, rename = "object", skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<ObjectDesc>,
    /// Reusable groups of objects, placed by `kind = "instance"` objects.
    #[serde(default, rename = "prefab", skip_serializing_if = "Vec::is_empty")]
    pub prefabs: Vec<PrefabDesc>,
}

impl SceneDesc {
    /// This description as TOML (see `serialize_scene`).
    pub fn to_toml(&self) -> String {
        serialize_scene(self)
    }

    /// Turns every image-space filter off (`[render] filter_indirect`, and
    /// `[medium] filter_inscatter` when there is a medium): the images are
    /// then the plain path-traced estimate. Call it after any weather preset,
    /// which brings its own medium.
    pub fn turn_image_filters_off(&mut self) {
        self.render.filter_indirect = false;
        if let Some(m) = self.medium.as_mut() {
            m.filter_inscatter = false;
        }
    }

    /// Whether any image-space filter is on (`[render] filter_indirect`,
    /// or a medium's `filter_inscatter`), and with it the denoiser.
    pub fn image_filters_on(&self) -> bool {
        self.render.filter_indirect || self.medium.as_ref().is_some_and(|m| m.filter_inscatter)
    }

    /// Checks the `[medium]`, `[rain]` and `[wetness]` sections (their
    /// checks live beside their descriptions); an error is (key, message).
    pub(crate) fn check_weather(&self) -> Result<(), (String, String)> {
        let checks = [
            self.medium.as_ref().map(|m| m.check()),
            self.rain.as_ref().map(|r| r.check()),
            self.wetness.as_ref().map(|w| w.check()),
        ];
        checks
            .into_iter()
            .flatten()
            .find_map(Result::err)
            .map_or(Ok(()), Err)
    }
}

/// Writes a description back as TOML; `toml::from_str` of the result gives an
/// equal `SceneDesc` (the resolved description written beside outputs).
pub fn serialize_scene(desc: &SceneDesc) -> String {
    toml::to_string(desc).expect("a SceneDesc always serialises to TOML")
}

/// The stereo rig: left (reference) camera pose, intrinsics, baselines.
///
/// Orientation: with yaw = pitch = roll = 0 the camera looks along world +x,
/// its image x axis points to world −y and its image y axis to world −z.
/// `yaw_deg` turns the rig counter-clockwise seen from above (about world z),
/// `pitch_deg` > 0 tilts it down, `roll_deg` > 0 turns it clockwise about the
/// optical axis as seen from behind the camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigDesc {
    /// Image width in pixels (default 1600).
    #[serde(default = "default_width")]
    pub width: u32,
    /// Image height in pixels (default 900).
    #[serde(default = "default_height")]
    pub height: u32,
    /// Horizontal field of view in degrees, in (0, 180) (default 60).
    #[serde(default = "default_hfov")]
    pub hfov_deg: f64,
    /// Baselines in centimetres, each > 0 (default 10, 54, 100, 200, 300).
    #[serde(default = "default_baselines")]
    pub baselines_cm: Vec<f64>,
    /// Left camera centre, world metres.
    pub position: [f64; 3],
    /// Heading in degrees, counter-clockwise from world +x about world z.
    #[serde(default)]
    pub yaw_deg: f64,
    /// Downward tilt in degrees, in [−90, 90].
    #[serde(default)]
    pub pitch_deg: f64,
    /// Roll about the optical axis in degrees, in [−180, 180].
    #[serde(default)]
    pub roll_deg: f64,
}

/// Render settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderDesc {
    /// Samples per pixel per view, ≥ 1 (default 64).
    #[serde(default = "default_spp")]
    pub spp: u32,
    /// Maximum path depth (number of bounces), ≥ 1 (default 8).
    #[serde(default = "default_max_depth")]
    pub max_depth: u32,
    /// Seed of every random stream. Absent: one is drawn and recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Filter, in image space, the light that Lambertian first surfaces
    /// (or the surfaces smooth glass and mirrors show) reflect beyond their
    /// direct lighting (sky and indirect light: the grain of shadowed
    /// areas), as a ratio to their albedo so texture and
    /// direct light stay exact per pixel, guided by the exact depth (default
    /// true: far less grain at equal time, at a small bias where that light
    /// changes within a few pixels; false gives the plain path-traced image
    /// bit for bit). Scenes with a medium use its fog filter instead. Ground
    /// truth is never filtered. True also regularises paths: metal and
    /// clear-coat lobes met after a rough bounce are widened to
    /// `integrator::path::REGULARIZE_ALPHA` (a little bias in caustics for
    /// far fewer fireflies).
    #[serde(default = "default_true", skip_serializing_if = "is_true")]
    pub filter_indirect: bool,
    /// The denoiser of the rendered views' surfaces where the filters are
    /// on: "parallax" (default, its own filters), "oidn" (Intel Open
    /// Image Denoise, found at run time: `pip install pyoidn`) or "blend"
    /// (the mean of the two). Fog light keeps parallax's filter in every
    /// case.
    #[serde(default, skip_serializing_if = "Denoiser::is_default")]
    pub denoiser: Denoiser,
}

impl Default for RenderDesc {
    fn default() -> Self {
        RenderDesc {
            spp: default_spp(),
            max_depth: default_max_depth(),
            seed: None,
            filter_indirect: true,
            denoiser: Denoiser::default(),
        }
    }
}

fn default_width() -> u32 {
    1600
}
fn default_height() -> u32 {
    900
}
fn default_hfov() -> f64 {
    60.0
}
fn default_baselines() -> Vec<f64> {
    vec![10.0, 54.0, 100.0, 200.0, 300.0]
}
fn default_spp() -> u32 {
    64
}
fn default_max_depth() -> u32 {
    8
}

/// Serde default `true` for switches that are on unless a file says otherwise.
pub(crate) fn default_true() -> bool {
    true
}
/// Serde `skip_serializing_if` for those switches: only `false` is written.
pub(crate) fn is_true(b: &bool) -> bool {
    *b
}
