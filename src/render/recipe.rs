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

use std::time::Instant;

use glam::DVec3;

use super::{render_frame, FrameOutput, RenderSettings};
use crate::accel::{build_accel, AccelError, AnyAccel, Backend};
use crate::camera::StereoRig;
use crate::film::apply_sensor_noise;
use crate::output::frame::{camera_file, CameraFile, FrameSeeds, TownFrameRecord};
use crate::scene::desc::SensorNoiseDesc;
use crate::scene::{build_scene, LoadedScene, Scene, SceneError};
use crate::town::{load_town_frame, CameraConfig, NamedTown};
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
}

impl std::fmt::Display for RecipeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RecipeError::Zero(name) => write!(f, "{name} must be at least 1"),
            RecipeError::Rig(e) | RecipeError::Scene(e) => write!(f, "{e}"),
            RecipeError::SensorNoise(e) => write!(f, "{e}"),
            RecipeError::Accel(e) => write!(f, "{e}"),
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

    /// Town frame `frame` of `town` generated with `seed`, seen from `config`.
    pub fn town(
        town: &NamedTown,
        seed: u64,
        frame: u64,
        config: CameraConfig,
    ) -> Result<FrameSource, SceneError> {
        Ok(FrameSource {
            loaded: load_town_frame(&town.desc, seed, frame, config, &town.path)?,
            origin: FrameOrigin {
                seeds: FrameSeeds::town(seed),
                town: Some(town.source.frame_record(frame, config)),
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
    /// Traversal backend.
    pub backend: Backend,
    /// Embree: paths trace a non-robust shading twin (off: the watertight scene).
    pub shading_twin: bool,
}

impl Default for FrameSpec {
    fn default() -> FrameSpec {
        FrameSpec {
            overrides: Overrides::default(),
            frame: 0,
            weather: None,
            sensor_noise_iso: None,
            filter: true,
            backend: Backend::default_backend(),
            shading_twin: true,
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
    /// Embree: build the shading twin.
    pub shading_twin: bool,
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
        }
        if !spec.filter {
            loaded.desc.turn_image_filters_off();
        }
        let noise = sensor_noise(spec.sensor_noise_iso, weather.as_mut())?;
        origin.seeds.samples = Some(seed);
        let settings = RenderSettings {
            spp: loaded.desc.render.spp,
            max_depth: loaded.desc.render.max_depth,
            seed,
            frame: spec.frame,
        };
        Ok(FrameRecipe {
            loaded,
            settings,
            weather,
            noise,
            origin,
            backend: spec.backend,
            shading_twin: spec.shading_twin,
        })
    }

    /// The rig, and the scene built around its left camera with its accelerator.
    pub fn prepare(&self) -> Result<PreparedFrame<'_>, RecipeError> {
        let rig = StereoRig::from_desc(&self.loaded.desc.camera);
        let built = BuiltScene::build_with(
            &self.loaded,
            rig.left.center_world,
            self.backend,
            self.shading_twin,
        )?;
        Ok(PreparedFrame {
            recipe: self,
            rig,
            built,
        })
    }
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

/// A scene built around an origin and its accelerator: the one place
/// `build_scene` and `build_accel` run in sequence.
pub struct BuiltScene {
    /// The scene (f32 coordinates relative to `scene.origin_world`).
    pub scene: Scene,
    /// Its accelerator.
    pub accel: AnyAccel,
    /// Seconds to build the scene.
    pub scene_seconds: f64,
    /// Seconds to build the accelerator.
    pub accel_seconds: f64,
}

impl BuiltScene {
    /// Builds `loaded` around `origin` (world metres) on `backend`.
    pub fn build(
        loaded: &LoadedScene,
        origin: DVec3,
        backend: Backend,
    ) -> Result<BuiltScene, RecipeError> {
        Self::build_with(loaded, origin, backend, true)
    }

    /// As [`BuiltScene::build`]; Embree without its shading twin when
    /// `shading_twin` is off (paths then trace the watertight scene).
    pub fn build_with(
        loaded: &LoadedScene,
        origin: DVec3,
        backend: Backend,
        shading_twin: bool,
    ) -> Result<BuiltScene, RecipeError> {
        let t = Instant::now();
        let scene = build_scene(loaded, origin).map_err(RecipeError::Scene)?;
        let scene_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let accel = accel_for(backend, shading_twin, &scene.accel_geometry())
            .map_err(RecipeError::Accel)?;
        Ok(BuiltScene {
            scene,
            accel,
            scene_seconds,
            accel_seconds: t.elapsed().as_secs_f64(),
        })
    }
}

/// The backend's accelerator, Embree without its twin if so asked.
fn accel_for(
    backend: Backend,
    shading_twin: bool,
    geo: &crate::accel::AccelGeometry,
) -> Result<AnyAccel, AccelError> {
    #[cfg(feature = "embree")]
    if backend == Backend::Embree && !shading_twin {
        return crate::accel::EmbreeAccel::build_with(geo, false).map(AnyAccel::Embree);
    }
    #[cfg(not(feature = "embree"))]
    let _ = shading_twin; // only Embree has a twin
    build_accel(backend, geo)
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
mod tests {
    use super::*;
    use crate::scene::parse_scene_str;

    /// A grey box 5 m ahead under a white sky, seen at 16×9 with one 54 cm
    /// baseline; no seed of its own.
    fn boxed() -> LoadedScene {
        let text = r#"
[camera]
width = 16
height = 9
hfov_deg = 60.0
position = [0.0, 0.0, 1.5]
baselines_cm = [54.0]
[render]
spp = 2
max_depth = 3
[sky]
kind = "constant"
le = [1.0, 1.0, 1.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
[[object]]
kind = "box"
size = [1.0, 4.0, 3.0]
material = "grey"
transform = { translate = [5.0, 0.0, 1.5] }
"#;
        parse_scene_str(text, std::path::Path::new("boxed.toml")).unwrap()
    }

    fn recipe(spec: &FrameSpec) -> Result<FrameRecipe, RecipeError> {
        FrameRecipe::new(FrameSource::scene(boxed()), spec)
    }

    fn seeded(seed: u64) -> FrameSpec {
        FrameSpec {
            overrides: Overrides {
                seed: Some(seed),
                ..Overrides::default()
            },
            ..FrameSpec::default()
        }
    }

    #[test]
    fn overrides_reach_the_description_and_the_settings() {
        let spec = FrameSpec {
            overrides: Overrides {
                spp: Some(3),
                max_depth: Some(4),
                width: Some(8),
                height: Some(6),
                baselines_cm: Some(vec![10.0, 30.0]),
                hfov_deg: Some(70.0),
                seed: Some(11),
            },
            frame: 7,
            ..FrameSpec::default()
        };
        let r = recipe(&spec).unwrap();
        let c = &r.loaded.desc.camera;
        assert_eq!((c.width, c.height, c.hfov_deg), (8, 6, 70.0));
        assert_eq!(c.baselines_cm, vec![10.0, 30.0]);
        let expected = RenderSettings {
            spp: 3,
            max_depth: 4,
            seed: 11,
            frame: 7,
        };
        assert_eq!(r.settings, expected);
        assert_eq!(r.origin.seeds.samples, Some(11));
        assert_eq!(r.origin.seeds.weather, None);
        assert!(r.weather.is_none() && r.noise.is_none());
        // Without overrides the description's own values stay.
        let r = recipe(&seeded(1)).unwrap();
        assert_eq!((r.settings.spp, r.settings.max_depth), (2, 3));
        assert_eq!(r.loaded.desc.camera.width, 16);
    }

    #[test]
    fn bad_overrides_are_refused_by_name() {
        for (name, o) in [
            (
                "width",
                Overrides {
                    width: Some(0),
                    ..Overrides::default()
                },
            ),
            (
                "height",
                Overrides {
                    height: Some(0),
                    ..Overrides::default()
                },
            ),
            (
                "max-depth",
                Overrides {
                    max_depth: Some(0),
                    ..Overrides::default()
                },
            ),
        ] {
            let spec = FrameSpec {
                overrides: o,
                ..FrameSpec::default()
            };
            match recipe(&spec) {
                Err(RecipeError::Zero(n)) => assert_eq!(n, name),
                other => panic!("{name}: {:?}", other.map(|r| r.settings)),
            }
        }
        let spec = FrameSpec {
            overrides: Overrides {
                hfov_deg: Some(180.0),
                ..Overrides::default()
            },
            ..FrameSpec::default()
        };
        let e = recipe(&spec).map(|r| r.settings).unwrap_err();
        assert!(matches!(e, RecipeError::Rig(_)), "{e:?}");
        let text = e.to_string();
        assert!(
            text.contains("boxed.toml") && text.contains("camera.hfov_deg"),
            "{text}"
        );
        assert!(text.contains("must be in (0, 180), got 180"), "{text}");
    }

    #[test]
    fn weather_is_drawn_with_its_seed_else_the_sample_seed_and_recorded() {
        let with = |seed| FrameSpec {
            weather: Some(WeatherChoice {
                preset: Weather::Storm,
                seed,
            }),
            ..seeded(5)
        };
        let r = recipe(&with(None)).unwrap();
        assert_eq!(r.origin.seeds.weather, Some(5));
        assert_eq!(
            r.weather,
            Some(crate::weather::draw_params(Weather::Storm, 5))
        );
        // The storm's own sensor noise is the one applied.
        assert!(r.noise.is_some());
        assert_eq!(r.noise, r.weather.as_ref().unwrap().sensor_noise);
        let r = recipe(&with(Some(9))).unwrap();
        assert_eq!(r.origin.seeds.weather, Some(9));
        assert_eq!(r.origin.seeds.samples, Some(5));
        assert_eq!(
            r.weather,
            Some(crate::weather::draw_params(Weather::Storm, 9))
        );
        // The preset replaced the description's sky.
        assert_ne!(r.loaded.desc.sky, boxed().desc.sky);
    }

    #[test]
    fn sensor_noise_iso_overrides_the_preset_and_is_recorded() {
        let with = |iso| FrameSpec {
            weather: Some(WeatherChoice {
                preset: Weather::Storm,
                seed: None,
            }),
            sensor_noise_iso: iso,
            ..seeded(5)
        };
        let off = recipe(&with(Some(0.0))).unwrap();
        assert_eq!(off.noise, None);
        assert_eq!(off.weather.unwrap().sensor_noise, None);
        let iso = recipe(&with(Some(1600.0))).unwrap();
        assert_eq!(iso.noise, Some(SensorNoiseDesc::at_iso(1600.0)));
        assert_eq!(iso.weather.unwrap().sensor_noise, iso.noise);
        let plain = FrameSpec {
            sensor_noise_iso: Some(400.0),
            ..seeded(5)
        };
        assert_eq!(
            recipe(&plain).unwrap().noise,
            Some(SensorNoiseDesc::at_iso(400.0))
        );
        let bad = recipe(&with(Some(-5.0))).map(|r| r.settings).unwrap_err();
        assert!(matches!(bad, RecipeError::SensorNoise(_)), "{bad:?}");
    }

    #[test]
    fn no_filter_turns_the_image_filters_off() {
        let on = recipe(&seeded(1)).unwrap();
        assert!(on.loaded.desc.render.filter_indirect);
        let off = recipe(&FrameSpec {
            filter: false,
            ..seeded(1)
        })
        .unwrap();
        assert!(!off.loaded.desc.render.filter_indirect);
        let built = off.prepare().unwrap().built;
        assert!(!built.scene.filter_indirect && !built.scene.filter_inscatter);
    }

    #[test]
    fn a_rendered_frame_carries_its_noise_seeds_and_settings() {
        let spec = |iso| FrameSpec {
            sensor_noise_iso: Some(iso),
            frame: 3,
            ..seeded(21)
        };
        let (quiet, noisy) = (recipe(&spec(0.0)).unwrap(), recipe(&spec(3200.0)).unwrap());
        let a = quiet.prepare().unwrap().render(&|_, _| {});
        let b = noisy.prepare().unwrap().render(&|_, _| {});
        // Noise touches the images only, never the ground truth.
        assert_eq!(a.out.left, b.out.left);
        assert_eq!(a.out.baselines, b.out.baselines);
        assert_eq!(a.out.images.len(), 2);
        assert_ne!(a.out.images[0].rgb, b.out.images[0].rgb);
        // The camera file records the recipe.
        assert_eq!((b.meta.seed, b.meta.frame, b.meta.spp), (21, 3, 2));
        assert_eq!(b.meta.seeds, noisy.origin.seeds);
        assert_eq!(b.meta.seeds.samples, Some(21));
        assert!(b.meta.town.is_none());
        // The same recipe gives the same frame.
        let again = noisy.prepare().unwrap().render(&|_, _| {});
        assert_eq!(again.out.images[1].rgb, b.out.images[1].rgb);
    }

    #[test]
    fn a_town_source_records_its_seeds_and_frame() {
        let town = crate::town::load_named_town("town01", None).unwrap();
        let s = FrameSource::town(&town, 42, 3, CameraConfig::Roll05).unwrap();
        assert_eq!(s.origin.seeds, FrameSeeds::town(42));
        let record = s.origin.town.clone().unwrap();
        assert_eq!(record, town.source.frame_record(3, CameraConfig::Roll05));
        let again = FrameSource::town(&town, 42, 3, CameraConfig::Roll05).unwrap();
        assert_eq!(s.loaded.desc.camera, again.loaded.desc.camera);
    }
}
