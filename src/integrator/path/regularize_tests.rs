//! Path regularisation (`Scene::regularize`): a diffuse floor in front of a
//! tall mirror under a small sun. The floor's light is the sun's direct
//! light plus the sun seen in the mirror, a caustic that only rare BSDF
//! samples find in plain path tracing; regularised, next-event estimation
//! at the widened mirror finds it, and the mean keeps the mirror's energy.

use std::path::Path;

use glam::Vec3;
use shaders_cpu::bsdf::fresnel::fr_complex_rgb;
use shaders_cpu::bsdf::Bsdf;

use crate::accel::{build_accel, Accel, Backend, Ray};
use crate::camera::StereoRig;
use crate::integrator::{RenderCamera, Shading};
use crate::sampler::{SampleStream, StreamKey};
use crate::scene::desc::SceneDesc;
use crate::scene::{build_scene, parse_scene_str, Scene};

const E_SUN: f32 = 1000.0;
const ALBEDO: f32 = 0.5;

/// Depth 2: the floor's direct light and what the mirror shows it, no more.
const SCENE: &str = r#"
[camera]
width = 80
height = 48
hfov_deg = 60.0
position = [0.0, 0.0, 1.65]
[render]
max_depth = 2
[[light]]
kind = "sun"
elevation_deg = 45.0
azimuth_deg = 180.0
irradiance = [1000.0, 1000.0, 1000.0]
[[material]]
name = "floor"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
[[material]]
name = "mirror"
kind = "conductor"
preset = "aluminium"
roughness = 0.0
[[object]]
kind = "quad"
size = [400.0, 400.0]
material = "floor"
[[object]]
kind = "quad"
size = [40.0, 80.0]
material = "mirror"
transform = { translate = [20.0, 0.0, 20.0], rotate_deg = [0.0, -90.0, 0.0] }
"#;

/// Mean radiance and its standard error over `n` paths through the bottom
/// centre pixel (floor 4.8 m ahead, lit by the sun and by its mirror image).
fn floor_pixel(scene: &Scene, rig: &StereoRig, n: u32) -> (Vec3, Vec3) {
    let accel = build_accel(Backend::default_backend(), &scene.accel_geometry()).expect("accel");
    let shading = Shading::new(scene, &accel);
    let ctx = shading.context(2);
    let cam = RenderCamera::new(&rig.left, scene.origin_world);
    let key = StreamKey {
        seed: 3,
        frame: 0,
        view: 0,
    };
    let (i, j) = (cam.intrinsics.width / 2, cam.intrinsics.height - 1);
    let d = cam
        .dir(i as f64 + 0.5, j as f64 + 0.5)
        .as_vec3()
        .normalize();
    let ray = Ray::new(cam.center_f32(), d);
    let hit = ctx.accel.intersect(&ray);
    let (mut sum, mut sq) = (Vec3::ZERO, Vec3::ZERO);
    for s in 0..n {
        let l = ctx
            .li_from_hit(
                ray,
                hit,
                cam.cone(ray.d),
                &mut SampleStream::new(key, i, j, s),
                &mut 0,
            )
            .l;
        sum += l;
        sq += l * l;
    }
    let mean = sum / n as f32;
    let var = (sq / n as f32 - mean * mean).max(Vec3::ZERO);
    (mean, (var / n as f32).powf(0.5))
}

/// The scene built as loaded, after `edit` of its description.
fn built_with(edit: impl FnOnce(&mut SceneDesc)) -> (Scene, StereoRig) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    let mut loaded = parse_scene_str(SCENE, &path).expect("scene parses");
    edit(&mut loaded.desc);
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let scene = build_scene(&loaded, rig.left.center_world).expect("scene builds");
    (scene, rig)
}

#[test]
fn a_mirrored_sun_on_a_diffuse_floor_is_found_by_next_event_estimation_when_regularised() {
    let (mut scene, rig) = built_with(|_| {});
    assert!(scene.regularize, "the default render regularises");
    let Bsdf::Conductor { eta, k, .. } = scene.materials[1].bsdf else {
        panic!("the mirror is a conductor");
    };
    // Sun at 45° on the floor and on the mirror (normal −x, sun towards −x).
    let cos45 = std::f32::consts::FRAC_1_SQRT_2;
    let r = fr_complex_rgb(cos45, eta, k);
    let direct = ALBEDO / std::f32::consts::PI * E_SUN * cos45;
    let expected = direct * (Vec3::ONE + r);

    let n = 16384;
    let (mean, se) = floor_pixel(&scene, &rig, n);
    for c in 0..3 {
        // The widened lobe keeps the mirror's light but for GGX's
        // single-scattering loss and the tail beyond the mirror (2.5 % of
        // the floor's light at alpha 0.1).
        let rel = (mean[c] - expected[c]) / expected[c];
        assert!(
            (-0.05..0.01).contains(&rel) && se[c] < 0.02 * expected[c],
            "channel {c}: {} ± {} vs {} ({rel})",
            mean[c],
            se[c],
            expected[c]
        );
    }

    // Plain path tracing (the reference mode) misses the caustic at this
    // count: a sun 0.53° wide is hit by about 1 in 40 000 BSDF samples, so
    // its estimate is the direct light alone or, once hit, far too bright.
    scene.regularize = false;
    let (plain, _) = floor_pixel(&scene, &rig, n);
    assert!(
        (plain.x - direct).abs() < 0.02 * direct || plain.x > 1.5 * expected.x,
        "plain {} direct {direct}",
        plain.x
    );
}

#[test]
fn reference_renders_do_not_regularise() {
    // What `render --reference` does (`render::recipe::reference_mode`).
    let (scene, _) = built_with(SceneDesc::turn_image_filters_off);
    assert!(!scene.regularize, "plain path tracing keeps every lobe");
}
