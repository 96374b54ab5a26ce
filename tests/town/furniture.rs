//! Street furniture in generated towns: every furniture class is built into
//! the towns whose style has it (guard rails on highways, fences, poles,
//! signs, signals and static fixtures), speed signs show limits from the
//! seeded set at most the town's speed, furniture is a pure function of the
//! seed, and a thin part (a 16 mm railing bar) seen by the camera has exact
//! depth: the ground truth equals the f64 slab intersection of the
//! independently built pixel ray with the bar, 1e-6 relative, kilometres
//! from the origin.

use std::path::Path;

use glam::DVec3;
use parallax::accel::Backend;
use parallax::scene::build_scene;
use parallax::scene::desc::{serialize_scene, ShapeDesc};
use parallax::scene::semantic::class_id;
use parallax::town::parts::{class, ground_quad, instance};
use parallax::town::street::barriers::{RAILING_M, RAILING_PANELS};
use parallax::town::street::names::SPEED_LIMITS;
use parallax::town::{load_town_frame, static_objects, town_scene, CameraConfig};

use crate::common;
use common::boxes::slab_interval;
use common::towns::town;

const SEED: u64 = 5;

/// Semantic ids present among the built meshes of `name`'s frame 0,
/// instances included.
fn built_classes(name: &str) -> Vec<u8> {
    let desc = town(name);
    let loaded = load_town_frame(&desc, SEED, 0, CameraConfig::Normal, Path::new("t.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let scene = build_scene(&loaded, DVec3::ZERO).expect("town builds");
    let mut ids: Vec<u8> = scene.flattened_meshes().map(|m| m.semantic).collect();
    ids.sort_unstable();
    ids.dedup();
    ids
}

#[test]
fn every_furniture_class_is_built_where_the_style_has_it() {
    let want: [(&str, &[&str]); 3] = [
        (
            "town03",
            &["pole", "traffic_sign", "traffic_light", "static", "fence"],
        ),
        ("town06", &["pole", "traffic_sign", "static", "guard_rail"]),
        ("town07", &["pole", "traffic_sign", "static", "fence"]),
    ];
    for (name, classes) in want {
        let ids = built_classes(name);
        for c in classes {
            let id = class_id(c).unwrap();
            assert!(ids.contains(&id), "{name} has no {c}");
        }
    }
    // No guard rails in a city.
    assert!(!built_classes("town02").contains(&class_id("guard_rail").unwrap()));
}

#[test]
fn speed_signs_show_seeded_limits_up_to_the_town_speed_and_furniture_follows_the_seed() {
    for name in ["town03", "town06"] {
        let desc = town(name);
        let objects = static_objects(&desc, SEED);
        let speeds: Vec<u32> = objects
            .iter()
            .filter_map(|o| match &o.shape {
                ShapeDesc::Instance { prefab, .. } => prefab.strip_prefix("sign_speed_"),
                _ => None,
            })
            .map(|s| s.parse().unwrap())
            .collect();
        assert!(speeds.len() >= 3, "{name}: {speeds:?}");
        for s in &speeds {
            assert!(SPEED_LIMITS.contains(s), "{name}: {s}");
            assert!(
                *s as f64 <= desc.speed_kmh,
                "{name}: {s} over the town speed"
            );
        }
        assert_eq!(objects, static_objects(&desc, SEED));
        assert_ne!(objects, static_objects(&desc, SEED + 1));
    }
}

#[test]
fn a_railing_bar_seen_by_the_camera_has_exact_depth() {
    let desc = town("town02");
    let mut scene = town_scene(&desc, SEED, 0, CameraConfig::Normal);
    // A kerb railing running along +y (heading 90: local x → world +y,
    // local y → world −x), far from the origin.
    let anchor = DVec3::new(3021.37, -1877.11, 0.0);
    let (w, h) = (160u32, 90u32);
    scene.objects = vec![
        instance("railing_run", anchor.to_array(), 90.0, &[], class("fence")),
        ground_quad(
            [anchor.x - 50.0, anchor.y - 50.0],
            [anchor.x + 50.0, anchor.y + 50.0],
            0.0,
            "sidewalk",
            class("sidewalk"),
        ),
    ];
    let eye = anchor + DVec3::new(-1.5, 3.0, 0.6);
    let cam = &mut scene.camera;
    (cam.width, cam.height, cam.hfov_deg) = (w, h, 60.0);
    cam.baselines_cm = vec![10.0];
    cam.position = eye.to_array();
    (cam.yaw_deg, cam.pitch_deg, cam.roll_deg) = (0.0, 0.0, 0.0);
    let loaded = common::scene_from_toml(&serialize_scene(&scene));
    let r = common::render(&loaded, Backend::Embree, 0);
    // The bars: 16 mm square, 0.2–1.0 m up, eight per 2 m panel.
    let bars: Vec<(DVec3, DVec3)> = (0..RAILING_PANELS)
        .flat_map(|p| (1..9).map(move |i| p as f64 * RAILING_M + i as f64 * RAILING_M / 9.0))
        .map(|along| {
            let c = anchor + DVec3::new(0.0, along, 0.6);
            let half = DVec3::new(0.008, 0.008, 0.4);
            (c - half, c + half)
        })
        .collect();
    // Pixel rays from first principles: looking along +x, image right is
    // −y, image down −z; camera-z component 1, so t is depth_z.
    let f = (w as f64 / 2.0) / 30f64.to_radians().tan();
    let fence = class_id("fence").unwrap();
    let mut checked = 0;
    for j in 0..h {
        for i in 0..w {
            let (u, v) = (
                i as f64 + 0.5 - w as f64 / 2.0,
                j as f64 + 0.5 - h as f64 / 2.0,
            );
            let d = DVec3::new(1.0, -u / f, -v / f);
            let Some(t) = bars
                .iter()
                .map(|(lo, hi)| slab_interval(eye, d, *lo, *hi))
                .filter(|(t0, t1)| t0 < t1 && t1 - t0 > 1e-5 * t0)
                .map(|(t0, _)| t0)
                .min_by(f64::total_cmp)
            else {
                continue;
            };
            // Away from the rails (radius 20 mm at 0.2 and 1.0 m).
            let z = eye.z + d.z * t;
            if (z - 0.2).abs() < 0.03 || (z - 1.0).abs() < 0.03 {
                continue;
            }
            let k = (j * w + i) as usize;
            let got = r.out.left.depth_z[k];
            assert!(
                (got - t).abs() <= 1e-6 * t,
                "pixel ({i}, {j}): {got} vs {t}"
            );
            assert_eq!(r.out.left.semantic[k], fence, "pixel ({i}, {j})");
            checked += 1;
        }
    }
    assert!(checked > 300, "{checked} bar pixels");
}
