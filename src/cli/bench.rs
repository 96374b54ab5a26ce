//! `parallax bench [SCENE.toml | MESH.obj]`: throughput against raw traversal.

use std::path::PathBuf;

use clap::Args;

use super::{show, thread_pool, CliError};
use crate::accel::Backend;
use crate::bench::{bench_scene_from_obj, run_bench, BenchSettings};
use crate::scene::{load_scene, parse_scene_str};

/// Arguments of `parallax bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// A scene description (.toml) or a plain OBJ mesh (default: the
    /// built-in scenes/street.toml).
    pub input: Option<PathBuf>,
    /// Camera file for an OBJ (the shared benchmark's camera.json format).
    #[arg(long)]
    pub camera: Option<PathBuf>,
    /// Worker threads.
    #[arg(long, default_value_t = 2)]
    pub threads: usize,
    /// Samples per pixel of the path pass.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=crate::sampler::MAX_SPP as i64))]
    pub spp: u32,
    /// Maximum path depth.
    #[arg(long, default_value_t = 5)]
    pub max_depth: u32,
    /// Image width override.
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height override.
    #[arg(long)]
    pub height: Option<u32>,
    /// Traversal backend: embree or bvh.
    #[arg(long, default_value_t = Backend::default_backend())]
    pub backend: Backend,
    /// Embree: trace the path pass on the watertight scene too (no non-robust twin).
    #[arg(long)]
    pub no_shading_twin: bool,
    /// Rounds of every measurement on the one scene and BVH: figures are the
    /// medians over rounds, with their range (noisy machines).
    #[arg(long, default_value_t = 1)]
    pub rounds: u32,
}

/// Runs `parallax bench`.
pub fn run(a: BenchArgs) -> Result<(), CliError> {
    // Without an input, the street built into the binary: works from any directory.
    let builtin = a.input.is_none();
    let input = a
        .input
        .clone()
        .unwrap_or_else(|| PathBuf::from("<built-in>/street.toml"));
    let is_obj = input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    let mut loaded = if is_obj {
        let camera = match &a.camera {
            Some(p) => Some(
                crate::bench::scene::read_obj_camera(p)
                    .map_err(|e| CliError::input(e.to_string()))?,
            ),
            None => None,
        };
        bench_scene_from_obj(&input, camera.as_ref())
    } else if builtin {
        parse_scene_str(crate::town::source::STREET_SCENE, &input)
    } else {
        load_scene(&input)
    }
    .map_err(|e| CliError::input(e.to_string()))?;
    if let Some(w) = a.width {
        loaded.desc.camera.width = w;
    }
    if let Some(h) = a.height {
        loaded.desc.camera.height = h;
    }
    if a.spp == 0 || a.max_depth == 0 || a.threads == 0 || a.rounds == 0 {
        return Err(CliError::input(
            "--spp, --max-depth, --threads and --rounds must be at least 1",
        ));
    }
    let settings = BenchSettings {
        spp: a.spp,
        max_depth: a.max_depth,
        backend: a.backend,
        shading_twin: !a.no_shading_twin,
        rounds: a.rounds,
    };
    let pool = thread_pool(a.threads)?;
    let report = pool
        .install(|| run_bench(&loaded, &settings))
        .map_err(|e| CliError::failure(format!("{}: {e}", show(&input))))?;
    println!("{}", report.render_text(a.threads));
    println!("{}", camera_line(&loaded.desc.camera, a.camera.as_deref()));
    Ok(())
}

/// Which view was measured: the camera file's, or the scene's own.
fn camera_line(c: &crate::scene::desc::RigDesc, file: Option<&std::path::Path>) -> String {
    let from = file.map_or_else(|| "the scene's camera".to_string(), show);
    format!(
        "camera: {from}: {}x{} px, hfov {} deg, position ({}, {}, {}) m (z up), yaw {} deg, pitch {} deg, roll {} deg",
        c.width, c.height, c.hfov_deg, c.position[0], c.position[1], c.position[2], c.yaw_deg, c.pitch_deg, c.roll_deg
    )
}
