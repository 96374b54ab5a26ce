//! The weather changes light, never geometry: one frame's ground truth is
//! bit-identical across all seven presets (the rain bit of the mask aside,
//! which marks particles, not surfaces, and the mirror bit, which puddles of
//! wet presets add on unchanged geometry), while the images do change.

use crate::common;

use std::path::Path;

use parallax::accel::Backend;
use parallax::scene::load_scene;
use parallax::scene::mask_bits::{MIRROR as MASK_MIRROR, RAIN as MASK_RAIN};
use parallax::weather::{apply, draw_params, Weather};

fn street_frame(weather: Option<Weather>) -> common::Rendered {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/street.toml");
    let mut loaded = load_scene(&path).expect("street loads");
    loaded.desc.camera.width = 96;
    loaded.desc.camera.height = 54;
    loaded.desc.render.max_depth = 3;
    loaded.desc.render.seed = Some(11);
    if let Some(w) = weather {
        apply(&mut loaded.desc, &draw_params(w, 11));
    }
    common::render(&loaded, Backend::default_backend(), 1)
}

#[test]
fn ground_truth_is_bit_identical_across_every_weather() {
    let reference = street_frame(None).out;
    let without_rain = |m: &[u8]| {
        m.iter()
            .map(|b| b & !(MASK_RAIN | MASK_MIRROR))
            .collect::<Vec<u8>>()
    };
    for w in Weather::ALL {
        let out = street_frame(Some(w)).out;
        let (a, b) = (&reference.left, &out.left);
        let bits = |v: &[f64]| v.iter().map(|z| z.to_bits()).collect::<Vec<u64>>();
        assert_eq!(bits(&a.depth_z), bits(&b.depth_z), "{w}: depth");
        assert_eq!(a.normal_world, b.normal_world, "{w}: normals");
        assert_eq!(a.semantic, b.semantic, "{w}: semantic");
        assert_eq!(a.instance, b.instance, "{w}: instance");
        assert_eq!(without_rain(&a.mask), without_rain(&b.mask), "{w}: mask");
        assert_eq!(reference.baselines, out.baselines, "{w}: per-baseline GT");
        assert_ne!(reference.images[0], out.images[0], "{w}: image unchanged");
    }
}

#[test]
fn night_is_darker_than_noon_after_exposure() {
    let mean_exposed = |w: Weather| {
        let out = street_frame(Some(w)).out;
        let film = &out.images[0];
        let sum: f64 = film
            .rgb
            .iter()
            .map(|c| parallax::film::luminance_rec709(*c) as f64)
            .sum();
        sum / film.rgb.len() as f64 * out.exposure_scale as f64
    };
    let (clear, night) = (mean_exposed(Weather::Clear), mean_exposed(Weather::Night));
    assert!(night < 0.5 * clear, "night {night} vs clear {clear}");
}

#[test]
fn preset_parameters_are_seeded_and_in_range() {
    for w in Weather::ALL {
        assert_eq!(draw_params(w, 5), draw_params(w, 5));
        assert_ne!(draw_params(w, 5), draw_params(w, 6), "{w}: no variation");
        let p = draw_params(w, 5);
        assert!((0.0..=1.0).contains(&p.cloud_cover) && (0.0..=1.0).contains(&p.wetness));
        match w {
            Weather::Foggy => {
                let v = p.visibility_m.expect("fog has a visibility");
                assert!((50.0..=150.0).contains(&v), "{v}");
            }
            Weather::Night => assert!(p.sun_elevation_deg < -12.0),
            Weather::Sunset => assert!(p.sun_elevation_deg < 8.0),
            Weather::Storm => assert!(p.rain_mm_per_h > 0.0),
            _ => {}
        }
        assert_eq!(w, w.name().parse().unwrap());
    }
    assert!("drizzle"
        .parse::<Weather>()
        .unwrap_err()
        .contains("clear, cloudy"));
}
