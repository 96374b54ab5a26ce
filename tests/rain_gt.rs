//! Rain and fog never touch the geometric ground truth; rain sets the mask's
//! rain bit where the streaks in front of the surface reach 1 % opacity; the streaks are
//! world-space, so a streak seen in the left view is found again from the
//! right camera at its reprojected position. Also the `[medium]`/`[rain]`
//! sections: round trip and bad input naming the key.

mod common;

use common::boxes::boxes_scene;
use common::{render, scene_from_toml, Rendered};
use parallax::accel::Backend;
use parallax::integrator::{frame_rain, RenderCamera};
use parallax::scene::{mask_bits, parse_scene_str, SceneDesc};

const FOG: &str = "\n[medium]\nkind = \"height_fog\"\nvisibility_m = 80.0\nheight_scale_m = 15.0\n";
const RAIN: &str = "\n[rain]\nrate_mm_per_h = 50.0\nextent_m = 25.0\n";

fn gt_only(extra: &str) -> Rendered {
    let text = boxes_scene(96, 64) + "[render]\nseed = 9\n" + extra;
    let mut loaded = scene_from_toml(&text);
    loaded.desc.camera.baselines_cm = vec![54.0, 200.0];
    render(&loaded, Backend::default_backend(), 0)
}

#[test]
fn gt_maps_are_bit_identical_with_and_without_fog_and_rain() {
    let clear = gt_only("");
    let rain_bits = |r: &Rendered| {
        r.out
            .left
            .mask
            .iter()
            .filter(|&&m| m & mask_bits::RAIN != 0)
            .count()
    };
    for extra in [FOG.to_string(), RAIN.to_string(), format!("{FOG}{RAIN}")] {
        let w = gt_only(&extra);
        let (a, b) = (&clear.out.left, &w.out.left);
        assert_eq!(
            a.depth_z.iter().map(|z| z.to_bits()).collect::<Vec<_>>(),
            b.depth_z.iter().map(|z| z.to_bits()).collect::<Vec<_>>()
        );
        assert_eq!(a.normal_world, b.normal_world);
        assert_eq!(a.semantic, b.semantic);
        assert_eq!(a.instance, b.instance);
        let strip = |m: &[u8]| m.iter().map(|x| x & !mask_bits::RAIN).collect::<Vec<_>>();
        assert_eq!(strip(&a.mask), strip(&b.mask));
        assert_eq!(clear.out.baselines, w.out.baselines);
        let n = rain_bits(&w);
        if extra.contains("[rain]") {
            assert!(n > 20, "{extra}: only {n} rain pixels");
        } else {
            assert_eq!(n, 0);
        }
    }
}

#[test]
fn rain_streak_seen_left_is_found_from_the_right_camera() {
    let r = gt_only(RAIN);
    let rain = frame_rain(&r.scene, 9, 0, r.rig.left.intrinsics.f_px).expect("rain");
    let min_coverage = rain.min_opacity_coverage();
    let left = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    let right_cam = r.rig.right(1);
    let w = left.intrinsics.width as usize;
    let mut checked = 0;
    for (k, &m) in r.out.left.mask.iter().enumerate() {
        if m & mask_bits::RAIN == 0 {
            continue;
        }
        let (i, j) = ((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
        let d = left.dir(i, j).normalize();
        let o = r.scene.origin_world + left.center;
        let hit = rain
            .first_streak(o, d, 0.0, f64::INFINITY, min_coverage)
            .expect("masked pixel sees a streak");
        let x = o + d * (0.5 * (hit.t + hit.t_far));
        // Reproject X into the right image and trace that pixel position.
        let uv = right_cam.project_world(x);
        if uv.x < 0.0 || uv.y < 0.0 || uv.x >= w as f64 || uv.y >= left.intrinsics.height as f64 {
            continue;
        }
        let o_r = right_cam.center_world;
        let d_r = right_cam.dir_world(uv.x, uv.y).normalize();
        let dist = (x - o_r).length();
        // The right ray passes X inside the capsule; its closest approach to
        // the axis lies within a few capsule radii of X along the ray.
        let mut along = [Default::default(); 8];
        let n = rain.streaks_along(o_r, d_r, (dist - 0.2, dist + 0.2), min_coverage, &mut along);
        assert!(
            along[..n].iter().any(|h| h.axis_top == hit.axis_top),
            "the right camera sees the streak at the reprojected point"
        );
        checked += 1;
    }
    assert!(checked > 20, "only {checked} rain pixels");
}

#[test]
fn medium_and_rain_sections_round_trip() {
    let text = boxes_scene(32, 16) + FOG + RAIN;
    let loaded = scene_from_toml(&text);
    let back: SceneDesc = toml::from_str(&loaded.desc.to_toml()).expect("re-parses");
    assert_eq!(back, loaded.desc);
    assert!(back.medium.is_some() && back.rain.is_some());
}

#[test]
fn bad_medium_and_rain_values_name_their_keys() {
    let path = std::path::Path::new("bad.toml");
    for (extra, key) in [
        (
            "\n[medium]\nkind = \"homogeneous\"\nvisibility_m = -5.0\nz_max_m = 100.0\n",
            "medium.visibility_m",
        ),
        (
            "\n[medium]\nkind = \"homogeneous\"\nvisibility_m = 50.0\nsigma_t = 0.1\n",
            "medium.sigma_t",
        ),
        (
            "\n[medium]\nkind = \"homogeneous\"\n",
            "medium.visibility_m",
        ),
        (
            "\n[medium]\nkind = \"height_fog\"\nsigma_t = 0.1\ng = 1.5\n",
            "medium.g",
        ),
        (
            "\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.1\nheight_scale_m = 3.0\n",
            "medium.height_scale_m",
        ),
        (
            "\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.1\nz_min_m = 5.0\nz_max_m = 1.0\n",
            "medium.z_max_m",
        ),
        (
            "\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.1\n",
            "medium.z_max_m",
        ),
        ("\n[rain]\nrate_mm_per_h = 0.0\n", "rain.rate_mm_per_h"),
        (
            "\n[rain]\nrate_mm_per_h = 5.0\nshutter_s = 2.0\n",
            "rain.shutter_s",
        ),
    ] {
        let text = boxes_scene(32, 16) + extra;
        let err = parse_scene_str(&text, path).expect_err(extra);
        let msg = err.to_string();
        assert!(
            msg.contains(key) && msg.contains("bad.toml"),
            "{extra}: {msg}"
        );
    }
}
