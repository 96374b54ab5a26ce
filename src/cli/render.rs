//! `parallax render SCENE.toml -o DIR` or `parallax render --town NAME --frame K
//! --config C -o DIR`: one frame in the native layout.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::{parse_baselines, show, thread_pool, CliError};
use crate::accel::{build_accel, Accel, Backend};
use crate::camera::StereoRig;
use crate::film::apply_sensor_noise;
use crate::output::frame::{
    camera_file, write_native_frame, FrameSeeds, TownFrameRecord, WriteOptions,
};
use crate::output::StagedDir;
use crate::render::{render_frame, RenderSettings};
use crate::scene::desc::SensorNoiseDesc;
use crate::scene::{build_scene, load_scene, LoadedScene};
use crate::town::{CameraConfig, NamedTown};

/// Arguments of `parallax render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene description (TOML); omit when rendering a town with --town.
    #[arg(conflicts_with = "town")]
    pub scene: Option<PathBuf>,
    /// Render a town frame: a built-in town's name (town01 … town10; with
    /// --scenes DIR, DIR/NAME.toml) or the path of a town file (.toml).
    #[arg(long)]
    pub town: Option<String>,
    /// Time step of the town (with --town): every vehicle's and pedestrian's
    /// pose at the town's frame rate (a camera file's `town.frame`).
    #[arg(long, default_value_t = 0, requires = "town")]
    pub frame: u32,
    /// Camera configuration on the ego vehicle (with --town): normal, roll05,
    /// roll15, roll30, pitch00, pitch30.
    #[arg(long, default_value = "normal", requires = "town")]
    pub config: crate::town::CameraConfig,
    /// Directory holding the town files (NAME.toml) for --town, instead of
    /// the built-in town descriptions.
    #[arg(long)]
    pub scenes: Option<PathBuf>,
    /// Output directory: one frame in the native layout, numbered
    /// --sample-frame, else --frame K with --town, else 000000. A new or empty directory, or an earlier render's output, which
    /// is replaced whole once the new frame is complete; any other non-empty
    /// directory is refused untouched.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Samples per pixel per view (overrides the scene).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=crate::sampler::MAX_SPP as i64))]
    pub spp: Option<u32>,
    /// Image width in pixels (overrides the scene).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels (overrides the scene).
    #[arg(long)]
    pub height: Option<u32>,
    /// Baselines in centimetres, comma-separated (overrides the scene).
    #[arg(long, value_parser = parse_baselines)]
    pub baselines: Option<super::BaselinesCm>,
    /// Seed of every random stream (overrides the scene); with --town also
    /// the town's seed (absent: one is drawn and recorded).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Seed of the sample streams, rain and sensor noise (default: --seed,
    /// else the scene's, else drawn); a dataset frame's `seeds.samples`.
    #[arg(long)]
    pub sample_seed: Option<u64>,
    /// Seed of the --weather preset's draw (default: the sample seed); a
    /// dataset frame's `seeds.weather`.
    #[arg(long, requires = "weather")]
    pub weather_seed: Option<u64>,
    /// Frame index of the sample streams and the output files (default:
    /// --frame with --town, else 0); a dataset frame's `frame`.
    #[arg(long)]
    pub sample_frame: Option<u32>,
    /// Horizontal field of view, degrees (overrides the scene).
    #[arg(long)]
    pub hfov: Option<f64>,
    /// Maximum path depth (overrides the scene).
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Traversal backend: embree or bvh.
    #[arg(long, default_value_t = Backend::default_backend())]
    pub backend: Backend,
    /// Also write linear HDR radiance (EXR) for every view.
    #[arg(long)]
    pub hdr: bool,
    /// Weather preset replacing the scene's sun and sky: clear, cloudy, foggy,
    /// humid, night, storm, sunset (its drawn parameters go into the camera file).
    #[arg(long)]
    pub weather: Option<crate::weather::Weather>,
    /// Camera sensor noise at this ISO (shot, read and PRNU noise on the
    /// linear film, independent per view); overrides a weather preset's. 0
    /// turns a preset's noise off.
    #[arg(long, value_name = "ISO")]
    pub sensor_noise: Option<f64>,
    /// Write the plain path-traced images: no image-space filter of sky and
    /// indirect light or of fog light (the scene's `filter_indirect` and
    /// `filter_inscatter` turned off, a weather preset's included).
    #[arg(long)]
    pub no_filter: bool,
}

