//! Determinism: a frame is a pure function of (scene, seed, frame index) —
//! the same bytes on 1 and 2 threads and across runs (GROUND_TRUTH.md).

use crate::common;

use common::{render, scene_from_toml, Rendered};
use parallax::accel::Backend;

fn scene() -> parallax::scene::LoadedScene {
    let text = format!(
        "{}[render]\nspp = 4\nmax_depth = 5\nseed = 11\n{}",
        common::camera_block(80, 48, [0.0, 0.0, 1.65]),
        r#"
[sky]
kind = "gradient"
zenith = [0.2, 0.4, 0.9]
horizon = [0.8, 0.8, 0.9]
ground = [0.1, 0.1, 0.1]
[[light]]
kind = "sun"
elevation_deg = 35.0
azimuth_deg = 200.0
irradiance = [800.0, 760.0, 700.0]
[[light]]
kind = "point"
position = [6.0, 2.0, 3.0]
intensity = [50.0, 40.0, 30.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
[[material]]
name = "metal"
kind = "conductor"
preset = "aluminium"
roughness = 0.3
[[material]]
name = "glass"
kind = "dielectric"
ior = 1.5
roughness = 0.0
tint = [1.0, 1.0, 1.0]
[[object]]
kind = "quad"
size = [200.0, 200.0]
material = "grey"
[[object]]
kind = "box"
size = [2.0, 2.0, 2.0]
material = "metal"
transform = { translate = [9.0, 1.0, 1.0], rotate_deg = [0.0, 0.0, 30.0] }
[[object]]
kind = "sphere"
radius = 1.0
material = "glass"
transform = { translate = [7.0, -1.5, 1.0] }
"#
    );
    scene_from_toml(&text)
}

fn render_on(threads: usize) -> Rendered {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| render(&scene(), Backend::default_backend(), 4))
}

fn assert_same(a: &Rendered, b: &Rendered) {
    assert_eq!(a.out.left, b.out.left, "left ground truth differs");
    assert_eq!(
        a.out.baselines, b.out.baselines,
        "per-baseline ground truth differs"
    );
    assert_eq!(a.out.images.len(), b.out.images.len());
    for (x, y) in a.out.images.iter().zip(&b.out.images) {
        let bits = |f: &parallax::film::Film| {
            f.rgb
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(x), bits(y), "images differ");
    }
    assert_eq!(
        a.out.exposure_scale.to_bits(),
        b.out.exposure_scale.to_bits()
    );
}

#[test]
fn frame_is_bitwise_identical_for_1_and_2_threads() {
    assert_same(&render_on(1), &render_on(2));
}

#[test]
fn frame_is_bitwise_identical_across_runs() {
    assert_same(&render_on(2), &render_on(2));
}

#[test]
fn different_seed_changes_the_image_but_not_the_ground_truth() {
    let a = render_on(2);
    let mut loaded = scene();
    loaded.desc.render.seed = Some(12);
    let b = render(&loaded, Backend::default_backend(), 4);
    assert_eq!(a.out.left, b.out.left);
    assert_ne!(a.out.images[0].rgb, b.out.images[0].rgb);
}
