//! The recipe's steps: overrides, seeds, weather, noise, filters and the
//! rendered frame's camera file.

use super::*;
use crate::scene::parse_scene_str;
use glam::DVec3;

/// A grey box 5 m ahead under a white sky, seen at 16×9 with one 54 cm
/// baseline; no seed of its own.
fn boxed() -> LoadedScene {
    let text = r#"
[camera]
width = 16
height = 9
hfov_deg = 60.0
position = [0.0, 0.0, 1.5]
baselines_cm = [54.0]
[render]
spp = 2
max_depth = 3
[sky]
kind = "constant"
le = [1.0, 1.0, 1.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
[[object]]
kind = "box"
size = [1.0, 4.0, 3.0]
material = "grey"
transform = { translate = [5.0, 0.0, 1.5] }
"#;
    parse_scene_str(text, std::path::Path::new("boxed.toml")).unwrap()
}

fn recipe(spec: &FrameSpec) -> Result<FrameRecipe, RecipeError> {
    FrameRecipe::new(FrameSource::scene(boxed()), spec)
}

fn seeded(seed: u64) -> FrameSpec {
    FrameSpec {
        overrides: Overrides {
            seed: Some(seed),
            ..Overrides::default()
        },
        ..FrameSpec::default()
    }
}

#[test]
fn overrides_reach_the_description_and_the_settings() {
    let spec = FrameSpec {
        overrides: Overrides {
            spp: Some(3),
            max_depth: Some(4),
            width: Some(8),
            height: Some(6),
            baselines_cm: Some(vec![10.0, 30.0]),
            hfov_deg: Some(70.0),
            seed: Some(11),
        },
        frame: 7,
        ..FrameSpec::default()
    };
    let r = recipe(&spec).unwrap();
    let c = &r.loaded.desc.camera;
    assert_eq!((c.width, c.height, c.hfov_deg), (8, 6, 70.0));
    assert_eq!(c.baselines_cm, vec![10.0, 30.0]);
    let expected = RenderSettings {
        spp: 3,
        max_depth: 4,
        seed: 11,
        frame: 7,
        adaptive: false,
    };
    assert_eq!(r.settings, expected);
    assert_eq!(r.origin.seeds.samples, Some(11));
    assert_eq!(r.origin.seeds.weather, None);
    assert!(r.weather.is_none() && r.noise.is_none());
    // Without overrides the description's own values stay.
    let r = recipe(&seeded(1)).unwrap();
    assert_eq!((r.settings.spp, r.settings.max_depth), (2, 3));
    assert_eq!(r.loaded.desc.camera.width, 16);
}

#[test]
fn bad_overrides_are_refused_by_name() {
    for (name, o) in [
        (
            "width",
            Overrides {
                width: Some(0),
                ..Overrides::default()
            },
        ),
        (
            "height",
            Overrides {
                height: Some(0),
                ..Overrides::default()
            },
        ),
        (
            "max-depth",
            Overrides {
                max_depth: Some(0),
                ..Overrides::default()
            },
        ),
    ] {
        let spec = FrameSpec {
            overrides: o,
            ..FrameSpec::default()
        };
        match recipe(&spec) {
            Err(RecipeError::Zero(n)) => assert_eq!(n, name),
            other => panic!("{name}: {:?}", other.map(|r| r.settings)),
        }
    }
    let spec = FrameSpec {
        overrides: Overrides {
            hfov_deg: Some(180.0),
            ..Overrides::default()
        },
        ..FrameSpec::default()
    };
    let e = recipe(&spec).map(|r| r.settings).unwrap_err();
    assert!(matches!(e, RecipeError::Rig(_)), "{e:?}");
    let text = e.to_string();
    assert!(
        text.contains("boxed.toml") && text.contains("camera.hfov_deg"),
        "{text}"
    );
    assert!(text.contains("must be in (0, 180), got 180"), "{text}");
}

#[test]
fn weather_is_drawn_with_its_seed_else_the_sample_seed_and_recorded() {
    let with = |seed| FrameSpec {
        weather: Some(WeatherChoice {
            preset: Weather::Storm,
            seed,
        }),
        ..seeded(5)
    };
    let r = recipe(&with(None)).unwrap();
    assert_eq!(r.origin.seeds.weather, Some(5));
    assert_eq!(
        r.weather,
        Some(crate::weather::draw_params(Weather::Storm, 5))
    );
    // The storm's own sensor noise is the one applied.
    assert!(r.noise.is_some());
    assert_eq!(r.noise, r.weather.as_ref().unwrap().sensor_noise);
    let r = recipe(&with(Some(9))).unwrap();
    assert_eq!(r.origin.seeds.weather, Some(9));
    assert_eq!(r.origin.seeds.samples, Some(5));
    assert_eq!(
        r.weather,
        Some(crate::weather::draw_params(Weather::Storm, 9))
    );
    // The preset replaced the description's sky.
    assert_ne!(r.loaded.desc.sky, boxed().desc.sky);
}

#[test]
fn sensor_noise_iso_overrides_the_preset_and_is_recorded() {
    let with = |iso| FrameSpec {
        weather: Some(WeatherChoice {
            preset: Weather::Storm,
            seed: None,
        }),
        sensor_noise_iso: iso,
        ..seeded(5)
    };
    let off = recipe(&with(Some(0.0))).unwrap();
    assert_eq!(off.noise, None);
    assert_eq!(off.weather.unwrap().sensor_noise, None);
    let iso = recipe(&with(Some(1600.0))).unwrap();
    assert_eq!(iso.noise, Some(SensorNoiseDesc::at_iso(1600.0)));
    assert_eq!(iso.weather.unwrap().sensor_noise, iso.noise);
    let plain = FrameSpec {
        sensor_noise_iso: Some(400.0),
        ..seeded(5)
    };
    assert_eq!(
        recipe(&plain).unwrap().noise,
        Some(SensorNoiseDesc::at_iso(400.0))
    );
    let bad = recipe(&with(Some(-5.0))).map(|r| r.settings).unwrap_err();
    assert!(matches!(bad, RecipeError::SensorNoise(_)), "{bad:?}");
}

#[test]
fn no_filter_turns_the_image_filters_off() {
    let on = recipe(&seeded(1)).unwrap();
    assert!(on.loaded.desc.render.filter_indirect);
    let off = recipe(&FrameSpec {
        filter: false,
        ..seeded(1)
    })
    .unwrap();
    assert!(!off.loaded.desc.render.filter_indirect);
    let built = off.prepare().unwrap().built;
    assert!(!built.scene.filter_indirect && !built.scene.filter_inscatter);
}

#[test]
fn a_rendered_frame_carries_its_noise_seeds_and_settings() {
    let spec = |iso| FrameSpec {
        sensor_noise_iso: Some(iso),
        frame: 3,
        ..seeded(21)
    };
    let (quiet, noisy) = (recipe(&spec(0.0)).unwrap(), recipe(&spec(3200.0)).unwrap());
    let a = quiet.prepare().unwrap().render(&|_, _| {});
    let b = noisy.prepare().unwrap().render(&|_, _| {});
    // Noise touches the images only, never the ground truth.
    assert_eq!(a.out.left, b.out.left);
    assert_eq!(a.out.baselines, b.out.baselines);
    assert_eq!(a.out.images.len(), 2);
    assert_ne!(a.out.images[0].rgb, b.out.images[0].rgb);
    // The camera file records the recipe.
    assert_eq!((b.meta.seed, b.meta.frame, b.meta.spp), (21, 3, 2));
    assert_eq!(b.meta.seeds.samples, Some(21));
    assert!(b.meta.town.is_none());
    // The same recipe gives the same frame.
    let again = noisy.prepare().unwrap().render(&|_, _| {});
    assert_eq!(again.out.images[1].rgb, b.out.images[1].rgb);
}

#[test]
fn a_town_source_records_its_seeds_and_frame() {
    let town = crate::town::load_named_town("town01", None).unwrap();
    let s = FrameSource::town(&town, 42, (0, 3), CameraConfig::Roll05).unwrap();
    let seeds = s.origin.seeds;
    assert_eq!((seeds.town, seeds.traffic), (Some(42), Some(42)));
    assert_eq!((seeds.weather, seeds.samples), (None, None));
    let record = s.origin.town.clone().unwrap();
    assert_eq!(
        (record.name.as_str(), record.source.as_str()),
        ("town01", "built-in")
    );
    assert_eq!((record.frame, record.config.as_str()), (3, "roll05"));
    // The built-in town01 is the repository's scenes/town01.toml.
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/town01.toml");
    let text = std::fs::read(file).unwrap();
    assert_eq!(record.sha256, crate::output::sha256_bytes(&text));
    let again = FrameSource::town(&town, 42, (0, 3), CameraConfig::Roll05).unwrap();
    assert_eq!(s.loaded.desc.camera, again.loaded.desc.camera);
}

#[test]
fn a_built_scene_sits_around_its_origin_on_either_backend() {
    use crate::accel::{Accel, Ray};
    let origin = DVec3::new(1.0, 2.0, 0.5);
    for backend in [Backend::Bvh, Backend::default_backend()] {
        let b = BuiltScene::build(&boxed(), origin, backend).unwrap();
        assert_eq!(b.scene.origin_world, origin);
        // From the camera (0, 0, 1.5) along +x: the box's near face at x = 4.5.
        let from = (DVec3::new(0.0, 0.0, 1.5) - origin).as_vec3();
        let hit = b.accel.intersect(&Ray::new(from, glam::Vec3::X)).unwrap();
        assert!((hit.t - 4.5).abs() < 1e-4, "{backend}: t = {}", hit.t);
    }
}

#[test]
fn pedestrians_carry_umbrellas_in_rain_only() {
    use crate::scene::desc::ShapeDesc;
    let town = crate::town::load_named_town("town01", None).unwrap();
    let people = |w: Weather| {
        let spec = FrameSpec {
            weather: Some(WeatherChoice {
                preset: w,
                seed: Some(1),
            }),
            ..seeded(3)
        };
        let s = FrameSource::town(&town, 3, (0, 0), CameraConfig::Normal).unwrap();
        let r = FrameRecipe::new(s, &spec).unwrap();
        let names: Vec<String> = r
            .loaded
            .desc
            .objects
            .iter()
            .filter(|o| o.semantic.as_deref() == Some("pedestrian"))
            .filter_map(|o| match &o.shape {
                ShapeDesc::Instance { prefab, .. } => Some(prefab.clone()),
                _ => None,
            })
            .collect();
        let defined = r.loaded.desc.prefabs.iter().map(|p| p.name.clone());
        (names, defined.collect::<std::collections::BTreeSet<_>>())
    };
    let (dry, _) = people(Weather::Cloudy);
    let (wet, prefabs) = people(Weather::Storm);
    assert!(
        dry.len() >= 8,
        "town01 frame 0 has {} pedestrians",
        dry.len()
    );
    assert_eq!(dry.len(), wet.len());
    assert!(dry.iter().all(|n| !n.ends_with("_umbrella")));
    let under = wet.iter().filter(|n| n.ends_with("_umbrella")).count();
    assert!(
        under * 2 > wet.len() && under < wet.len(),
        "{under} of {} under umbrellas",
        wet.len()
    );
    // Each umbrella walker keeps its walk phase and has its prefab.
    for (d, w) in dry.iter().zip(&wet) {
        assert!(w == d || *w == format!("{d}_umbrella"), "{d} became {w}");
        assert!(prefabs.contains(w), "{w} is not defined");
    }
}

#[test]
fn a_town_frame_in_fog_takes_fewer_samples_only_when_none_are_given() {
    let town = crate::town::load_named_town("town01", None).unwrap();
    let spp = |w: Weather, spp: Option<u32>, filter: bool, reference: bool| {
        let spec = FrameSpec {
            overrides: Overrides {
                spp,
                ..seeded(3).overrides
            },
            weather: Some(WeatherChoice {
                preset: w,
                seed: Some(1),
            }),
            filter,
            reference,
            ..FrameSpec::default()
        };
        let s = FrameSource::town(&town, 3, (0, 0), CameraConfig::Normal).unwrap();
        let r = FrameRecipe::new(s, &spec).unwrap();
        assert_eq!(r.loaded.desc.render.spp, r.settings.spp);
        r.settings.spp
    };
    // The town's default, 16: three quarters of it in fog.
    assert_eq!(spp(Weather::Foggy, None, true, false), 12);
    for w in Weather::ALL.into_iter().filter(|&w| w != Weather::Foggy) {
        assert_eq!(spp(w, None, true, false), 16, "{w}");
    }
    // A given count, plain images and reference mode keep every sample.
    assert_eq!(spp(Weather::Foggy, Some(16), true, false), 16);
    assert_eq!(spp(Weather::Foggy, Some(7), true, false), 7);
    assert_eq!(spp(Weather::Foggy, None, false, false), 16);
    assert_eq!(spp(Weather::Foggy, None, true, true), 16);
}

#[test]
fn a_scene_files_own_sample_count_stays_in_fog() {
    let spec = FrameSpec {
        weather: Some(WeatherChoice {
            preset: Weather::Foggy,
            seed: Some(1),
        }),
        ..seeded(3)
    };
    assert_eq!(recipe(&spec).unwrap().settings.spp, 2);
}
