//! Weather presets: the seven weathers of DATASET.md as named parameter sets
//! with seeded variation, applied to a scene description before it is built.
//!
//! A preset draws its parameters once per (seed) — a dataset passes one seed
//! per sequence, so a video does not change weather between frames — and
//! records them in the frame's camera file. The ground truth never depends on
//! the weather: only lights, sky, media and surface wetness (shading) change,
//! never geometry; puddles only add the mask's mirror bit.

mod sun;

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::scene::desc::{
    LightDesc, MediumDesc, MediumKindDesc, RainDesc, SceneDesc, SkyDesc, WetnessDesc,
};
use crate::town::rng::Rng;

/// Stream tag of the weather draws (apart from the town generator's tags).
const WEATHER_TAG: u64 = 0x5745_4154_4845_5200;

pub use sun::{overcast_irradiance, sun_irradiance};

/// One of the seven weathers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Weather {
    /// Clear sky, sun high or mid.
    Clear,
    /// Broken to full cloud cover, sun diffused.
    Cloudy,
    /// Visibility 50–150 m.
    Foggy,
    /// Wet roads, puddles, haze.
    Humid,
    /// Moon, sky glow and artificial lights.
    Night,
    /// Rain, wet roads, dark overcast, haze.
    Storm,
    /// Low sun, long shadows, warm sky.
    Sunset,
}

impl Weather {
    /// Every weather, in DATASET.md order.
    pub const ALL: [Weather; 7] = [
        Weather::Clear,
        Weather::Cloudy,
        Weather::Foggy,
        Weather::Humid,
        Weather::Night,
        Weather::Storm,
        Weather::Sunset,
    ];

    /// The preset's name as used on the command line and in paths.
    pub fn name(self) -> &'static str {
        match self {
            Weather::Clear => "clear",
            Weather::Cloudy => "cloudy",
            Weather::Foggy => "foggy",
            Weather::Humid => "humid",
            Weather::Night => "night",
            Weather::Storm => "storm",
            Weather::Sunset => "sunset",
        }
    }
}

impl fmt::Display for Weather {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Weather {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Weather::ALL
            .into_iter()
            .find(|w| w.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Weather::ALL.iter().map(|w| w.name()).collect();
                format!(
                    "unknown weather '{s}' (expected one of {})",
                    names.join(", ")
                )
            })
    }
}

/// The drawn parameters of one preset, recorded in every frame's camera file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WeatherParams {
    /// Preset name.
    pub preset: Weather,
    /// Sun elevation above the horizon, degrees (negative below).
    pub sun_elevation_deg: f64,
    /// Direction towards the sun, degrees counter-clockwise from world +x.
    pub sun_azimuth_deg: f64,
    /// Fraction of the sky covered by cloud, 0–1.
    pub cloud_cover: f64,
    /// Meteorological visibility in metres (Koschmieder), none for clear air.
    pub visibility_m: Option<f64>,
    /// Surface wetness, 0 (dry) – 1 (standing water).
    pub wetness: f64,
    /// Rain rate, mm/h (0 without rain).
    pub rain_mm_per_h: f64,
}

/// Draws the parameters of `weather` from `seed` (the same seed gives the same
/// look; a dataset passes one seed per sequence).
pub fn draw_params(weather: Weather, seed: u64) -> WeatherParams {
    let mut rng = Rng::new(&[seed, WEATHER_TAG, weather as u64]);
    let azimuth = rng.range(0.0, 360.0);
    let (elevation, cover, visibility, wetness, rain) = match weather {
        Weather::Clear => (rng.range(25.0, 70.0), rng.range(0.0, 0.1), None, 0.0, 0.0),
        Weather::Cloudy => (rng.range(20.0, 65.0), rng.range(0.6, 1.0), None, 0.0, 0.0),
        Weather::Foggy => (
            rng.range(10.0, 45.0),
            rng.range(0.3, 0.8),
            Some(rng.range(50.0, 150.0)),
            rng.range(0.1, 0.3),
            0.0,
        ),
        Weather::Humid => (
            rng.range(15.0, 55.0),
            rng.range(0.3, 0.7),
            Some(rng.range(1500.0, 4000.0)),
            rng.range(0.5, 0.9),
            0.0,
        ),
        Weather::Night => (rng.range(-40.0, -18.0), rng.range(0.0, 0.4), None, 0.0, 0.0),
        Weather::Storm => (
            rng.range(15.0, 50.0),
            1.0,
            Some(rng.range(800.0, 2500.0)),
            rng.range(0.8, 1.0),
            rng.range(4.0, 16.0),
        ),
        Weather::Sunset => (rng.range(-2.0, 6.0), rng.range(0.0, 0.3), None, 0.0, 0.0),
    };
    WeatherParams {
        preset: weather,
        sun_elevation_deg: elevation,
        sun_azimuth_deg: azimuth,
        cloud_cover: cover,
        visibility_m: visibility,
        wetness,
        rain_mm_per_h: rain,
    }
}

