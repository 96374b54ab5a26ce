//! Rain and fog never touch the geometric ground truth; rain sets the mask's
//! rain bit where the streaks in front of the surface reach 1 % opacity; the streaks are
//! world-space, so a streak seen in the left view is found again from the
//! right camera at its reprojected position. Also the `[medium]`/`[rain]`
//! sections: round trip and bad input naming the key.

use crate::common;

use common::boxes::boxes_scene;
use common::{render, scene_from_toml, Rendered};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::integrator::rain::{rain_opacity, MASK_MIN_OPACITY};
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
    let origin = r.scene.origin_world;
    let left = RenderCamera::new(&r.rig.left, origin);
    // Baseline 1 of `gt_only` is 2 m: the right camera at C_L + 2·x_L (x_L =
    // world −y for this level rig looking along +x).
    let b = 1;
    assert_eq!(r.out.baselines[b].baseline_m, 2.0);
    let right_cam = r.rig.right(b);
    assert!(
        (right_cam.center_world - (r.rig.left.center_world + DVec3::new(0.0, -2.0, 0.0))).length()
            < 1e-12
    );
    // The renderer's own right-view rain pass, bounded by the right depth.
    let right = RenderCamera::new(&right_cam, origin);
    let depth_right: Vec<f64> = r.out.baselines[b]
        .depth_right
        .iter()
        .map(|&z| z as f64)
        .collect();
    let alpha_right = rain_opacity(&r.scene, &rain, &right, &depth_right);
    let (w, h) = (
        left.intrinsics.width as usize,
        left.intrinsics.height as usize,
    );
    let o_r = right_cam.center_world;
    // Streaks the unit ray o + t·d meets before t_surface, and the opacity
    // they make: 1 − Π(1 − a).
    let streaks_before = |o: DVec3, d: DVec3, t_surface: f64| {
        let mut along = [Default::default(); 64];
        let n = rain.streaks_along(o, d, (0.0, t_surface), min_coverage, &mut along);
        assert!(n < along.len(), "more streaks than the buffer holds");
        let alpha = 1.0
            - along[..n]
                .iter()
                .map(|h| 1.0 - rain.streak_opacity(h))
                .product::<f64>();
        (along[..n].to_vec(), alpha)
    };
    // The same for the centre ray of right pixel (pi, pj), up to the right surface.
    let right_streaks = |pi: usize, pj: usize| {
        let dir = right.dir(pi as f64 + 0.5, pj as f64 + 0.5);
        streaks_before(
            o_r,
            dir.normalize(),
            depth_right[pj * w + pi] * dir.length(),
        )
    };
    let (mut pairs, mut found, mut found_unshifted) = (0usize, 0usize, 0usize);
    for (k, &m) in r.out.left.mask.iter().enumerate() {
        if m & mask_bits::RAIN == 0 {
            continue;
        }
        let (i, j) = ((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
        let dir = left.dir(i, j);
        let d = dir.normalize();
        // Rain counts only in front of the surface: t < Z·|dir| (dir has camera z 1).
        let t_surface = r.out.left.depth_z[k] * dir.length();
        let o = origin + left.center;
        let hit = rain
            .first_streak(o, d, 0.0, t_surface, min_coverage)
            .expect("a masked pixel sees a streak in front of its surface");
        assert!(hit.t_axis > 0.0 && hit.t_axis < t_surface);
        // The mask bit means the streaks before the surface reach 1 % opacity.
        let (_, alpha_left) = streaks_before(o, d, t_surface);
        assert!(
            alpha_left >= MASK_MIN_OPACITY as f64 * (1.0 - 1e-5),
            "masked left pixel {k}: opacity {alpha_left}"
        );
        // The drop's axis at the height where the left ray meets it,
        // reprojected into the right image.
        let x = o + d * hit.t_axis;
        let a = DVec3::new(hit.axis_top.x, hit.axis_top.y, x.z);
        let uv = right_cam.project_world(a);
        if uv.x < 0.0 || uv.y < 0.0 || uv.x >= w as f64 || uv.y >= h as f64 {
            continue;
        }
        let (pi, pj) = (uv.x as usize, uv.y as usize);
        let kr = pj * w + pi;
        // The drop must be in front of the right view's surface there.
        if depth_right[kr] <= right_cam.cam_from_world(a).z {
            continue;
        }
        pairs += 1;
        // The renderer's right-view opacity at that pixel is the streaks its
        // centre ray meets, and among them is the drop seen from the left.
        let (streaks, alpha) = right_streaks(pi, pj);
        assert!(
            (alpha_right[kr] as f64 - alpha).abs() <= 1e-6 + 1e-5 * alpha,
            "right pixel ({pi}, {pj}): rain opacity {} vs {alpha} from its streaks",
            alpha_right[kr]
        );
        if let Some(s) = streaks.iter().find(|s| s.axis_top == hit.axis_top) {
            assert!(alpha_right[kr] as f64 >= rain.streak_opacity(s) * (1.0 - 1e-5));
            found += 1;
        }
        // Control: the same pixel position without the disparity shift.
        if right_streaks(k % w, k / w)
            .0
            .iter()
            .any(|s| s.axis_top == hit.axis_top)
        {
            found_unshifted += 1;
        }
    }
    eprintln!(
        "{found}/{pairs} reprojected right pixels carry the left streak, \
         {found_unshifted} at the unshifted position"
    );
    assert!(
        pairs > 20,
        "only {pairs} rain pixels reproject into the right view"
    );
    assert!(
        found as f64 >= 0.9 * pairs as f64,
        "only {found}/{pairs} reprojected right pixels carry the left streak"
    );
    assert!(
        found_unshifted as f64 <= 0.1 * pairs as f64,
        "{found_unshifted}/{pairs} unshifted pixels carry the streak: the test cannot tell"
    );
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
