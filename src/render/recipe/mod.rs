//! The frame recipe: the one path from what a frame is made of (a scene file
//! or a generated town frame, the overrides, the weather preset, the filters,
//! the seeds) to the rendered frame after sensor noise and its camera file.
//! `render`, `dataset`, `town`, `bench` and the tests all go through it, so a
//! new step of the recipe is written once.
//!
//! Steps, in order: overrides → rig check → sample seed → weather → image
//! filters → sensor noise ([`FrameRecipe::new`]); rig → scene → accelerator
//! ([`FrameRecipe::prepare`], or [`BuiltScene::build`] for callers that need
//! only the geometry); render → sensor noise → camera file
//! ([`PreparedFrame::render`]).

mod built;

pub use built::BuiltScene;

use super::{render_frame, FrameOutput, RenderSettings};
use crate::accel::{AccelCache, AccelError, Backend};
use crate::camera::StereoRig;
use crate::denoise::Denoiser;
use crate::film::apply_sensor_noise;
use crate::output::frame::{camera_file, CameraFile, FrameSeeds, TownFrameRecord};
use crate::scene::desc::SensorNoiseDesc;
use crate::scene::{LoadedScene, SceneError};
use crate::town::{load_town_frame_with, CameraConfig, NamedTown, StaticScene};
use crate::weather::{Weather, WeatherParams};

/// Why a recipe could not be followed.
#[derive(Debug)]
pub enum RecipeError {
    /// An override that must be at least 1 was 0 (the override's name:
    /// `width`, `height` or `max-depth`).
    Zero(&'static str),
    /// The rig after the overrides is invalid.
    Rig(SceneError),
    /// The sensor noise override is out of range.
    SensorNoise(String),
    /// The description does not build into a scene.
    Scene(SceneError),
    /// The accelerator does not build (not the input's fault).
    Accel(AccelError),
    /// The chosen denoiser cannot run here (Open Image Denoise missing).
    Denoiser(String),
}

impl std::fmt::Display for RecipeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RecipeError::Zero(name) => write!(f, "{name} must be at least 1"),
            RecipeError::Rig(e) | RecipeError::Scene(e) => write!(f, "{e}"),
            RecipeError::SensorNoise(e) => write!(f, "{e}"),
            RecipeError::Accel(e) => write!(f, "{e}"),
            RecipeError::Denoiser(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for RecipeError {}

/// A seed for runs that named none; recorded in the outputs (STYLE.md rule 7).
pub fn draw_seed() -> u64 {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos() as u64)
        .unwrap_or(0);
    crate::sampler::mix64(nanos ^ std::process::id() as u64)
}

/// What the camera file records of where the frame's description came from.
#[derive(Clone, Debug, Default)]
pub struct FrameOrigin {
    /// The description's seeds (town and traffic for a town frame); the
    /// recipe adds the weather and sample seeds.
    pub seeds: FrameSeeds,
    /// The town frame, for a generated town.
    pub town: Option<TownFrameRecord>,
}

/// A frame's description and where it came from.
#[derive(Clone, Debug)]
pub struct FrameSource {
    /// The description, as loaded or generated.
    pub loaded: LoadedScene,
    /// Where it came from.
    pub origin: FrameOrigin,
}

impl FrameSource {
    /// A scene file's description.
    pub fn scene(loaded: LoadedScene) -> FrameSource {
        FrameSource {
            loaded,
            origin: FrameOrigin::default(),
        }
    }

    /// Town frame `frame` of drive `drive` of `town` generated with
    /// `seed`, seen from `config`.
    pub fn town(
        town: &NamedTown,
        seed: u64,
        (drive, frame): (u64, u64),
        config: CameraConfig,
    ) -> Result<FrameSource, SceneError> {
        let stat = StaticScene::new(&town.desc, seed);
        Self::town_with(&stat, town, seed, (drive, frame), config)
    }

    /// As [`FrameSource::town`] over the town's static part already
    /// generated (`stat` = `StaticScene::new(&town.desc, seed)`): the same
    /// description, without generating the town again.
    pub fn town_with(
        stat: &StaticScene,
        town: &NamedTown,
        seed: u64,
        (drive, frame): (u64, u64),
        config: CameraConfig,
    ) -> Result<FrameSource, SceneError> {
        let (desc, path) = (&town.desc, &town.path);
        Ok(FrameSource {
            loaded: load_town_frame_with(stat, desc, seed, (drive, frame), config, path)?,
            origin: FrameOrigin {
                seeds: FrameSeeds::town(seed),
                town: Some(town.source.frame_record((drive, frame), config)),
            },
        })
    }
}

/// Values replacing the description's rig and render settings.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Samples per pixel per view (0 renders ground truth only).
    pub spp: Option<u32>,
    /// Maximum path depth (at least 1).
    pub max_depth: Option<u32>,
    /// Image width, pixels (at least 1).
    pub width: Option<u32>,
    /// Image height, pixels (at least 1).
    pub height: Option<u32>,
    /// Baselines, centimetres.
    pub baselines_cm: Option<Vec<f64>>,
    /// Horizontal field of view, degrees.
    pub hfov_deg: Option<f64>,
    /// Seed of the sample streams, rain and sensor noise.
    pub seed: Option<u64>,
}

