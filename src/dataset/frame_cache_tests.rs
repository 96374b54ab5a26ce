//! The cached static world renders the bytes a fresh build renders.

use super::*;
use crate::dataset::{parse_config, plan};
use crate::town::StaticScene;

/// The file records (paths and SHA-256) of `job` rendered through `cache`
/// and written below `root`.
fn files(
    config: &DatasetConfig,
    towns: &Towns,
    job: &Job,
    cache: &StaticCache,
    root: &Path,
) -> Vec<FileRecord> {
    let q = Quality::of(config);
    let r = render_job(
        config,
        towns,
        job,
        q,
        Backend::default_backend(),
        cache,
        &|_, _| {},
    )
    .unwrap();
    write_job(root, config, job, &r, 0.0).unwrap().files
}

/// A tiny configuration of town01 with `seed`.
fn config(seed: u64) -> DatasetConfig {
    let text = format!(
        "seed = {seed}\ntowns = [\"town01\"]\nconfigs = [\"normal\"]\n\
         weathers = [\"clear\"]\nbaselines_cm = [54.0]\nframes_per_sequence = 3\n\
         stride = 9\nwidth = 48\nheight = 27\nspp = 1\nmax_depth = 2\n"
    );
    parse_config(&text, "c.toml").unwrap()
}

/// Distinct (prefab, material map) placed by the moving objects of `job`:
/// at most this many prototypes are new from frame to frame.
fn moving_prototypes(config: &DatasetConfig, towns: &Towns, job: &Job) -> usize {
    let town = towns.get(&job.town).unwrap();
    let seed = town_seed(config.seed, &job.town);
    let stat = StaticScene::new(&town.desc, seed);
    let at = (drive_index(config, job), town_frame(config, job));
    let source = FrameSource::town_with(&stat, town, seed, at, job.config).unwrap();
    let l = &source.loaded;
    let keys: std::collections::BTreeSet<_> = (0..l.desc.objects.len())
        .filter(|&i| l.moves(i))
        .filter_map(|i| match &l.desc.objects[i].shape {
            crate::scene::desc::ShapeDesc::Instance {
                prefab,
                material_map,
            } => Some((prefab.clone(), material_map.clone())),
            _ => None,
        })
        .collect();
    keys.len()
}

#[test]
fn a_frame_through_the_cached_static_world_has_the_fresh_bytes() {
    let config = config(5);
    let towns = Towns::load(&config, None).unwrap();
    let jobs = plan(&config);
    let dir = tempfile::tempdir().unwrap();
    // Job 2 alone, as a shard starting mid-sequence renders it.
    let fresh = files(
        &config,
        &towns,
        &jobs[2],
        &StaticCache::default(),
        &dir.path().join("a"),
    );
    // Jobs 0 then 2 through one cache: job 2 reuses job 0's static world.
    let cache = StaticCache::default();
    files(&config, &towns, &jobs[0], &cache, &dir.path().join("b"));
    let cached = files(&config, &towns, &jobs[2], &cache, &dir.path().join("b"));
    assert_eq!(fresh, cached);
    if cfg!(feature = "embree") && Backend::default_backend() == Backend::Embree {
        // Every static prototype (static tiles and furniture, trees and
        // façade prefabs) was taken from the cache: only prototypes of the
        // moving objects may be new.
        let kept = cache.accel.prototypes();
        let moving = moving_prototypes(&config, &towns, &jobs[2]);
        assert!(kept > 50, "{kept} prototypes kept");
        assert!(
            cache.accel.reused() + moving >= kept,
            "{} of {kept} reused, {moving} moving",
            cache.accel.reused()
        );
    }
}

#[test]
fn a_cache_filled_by_another_town_gives_the_fresh_bytes() {
    let (a, b) = (config(5), config(6));
    let (towns_a, towns_b) = (
        Towns::load(&a, None).unwrap(),
        Towns::load(&b, None).unwrap(),
    );
    let (job_a, job_b) = (&plan(&a)[0], &plan(&b)[0]);
    let dir = tempfile::tempdir().unwrap();
    let fresh = files(
        &b,
        &towns_b,
        job_b,
        &StaticCache::default(),
        &dir.path().join("a"),
    );
    // The cache holds seed 5's town (its static tiles) when seed 6's comes.
    let cache = StaticCache::default();
    files(&a, &towns_a, job_a, &cache, &dir.path().join("b"));
    let held = cache.accel.prototypes();
    let cached = files(&b, &towns_b, job_b, &cache, &dir.path().join("b"));
    assert_eq!(fresh, cached);
    if cfg!(feature = "embree") && Backend::default_backend() == Backend::Embree {
        // Shared prefabs (vehicles, people, street props) may come from the
        // cache; another layout's tiles cannot.
        assert!(held > 50, "{held} prototypes held");
        assert!(cache.accel.reused() < cache.accel.prototypes());
    }
}
