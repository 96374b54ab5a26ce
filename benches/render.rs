//! Criterion benches on `scenes/street.toml`: the ground-truth pass (every view
//! and baseline, no path pass) and path tracing of the left view at 1 spp,
//! plain and with its image-space filter of sky and indirect light.
//! Images are reduced so a run stays short; `parallax bench` reports full-size
//! Mrays/s and the ratios to raw traversal.

use criterion::{criterion_group, criterion_main, Criterion};
use parallax::camera::StereoRig;
use parallax::render::recipe::{FrameRecipe, FrameSource, FrameSpec, Overrides};
use parallax::render::render_frame;
use parallax::scene::load_scene;

fn street(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/street.toml");
    let loaded = load_scene(std::path::Path::new(path)).expect("street.toml loads");
    // The street at 400×225, built once; without and with its image filters
    // (plain flags of the built scene, as in `parallax bench`).
    let spec = FrameSpec {
        overrides: Overrides {
            width: Some(400),
            height: Some(225),
            ..Overrides::default()
        },
        ..FrameSpec::default()
    };
    let recipe = FrameRecipe::new(FrameSource::scene(loaded), &spec).expect("street recipe");
    let prepared = recipe.prepare().expect("street builds");
    let (filtered, accel, rig) = (&prepared.built.scene, &prepared.built.accel, &prepared.rig);
    let mut plain = filtered.clone();
    (plain.filter_indirect, plain.filter_inscatter) = (false, false);
    let scene = &plain;
    let gt = parallax::render::RenderSettings {
        spp: 0,
        max_depth: 5,
        seed: 1,
        frame: 0,
        adaptive: false,
    };
    let mut group = c.benchmark_group("street_400x225");
    group.sample_size(10);
    group.bench_function("gt_pass_all_baselines", |b| {
        b.iter(|| render_frame(scene, accel, rig, &gt, &|_, _| {}))
    });
    let left_only = StereoRig {
        left: rig.left,
        baselines_m: Vec::new(),
    };
    let path = parallax::render::RenderSettings { spp: 1, ..gt };
    group.bench_function("path_left_1spp_depth5", |b| {
        b.iter(|| render_frame(scene, accel, &left_only, &path, &|_, _| {}))
    });
    group.bench_function("path_left_1spp_depth5_filtered", |b| {
        b.iter(|| render_frame(filtered, accel, &left_only, &path, &|_, _| {}))
    });
    group.finish();
}

criterion_group!(benches, street);
criterion_main!(benches);
