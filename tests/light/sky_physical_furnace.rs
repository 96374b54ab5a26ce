//! The physical sky in the renderer: a Lambert plane under the tabulated sky
//! and its sun converges (NEE + MIS) to ρ/π·(E_sky + E_sun·sin e) with E_sky
//! integrated from the table, and the weather presets wire the skies:
//! physical with an atmosphere-driven sun, overcast without one, night with a
//! moon; cloud shadows in NEE agree between two render origins.

use crate::common;

use common::{mean_stderr, render, scene_from_toml};
use glam::{DVec3, Vec2, Vec3};
use parallax::accel::Backend;
use parallax::light::{Light, LightSet};
use parallax::scene::build_scene;
use parallax::weather::{apply, draw_params, Weather};
use shaders_cpu::sky::Sky;

/// ∫_{z>0} le·cos θ dω (green) by a midpoint rule uniform in z and φ.
fn upper_irradiance(sky: &Sky) -> f64 {
    let (nz, np) = (400, 800);
    let mut e = 0.0f64;
    for j in 0..nz {
        let z = (j as f32 + 0.5) / nz as f32;
        let r = (1.0 - z * z).sqrt();
        for i in 0..np {
            let phi = std::f32::consts::TAU * (i as f32 + 0.5) / np as f32;
            e += (sky.le(Vec3::new(r * phi.cos(), r * phi.sin(), z)).y * z) as f64;
        }
    }
    e * std::f64::consts::TAU / (nz * np) as f64
}

fn plane_scene(sky: &str, rho: f64) -> String {
    format!(
        "[camera]\nwidth = 96\nheight = 64\nhfov_deg = 40.0\nbaselines_cm = [10.0]\nposition = [0.0, 0.0, 2.0]\npitch_deg = 60.0\n\
[render]\nspp = 64\nmax_depth = 4\nseed = 5\n{sky}\n\
[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [{rho:?}, {rho:?}, {rho:?}]\n\
[[object]]\nkind = \"quad\"\nsize = [1000.0, 1000.0]\nmaterial = \"m\"\ninstance = 3\n"
    )
}

#[test]
fn lambert_plane_under_tabulated_sky_and_sun_matches_table_irradiance() {
    let (rho, elev) = (0.5f64, 25.0f64);
    let sky = format!(
        "[sky]\nkind = \"physical\"\nsun_elevation_deg = {elev:?}\nsun_azimuth_deg = 120.0\n"
    );
    let r = render(
        &scene_from_toml(&plane_scene(&sky, rho)),
        Backend::default_backend(),
        64,
    );
    let e_sky = upper_irradiance(&r.scene.sky);
    let e_sun = match r.scene.lights.as_slice() {
        [Light::Sun { irradiance, .. }] => irradiance.y as f64,
        other => panic!("expected the sky's sun, got {other:?}"),
    };
    let expected = rho / std::f64::consts::PI * (e_sky + e_sun * elev.to_radians().sin());
    let (w, h) = (r.out.left.width as usize, r.out.left.height as usize);
    let values: Vec<f64> = (0..w * h)
        .filter(|&k| r.out.left.instance[k] == 3)
        .map(|k| r.out.images[0].rgb[k].y as f64)
        .collect();
    let (mean, se) = mean_stderr(&values);
    eprintln!(
        "E_sky {e_sky:.3}, E_sun {e_sun:.3}: mean {mean:.4} ± {se:.4}, expected {expected:.4}"
    );
    assert!(values.len() > 1000);
    assert!(
        (mean - expected).abs() <= 0.01 * expected,
        "{mean} vs {expected}"
    );
    assert!(
        (mean - expected).abs() <= 4.0 * se + 1e-4 * expected,
        "z-score"
    );
}

/// The irradiance of every sun (or moon) of `scene`.
fn sun_irradiances(scene: &parallax::scene::Scene) -> Vec<Vec3> {
    scene
        .lights
        .iter()
        .filter_map(|l| match l {
            Light::Sun { irradiance, .. } => Some(*irradiance),
            _ => None,
        })
        .collect()
}

fn weather_scene(w: Weather, origin: DVec3) -> parallax::scene::Scene {
    let mut loaded = scene_from_toml(&plane_scene(
        "[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n[[light]]\nkind = \"sun\"\nelevation_deg = 40.0\nazimuth_deg = 0.0\nirradiance = [1.0, 1.0, 1.0]\n",
        0.5,
    ));
    apply(&mut loaded.desc, &draw_params(w, 17));
    build_scene(&loaded, origin).expect("weather scene builds")
}

