//! Light and sky descriptions: `[[light]]` (sun, point, spot) and `[sky]`.
//!
//! Degrees in files; azimuth counter-clockwise from world +x seen from above,
//! elevation up from the horizon (world z up). Radiometric units: irradiance
//! W·m⁻², intensity W·sr⁻¹, radiance W·m⁻²·sr⁻¹, per RGB channel.

use serde::{Deserialize, Serialize};

/// One explicit light, selected by `kind`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum LightDesc {
    /// The sun: a distant disk.
    Sun {
        /// Height above the horizon in degrees, in [−90, 90].
        elevation_deg: f64,
        /// Direction towards the sun in degrees, counter-clockwise from +x.
        azimuth_deg: f64,
        /// RGB irradiance on a surface facing the sun, W·m⁻², each ≥ 0.
        irradiance: [f64; 3],
        /// Apparent diameter in degrees, in (0, 90) (default 0.533, the sun's).
        #[serde(default = "default_sun_diameter")]
        angular_diameter_deg: f64,
    },
    /// An isotropic point light.
    Point {
        /// Position, world metres.
        position: [f64; 3],
        /// Radiant intensity, W·sr⁻¹ per channel, each ≥ 0.
        intensity: [f64; 3],
    },
    /// A spot light, full intensity inside `inner_deg`, none beyond `outer_deg`.
    Spot {
        /// Position, world metres.
        position: [f64; 3],
        /// Cone axis (any non-zero length), world.
        direction: [f64; 3],
        /// Radiant intensity on the axis, W·sr⁻¹ per channel, each ≥ 0.
        intensity: [f64; 3],
        /// Half-angle of full intensity in degrees, in [0, outer_deg].
        inner_deg: f64,
        /// Cut-off half-angle in degrees, in (0, 180).
        outer_deg: f64,
    },
}

/// The environment, selected by `kind`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SkyDesc {
    /// The same radiance in every direction.
    Constant {
        /// Radiance, W·m⁻²·sr⁻¹ per channel, each ≥ 0.
        le: [f64; 3],
    },
    /// Zenith-to-horizon gradient above the horizon, constant below.
    Gradient {
        /// Radiance straight up.
        zenith: [f64; 3],
        /// Radiance at the horizon.
        horizon: [f64; 3],
        /// Radiance of every downward direction.
        ground: [f64; 3],
    },
}

fn default_sun_diameter() -> f64 {
    0.533
}