impl Overrides {
    /// Applies the overrides to `loaded` and checks the resulting rig.
    pub fn apply(&self, loaded: &mut LoadedScene) -> Result<(), RecipeError> {
        let positive = |name, v: u32| {
            if v == 0 {
                Err(RecipeError::Zero(name))
            } else {
                Ok(v)
            }
        };
        let d = &mut loaded.desc;
        if let Some(v) = self.spp {
            d.render.spp = v;
        }
        if let Some(v) = self.max_depth {
            d.render.max_depth = positive("max-depth", v)?;
        }
        if let Some(v) = self.width {
            d.camera.width = positive("width", v)?;
        }
        if let Some(v) = self.height {
            d.camera.height = positive("height", v)?;
        }
        if let Some(b) = &self.baselines_cm {
            d.camera.baselines_cm = b.clone();
        }
        if let Some(h) = self.hfov_deg {
            d.camera.hfov_deg = h;
        }
        if let Some(s) = self.seed {
            d.render.seed = Some(s);
        }
        crate::scene::validate::check_rig(&loaded.desc.camera, &loaded.path)
            .map_err(RecipeError::Rig)
    }
}

/// A weather preset and the seed of its draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WeatherChoice {
    /// The preset replacing the description's sun and sky.
    pub preset: Weather,
    /// Seed of the preset's draw (default: the sample seed).
    pub seed: Option<u64>,
}

/// Everything besides the description that decides a frame.
#[derive(Clone, Debug)]
pub struct FrameSpec {
    /// Rig and render overrides.
    pub overrides: Overrides,
    /// Frame index: the sample streams' frame key and the output files' number.
    pub frame: u32,
    /// Weather preset, if any.
    pub weather: Option<WeatherChoice>,
    /// Sensor noise at this ISO over the preset's (0: none); None keeps the preset's.
    pub sensor_noise_iso: Option<f64>,
    /// The description's image-space filters (off: plain path-traced images).
    pub filter: bool,
    /// The denoiser where the filters are on; None keeps the description's.
    pub denoiser: Option<Denoiser>,
    /// Reference mode: plain, unbiased path tracing ([`reference_mode`]).
    pub reference: bool,
    /// Adaptive sampling (`RenderSettings::adaptive`; off by default, and
    /// always off in reference mode).
    pub adaptive: bool,
    /// Traversal backend.
    pub backend: Backend,
}

impl Default for FrameSpec {
    fn default() -> FrameSpec {
        FrameSpec {
            overrides: Overrides::default(),
            frame: 0,
            weather: None,
            sensor_noise_iso: None,
            filter: true,
            denoiser: None,
            reference: false,
            adaptive: false,
            backend: Backend::default_backend(),
        }
    }
}

/// A frame ready to build and render: the final description, its settings,
/// weather and noise, and what its camera file records of its origin.
#[derive(Clone, Debug)]
pub struct FrameRecipe {
    /// The description after overrides, weather and filters.
    pub loaded: LoadedScene,
    /// Samples, depth, sample seed and frame.
    pub settings: RenderSettings,
    /// The weather preset's drawn parameters (its sensor noise is the one applied).
    pub weather: Option<WeatherParams>,
    /// Sensor noise applied to the images.
    pub noise: Option<SensorNoiseDesc>,
    /// Seeds (weather and samples included) and town frame of the camera file.
    pub origin: FrameOrigin,
    /// Traversal backend.
    pub backend: Backend,
}

impl FrameRecipe {
    /// Applies `spec` to `source`: overrides (checked), the sample seed (the
    /// description's, else drawn), the weather preset (drawn with its seed,
    /// else the sample seed), the filters and the sensor noise.
    pub fn new(source: FrameSource, spec: &FrameSpec) -> Result<FrameRecipe, RecipeError> {
        let FrameSource {
            mut loaded,
            mut origin,
        } = source;
        spec.overrides.apply(&mut loaded)?;
        let seed = loaded.desc.render.seed.unwrap_or_else(draw_seed);
        let mut weather = spec.weather.map(|w| {
            let s = w.seed.unwrap_or(seed);
            origin.seeds.weather = Some(s);
            crate::weather::draw_params(w.preset, s)
        });
        if let Some(p) = &weather {
            crate::weather::apply(&mut loaded.desc, p);
            // A town's vehicles drive with head-lights on at night and dusk.
            if origin.town.is_some() && crate::town::vehicles::needs_headlights(p.preset) {
                crate::town::vehicles::add_headlights(&mut loaded.desc);
            }
            // In rain most pedestrians walk under an umbrella.
            if origin.town.is_some() && p.rain_mm_per_h > 0.0 {
                crate::town::people::umbrella::add_umbrellas(&mut loaded.desc);
            }
        }
        if let Some(d) = spec.denoiser {
            loaded.desc.render.denoiser = d;
        }
        if !spec.filter {
            loaded.desc.turn_image_filters_off();
        }
        let mut adaptive = spec.adaptive;
        let noise_iso = reference_mode(spec.reference, &mut loaded, &mut adaptive)
            .unwrap_or(spec.sensor_noise_iso);
        // A town frame's sample count is the town's default unless given:
        // its weather's then (fewer in fog, where the fog light's filter
        // makes up for them).
        if let Some(p) = weather.as_ref().filter(|_| {
            spec.overrides.spp.is_none() && origin.town.is_some() && loaded.desc.image_filters_on()
        }) {
            loaded.desc.render.spp = p.preset.default_spp(loaded.desc.render.spp);
        }
        if loaded.desc.render.denoiser.needs_oidn() && loaded.desc.image_filters_on() {
            crate::denoise::oidn::check().map_err(RecipeError::Denoiser)?;
        }
        let noise = sensor_noise(noise_iso, weather.as_mut())?;
        origin.seeds.samples = Some(seed);
        let settings = RenderSettings {
            spp: loaded.desc.render.spp,
            max_depth: loaded.desc.render.max_depth,
            seed,
            frame: spec.frame,
            adaptive,
        };
        Ok(FrameRecipe {
            loaded,
            settings,
            weather,
            noise,
            origin,
            backend: spec.backend,
        })
    }

