//! `parallax render SCENE.toml -o DIR` or `parallax render --town NAME --frame K
//! --config C -o DIR`: one frame in the native layout.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::{parse_baselines, show, thread_pool, CliError};
use crate::accel::{Accel, Backend};
use crate::output::frame::{write_native_frame, WriteOptions};
use crate::output::StagedDir;
use crate::render::recipe::{
    draw_seed, FrameRecipe, FrameRender, FrameSource, FrameSpec, Overrides, RecipeError,
    WeatherChoice,
};
use crate::scene::load_scene;

/// What a frame is made from: a scene file, or a town's frame (as `render`
/// and `export` take it).
#[derive(Args, Debug)]
pub struct FrameSourceArgs {
    /// Scene description (TOML); omit for a town frame (--town).
    #[arg(conflicts_with = "town")]
    pub scene: Option<PathBuf>,
    /// A town frame: a built-in town's name (town01 … town10; with
    /// --scenes DIR, DIR/NAME.toml) or the path of a town file (.toml).
    #[arg(long)]
    pub town: Option<String>,
    /// Time step of the town (with --town): every vehicle's and pedestrian's
    /// pose at the town's frame rate (a camera file's `town.frame`).
    #[arg(long, default_value_t = 0, requires = "town")]
    pub frame: u32,
    /// Drive of the town (with --town): the ego's route and the traffic's
    /// time window; a dataset sequence's drive (docs/drives.md).
    #[arg(long, default_value_t = 0, requires = "town")]
    pub sequence: u64,
    /// Camera configuration on the ego vehicle (with --town): normal, roll05,
    /// roll15, roll30, pitch00, pitch30.
    #[arg(long, default_value = "normal", requires = "town")]
    pub config: crate::town::CameraConfig,
    /// Directory holding the town files (NAME.toml) for --town, instead of
    /// the built-in town descriptions.
    #[arg(long)]
    pub scenes: Option<PathBuf>,
}

/// Arguments of `parallax render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub source: FrameSourceArgs,
    /// Output directory: one frame in the native layout, numbered
    /// --sample-frame, else --frame K with --town, else 000000. A new or empty directory, or an earlier render's output, which
    /// is replaced whole once the new frame is complete; any other non-empty
    /// directory is refused untouched.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Samples per pixel per view (overrides the scene; a town frame without it: 16, and 12 in fog with the filters on).
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
    /// Also write linear HDR radiance (EXR) for every view, and the left
    /// view's first visible surfaces' albedo and normal (`left/albedo/`,
    /// `left/aov_normal/`: the auxiliary inputs of an external denoiser).
    #[arg(long)]
    pub hdr: bool,
    /// Weather preset replacing the scene's sun and sky: clear, cloudy, foggy,
    /// humid, night, storm, sunset (its drawn parameters go into the camera file).
    #[arg(long)]
    pub weather: Option<crate::weather::Weather>,
    /// Camera sensor noise at this ISO (shot, read and PRNU noise on the
    /// linear film, independent per view); overrides a weather preset's. 0
    /// turns a preset's noise off.
    #[arg(long, value_name = "ISO", conflicts_with = "reference")]
    pub sensor_noise: Option<f64>,
    /// Write the plain path-traced images: no image-space filter of sky and
    /// indirect light or of fog light (the scene's `filter_indirect` and
    /// `filter_inscatter` turned off, a weather preset's included).
    #[arg(long)]
    pub no_filter: bool,
    /// Denoiser of the surfaces: parallax (its own filters), oidn (Intel
    /// Open Image Denoise, found at run time: `pip install pyoidn`, or
    /// PARALLAX_OIDN=path) or blend (the mean of the two: less error than
    /// either); fog light keeps parallax's filter. Default: the scene's
    /// `[render] denoiser`, else parallax.
    #[arg(long, value_name = "NAME", conflicts_with_all = ["no_filter", "reference"])]
    pub denoiser: Option<crate::denoise::Denoiser>,
    /// Reference mode: plain, unbiased path tracing, as a reference renderer
    /// (no image filter, no clamp, no sensor noise, no adaptive sampling;
    /// the samples are --spp's). Compare with Mitsuba 3: docs/reference.md.
    #[arg(long)]
    pub reference: bool,
    /// Adaptive sampling: each view's pixels × spp samples shared by a
    /// pilot pass's per-pixel error estimate instead of --spp in every
    /// pixel (off by default: it does not gain at the default filters,
    /// docs/reference.md; reference mode is never adaptive).
    #[arg(long, conflicts_with = "reference")]
    pub adaptive: bool,
}

