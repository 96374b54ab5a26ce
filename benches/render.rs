//! Criterion benches on `scenes/street.toml`: the ground-truth pass (every view
//! and baseline, no path pass) and path tracing of the left view at 1 spp,
//! plain and with its image-space filter of sky and indirect light.
//! Images are reduced so a run stays short; `parallax bench` reports full-size
//! Mrays/s and the ratios to raw traversal.

use criterion::{criterion_group, criterion_main, Criterion};
use parallax::accel::{build_accel, Backend};
use parallax::camera::StereoRig;
use parallax::render::{render_frame, RenderSettings};
use parallax::scene::{build_scene, load_scene};

fn street(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/street.toml");
    let mut loaded = load_scene(std::path::Path::new(path)).expect("street.toml loads");
    loaded.desc.camera.width = 400;
    loaded.desc.camera.height = 225;
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let filtered = build_scene(&loaded, rig.left.center_world).expect("street builds");
    loaded.desc.turn_image_filters_off();
    let scene = build_scene(&loaded, rig.left.center_world).expect("street builds");
    let accel = build_accel(Backend::default_backend(), &scene.accel_geometry()).expect("accel");
    let gt = RenderSettings {
        spp: 0,
        max_depth: 5,
        seed: 1,
        frame: 0,
    };
    let mut group = c.benchmark_group("street_400x225");
    group.sample_size(10);
    group.bench_function("gt_pass_all_baselines", |b| {
        b.iter(|| render_frame(&scene, &accel, &rig, &gt, &|_, _| {}))
    });
    let left_only = StereoRig {
        left: rig.left,
        baselines_m: Vec::new(),
    };
    let path = RenderSettings { spp: 1, ..gt };
    group.bench_function("path_left_1spp_depth5", |b| {
        b.iter(|| render_frame(&scene, &accel, &left_only, &path, &|_, _| {}))
    });
    group.bench_function("path_left_1spp_depth5_filtered", |b| {
        b.iter(|| render_frame(&filtered, &accel, &left_only, &path, &|_, _| {}))
    });
    group.finish();
}

criterion_group!(benches, street);
criterion_main!(benches);
