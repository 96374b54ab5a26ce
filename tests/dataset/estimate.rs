//! The dry run's cost estimate: the arithmetic from given per-class costs
//! and the plan's (town, weather) mix, the calibration's size, and
//! `dataset --preset demo --dry-run` through the real binary.

use crate::common::dataset;

use dataset::*;
use parallax::dataset::calibrate::calibration_quality;
use parallax::dataset::estimate::{calibration_job, class_mix, estimate, ClassCost};
use parallax::dataset::{parse_config, presets, Shard};
use parallax::weather::Weather;

/// 2 towns × 1 configuration × 2 weathers × 3 frames, 100×50 px, 8 spp.
fn small_plan() -> parallax::dataset::DatasetConfig {
    parse_config(
        "seed = 1\ntowns = [\"town01\", \"town02\"]\nconfigs = [\"normal\"]\n\
         weathers = [\"clear\", \"foggy\"]\nframes_per_sequence = 3\n\
         width = 100\nheight = 50\nspp = 8\n",
        "t.toml",
    )
    .unwrap()
}

fn cost(town: &str, weather: Weather, fixed: f64, per_sample: f64) -> ClassCost {
    ClassCost {
        town: town.into(),
        weather,
        calibrated_on: None,
        fixed,
        per_pixel: 1e-4,
        per_sample,
        write_per_pixel: 2e-5,
        write_wait: 0.4,
    }
}

#[test]
fn estimate_weights_each_class_by_the_plans_mix() {
    let c = small_plan();
    // 5000 px: per pixel 0.5 s, writing 0.1 s + 0.4 s waiting; clear paths
    // 8 × 5000 × 1e-4 = 4 s, foggy six times that (24 s); town02 builds 2 s longer.
    let costs = [
        cost("town02", Weather::Foggy, 3.0, 6e-4),
        cost("town01", Weather::Clear, 1.0, 1e-4),
        cost("town01", Weather::Foggy, 1.0, 6e-4),
        cost("town02", Weather::Clear, 3.0, 1e-4),
    ];
    // On 2 threads: fixed + writing + (pixels + paths) / 2.
    let want = [
        1.0 + 0.5 + 4.5 / 2.0,  // town01 clear: 3.75
        1.0 + 0.5 + 24.5 / 2.0, // town01 foggy: 13.75
        3.0 + 0.5 + 4.5 / 2.0,  // town02 clear: 5.75
        3.0 + 0.5 + 24.5 / 2.0, // town02 foggy: 15.75
    ];
    let e = estimate(&c, &costs, Shard::ALL, 2).unwrap();
    assert_eq!((e.frames, e.frames_in_shard, e.cores), (12, 12, 2));
    let got: Vec<(&str, Weather, u64)> = e
        .classes
        .iter()
        .map(|k| (k.cost.town.as_str(), k.cost.weather, k.frames))
        .collect();
    assert_eq!(
        got,
        [
            ("town01", Weather::Clear, 3),
            ("town01", Weather::Foggy, 3),
            ("town02", Weather::Clear, 3),
            ("town02", Weather::Foggy, 3)
        ]
    );
    for (k, w) in e.classes.iter().zip(want) {
        assert!((k.seconds_per_frame - w).abs() < 1e-9, "{k:?} != {w}");
    }
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9 * b.abs().max(1.0);
    assert!(close(e.seconds_per_frame, 9.75), "{}", e.seconds_per_frame);
    assert!(close(e.core_hours, 12.0 * 9.75 * 2.0 / 3600.0));
    // CPU: fixed + (1e-4 + spp · per_sample + 2e-5) · 5000, mean of the four.
    let cpu = (1.0 + 4.6 + 1.0 + 24.6 + 3.0 + 4.6 + 3.0 + 24.6) / 4.0;
    assert!(
        close(e.cpu_seconds_per_frame, cpu),
        "{}",
        e.cpu_seconds_per_frame
    );

    // Shard 1/2 takes jobs 0, 2, 4, …: two frames of each clear class and
    // one of each foggy class, and its hours follow that mix.
    let e = estimate(&c, &costs, Shard::parse("1/2").unwrap(), 2).unwrap();
    let mine: Vec<u64> = e.classes.iter().map(|k| k.frames_in_shard).collect();
    assert_eq!((mine, e.frames_in_shard), (vec![2, 1, 2, 1], 6));
    let shard = (2.0 * want[0] + want[1] + 2.0 * want[2] + want[3]) * 2.0 / 3600.0;
    assert!(close(e.shard_core_hours, shard), "{}", e.shard_core_hours);

    // More threads shorten only the parallel part.
    let e4 = estimate(&c, &costs, Shard::ALL, 4).unwrap();
    assert!((e4.classes[0].seconds_per_frame - (1.5 + 4.5 / 4.0)).abs() < 1e-9);

    // A class of the plan without a measurement is an error naming it.
    let err = estimate(&c, &costs[..3], Shard::ALL, 2).unwrap_err();
    assert!(err.contains("town02 clear"), "{err}");
}

