//! The `[wetness]` section: wet roads and puddles (weathers humid and storm).
//!
//! Wetness is shading, never geometry: up-facing road, lane-marking, sidewalk
//! and terrain surfaces get a darkened albedo under a water film, and a
//! world-space (x, y) noise mask turns part of the road and sidewalk into
//! smooth water. Depth and disparity never change; puddles set the mask's
//! mirror bit. The shading lives in `material::wet`.

use serde::{Deserialize, Serialize};

use super::medium::KeyError;

/// Scene-level wetness.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WetnessDesc {
    /// How wet exposed surfaces are, in [0, 1]: 0 dry, 1 soaked (darkest
    /// albedo, smoothest water film).
    pub wetness: f64,
    /// Fraction of road and sidewalk under standing water, in [0, 1]
    /// (default 0: no puddles).
    #[serde(default)]
    pub puddle_cover: f64,
    /// Typical puddle size in metres, in (0, 100] (default 4).
    #[serde(default = "default_puddle_scale")]
    pub puddle_scale_m: f64,
    /// Seed of the puddle pattern (default 0).
    #[serde(default)]
    pub seed: u64,
}

fn default_puddle_scale() -> f64 {
    4.0
}

impl WetnessDesc {
    /// Checks ranges; errors name the key under `wetness.`.
    pub(crate) fn check(&self) -> Result<(), KeyError> {
        let fields = [
            ("wetness.wetness", self.wetness, 0.0, 1.0),
            ("wetness.puddle_cover", self.puddle_cover, 0.0, 1.0),
            ("wetness.puddle_scale_m", self.puddle_scale_m, 1e-3, 100.0),
        ];
        for (key, v, lo, hi) in fields {
            if !(v.is_finite() && v >= lo && v <= hi) {
                return Err((key.into(), format!("must be in [{lo}, {hi}], got {v}")));
            }
        }
        Ok(())
    }
}