/// Applies command-line overrides to the loaded description and validates them.
fn apply_overrides(loaded: &mut LoadedScene, a: &RenderArgs) -> Result<(), CliError> {
    let d = &mut loaded.desc;
    let positive = |name: &str, v: u32| {
        if v == 0 {
            Err(CliError::input(format!("--{name} must be at least 1")))
        } else {
            Ok(v)
        }
    };
    if let Some(v) = a.spp {
        d.render.spp = v; // clap checked 1..=MAX_SPP
    }
    if let Some(v) = a.max_depth {
        d.render.max_depth = positive("max-depth", v)?;
    }
    if let Some(v) = a.width {
        d.camera.width = positive("width", v)?;
    }
    if let Some(v) = a.height {
        d.camera.height = positive("height", v)?;
    }
    if let Some(b) = &a.baselines {
        d.camera.baselines_cm = b.0.clone();
    }
    if let Some(h) = a.hfov {
        d.camera.hfov_deg = h;
    }
    if let Some(s) = a.sample_seed.or(a.seed) {
        d.render.seed = Some(s);
    }
    crate::scene::validate::check_rig(&loaded.desc.camera, &loaded.path)
        .map_err(|e| CliError::input(format!("with the command-line overrides: {e}")))
}

/// A seed for runs that named none; recorded in the outputs (STYLE.md rule 7).
pub(super) fn draw_seed() -> u64 {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos() as u64)
        .unwrap_or(0);
    crate::sampler::mix64(nanos ^ std::process::id() as u64)
}