#[test]
fn calibration_covers_every_class_and_configuration_at_a_bounded_size() {
    let demo = presets::demo();
    let mix = class_mix(&demo, Shard::ALL);
    assert_eq!(mix.len(), 2);
    let q = calibration_quality(&demo, mix.len());
    assert_eq!((q.width, q.height, q.spp), (160, 90, 2));

    // stereocarla: 8 towns × 7 weathers, each class 6 configurations × 7
    // sequences × 59 frames; 56 calibration frames shrink to 64×36.
    let sc = presets::stereocarla();
    let mix = class_mix(&sc, Shard::ALL);
    assert_eq!(mix.len(), 56);
    assert!(mix
        .iter()
        .all(|(_, all, mine)| *all == 6 * 7 * 59 && mine == all));
    let q = calibration_quality(&sc, mix.len());
    assert_eq!((q.width, q.height, q.spp), (64, 36, 2));
    // The configurations are taken in turn: all six are sampled.
    let configs: std::collections::BTreeSet<&str> = mix
        .iter()
        .enumerate()
        .map(|(k, ((town, w), _, _))| calibration_job(&sc, k, town, *w).config.name())
        .collect();
    assert_eq!(configs.len(), 6);
    // A frame from the middle of the first sequence.
    let j = calibration_job(&sc, 0, "town01", Weather::Clear);
    assert_eq!((j.sequence, j.frame), (0, 29));

    // Never larger than the configuration, never more spp than it asks for.
    let mut tiny = small_plan();
    (tiny.width, tiny.height, tiny.spp) = (48, 27, Some(1));
    let q = calibration_quality(&tiny, 1);
    assert_eq!((q.width, q.height, q.spp), (48, 27, 1));
}

#[test]
fn demo_dry_run_prints_the_plan_and_an_estimate_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let s = scenes();
    let o = parallax(&[
        "dataset",
        "--preset",
        "demo",
        "--dry-run",
        "-o",
        out.to_str().unwrap(),
        "--scenes",
        &s,
        "--threads",
        "2",
    ])
    .output()
    .unwrap();
    ok(&o);
    let t = text(&o);
    assert!(t.contains("= 24 frames"), "{t}");
    for class in [
        "town01 clear (normal frame 1)",
        "town01 sunset (roll05 frame 1)",
    ] {
        assert!(t.contains(class), "no calibration line for {class}:\n{t}");
    }
    let line = t
        .lines()
        .find(|l| l.starts_with("estimate: "))
        .unwrap_or_else(|| panic!("no estimate line:\n{t}"));
    let seconds: f64 = line["estimate: ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(seconds.is_finite() && seconds > 0.0, "{line}");
    assert!(line.contains("24 frames of shard 1/1"), "{line}");
    let left = std::fs::read_dir(&out).unwrap().count();
    assert_eq!(left, 0, "the dry run wrote into -o:\n{t}");
}