/// Replaces the sun(s) and sky of `desc` with the weather's: the physical
/// sky (which brings the sun, red and dim at sunset, none once set, and a
/// world-fixed cloud deck of the drawn cover) for clear, sunset, humid and
/// foggy; the CIE overcast sky, sun diffused, for cloudy and storm; the night
/// sky with a full moon opposite the sun for night. Point, spot and emissive
/// lights of the scene stay (street lights, vehicle lights). Humid and storm
/// also set `[wetness]` (wet roads, puddles); every other preset leaves the
/// scene dry.
pub fn apply(desc: &mut SceneDesc, p: &WeatherParams) {
    desc.lights.retain(|l| !matches!(l, LightDesc::Sun { .. }));
    let seed = pattern_seed(p);
    desc.sky = Some(match p.preset {
        Weather::Clear | Weather::Sunset | Weather::Humid | Weather::Foggy => SkyDesc::Physical {
            sun_elevation_deg: p.sun_elevation_deg,
            sun_azimuth_deg: p.sun_azimuth_deg,
            turbidity: turbidity(p.preset),
            ground_albedo: 0.1,
            cloud_cover: p.cloud_cover,
            cloud_seed: seed,
        },
        Weather::Cloudy | Weather::Storm => SkyDesc::Overcast {
            irradiance: overcast_irradiance(
                p.sun_elevation_deg,
                p.cloud_cover,
                p.preset == Weather::Storm,
            ),
            ground_albedo: 0.1,
        },
        Weather::Night => SkyDesc::Night {
            moon_elevation_deg: -p.sun_elevation_deg,
            moon_azimuth_deg: (p.sun_azimuth_deg + 180.0) % 360.0,
            moon_phase_deg: 0.0,
            sky_glow: 2e-5,
            stars: true,
            star_seed: seed,
            turbidity: 1.0,
        },
    });
    desc.medium = p.visibility_m.map(|v| haze(p.preset, v));
    desc.rain = (p.rain_mm_per_h > 0.0).then_some(RainDesc {
        rate_mm_per_h: p.rain_mm_per_h,
        shutter_s: 0.01,
        fall_speed_m_per_s: 9.0,
        drop_diameter_mm: 2.5,
        density_scale: 1.0,
        extent_m: 30.0,
    });
    desc.wetness = wetness(p);
}

/// Wet roads for humid and storm, none otherwise: puddle cover grows from 0
/// at wetness 0.5 to 25% when soaked (storm ≈ 15–25%, humid ≤ 20%).
fn wetness(p: &WeatherParams) -> Option<WetnessDesc> {
    matches!(p.preset, Weather::Humid | Weather::Storm).then(|| WetnessDesc {
        wetness: p.wetness,
        puddle_cover: (0.5 * (p.wetness - 0.5)).clamp(0.0, 0.25),
        puddle_scale_m: 4.0,
        seed: pattern_seed(p) as u64,
    })
}

/// Height fog of ground visibility `visibility_m`: shallow and dense for
/// fog (scale height 30 m), deep and thin for haze (200 m), both above the
/// ground plane z = 0 where towns and scenes put their roads.
fn haze(w: Weather, visibility_m: f64) -> MediumDesc {
    MediumDesc {
        kind: MediumKindDesc::HeightFog,
        visibility_m: Some(visibility_m),
        sigma_t: None,
        albedo: [0.99; 3],
        g: if w == Weather::Foggy { 0.85 } else { 0.7 },
        base_height_m: 0.0,
        height_scale_m: Some(if w == Weather::Foggy { 30.0 } else { 200.0 }),
        z_min_m: None,
        z_max_m: None,
    }
}

/// Aerosol density multiplier of the physical sky per preset.
fn turbidity(w: Weather) -> f64 {
    match w {
        Weather::Sunset => 1.5,
        Weather::Humid => 3.0,
        Weather::Foggy => 4.0,
        _ => 1.0,
    }
}

/// A seed for cloud and star patterns, fixed by the drawn parameters (so by
/// the sequence's seed).
fn pattern_seed(p: &WeatherParams) -> u32 {
    let h = p.sun_azimuth_deg.to_bits() ^ p.sun_elevation_deg.to_bits().rotate_left(17);
    (h ^ (h >> 32)) as u32
}
