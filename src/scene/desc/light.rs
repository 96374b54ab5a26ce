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
    /// Physically based clear sky (Rayleigh, Mie, ozone atmosphere), valid
    /// from noon to astronomical twilight. Brings its own sun: a disk of the
    /// true size whose irradiance is the atmosphere's (red at sunset, none once
    /// set), so the scene must not also have a `[[light]]` sun.
    Physical {
        /// Sun height above the horizon in degrees, in [−90, 90].
        sun_elevation_deg: f64,
        /// Direction towards the sun in degrees, counter-clockwise from +x.
        sun_azimuth_deg: f64,
        /// Aerosol (Mie) density multiplier, in [0, 20]: 1 clear, 3–5 hazy.
        #[serde(default = "one")]
        turbidity: f64,
        /// Albedo of the ground seen below the horizon, in [0, 1].
        #[serde(default = "default_ground_albedo")]
        ground_albedo: f64,
        /// Fraction of the sky under a world-fixed cloud deck at 1.5 km, in
        /// [0, 1]: its shadows dim the sun, the same in every view.
        #[serde(default)]
        cloud_cover: f64,
        /// Seed of the cloud pattern.
        #[serde(default)]
        cloud_seed: u32,
    },
    /// CIE standard overcast sky, L(θ) ∝ (1 + 2 cos θ)/3; no sun disk.
    Overcast {
        /// Diffuse horizontal irradiance under the deck, W·m⁻² per channel, ≥ 0.
        irradiance: [f64; 3],
        /// Albedo of the ground seen below the horizon, in [0, 1].
        #[serde(default = "default_ground_albedo")]
        ground_albedo: f64,
    },
    /// Night: the moonlit atmosphere, airglow, artificial sky glow and stars,
    /// with the moon as a disk light (about 2.5e-6 of the sun at full moon).
    Night {
        /// Moon height above the horizon in degrees, in [−90, 90].
        moon_elevation_deg: f64,
        /// Direction towards the moon in degrees, counter-clockwise from +x.
        moon_azimuth_deg: f64,
        /// Phase angle in degrees, in [0, 180]: 0 full, 90 half, 180 new.
        #[serde(default)]
        moon_phase_deg: f64,
        /// Artificial sky glow at the horizon, W·m⁻²·sr⁻¹, ≥ 0 (0 wilderness,
        /// 1e-4 suburban; 1 W·m⁻²·sr⁻¹ ≈ 100 cd·m⁻²).
        #[serde(default = "default_sky_glow")]
        sky_glow: f64,
        /// Whether stars are drawn.
        #[serde(default = "super::default_true")]
        stars: bool,
        /// Seed of the star field.
        #[serde(default)]
        star_seed: u32,
        /// Aerosol (Mie) density multiplier, in [0, 20].
        #[serde(default = "one")]
        turbidity: f64,
    },
}

fn one() -> f64 {
    1.0
}

fn default_ground_albedo() -> f64 {
    0.1
}

fn default_sky_glow() -> f64 {
    2e-5
}

fn default_sun_diameter() -> f64 {
    0.533
}
