//! `parallax town NAME [--seed S] [--frame K] [--config C] [--export FILE.obj]
//! [--report FILE.json] [--sequence N] [--trajectory COUNT]`: generates one
//! town frame of drive N, reports its size and
//! build times, optionally writes its content report (`town::report`) and
//! its geometry as OBJ + MTL with the frame's cameras beside it. Without `--seed` a seed is drawn and printed (as `render
//! --town` draws and records one).

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;

#[path = "town_trajectory.rs"]
mod trajectory;

use super::render::recipe_error;
use super::{parse_baselines, show, thread_pool, CliError};
use crate::accel::{Accel, Backend};
use crate::render::recipe::{draw_seed, FrameRecipe, FrameSource, FrameSpec, Overrides};
use crate::town::export::{write_cameras, ExportCameras};
use crate::town::report::{objects_per_class, peak_rss_bytes, BuildSeconds, ContentReport};
use crate::town::{load_named_town, CameraConfig};

/// Arguments of `parallax town`.
#[derive(Args, Debug)]
pub struct TownArgs {
    /// Town name (built in, or SCENES/NAME.toml with --scenes) or a town
    /// file path (.toml).
    pub name: String,
    /// Town seed (absent: one is drawn, printed and recorded in the
    /// exported cameras); a dataset frame's `seeds.town`.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Time step of the town: every vehicle's and pedestrian's pose at the
    /// town's frame rate (a camera file's `town.frame`).
    #[arg(long, default_value_t = 0)]
    pub frame: u64,
    /// Drive: the ego's route and the traffic's time window (a dataset
    /// sequence's drive, docs/drives.md).
    #[arg(long, default_value_t = 0)]
    pub sequence: u64,
    /// Print the ego pose of the drive's first COUNT frames as JSON lines
    /// (frame, time, position, rotation [roll, pitch, yaw] degrees, speed)
    /// instead of building the frame.
    #[arg(long, value_name = "COUNT")]
    pub trajectory: Option<u64>,
    /// Print the lane length that drives 0..DRIVES (59 frames at stride 10
    /// each, as the stereocarla preset's sequences) pass, instead of
    /// building the frame (the preset plans 294 drives per town).
    #[arg(long, value_name = "DRIVES")]
    pub coverage: Option<u64>,
    /// Camera configuration: normal, roll05, roll15, roll30, pitch00, pitch30.
    #[arg(long, default_value = "normal")]
    pub config: CameraConfig,
    /// Directory holding the town files (NAME.toml), instead of the
    /// built-in town descriptions.
    #[arg(long)]
    pub scenes: Option<PathBuf>,
    /// Write the frame's geometry as OBJ, with a .mtl and the frame's
    /// cameras (STEM.cameras.json) beside it.
    #[arg(long)]
    pub export: Option<PathBuf>,
    /// Write what the frame holds as JSON: objects per class, prototypes,
    /// instances, unique and instanced triangles, build seconds, peak memory.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Image width of the exported cameras, pixels (default: the town rig's).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height of the exported cameras, pixels.
    #[arg(long)]
    pub height: Option<u32>,
    /// Horizontal field of view of the exported cameras, degrees.
    #[arg(long)]
    pub hfov: Option<f64>,
    /// Baselines of the exported cameras in centimetres, comma-separated.
    #[arg(long, value_parser = parse_baselines)]
    pub baselines: Option<super::BaselinesCm>,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Traversal backend for the build-time measurement: embree or bvh.
    #[arg(long, default_value_t = Backend::default_backend())]
    pub backend: Backend,
}