    /// The rig, and the scene built around its left camera with its accelerator.
    pub fn prepare(&self) -> Result<PreparedFrame<'_>, RecipeError> {
        self.prepare_cached(&AccelCache::default())
    }

    /// As [`FrameRecipe::prepare`], reusing the accelerator parts `cache`
    /// holds from the previous frame of the same static world (same bytes).
    pub fn prepare_cached(&self, cache: &AccelCache) -> Result<PreparedFrame<'_>, RecipeError> {
        let rig = StereoRig::from_desc(&self.loaded.desc.camera);
        let origin = rig.left.center_world;
        let built = BuiltScene::build_cached(&self.loaded, origin, self.backend, cache)?;
        Ok(PreparedFrame {
            recipe: self,
            rig,
            built,
        })
    }
}

/// Reference mode (`render --reference`), decided here and only here: plain,
/// unbiased path tracing. It turns the description's image-space filters
/// and adaptive sampling off (`adaptive`: a reference takes the same
/// samples in every pixel) and returns the sensor noise override it forces
/// (ISO 0: none, also over a weather preset's). Every biased pass today
/// (the image filters, including the direct-light denoiser) hangs on those
/// filter switches, so nothing else needs the flag; a new biased pass must
/// be turned off here. None when `reference` is off.
pub fn reference_mode(
    reference: bool,
    loaded: &mut LoadedScene,
    adaptive: &mut bool,
) -> Option<Option<f64>> {
    if !reference {
        return None;
    }
    loaded.desc.turn_image_filters_off();
    *adaptive = false;
    Some(Some(0.0))
}

/// The frame's sensor noise: `iso` (0 = none) over the weather preset's; the
/// choice is written back into the weather parameters so the camera file
/// records what was applied.
fn sensor_noise(
    iso: Option<f64>,
    weather: Option<&mut WeatherParams>,
) -> Result<Option<SensorNoiseDesc>, RecipeError> {
    let preset = weather.as_ref().and_then(|p| p.sensor_noise);
    let noise = match iso {
        Some(0.0) => None,
        Some(iso) => {
            let d = SensorNoiseDesc::at_iso(iso);
            d.check().map_err(RecipeError::SensorNoise)?;
            Some(d)
        }
        None => preset,
    };
    if let Some(p) = weather {
        p.sensor_noise = noise;
    }
    Ok(noise)
}

/// A recipe's rig, scene and accelerator, ready to render.
pub struct PreparedFrame<'a> {
    /// The recipe followed.
    pub recipe: &'a FrameRecipe,
    /// The stereo rig.
    pub rig: StereoRig,
    /// The scene built around the rig's left camera, and its accelerator.
    pub built: BuiltScene,
}

/// A rendered frame: images after sensor noise, ground truth and the camera file.
pub struct FrameRender {
    /// Every image and ground-truth map.
    pub out: FrameOutput,
    /// The frame's camera file (seeds and town frame included).
    pub meta: CameraFile,
}

impl PreparedFrame<'_> {
    /// Renders every view (`progress(views_done, views)` as views finish),
    /// adds the sensor noise and describes the frame in its camera file.
    pub fn render(&self, progress: &(dyn Fn(usize, usize) + Sync)) -> FrameRender {
        let r = self.recipe;
        let s = &r.settings;
        let mut out = render_frame(&self.built.scene, &self.built.accel, &self.rig, s, progress);
        if let Some(noise) = &r.noise {
            let scale = out.exposure_scale;
            apply_sensor_noise(&mut out.images, &noise.model(), scale, s.seed, s.frame);
        }
        let mut meta = camera_file(&self.built.scene, &self.rig, &out, s, r.weather.as_ref());
        meta.seeds = r.origin.seeds;
        meta.town = r.origin.town.clone();
        FrameRender { out, meta }
    }
}

#[cfg(test)]
mod tests;