impl RenderArgs {
    /// The recipe's overrides and choices named on the command line.
    fn spec(&self, frame: u32) -> FrameSpec {
        FrameSpec {
            overrides: Overrides {
                spp: self.spp, // clap checked 1..=MAX_SPP
                max_depth: self.max_depth,
                width: self.width,
                height: self.height,
                baselines_cm: self.baselines.as_ref().map(|b| b.0.clone()),
                hfov_deg: self.hfov,
                seed: self.sample_seed.or(self.seed),
            },
            frame,
            weather: self.weather.map(|preset| WeatherChoice {
                preset,
                seed: self.weather_seed,
            }),
            sensor_noise_iso: self.sensor_noise,
            filter: !self.no_filter,
            denoiser: self.denoiser,
            reference: self.reference,
            adaptive: self.adaptive,
            backend: self.backend,
        }
    }
}

/// A recipe error as the command line reports it: the override's flag, the
/// overrides as the rig's context.
pub(super) fn recipe_error(e: RecipeError) -> CliError {
    match e {
        RecipeError::Zero(name) => CliError::input(format!("--{name} must be at least 1")),
        RecipeError::Rig(e) => CliError::input(format!("with the command-line overrides: {e}")),
        RecipeError::SensorNoise(e) => CliError::input(format!("--sensor-noise: {e}")),
        RecipeError::Scene(e) => CliError::input(e.to_string()),
        RecipeError::Accel(e) => CliError::failure(e.to_string()),
        RecipeError::Denoiser(e) => CliError::input(format!("denoiser oidn: {e}")),
    }
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

impl FrameSourceArgs {
    /// The frame source and its town frame (0 for a scene file); `seed` is
    /// the town's (None: drawn).
    pub fn load(&self, seed: Option<u64>) -> Result<(FrameSource, u32), CliError> {
        let (sequence, frame) = (self.sequence, self.frame);
        match (self.town.as_deref(), self.scene.as_deref()) {
            (Some(name), _) => {
                let t = crate::town::load_named_town(name, self.scenes.as_deref())
                    .map_err(CliError::input)?;
                let seed = seed.unwrap_or_else(draw_seed);
                let source = FrameSource::town(&t, seed, (sequence, frame as u64), self.config)
                    .map_err(|e| CliError::input(e.to_string()))?;
                Ok((source, frame))
            }
            (None, Some(scene)) => Ok((
                FrameSource::scene(load_scene(scene).map_err(|e| CliError::input(e.to_string()))?),
                0,
            )),
            (None, None) => Err(CliError::input("give a SCENE file or --town NAME")),
        }
    }
}

/// Runs `parallax render`.
pub fn run(a: RenderArgs) -> Result<(), CliError> {
    let (source, frame) = a.source.load(a.seed)?;
    let recipe =
        FrameRecipe::new(source, &a.spec(a.sample_frame.unwrap_or(frame))).map_err(recipe_error)?;
    // Before any render work: refuse a foreign directory, prove it writable.
    let staged = StagedDir::prepare(&a.output)
        .map_err(|e| CliError::input(format!("--output {}: {e}", show(&a.output))))?;
    let pool = thread_pool(a.threads)?;
    pool.install(|| render_to(&recipe, &a, staged))
}

/// Renders the frame into `staged` and swaps it in as `a.output`.
fn render_to(recipe: &FrameRecipe, a: &RenderArgs, staged: StagedDir) -> Result<(), CliError> {
    let started = Instant::now();
    let prepared = recipe.prepare().map_err(recipe_error)?;
    let n_views = 1 + prepared.rig.baselines_m.len();
    let pb = progress_bar(n_views as u64);
    pb.set_message(format!("{} tris", prepared.built.scene.triangle_count()));
    let FrameRender { out, meta } = prepared.render(&|done, _| pb.set_position(done as u64));
    pb.finish_and_clear();
    write_native_frame(
        staged.path(),
        recipe.settings.frame,
        &prepared.rig,
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
        prepared.built.accel_seconds,
        prepared.built.accel.backend_name(),
    );
    Ok(())
}

fn summary(dir: &Path, s: &crate::render::RenderStats, seconds: f64, build_s: f64, backend: &str) {
    let rays = s.gt_rays + s.path_rays;
    let traced_s = (s.gt_seconds + s.path_seconds).max(1e-9);
    println!(
        "rendered {}: {:.2} s total (build {:.2} s, gt {:.2} s, path {:.2} s of which denoise {:.2} s), {} samples, {} rays, {:.2} Mrays/s, backend {}",
        show(dir),
        seconds,
        build_s,
        s.gt_seconds,
        s.path_seconds,
        s.denoise_seconds,
        s.samples,
        rays,
        rays as f64 / traced_s / 1e6,
        backend
    );
    if let Some(warning) = s.non_finite_warning() {
        eprintln!("{warning}");
    }
}