/// Runs `parallax town`.
pub fn run(a: TownArgs) -> Result<(), CliError> {
    let town = load_named_town(&a.name, a.scenes.as_deref()).map_err(CliError::input)?;
    if let Some(path) = &a.report {
        check_report_path(path)?;
    }
    if let Some(drives) = a.coverage {
        let seed = a.seed.unwrap_or_else(draw_seed);
        println!("{}", trajectory::coverage_line(&town, seed, drives)?);
        return Ok(());
    }
    if let Some(count) = a.trajectory {
        trajectory::check_count(count)?;
        let seed = a.seed.unwrap_or_else(draw_seed);
        for line in trajectory::lines(&town, seed, a.sequence, count) {
            println!("{line}");
        }
        return Ok(());
    }
    let seed = a.seed.unwrap_or_else(draw_seed);
    let pool = thread_pool(a.threads)?;
    pool.install(|| {
        let t0 = Instant::now();
        let source = FrameSource::town(&town, seed, (a.sequence, a.frame), a.config)
            .map_err(|e| CliError::input(e.to_string()))?;
        let recipe = FrameRecipe::new(source, &a.spec()).map_err(recipe_error)?;
        let gen_s = t0.elapsed().as_secs_f64();
        let prepared = recipe.prepare().map_err(recipe_error)?;
        let (loaded, built) = (&recipe.loaded, &prepared.built);
        let (scene_s, accel_s) = (built.scene_seconds, built.accel_seconds);
        let content = built.scene.content();
        println!(
            "{} seed {} frame {} ({}): {} objects, {} meshes, {} prototypes, {} instances, {} triangles ({} unique); generate {:.2} s, scene {:.2} s, accel {:.2} s ({}), total {:.2} s",
            town.desc.name,
            seed,
            a.frame,
            a.config,
            loaded.desc.objects.len(),
            content.meshes,
            content.prototypes,
            content.instances,
            content.instanced_triangles,
            content.unique_triangles,
            gen_s,
            scene_s,
            accel_s,
            built.accel.backend_name(),
            gen_s + scene_s + accel_s
        );
        if let Some(path) = &a.report {
            let report = ContentReport {
                town: town.desc.name.clone(),
                seed,
                frame: a.frame,
                config: a.config.to_string(),
                objects: loaded.desc.objects.len(),
                objects_per_class: objects_per_class(&loaded.desc),
                geometry: content.clone(),
                seconds: BuildSeconds {
                    generate: gen_s,
                    scene: scene_s,
                    accel: accel_s,
                },
                peak_rss_bytes: peak_rss_bytes(),
            };
            report
                .write(path)
                .map_err(|e| CliError::failure(format!("--report {}: {e}", show(path))))?;
            println!("wrote {}", show(path));
        }
        if let Some(obj) = &a.export {
            let stats = crate::town::export::write_obj(loaded, &built.scene, obj)
                .map_err(|e| CliError::failure(format!("--export {}: {e}", show(obj))))?;
            let record = town.source.frame_record((a.sequence, a.frame), a.config);
            let cameras = ExportCameras::new(&prepared.rig, seed, record);
            let cam_path = write_cameras(obj, &cameras)
                .map_err(|e| CliError::failure(format!("--export {}: {e}", show(obj))))?;
            println!(
                "wrote {} ({} triangles, {} vertices, {} materials) and {}",
                show(obj),
                stats.triangles,
                stats.vertices,
                stats.materials,
                show(&cam_path)
            );
        }
        Ok(())
    })
}

/// Refuses a report path whose directory does not exist, before any work.
fn check_report_path(path: &Path) -> Result<(), CliError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if dir.is_dir() {
        Ok(())
    } else {
        Err(CliError::input(format!(
            "--report {}: directory {} does not exist",
            show(path),
            show(dir)
        )))
    }
}

impl TownArgs {
    /// The frame's recipe: the town's own render settings under the rig
    /// overrides (nothing is rendered).
    fn spec(&self) -> FrameSpec {
        FrameSpec {
            overrides: Overrides {
                width: self.width,
                height: self.height,
                baselines_cm: self.baselines.as_ref().map(|b| b.0.clone()),
                hfov_deg: self.hfov,
                ..Overrides::default()
            },
            backend: self.backend,
            ..FrameSpec::default()
        }
    }
}
