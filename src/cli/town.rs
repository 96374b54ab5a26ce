//! `parallax town NAME [--seed S] [--frame K] [--config C] [--export FILE.obj]`:
//! generates one town frame, reports its size and build times, and
//! optionally writes its geometry as OBJ + MTL with the frame's cameras
//! beside it. Without `--seed` a seed is drawn and printed (as `render
//! --town` draws and records one).

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use super::{parse_baselines, show, thread_pool, CliError};
use crate::accel::{build_accel, Accel, Backend};
use crate::camera::StereoRig;
use crate::scene::build_scene;
use crate::town::export::{write_cameras, ExportCameras};
use crate::town::{load_named_town, load_town_frame, CameraConfig};

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
    let seed = a.seed.unwrap_or_else(super::render::draw_seed);
    let pool = thread_pool(a.threads)?;
    pool.install(|| {
        let t0 = Instant::now();
        let mut loaded = load_town_frame(&town.desc, seed, a.frame, a.config, &town.path)
            .map_err(|e| CliError::input(e.to_string()))?;
        override_rig(&mut loaded.desc.camera, &a)?;
        crate::scene::validate::check_rig(&loaded.desc.camera, &town.path)
            .map_err(|e| CliError::input(format!("with the command-line overrides: {e}")))?;
        let gen_s = t0.elapsed().as_secs_f64();
        let rig = StereoRig::from_desc(&loaded.desc.camera);
        let t1 = Instant::now();
        let scene = build_scene(&loaded, rig.left.center_world)
            .map_err(|e| CliError::input(e.to_string()))?;
        let scene_s = t1.elapsed().as_secs_f64();
        let t2 = Instant::now();
        let accel = build_accel(a.backend, &scene.accel_geometry())
            .map_err(|e| CliError::failure(e.to_string()))?;
        let accel_s = t2.elapsed().as_secs_f64();
        println!(
            "{} seed {} frame {} ({}): {} objects, {} meshes, {} triangles; generate {:.2} s, scene {:.2} s, accel {:.2} s ({}), total {:.2} s",
            town.desc.name,
            seed,
            a.frame,
            a.config,
            loaded.desc.objects.len(),
            scene.meshes.len(),
            scene.triangle_count(),
            gen_s,
            scene_s,
            accel_s,
            accel.backend_name(),
            gen_s + scene_s + accel_s
        );
        if let Some(obj) = &a.export {
            let stats = crate::town::export::write_obj(&loaded, &scene, obj)
                .map_err(|e| CliError::failure(format!("--export {}: {e}", show(obj))))?;
            let cameras = ExportCameras::new(&rig, seed, town.source.frame_record(a.frame, a.config));
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

/// Applies --width, --height, --hfov and --baselines to the town's rig.
fn override_rig(rig: &mut crate::scene::desc::RigDesc, a: &TownArgs) -> Result<(), CliError> {
    for (name, v) in [("width", a.width), ("height", a.height)] {
        if v == Some(0) {
            return Err(CliError::input(format!("--{name} must be at least 1")));
        }
    }
    rig.width = a.width.unwrap_or(rig.width);
    rig.height = a.height.unwrap_or(rig.height);
    rig.hfov_deg = a.hfov.unwrap_or(rig.hfov_deg);
    if let Some(b) = &a.baselines {
        rig.baselines_cm = b.0.clone();
    }
    Ok(())
}