fn progress_bar(total: u64) -> ProgressBar {
    let pb = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    pb.set_style(
        ProgressStyle::with_template(
            "{spinner} {msg} [{bar:30}] {pos}/{len} views, {elapsed} (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    pb
}

/// Runs `parallax render`.
pub fn run(a: RenderArgs) -> Result<(), CliError> {
    let (mut loaded, mut origin) = match (&a.town, &a.scene) {
        (Some(name), _) => {
            let t =
                crate::town::load_named_town(name, a.scenes.as_deref()).map_err(CliError::input)?;
            let seed = a.seed.unwrap_or_else(draw_seed);
            let loaded =
                crate::town::load_town_frame(&t.desc, seed, a.frame as u64, a.config, &t.path)
                    .map_err(|e| CliError::input(e.to_string()))?;
            (loaded, Origin::town(&t, seed, a.frame, a.config))
        }
        (None, Some(scene)) => (
            load_scene(scene).map_err(|e| CliError::input(e.to_string()))?,
            Origin::default(),
        ),
        (None, None) => return Err(CliError::input("give a SCENE file or --town NAME")),
    };
    origin.frame = a.sample_frame.unwrap_or(origin.frame);
    apply_overrides(&mut loaded, &a)?;
    let seed = loaded.desc.render.seed.unwrap_or_else(draw_seed);
    let mut weather = a.weather.map(|w| {
        let s = a.weather_seed.unwrap_or(seed);
        origin.seeds.weather = Some(s);
        crate::weather::draw_params(w, s)
    });
    if let Some(p) = &weather {
        crate::weather::apply(&mut loaded.desc, p);
    }
    if a.no_filter {
        loaded.desc.turn_image_filters_off();
    }
    let noise = sensor_noise(a.sensor_noise, weather.as_mut())?;
    // Before any render work: refuse a foreign directory, prove it writable.
    let staged = StagedDir::prepare(&a.output)
        .map_err(|e| CliError::input(format!("--output {}: {e}", show(&a.output))))?;
    let pool = thread_pool(a.threads)?;
    pool.install(|| render_to(&loaded, &a, staged, seed, weather.as_ref(), noise, origin))
}

/// What the camera file records of where the frame came from.
#[derive(Default)]
struct Origin {
    /// Frame index: the output files' number and the sample streams' frame key.
    frame: u32,
    seeds: FrameSeeds,
    town: Option<TownFrameRecord>,
}

impl Origin {
    /// A town frame generated with `seed`.
    fn town(t: &NamedTown, seed: u64, frame: u32, config: CameraConfig) -> Origin {
        Origin {
            frame,
            seeds: FrameSeeds::town(seed),
            town: Some(t.source.frame_record(frame as u64, config)),
        }
    }
}

/// The frame's sensor noise: `--sensor-noise ISO` (0 = none) over the
/// weather preset's; the choice is written back into the weather parameters
/// so the camera file records what was applied.
fn sensor_noise(
    iso: Option<f64>,
    weather: Option<&mut crate::weather::WeatherParams>,
) -> Result<Option<SensorNoiseDesc>, CliError> {
    let preset = weather.as_ref().and_then(|p| p.sensor_noise);
    let noise = match iso {
        Some(0.0) => None,
        Some(iso) => {
            let d = SensorNoiseDesc::at_iso(iso);
            d.check()
                .map_err(|e| CliError::input(format!("--sensor-noise: {e}")))?;
            Some(d)
        }
        None => preset,
    };
    if let Some(p) = weather {
        p.sensor_noise = noise;
    }
    Ok(noise)
}

/// Renders the frame into `staged` and swaps it in as `a.output`.
fn render_to(
    loaded: &LoadedScene,
    a: &RenderArgs,
    staged: StagedDir,
    seed: u64,
    weather: Option<&crate::weather::WeatherParams>,
    noise: Option<SensorNoiseDesc>,
    origin: Origin,
) -> Result<(), CliError> {
    let started = Instant::now();
    let frame = origin.frame;
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let scene =
        build_scene(loaded, rig.left.center_world).map_err(|e| CliError::input(e.to_string()))?;
    let t_build = Instant::now();
    let accel = build_accel(a.backend, &scene.accel_geometry())
        .map_err(|e| CliError::failure(e.to_string()))?;
    let build_s = t_build.elapsed().as_secs_f64();
    let settings = RenderSettings {
        spp: loaded.desc.render.spp,
        max_depth: loaded.desc.render.max_depth,
        seed,
        frame,
    };
    let n_views = 1 + rig.baselines_m.len();
    let pb = progress_bar(n_views as u64);
    pb.set_message(format!("{} tris", scene.triangle_count()));
    let mut out = render_frame(&scene, &accel, &rig, &settings, &|done, _| {
        pb.set_position(done as u64)
    });
    if let Some(noise) = noise {
        let scale = out.exposure_scale;
        apply_sensor_noise(&mut out.images, &noise.model(), scale, seed, frame);
    }
    pb.finish_and_clear();
    let mut meta = camera_file(&scene, &rig, &out, &settings, weather);
    // camera_file recorded the sample seed; the rest is where the frame came from.
    meta.seeds = FrameSeeds {
        samples: meta.seeds.samples,
        ..origin.seeds
    };
    meta.town = origin.town;
    write_native_frame(
        staged.path(),
        frame,
        &rig,
        &out,
        meta,
        WriteOptions { hdr: a.hdr },
    )
    .map_err(|e| CliError::failure(e.to_string()))?;
    let warning = staged
        .commit()
        .map_err(|e| CliError::failure(format!("--output {}: {e}", show(&a.output))))?;
    if let Some(w) = warning {
        eprintln!("parallax: --output {}: {w}", show(&a.output));
    }
    summary(
        &a.output,
        &out.stats,
        started.elapsed().as_secs_f64(),
        build_s,
        accel.backend_name(),
    );
    Ok(())
}

fn summary(dir: &Path, s: &crate::render::RenderStats, seconds: f64, build_s: f64, backend: &str) {
    let rays = s.gt_rays + s.path_rays;
    let traced_s = (s.gt_seconds + s.path_seconds).max(1e-9);
    println!(
        "rendered {}: {:.2} s total (build {:.2} s, gt {:.2} s, path {:.2} s), {} samples, {} rays, {:.2} Mrays/s, backend {}",
        show(dir),
        seconds,
        build_s,
        s.gt_seconds,
        s.path_seconds,
        s.samples,
        rays,
        rays as f64 / traced_s / 1e6,
        backend
    );
    if let Some(warning) = s.non_finite_warning() {
        eprintln!("{warning}");
    }
}
