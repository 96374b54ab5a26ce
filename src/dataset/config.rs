//! The dataset configuration (`parallax dataset CONFIG.toml`): which towns,
//! camera configurations, weathers and baselines, how many sequences and
//! frames, at what resolution and quality, in which layouts, from which seed.
//!
//! TOML with `deny_unknown_fields`; every error names the file and the key
//! (`weathers[1]`, `spp`). The resolved configuration is stored whole in
//! `dataset.json`, so a dataset's job list can always be recomputed from it.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::denoise::Denoiser;
use crate::output::layouts::LayoutKind;
use crate::town::CameraConfig;
use crate::weather::Weather;

/// A dataset configuration. Field docs are the config-file manual.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DatasetConfig {
    /// Master seed: every town, weather draw and sample stream derives from it.
    pub seed: u64,
    /// Town names (files `SCENES/<name>.toml`), e.g. `["town01", "town03"]`.
    pub towns: Vec<String>,
    /// Camera configurations: normal, roll05, roll15, roll30, pitch00, pitch30
    /// (default: all six).
    #[serde(default = "all_configs")]
    pub configs: Vec<String>,
    /// Weathers: clear, cloudy, foggy, humid, night, storm, sunset (default: clear).
    #[serde(default = "default_weathers")]
    pub weathers: Vec<String>,
    /// Baselines in centimetres, each > 0 (default 10, 54, 100, 200, 300).
    #[serde(default = "default_baselines")]
    pub baselines_cm: Vec<f64>,
    /// Sequences (drives) per (town, configuration, weather), ≥ 1 (default 1).
    #[serde(default = "one")]
    pub sequences: u32,
    /// Frames per sequence, ≥ 1.
    pub frames_per_sequence: u32,
    /// Town frames (at the town's fps) between consecutive dataset frames, ≥ 1
    /// (default 10: one second of driving at a town's default 10 fps, so
    /// consecutive frames differ; 1 gives near-duplicate frames).
    #[serde(default = "default_stride")]
    pub stride: u32,
    /// Image width in pixels (default 1600).
    #[serde(default = "default_width")]
    pub width: u32,
    /// Image height in pixels (default 900).
    #[serde(default = "default_height")]
    pub height: u32,
    /// Horizontal field of view, degrees, in (0, 180) (default 60).
    #[serde(default = "default_hfov")]
    pub hfov_deg: f64,
    /// Samples per pixel per view, ≥ 1. Absent: 64, and 48 in fog where
    /// the image filters are on (the fog light's filter makes up for them);
    /// a count given is used in every weather.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spp: Option<u32>,
    /// Maximum path depth, ≥ 1 (default 5).
    #[serde(default = "default_max_depth")]
    pub max_depth: u32,
    /// Layouts to write: native, stereocarla, kitti, sceneflow (default: native).
    #[serde(default = "default_layouts")]
    pub layouts: Vec<LayoutKind>,
    /// Also write linear HDR radiance EXRs in the native layout (default false).
    #[serde(default)]
    pub hdr: bool,
    /// Filter sky and indirect light (and fog light) in image space, guided
    /// by the exact depth (`[render] filter_indirect`, `[medium]
    /// filter_inscatter`; default true). false writes the plain path-traced
    /// images. Ground truth is never filtered. Always written to
    /// `dataset.json`, so the record says which images a dataset holds.
    #[serde(default = "crate::scene::desc::default_true")]
    pub filter: bool,
    /// The denoiser of the surfaces where `filter` is on: "parallax"
    /// (default), "oidn" (Intel Open Image Denoise, found at run time:
    /// `pip install pyoidn`) or "blend" (the mean of the two); fog light
    /// keeps parallax's filter. Always
    /// written to `dataset.json`; a record without it (older versions)
    /// reads as "parallax", so such a dataset resumes as it is.
    #[serde(default)]
    pub denoiser: Denoiser,
}

