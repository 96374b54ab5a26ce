//! Ground truth on a façade close-up: one window bay prefab of the
//! `modern_mixed` style (one pane, no transom) 4 m ahead of a level rig,
//! its glass recessed `recess_m` into the wall. Every pixel whose ray meets
//! the glass inside its frame has depth exactly 4 m + recess (the glass is
//! the first surface, transparent-flagged), every pixel on the piers beside
//! the opening exactly 4 m, and disparities f·B/Z at every baseline — the
//! expected values from the style's numbers, not from the renderer.

use crate::common;

use common::{camera_block, render, scene_from_toml};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::scene::serialize_scene;
use parallax::town::facade::{self, bay, STYLES};

const W: u32 = 96;
const H: u32 = 54;
/// Distance of the wall plane ahead of the rig.
const WALL_X: f64 = 4.0;
const EYE_Z: f64 = 1.5;

#[test]
fn facade_glass_depth_is_the_wall_distance_plus_the_recess() {
    let s = STYLES.iter().find(|s| s.name == "modern_mixed").unwrap();
    assert!(s.panes == 1 && !s.transom);
    let o = bay::window_opening(s);
    // The bay faces the rig (heading 270°: its outside, local −y, is
    // world −x), the opening's centre at eye height.
    let z0 = EYE_Z - (o.z0 + o.z1) / 2.0;
    let base = format!(
        "{}baselines_cm = [10.0, 54.0, 300.0]\n[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n",
        camera_block(W, H, [0.0, 0.0, EYE_Z])
    );
    let mut scene = scene_from_toml(&format!(
        "{base}[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n"
    ))
    .desc;
    let town = parallax::town::load_named_town("town01", None)
        .unwrap()
        .desc;
    scene.materials = parallax::town::materials::town_materials(&town);
    scene.prefabs = facade::facade_prefabs();
    let label = parallax::town::parts::Label {
        class: "building",
        instance: 1234,
    };
    let name = facade::prefab_name(s, "window_0");
    let bay = parallax::town::parts::instance(&name, [WALL_X, 0.0, z0], 270.0, &[], label);
    scene.objects = vec![bay];
    let r = render(
        &scene_from_toml(&serialize_scene(&scene)),
        Backend::default_backend(),
        0,
    );

    let f = (W as f64 / 2.0) / 30f64.to_radians().tan();
    let glass_z = WALL_X + s.recess_m;
    let (mut glass, mut wall) = (0, 0);
    for j in 0..H {
        for i in 0..W {
            let d = DVec3::new(
                1.0,
                -((i as f64 + 0.5) - W as f64 / 2.0) / f,
                -((j as f64 + 0.5) - H as f64 / 2.0) / f,
            );
            let k = (j * W + i) as usize;
            // Where the ray meets the glass plane and the wall plane
            // (y along the wall, z up), in the bay's frame.
            let at = |x: f64| (d.y * x, EYE_Z + d.z * x - z0);
            let (gy, gz) = at(glass_z);
            let frame = 0.06 + 0.01;
            let in_glass = gy.abs() < o.half_w - frame && gz > o.z0 + frame && gz < o.z1 - frame;
            let (wy, wz) = at(WALL_X);
            let on_pier = wy.abs() > o.half_w + 0.2
                && wy.abs() < s.bay_m / 2.0 - 0.01
                && wz > o.z0 + 0.1
                && wz < o.z1 - 0.1;
            let expected = if in_glass {
                glass += 1;
                glass_z
            } else if on_pier {
                wall += 1;
                WALL_X
            } else {
                continue;
            };
            let z = r.out.left.depth_z[k];
            assert!(
                (z - expected).abs() <= 1e-5 * expected,
                "pixel ({i},{j}): Z {z} vs {expected}"
            );
            assert_eq!(r.out.left.instance[k], 1234, "pixel ({i},{j})");
            let transparent = r.out.left.mask[k] & 4 != 0;
            assert_eq!(
                transparent, in_glass,
                "pixel ({i},{j}) mask {}",
                r.out.left.mask[k]
            );
            for b in &r.out.baselines {
                let dt = f * b.baseline_m / expected;
                let dd = b.disparity_left[k] as f64;
                assert!(
                    (dd - dt).abs() <= 1e-5 * dt + 1e-6,
                    "pixel ({i},{j}) B={}: d {dd} vs {dt}",
                    b.baseline_m
                );
            }
        }
    }
    assert!(
        glass > 300 && wall > 20,
        "{glass} glass and {wall} wall pixels"
    );
}
