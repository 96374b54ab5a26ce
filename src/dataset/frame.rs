//! One job, rendered and written: the town frame seen from the job's camera
//! configuration under the sequence's weather, at the configuration's
//! resolution and quality (the frame recipe `render::recipe`, as `parallax
//! render --town` follows it), then every file written atomically and
//! described by a manifest line.

use std::collections::BTreeMap;
use std::io;
use std::path::Path;
use std::sync::{Arc, Mutex};

use super::config::DatasetConfig;
use super::layouts::write_extra_layouts;
use super::manifest::{DisparityRecord, ManifestLine, RenderRecord};
use super::plan::{drive_index, frame_seed, sequence_seed, town_frame, town_seed, Job};
use crate::accel::{AccelCache, Backend};
use crate::camera::StereoRig;
use crate::output::frame::{write_native_frame, CameraFile, WriteOptions};
use crate::output::FileRecord;
use crate::render::recipe::{
    FrameRecipe, FrameRender, FrameSource, FrameSpec, Overrides, WeatherChoice,
};
use crate::render::FrameOutput;
use crate::town::{load_named_town, NamedTown, StaticScene, TownSource};

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

/// What the jobs of one town (name and seed) share, kept while consecutive
/// jobs render it: the static part of the town (`StaticScene`) and the
/// accelerators of its prototypes (`AccelCache`). Everything cached is a pure
/// function of the town, its seed and geometry bits, so a job renders the
/// same bytes whether the cache was filled by an earlier job or not.
#[derive(Default)]
pub struct StaticCache {
    town: Mutex<Option<HeldTown>>,
    accel: AccelCache,
}

impl StaticCache {
    /// The static part of `town` with `seed`: the one held, else generated
    /// (dropping what was held for another town or seed).
    fn scene(&self, name: &str, town: &NamedTown, seed: u64) -> Arc<StaticScene> {
        let mut held = self.town.lock().unwrap_or_else(|e| e.into_inner());
        match &*held {
            Some((key, s)) if key.0 == name && key.1 == seed => s.clone(),
            _ => {
                // Drop the old town before generating the new one.
                *held = None;
                let s = Arc::new(StaticScene::new(&town.desc, seed));
                *held = Some(((name.to_string(), seed), s.clone()));
                s
            }
        }
    }
}

/// (town name, seed) and its static part.
type HeldTown = ((String, u64), Arc<StaticScene>);

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
            spp: config.spp(),
        }
    }
}

/// Renders `job` at `quality` with what `cache` holds of its town (see
/// [`StaticCache`]); `progress(views_done, views)` is called as views finish.
pub fn render_job(
    config: &DatasetConfig,
    towns: &Towns,
    job: &Job,
    quality: Quality,
    backend: Backend,
    cache: &StaticCache,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<RenderedFrame, String> {
    let town = towns.get(&job.town)?;
    let t_frame = town_frame(config, job);
    let t_seed = town_seed(config.seed, &job.town);
    let drive = drive_index(config, job);
    let stat = cache.scene(&job.town, town, t_seed);
    let source = FrameSource::town_with(&stat, town, t_seed, (drive, t_frame), job.config)
        .map_err(|e| e.to_string())?;
    drop(stat);
    let spec = FrameSpec {
        overrides: Overrides {
            spp: Some(config.frame_spp(job.weather, quality.spp)),
            max_depth: Some(config.max_depth),
            width: Some(quality.width),
            height: Some(quality.height),
            baselines_cm: Some(config.baselines_cm.clone()),
            hfov_deg: Some(config.hfov_deg),
            seed: Some(frame_seed(config.seed, job)),
        },
        frame: job.frame,
        weather: Some(WeatherChoice {
            preset: job.weather,
            seed: Some(sequence_seed(
                config.seed,
                &job.town,
                job.weather,
                job.sequence,
            )),
        }),
        sensor_noise_iso: None,
        filter: config.filter,
        denoiser: Some(config.denoiser),
        reference: false,
        adaptive: false,
        backend,
    };
    let recipe = FrameRecipe::new(source, &spec).map_err(|e| e.to_string())?;
    let prepared = recipe
        .prepare_cached(&cache.accel)
        .map_err(|e| e.to_string())?;
    let FrameRender { out, meta } = prepared.render(progress);
    Ok(RenderedFrame {
        rig: prepared.rig,
        out,
        seed: recipe.settings.seed,
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
            spp: r.meta.spp,
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

#[cfg(test)]
#[path = "frame_cache_tests.rs"]
mod cache_tests;
