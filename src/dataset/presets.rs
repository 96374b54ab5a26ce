//! Built-in configurations: `demo` (a small real dataset in minutes on two
//! cores) and `stereocarla` (every axis at StereoCarla's scale, ~139k left
//! frames: computable and shardable, not meant for one machine).

use super::config::DatasetConfig;
use crate::denoise::Denoiser;
use crate::output::layouts::LayoutKind;

/// Names accepted by `--preset`.
pub const PRESETS: [&str; 2] = ["demo", "stereocarla"];

/// The preset called `name`, or an error listing the names.
pub fn preset(name: &str) -> Result<DatasetConfig, String> {
    match name {
        "demo" => Ok(demo()),
        "stereocarla" => Ok(stereocarla()),
        _ => Err(format!(
            "unknown preset '{name}' (one of {})",
            PRESETS.join(", ")
        )),
    }
}

/// One town, all six configurations, two weathers, two frames per sequence,
/// 320×180 at 4 spp: 24 frames, 144 images.
pub fn demo() -> DatasetConfig {
    DatasetConfig {
        seed: 2024,
        towns: vec!["town01".into()],
        configs: names(crate::town::CONFIGS.iter().map(|c| c.name())),
        weathers: vec!["clear".into(), "sunset".into()],
        baselines_cm: vec![10.0, 54.0, 100.0, 200.0, 300.0],
        sequences: 1,
        frames_per_sequence: 2,
        stride: 10,
        width: 320,
        height: 180,
        hfov_deg: 60.0,
        spp: Some(4),
        max_depth: 3,
        layouts: vec![LayoutKind::Native],
        hdr: false,
        filter: true,
        denoiser: Denoiser::default(),
    }
}

/// Eight towns × six configurations × seven weathers × 7 sequences × 59
/// frames = 138,768 left frames (StereoCarla: 693,435 samples / 5 baselines
/// ≈ 138,687), 1600×900, 64 spp.
pub fn stereocarla() -> DatasetConfig {
    DatasetConfig {
        seed: 2024,
        towns: names(
            [
                "town01", "town02", "town03", "town04", "town05", "town06", "town07", "town10",
            ]
            .into_iter(),
        ),
        configs: names(crate::town::CONFIGS.iter().map(|c| c.name())),
        weathers: names(crate::weather::Weather::ALL.iter().map(|w| w.name())),
        baselines_cm: vec![10.0, 54.0, 100.0, 200.0, 300.0],
        sequences: 7,
        frames_per_sequence: 59,
        stride: 10,
        width: 1600,
        height: 900,
        hfov_deg: 60.0,
        spp: Some(64),
        max_depth: 5,
        layouts: vec![LayoutKind::Native],
        hdr: false,
        filter: true,
        denoiser: Denoiser::default(),
    }
}

fn names<'a>(it: impl Iterator<Item = &'a str>) -> Vec<String> {
    it.map(str::to_string).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_validate_and_stereocarla_has_139k_left_frames() {
        demo().validate("demo").unwrap();
        let s = stereocarla();
        s.validate("stereocarla").unwrap();
        let frames = super::super::plan::plan(&s).len();
        assert_eq!(frames, 8 * 6 * 7 * 7 * 59);
        assert!((frames as f64 - 693_435.0 / 5.0).abs() < 200.0);
    }
}