fn all_configs() -> Vec<String> {
    crate::town::CONFIGS
        .iter()
        .map(|c| c.name().to_string())
        .collect()
}
fn default_weathers() -> Vec<String> {
    vec!["clear".into()]
}
fn default_baselines() -> Vec<f64> {
    vec![10.0, 54.0, 100.0, 200.0, 300.0]
}
fn one() -> u32 {
    1
}
fn default_stride() -> u32 {
    10
}
fn default_width() -> u32 {
    1600
}
fn default_height() -> u32 {
    900
}
fn default_hfov() -> f64 {
    60.0
}
fn default_max_depth() -> u32 {
    5
}
fn default_layouts() -> Vec<LayoutKind> {
    vec![LayoutKind::Native]
}

/// A configuration error naming the file and the key.
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigError {
    /// The configuration file (or `--preset NAME`).
    pub file: String,
    /// Key path such as `weathers[1]` (empty for syntax errors without one).
    pub key: String,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for ConfigError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}: key '{}': {}", self.file, self.key, self.message)
        }
    }
}

impl std::error::Error for ConfigError {}

/// Reads and validates a configuration file.
pub fn load_config(path: &Path) -> Result<DatasetConfig, ConfigError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| ConfigError {
        file: file.clone(),
        key: String::new(),
        message: format!("cannot read the configuration: {e}"),
    })?;
    parse_config(&text, &file)
}

/// Parses and validates configuration text; `file` names it in errors.
pub fn parse_config(text: &str, file: &str) -> Result<DatasetConfig, ConfigError> {
    let de = toml::Deserializer::new(text);
    let config: DatasetConfig = serde_path_to_error::deserialize(de).map_err(|e| {
        let mut key = e.path().to_string();
        let inner = e.into_inner();
        if key == "." {
            key.clear();
        }
        let (msg, pos) = crate::scene::load::toml_error(text, &inner);
        // Unknown keys and missing fields: name the key itself.
        for prefix in ["unknown field `", "missing field `"] {
            if let Some(field) = msg.strip_prefix(prefix).and_then(|r| r.split('`').next()) {
                key = field.to_string();
            }
        }
        // Syntax errors have no key: give their place instead.
        let message = match pos {
            Some((line, col)) if key.is_empty() => format!("line {line}, column {col}: {msg}"),
            _ => msg,
        };
        ConfigError {
            file: file.to_string(),
            key,
            message,
        }
    })?;
    config.validate(file)?;
    Ok(config)
}

/// A failed check: the key path and what is wrong.
type Check = Result<(), (String, String)>;

/// Fails with `message` at `key`.
fn fail(key: impl Into<String>, message: impl Into<String>) -> Check {
    Err((key.into(), message.into()))
}

/// Samples per pixel per view where the configuration gives none.
pub const DEFAULT_SPP: u32 = 64;

impl DatasetConfig {
    /// Samples per pixel per view: the configuration's, else [`DEFAULT_SPP`].
    pub fn spp(&self) -> u32 {
        self.spp.unwrap_or(DEFAULT_SPP)
    }

    /// Samples per pixel of a frame of `weather` rendered at `spp` (the
    /// configuration's [`DatasetConfig::spp`], or a calibration's): `spp`
    /// where the configuration gives a count or the filters are off, else
    /// the weather's share of it ([`Weather::default_spp`]).
    pub fn frame_spp(&self, weather: Weather, spp: u32) -> u32 {
        if self.spp.is_some() || !self.filter {
            spp
        } else {
            weather.default_spp(spp)
        }
    }

    /// Checks every value; the error names `file` and the key.
    pub fn validate(&self, file: &str) -> Result<(), ConfigError> {
        self.check_lists_nonempty()
            .and_then(|_| self.check_names())
            .and_then(|_| self.check_baselines())
            .and_then(|_| self.check_counts())
            .and_then(|_| self.check_hfov())
            .and_then(|_| self.check_no_duplicates())
            .map_err(|(key, message)| ConfigError {
                file: file.to_string(),
                key,
                message,
            })
    }