#[test]
fn weather_presets_choose_their_sky_and_source() {
    for w in Weather::ALL {
        let p = draw_params(w, 17);
        let scene = weather_scene(w, DVec3::ZERO);
        let suns = sun_irradiances(&scene);
        eprintln!(
            "{w}: elevation {:.1}°, sources {suns:?}",
            p.sun_elevation_deg
        );
        match w {
            Weather::Clear | Weather::Humid | Weather::Foggy => {
                assert!(matches!(scene.sky, Sky::Physical(_)), "{w}");
                assert_eq!(suns.len(), 1, "{w}");
                // Atmosphere-driven: a high sun gives hundreds of W·m⁻², less than the 980 zenith sun.
                assert!(suns[0].x > 200.0 && suns[0].x < 980.0, "{w}: {:?}", suns[0]);
            }
            Weather::Sunset => {
                assert!(matches!(scene.sky, Sky::Physical(_)));
                check_sunset_sun(p.sun_elevation_deg, &suns);
            }
            Weather::Cloudy if p.cloud_cover < parallax::weather::OVERCAST_COVER => {
                // Broken cloud: the physical sky with its drawn deck and the sun.
                assert!(matches!(scene.sky, Sky::Physical(_)), "{w}");
                assert_eq!(suns.len(), 1, "{w}");
            }
            Weather::Cloudy | Weather::Storm => {
                assert!(matches!(scene.sky, Sky::Overcast(_)), "{w}");
                assert!(suns.is_empty(), "{w}: sun not diffused");
            }
            Weather::Night => {
                assert!(matches!(scene.sky, Sky::Physical(_)));
                assert_eq!(suns.len(), 1, "the moon");
                // Full moon ≈ 2.5e-6 of the sun, dimmed by the atmosphere and
                // scaled by the drawn phase (Lambert-sphere law).
                let moon = p.moon.expect("night draws a moon");
                let phase = parallax::light::moon_phase_factor(moon.phase_deg) as f32;
                let y = suns[0].y / phase;
                assert!(y > 5e-4 && y < 2.7e-3, "{:?} / {phase}", suns[0]);
            }
        }
    }
}

/// The sun's disk has an angular radius of about 0.27°: while its centre is
/// above the horizon there is exactly one sun, red (the long air mass takes
/// the blue); once the whole disk is below (centre ≤ −0.27°) there is none.
/// In between (a partly set disk) either is allowed.
fn check_sunset_sun(elevation_deg: f64, suns: &[Vec3]) {
    if elevation_deg > 0.0 {
        assert_eq!(suns.len(), 1, "sunset at {elevation_deg:.2}°: {suns:?}");
        let s = suns[0];
        assert!(s.x > 0.0, "sunset sun at {elevation_deg:.2}° is black: {s}");
        assert!(
            s.x > 2.0 * s.z,
            "sunset sun at {elevation_deg:.2}° not red: {s}"
        );
    } else if elevation_deg <= -0.27 {
        assert!(suns.is_empty(), "set sun at {elevation_deg:.2}°: {suns:?}");
    }
}

#[test]
fn sunset_has_one_red_sun_until_the_disk_sets() {
    // Sunset draws the elevation in [−2°, 6°]: over these seeds both a sun
    // above the horizon and a set one must occur.
    let (mut up, mut set) = (0, 0);
    for seed in 0..24 {
        let p = draw_params(Weather::Sunset, seed);
        let mut loaded = scene_from_toml(&plane_scene(
            "[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n",
            0.5,
        ));
        apply(&mut loaded.desc, &p);
        let scene = build_scene(&loaded, DVec3::ZERO).expect("sunset scene builds");
        assert!(matches!(scene.sky, Sky::Physical(_)), "seed {seed}");
        let suns = sun_irradiances(&scene);
        check_sunset_sun(p.sun_elevation_deg, &suns);
        up += (p.sun_elevation_deg > 0.0) as u32;
        set += (p.sun_elevation_deg <= -0.27) as u32;
    }
    assert!(up > 0 && set > 0, "{up} suns up, {set} set over 24 seeds");
}

#[test]
fn cloud_shadow_in_nee_is_the_same_from_two_render_origins() {
    // Same world points, scenes centred 0.54 m and 2 km apart.
    let mut loaded = scene_from_toml(&plane_scene(
        "[sky]\nkind = \"physical\"\nsun_elevation_deg = 50.0\nsun_azimuth_deg = 30.0\ncloud_cover = 0.5\ncloud_seed = 9\n",
        0.5,
    ));
    loaded.desc.render.seed = Some(1);
    let origins = [DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.54, 2000.0, 2.0)];
    let scenes: Vec<_> = origins
        .iter()
        .map(|&o| build_scene(&loaded, o).unwrap())
        .collect();
    let sets: Vec<_> = scenes.iter().map(LightSet::build).collect();
    let sun_k = (0..sets[0].distant_count())
        .find(|&k| {
            sets[0]
                .sample_distant(&scenes[0], k, Vec3::ZERO, Vec2::splat(0.5))
                .is_some_and(|s| s.pdf > 1e3)
        })
        .expect("a sun among the distant lights");
    let (mut lit, mut dark) = (0, 0);
    for i in 0..400 {
        let p_world = DVec3::new(53.0 * i as f64, -31.0 * i as f64, 0.0);
        let li: Vec<f32> = (0..2)
            .map(|s| {
                let p_render = (p_world - origins[s]).as_vec3();
                sets[s]
                    .sample_distant(&scenes[s], sun_k, p_render, Vec2::splat(0.5))
                    .unwrap()
                    .li
                    .y
            })
            .collect();
        assert!(
            (li[0] - li[1]).abs() <= 1e-3 * li[0].max(1e-6),
            "{i}: {li:?}"
        );
        let full = sets[0]
            .sample_distant(
                &scenes[0],
                sun_k,
                (DVec3::new(0.0, 0.0, 5000.0) - origins[0]).as_vec3(),
                Vec2::splat(0.5),
            )
            .unwrap()
            .li
            .y;
        if li[0] < 0.5 * full {
            dark += 1;
        } else {
            lit += 1;
        }
    }
    eprintln!("lit {lit}, shadowed {dark}");
    assert!(lit > 50 && dark > 50, "lit {lit}, shadowed {dark}");
}
