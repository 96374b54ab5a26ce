//! The cached static world renders the bytes a fresh build renders.

use super::*;
use crate::dataset::{parse_config, plan};

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

#[test]
fn a_frame_through_the_cached_static_world_has_the_fresh_bytes() {
    let text = "seed = 5\ntowns = [\"town01\"]\nconfigs = [\"normal\"]\n\
                weathers = [\"clear\"]\nbaselines_cm = [54.0]\nframes_per_sequence = 3\n\
                stride = 9\nwidth = 48\nheight = 27\nspp = 1\nmax_depth = 2\n";
    let config = parse_config(text, "c.toml").unwrap();
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
    let kept = cache.accel.prototypes();
    let cached = files(&config, &towns, &jobs[2], &cache, &dir.path().join("b"));
    assert_eq!(fresh, cached);
    if cfg!(feature = "embree") && Backend::default_backend() == Backend::Embree {
        // The static prototypes were taken from the cache, not rebuilt.
        assert!(kept > 50, "{kept} prototypes kept");
        assert!(
            cache.accel.reused() * 10 >= kept * 9,
            "{} of {kept}",
            cache.accel.reused()
        );
    }
}