    /// Every list names at least one value.
    fn check_lists_nonempty(&self) -> Check {
        for (key, n) in [
            ("towns", self.towns.len()),
            ("configs", self.configs.len()),
            ("weathers", self.weathers.len()),
            ("baselines_cm", self.baselines_cm.len()),
            ("layouts", self.layouts.len()),
        ] {
            if n == 0 {
                return fail(key, "must list at least one value");
            }
        }
        Ok(())
    }

    /// Town names are file-name safe; configurations and weathers exist.
    fn check_names(&self) -> Check {
        for (i, t) in self.towns.iter().enumerate() {
            let ok = !t.is_empty()
                && t.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            if !ok {
                return fail(
                    format!("towns[{i}]"),
                    format!("'{t}' is not a town name (letters, digits, '_', '-')"),
                );
            }
        }
        for (i, c) in self.configs.iter().enumerate() {
            c.parse::<CameraConfig>()
                .map_err(|m| (format!("configs[{i}]"), m))?;
        }
        for (i, w) in self.weathers.iter().enumerate() {
            w.parse::<Weather>()
                .map_err(|m| (format!("weathers[{i}]"), m))?;
        }
        Ok(())
    }

    /// Baselines are positive and each gets a folder of its own.
    fn check_baselines(&self) -> Check {
        for (i, b) in self.baselines_cm.iter().enumerate() {
            if !(b.is_finite() && *b > 0.0) {
                return fail(
                    format!("baselines_cm[{i}]"),
                    format!("{b} must be a positive number of centimetres"),
                );
            }
        }
        crate::output::check_baseline_dirs(&self.baselines_cm)
            .map_err(|e| (format!("baselines_cm[{}]", e.index), e.to_string()))
    }

    /// Counts and sizes are at least 1 and within their limits.
    fn check_counts(&self) -> Check {
        for (key, v) in [
            ("sequences", self.sequences),
            ("frames_per_sequence", self.frames_per_sequence),
            ("stride", self.stride),
            ("width", self.width),
            ("height", self.height),
            ("spp", self.spp()),
            ("max_depth", self.max_depth),
        ] {
            if v == 0 {
                return fail(key, "must be at least 1");
            }
        }
        if self.spp() > crate::sampler::MAX_SPP {
            return fail(
                "spp",
                format!("must be at most {}", crate::sampler::MAX_SPP),
            );
        }
        if self.frames_per_sequence > 999_999 {
            return fail(
                "frames_per_sequence",
                "must be at most 999999 (six-digit frame names)",
            );
        }
        Ok(())
    }

    /// The field of view lies in (0, 180) degrees.
    fn check_hfov(&self) -> Check {
        if !(self.hfov_deg > 0.0 && self.hfov_deg < 180.0) {
            return fail(
                "hfov_deg",
                format!("{} must lie in (0, 180)", self.hfov_deg),
            );
        }
        Ok(())
    }

    /// No list names a value twice.
    fn check_no_duplicates(&self) -> Check {
        fn dup<T: PartialEq + std::fmt::Display>(key: &str, v: &[T]) -> Check {
            for (i, a) in v.iter().enumerate() {
                if v[..i].contains(a) {
                    return fail(format!("{key}[{i}]"), format!("'{a}' is listed twice"));
                }
            }
            Ok(())
        }
        dup("towns", &self.towns)?;
        dup("configs", &self.configs)?;
        dup("weathers", &self.weathers)?;
        dup("layouts", &self.layouts)
    }

    /// The camera configurations, parsed (valid after `validate`).
    pub fn camera_configs(&self) -> Vec<CameraConfig> {
        self.configs.iter().filter_map(|c| c.parse().ok()).collect()
    }

