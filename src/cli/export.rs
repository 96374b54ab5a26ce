//! `parallax export --mitsuba SCENE.toml|--town NAME [...] -o DIR`: the frame
//! `render` would render, written as a Mitsuba 3 scene (docs/reference.md).

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use super::render::recipe_error;
use super::{show, CliError};
use crate::camera::StereoRig;
use crate::output::mitsuba::{write_mitsuba, MitsubaOptions};
use crate::render::recipe::{FrameRecipe, FrameSpec, Overrides, WeatherChoice};
use crate::scene::build_scene;

/// Which camera of the rig the exported scene looks through.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum View {
    /// The left (reference) camera.
    Left,
    /// The right camera at --baseline.
    Right,
}

/// Arguments of `parallax export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// Write a Mitsuba 3 scene (XML, PLY meshes, baked sky); the only format.
    #[arg(long, required = true)]
    pub mitsuba: bool,
    #[command(flatten)]
    pub source: super::render::FrameSourceArgs,
    /// Output directory (new or empty): scene.xml, meshes/, sky.exr.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Seed (as `render --seed`: the sample seed, and with --town the town's).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Weather preset replacing the scene's sun and sky (as `render --weather`).
    #[arg(long)]
    pub weather: Option<crate::weather::Weather>,
    /// Seed of the --weather preset's draw (default: --seed).
    #[arg(long, requires = "weather")]
    pub weather_seed: Option<u64>,
    /// Samples per pixel written as the scene's default (overrides the scene).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=crate::sampler::MAX_SPP as i64))]
    pub spp: Option<u32>,
    /// Image width in pixels (overrides the scene).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels (overrides the scene).
    #[arg(long)]
    pub height: Option<u32>,
    /// Horizontal field of view, degrees (overrides the scene).
    #[arg(long)]
    pub hfov: Option<f64>,
    /// parallax's maximum path depth D (overrides the scene); Mitsuba's
    /// max_depth is written as D + 1.
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// The camera: left, or right at --baseline.
    #[arg(long, value_enum, default_value_t = View::Left)]
    pub view: View,
    /// Baseline of the right view in centimetres (default: the scene's first).
    #[arg(long)]
    pub baseline: Option<f64>,
    /// Width of the baked sky map in pixels (its height is half), 8..=8192.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(8..=8192))]
    pub sky_width: u32,
}

/// Runs `parallax export`.
pub fn run(a: ExportArgs) -> Result<(), CliError> {
    let (source, _) = a.source.load(a.seed)?;
    if let Some(b) = a.baseline {
        if !(b.is_finite() && b > 0.0) {
            return Err(CliError::input(format!(
                "--baseline {b}: must be a positive number of centimetres"
            )));
        }
        if a.view == View::Left {
            return Err(CliError::input("--baseline applies to --view right only"));
        }
    }
    let spec = FrameSpec {
        overrides: Overrides {
            spp: a.spp,
            max_depth: a.max_depth,
            width: a.width,
            height: a.height,
            hfov_deg: a.hfov,
            seed: a.seed,
            ..Overrides::default()
        },
        weather: a.weather.map(|preset| WeatherChoice {
            preset,
            seed: a.weather_seed,
        }),
        // The export is of what the reference mode renders.
        reference: true,
        ..FrameSpec::default()
    };
    let recipe = FrameRecipe::new(source, &spec).map_err(recipe_error)?;
    let rig = StereoRig::from_desc(&recipe.loaded.desc.camera);
    let camera = match a.view {
        View::Left => rig.left,
        View::Right => {
            let b_m = match a.baseline {
                Some(cm) => cm / 100.0,
                None => *rig.baselines_m.first().ok_or_else(|| {
                    CliError::input("--view right: the scene has no baseline; give --baseline CM")
                })?,
            };
            crate::camera::Camera {
                center_world: rig.left.center_world + rig.left.world_from_camera.x_axis * b_m,
                ..rig.left
            }
        }
    };
    let scene = build_scene(&recipe.loaded, rig.left.center_world)
        .map_err(|e| CliError::input(e.to_string()))?;
    crate::output::mitsuba::check(&scene).map_err(|e| CliError::input(e.to_string()))?;
    check_output_dir(&a.output)?;
    let opts = MitsubaOptions {
        camera: &camera,
        max_depth: recipe.settings.max_depth,
        spp: recipe.settings.spp.max(1),
        sky_width: a.sky_width,
    };
    let export = write_mitsuba(&recipe.loaded, &scene, &opts, &a.output)
        .map_err(|e| CliError::failure(format!("--output {}: {e}", show(&a.output))))?;
    let stored: u64 = export.meshes.iter().map(|m| m.1).sum();
    println!(
        "wrote {} ({} mesh files, {} triangles stored, {} placed)",
        show(&export.xml),
        export.meshes.len(),
        stored,
        scene.triangle_count()
    );
    for n in &export.notes {
        eprintln!("parallax: export: {n}");
    }
    Ok(())
}

/// Refuses an output path that is a file or a non-empty directory.
fn check_output_dir(dir: &std::path::Path) -> Result<(), CliError> {
    if dir.exists() {
        let empty = std::fs::read_dir(dir)
            .map(|mut d| d.next().is_none())
            .unwrap_or(false);
        if !empty {
            return Err(CliError::input(format!(
                "--output {}: must be a new or empty directory",
                show(dir)
            )));
        }
    }
    std::fs::create_dir_all(dir.join("meshes"))
        .map_err(|e| CliError::input(format!("--output {}: {e}", show(dir))))
}
