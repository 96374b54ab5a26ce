//! One job, rendered and written: the town frame seen from the job's camera
//! configuration under the sequence's weather, at the configuration's
//! resolution and quality (the same steps as `parallax render --town`), then
//! every file written atomically and described by a manifest line.

use std::collections::BTreeMap;
use std::io;
use std::path::Path;

use super::config::DatasetConfig;
use super::layouts::write_extra_layouts;
use super::manifest::{DisparityRecord, ManifestLine, RenderRecord};
use super::plan::{frame_seed, sequence_seed, town_frame, town_seed, Job};
use crate::accel::{build_accel, Backend};
use crate::camera::StereoRig;
use crate::film::apply_sensor_noise;
use crate::output::frame::{camera_file, write_native_frame, CameraFile, FrameSeeds, WriteOptions};
use crate::output::FileRecord;
use crate::render::{render_frame, FrameOutput, RenderSettings};
use crate::scene::build_scene;
use crate::town::{load_named_town, load_town_frame, NamedTown, TownSource};

/// The town descriptions a configuration names, loaded once.
pub struct Towns {
    by_name: BTreeMap<String, NamedTown>,
}

impl Towns {
    /// Loads every town of `config`: from `scenes_dir` (`<dir>/<name>.toml`)
    /// when given, else the built-in descriptions.
    pub fn load(config: &DatasetConfig, scenes_dir: Option<&Path>) -> Result<Towns, String> {
        let mut by_name = BTreeMap::new();
        for name in &config.towns {
            by_name.insert(name.clone(), load_named_town(name, scenes_dir)?);
        }
        Ok(Towns { by_name })
    }

    fn get(&self, name: &str) -> Result<&NamedTown, String> {
        self.by_name
            .get(name)
            .ok_or_else(|| format!("town '{name}' is not loaded"))
    }

    /// Where each town's description came from, in the configuration's order.
    pub fn sources(&self, config: &DatasetConfig) -> Vec<TownSource> {
        config
            .towns
            .iter()
            .filter_map(|n| self.by_name.get(n).map(|t| t.source.clone()))
            .collect()
    }
}

/// A rendered frame, still in memory.
pub struct RenderedFrame {
    /// The rig the frame was rendered from.
    pub rig: StereoRig,
    /// Every image and ground-truth map.
    pub out: FrameOutput,
    /// The camera file of the frame.
    pub meta: CameraFile,
    /// Seed of the frame's sample streams.
    pub seed: u64,
    /// Town frame (time step) rendered.
    pub town_frame: u64,
}

/// Image size and quality overriding the town's defaults.
#[derive(Clone, Copy, Debug)]
pub struct Quality {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Samples per pixel per view.
    pub spp: u32,
}

impl Quality {
    /// The configuration's own quality.
    pub fn of(config: &DatasetConfig) -> Quality {
        Quality {
            width: config.width,
            height: config.height,
            spp: config.spp,
        }
    }
}

/// Renders `job` at `quality`; `progress(views_done, views)` is called as views finish.
pub fn render_job(
    config: &DatasetConfig,
    towns: &Towns,
    job: &Job,
    quality: Quality,
    backend: Backend,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<RenderedFrame, String> {
    let town = towns.get(&job.town)?;
    let path = &town.path;
    let t_frame = town_frame(config, job);
    let t_seed = town_seed(config.seed, &job.town);
    let mut loaded = load_town_frame(&town.desc, t_seed, t_frame, job.config, path)
        .map_err(|e| e.to_string())?;
    let seed = frame_seed(config.seed, job);
    let w_seed = sequence_seed(config.seed, &job.town, job.weather, job.sequence);
    {
        let d = &mut loaded.desc;
        d.camera.width = quality.width;
        d.camera.height = quality.height;
        d.camera.hfov_deg = config.hfov_deg;
        d.camera.baselines_cm = config.baselines_cm.clone();
        d.render.spp = quality.spp;
        d.render.max_depth = config.max_depth;
        d.render.seed = Some(seed);
    }
    crate::scene::validate::check_rig(&loaded.desc.camera, path).map_err(|e| e.to_string())?;
    let weather = crate::weather::draw_params(job.weather, w_seed);
    crate::weather::apply(&mut loaded.desc, &weather);
    if !config.filter {
        loaded.desc.turn_image_filters_off();
    }
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let scene = build_scene(&loaded, rig.left.center_world).map_err(|e| e.to_string())?;
    let accel = build_accel(backend, &scene.accel_geometry()).map_err(|e| e.to_string())?;
    let settings = RenderSettings {
        spp: quality.spp,
        max_depth: config.max_depth,
        seed,
        frame: job.frame,
    };
    let mut out = render_frame(&scene, &accel, &rig, &settings, progress);
    if let Some(noise) = &weather.sensor_noise {
        let scale = out.exposure_scale;
        apply_sensor_noise(&mut out.images, &noise.model(), scale, seed, job.frame);
    }
    let mut meta = camera_file(&scene, &rig, &out, &settings, Some(&weather));
    meta.seeds = FrameSeeds {
        weather: Some(w_seed),
        samples: meta.seeds.samples,
        ..FrameSeeds::town(t_seed)
    };
    meta.town = Some(town.source.frame_record(t_frame, job.config));
    Ok(RenderedFrame {
        rig,
        out,
        seed,
        meta,
        town_frame: t_frame,
    })
}

/// Writes every file of a rendered job below `root` (native layout in the
/// job's sequence directory, then the other layouts) and returns its
/// manifest line; `seconds` is the frame's wall time so far.
pub fn write_job(
    root: &Path,
    config: &DatasetConfig,
    job: &Job,
    r: &RenderedFrame,
    seconds: f64,
) -> io::Result<ManifestLine> {
    let seq_dir = root.join(job.sequence_dir());
    let mut paths = write_native_frame(
        &seq_dir,
        job.frame,
        &r.rig,
        &r.out,
        r.meta.clone(),
        WriteOptions { hdr: config.hdr },
    )?;
    paths.extend(write_extra_layouts(
        &config.layouts,
        root,
        job,
        &r.rig,
        &r.out,
        &r.meta,
    )?);
    let mut files = paths
        .iter()
        .map(|p| FileRecord::of(root, p))
        .collect::<io::Result<Vec<_>>>()?;
    files.sort_by(|a, b| a.path.cmp(&b.path));
    let s = &r.out.stats;
    Ok(ManifestLine {
        town: job.town.clone(),
        config: job.config.name().to_string(),
        weather: job.weather.name().to_string(),
        sequence: job.sequence,
        frame: job.frame,
        town_frame: r.town_frame,
        seed: r.seed,
        seeds: Some(r.meta.seeds),
        files,
        render: RenderRecord {
            spp: config.spp,
            rays: s.gt_rays + s.path_rays,
            seconds,
        },
        disparity: r
            .out
            .baselines
            .iter()
            .map(|b| DisparityRecord::of(b.baseline_m * 100.0, &b.disparity_left))
            .collect(),
    })
}

/// True when every file of `line` exists with its recorded size (and, with
/// `check_hashes`, its SHA-256).
pub fn frame_complete(root: &Path, line: &ManifestLine, check_hashes: bool) -> bool {
    line.files.iter().all(|f| {
        if check_hashes {
            f.verify(root).unwrap_or(false)
        } else {
            std::fs::metadata(root.join(&f.path)).is_ok_and(|m| m.len() == f.bytes)
        }
    })
}
