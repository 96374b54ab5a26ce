//! `parallax town NAME [--seed S] [--frame K] [--config C] [--export FILE.obj]`:
//! generates one town frame, reports its size and build times, and
//! optionally writes its geometry as OBJ + MTL.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use super::{show, thread_pool, CliError};
use crate::accel::{build_accel, Accel, Backend};
use crate::camera::StereoRig;
use crate::scene::build_scene;
use crate::town::{load_named_town, load_town_frame, CameraConfig};

/// Arguments of `parallax town`.
#[derive(Args, Debug)]
pub struct TownArgs {
    /// Town name (resolved to SCENES/NAME.toml) or a town file path (.toml).
    pub name: String,
    /// Town seed (default 0).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Frame index of the sequence.
    #[arg(long, default_value_t = 0)]
    pub frame: u64,
    /// Camera configuration: normal, roll05, roll15, roll30, pitch00, pitch30.
    #[arg(long, default_value = "normal")]
    pub config: CameraConfig,
    /// Directory holding the town files.
    #[arg(long, default_value = "scenes")]
    pub scenes: PathBuf,
    /// Write the frame's geometry as OBJ (and a .mtl beside it).
    #[arg(long)]
    pub export: Option<PathBuf>,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Traversal backend for the build-time measurement: embree or bvh.
    #[arg(long, default_value_t = Backend::default_backend())]
    pub backend: Backend,
}

/// Runs `parallax town`.
pub fn run(a: TownArgs) -> Result<(), CliError> {
    let (desc, path) = load_named_town(&a.name, &a.scenes).map_err(CliError::input)?;
    let pool = thread_pool(a.threads)?;
    pool.install(|| {
        let t0 = Instant::now();
        let loaded = load_town_frame(&desc, a.seed, a.frame, a.config, &path)
            .map_err(|e| CliError::input(e.to_string()))?;
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
            desc.name,
            a.seed,
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
            println!(
                "wrote {} ({} triangles, {} vertices, {} materials)",
                show(obj),
                stats.triangles,
                stats.vertices,
                stats.materials
            );
        }
        Ok(())
    })
}