    /// The weathers, parsed (valid after `validate`).
    pub fn weather_list(&self) -> Vec<Weather> {
        self.weathers
            .iter()
            .filter_map(|w| w.parse().ok())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINIMAL: &str = "seed = 1\ntowns = [\"town01\"]\nframes_per_sequence = 2\n";

    #[test]
    fn defaults_fill_the_full_axes() {
        let c = parse_config(MINIMAL, "c.toml").unwrap();
        assert_eq!(c.configs.len(), 6);
        assert_eq!(c.baselines_cm, vec![10.0, 54.0, 100.0, 200.0, 300.0]);
        assert_eq!(
            (c.width, c.height, c.sequences, c.stride),
            (1600, 900, 1, 10)
        );
        assert_eq!(c.layouts, vec![LayoutKind::Native]);
    }

    #[test]
    fn fog_takes_fewer_samples_only_where_the_count_is_the_default() {
        let c = parse_config(MINIMAL, "c.toml").unwrap();
        assert_eq!((c.spp, c.spp()), (None, DEFAULT_SPP));
        assert_eq!(c.frame_spp(Weather::Foggy, 64), 48);
        assert_eq!(c.frame_spp(Weather::Night, 64), 64);
        // A calibration's count is shared the same way.
        assert_eq!(c.frame_spp(Weather::Foggy, 8), 6);
        let given = parse_config(&format!("{MINIMAL}spp = 64\n"), "c.toml").unwrap();
        assert_eq!(given.frame_spp(Weather::Foggy, 64), 64);
        let plain = parse_config(&format!("{MINIMAL}filter = false\n"), "c.toml").unwrap();
        assert_eq!(plain.frame_spp(Weather::Foggy, 64), 64);
        // dataset.json keeps an absent count absent, so a resumed dataset
        // renders its fog as before; a given one stays given.
        for config in [c, given] {
            let json = serde_json::to_string(&config).unwrap();
            assert_eq!(json.contains("\"spp\""), config.spp.is_some(), "{json}");
            let back: DatasetConfig = serde_json::from_str(&json).unwrap();
            assert_eq!(back, config);
        }
    }

    #[test]
    fn errors_name_file_and_key() {
        let e = parse_config(
            &format!("{MINIMAL}weathers = [\"clear\", \"snow\"]\n"),
            "c.toml",
        )
        .unwrap_err();
        assert_eq!((e.file.as_str(), e.key.as_str()), ("c.toml", "weathers[1]"));
        let e = parse_config(&format!("{MINIMAL}sppp = 3\n"), "c.toml").unwrap_err();
        assert_eq!(e.key, "sppp");
        let e = parse_config(&format!("{MINIMAL}spp = \"many\"\n"), "c.toml").unwrap_err();
        assert_eq!(e.key, "spp");
        let e = parse_config("seed = 1\ntowns = [\"town01\"]\n", "c.toml").unwrap_err();
        assert_eq!(e.key, "frames_per_sequence");
        let e = parse_config(&format!("{MINIMAL}stride = 0\n"), "c.toml").unwrap_err();
        assert_eq!(e.key, "stride");
    }

    #[test]
    fn every_layout_name_is_accepted() {
        let text =
            format!("{MINIMAL}layouts = [\"native\", \"stereocarla\", \"kitti\", \"sceneflow\"]\n");
        assert_eq!(parse_config(&text, "c.toml").unwrap().layouts.len(), 4);
        let e = parse_config(&format!("{MINIMAL}layouts = [\"coco\"]\n"), "c.toml").unwrap_err();
        assert_eq!(e.key, "layouts[0]");
        assert_eq!(
            e.to_string(),
            "c.toml: key 'layouts[0]': unknown layout 'coco' (one of native, stereocarla, kitti, sceneflow)"
        );
        let twice = format!("{MINIMAL}layouts = [\"kitti\", \"native\", \"kitti\"]\n");
        let e = parse_config(&twice, "c.toml").unwrap_err();
        assert_eq!(
            e.to_string(),
            "c.toml: key 'layouts[2]': 'kitti' is listed twice"
        );
    }
}
