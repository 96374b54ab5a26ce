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

use crate::sampler::rng::Rng;
use crate::scene::desc::{
    LightDesc, MediumDesc, MediumKindDesc, RainDesc, SceneDesc, SensorNoiseDesc, SkyDesc,
    WetnessDesc,
};

/// Opacity factor of the storm's streaks: their physical coverage (≤ 4 %)
/// leaves them invisible at a 10 ms exposure; ×8 makes them read as the
/// streaks an eye or a video camera shows in heavy rain.
const STORM_STREAK_GAIN: f64 = 8.0;

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

/// Share of a default sample count that a filtered frame in fog takes: the
/// fog light's filter makes up for the rest (measured in
/// docs/reference.md, session 36).
const FOG_SAMPLE_SHARE: (u32, u32) = (3, 4);

impl Weather {
    /// Samples per pixel a filtered frame of this weather takes where `spp`
    /// is a default, not a count the user gave (callers decide which):
    /// fewer in fog, `spp` elsewhere; at least 1.
    pub fn default_spp(self, spp: u32) -> u32 {
        match self {
            Weather::Foggy => (spp * FOG_SAMPLE_SHARE.0)
                .div_ceil(FOG_SAMPLE_SHARE.1)
                .max(1),
            _ => spp,
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
    /// The moon of the night preset (none by day): where it stands and its phase.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moon: Option<MoonParams>,
    /// Camera sensor noise of the preset (none: a noiseless sensor); the
    /// dark presets (night, storm) shoot at a high ISO.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensor_noise: Option<SensorNoiseDesc>,
}

/// The moon's place and phase, drawn independently of the sun: the phase
/// angle follows from the sun–moon elongation ψ as α = 180° − ψ (the moon
/// is so far that Earth's and the moon's views of the sun are parallel).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MoonParams {
    /// Moon elevation above the horizon, degrees.
    pub elevation_deg: f64,
    /// Direction towards the moon, degrees counter-clockwise from world +x.
    pub azimuth_deg: f64,
    /// Phase angle sun–moon–observer, degrees: 0 full, 90 half, 180 new.
    pub phase_deg: f64,
    /// Unit vector towards the moon, world frame (z up).
    pub direction_world: [f64; 3],
}

impl MoonParams {
    /// The moon at (`elevation_deg`, `azimuth_deg`) with the phase the sun at
    /// (`sun_elevation_deg`, `sun_azimuth_deg`) gives it.
    pub fn new(
        elevation_deg: f64,
        azimuth_deg: f64,
        sun_elevation_deg: f64,
        sun_azimuth_deg: f64,
    ) -> Self {
        let moon = unit_dir(elevation_deg, azimuth_deg);
        let sun = unit_dir(sun_elevation_deg, sun_azimuth_deg);
        let elongation_deg = moon.dot(sun).clamp(-1.0, 1.0).acos().to_degrees();
        MoonParams {
            elevation_deg,
            azimuth_deg,
            phase_deg: 180.0 - elongation_deg,
            direction_world: moon.to_array(),
        }
    }
}

/// Unit world vector at elevation/azimuth in degrees (azimuth CCW from +x, z up).
fn unit_dir(elevation_deg: f64, azimuth_deg: f64) -> glam::DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    glam::DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}

/// Cloud cover from which the cloudy preset is a closed overcast deck (CIE
/// overcast sky, no sun disk); below it the deck is broken and drawn.
pub const OVERCAST_COVER: f64 = 0.85;

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
            rng.range(10.0, 40.0),
        ),
        Weather::Sunset => (rng.range(-2.0, 6.0), rng.range(0.0, 0.3), None, 0.0, 0.0),
    };
    // Drawn after the shared draws, so adding them left the other parameters
    // of every preset unchanged.
    let moon = (weather == Weather::Night).then(|| {
        let (moon_elevation, moon_azimuth) = (rng.range(12.0, 65.0), rng.range(0.0, 360.0));
        MoonParams::new(moon_elevation, moon_azimuth, elevation, azimuth)
    });
    let sensor_noise = match weather {
        Weather::Night => Some(SensorNoiseDesc::at_iso(rng.range(800.0, 3200.0).round())),
        Weather::Storm => Some(SensorNoiseDesc::at_iso(rng.range(200.0, 800.0).round())),
        _ => None,
    };
    WeatherParams {
        preset: weather,
        sun_elevation_deg: elevation,
        sun_azimuth_deg: azimuth,
        cloud_cover: cover,
        visibility_m: visibility,
        wetness,
        rain_mm_per_h: rain,
        moon,
        sensor_noise,
    }
}

/// Replaces the sun(s) and sky of `desc` with the weather's: the physical
/// sky (which brings the sun, red and dim at sunset, none once set, and a
/// world-fixed cloud deck of the drawn cover) for clear, sunset, humid and
/// foggy, and for cloudy with broken cover (below `OVERCAST_COVER`); the CIE
/// overcast sky, sun diffused, for closed cloudy and storm; the night
/// sky with the drawn moon (phase from its angle to the sun) for night. Point, spot and emissive
/// lights of the scene stay (street lights, vehicle lights). Humid and storm
/// also set `[wetness]` (wet roads, puddles); every other preset leaves the
/// scene dry.
pub fn apply(desc: &mut SceneDesc, p: &WeatherParams) {
    desc.lights.retain(|l| !matches!(l, LightDesc::Sun { .. }));
    let seed = pattern_seed(p);
    // Parameters drawn before the moon existed (or by hand) get the full
    // moon opposite the sun they always had.
    let moon = p.moon.unwrap_or_else(|| {
        MoonParams::new(
            -p.sun_elevation_deg,
            (p.sun_azimuth_deg + 180.0) % 360.0,
            p.sun_elevation_deg,
            p.sun_azimuth_deg,
        )
    });
    // Broken cloud (cloudy below `OVERCAST_COVER`) is the physical sky with
    // its deck: clouds drawn in the sky, sun through the gaps.
    let broken = p.preset == Weather::Cloudy && p.cloud_cover < OVERCAST_COVER;
    // Cloudy (closed cover) and storm fall through to the overcast sky.
    desc.sky = Some(match p.preset {
        Weather::Night => SkyDesc::Night {
            moon_elevation_deg: moon.elevation_deg,
            moon_azimuth_deg: moon.azimuth_deg,
            moon_phase_deg: moon.phase_deg,
            sky_glow: 2e-5,
            stars: true,
            star_seed: seed,
            turbidity: 1.0,
        },
        Weather::Clear | Weather::Sunset | Weather::Humid | Weather::Foggy | Weather::Cloudy
            if p.preset != Weather::Cloudy || broken =>
        {
            SkyDesc::Physical {
                sun_elevation_deg: p.sun_elevation_deg,
                sun_azimuth_deg: p.sun_azimuth_deg,
                turbidity: turbidity(p.preset),
                ground_albedo: 0.1,
                cloud_cover: p.cloud_cover,
                cloud_seed: seed,
            }
        }
        _ => SkyDesc::Overcast {
            irradiance: overcast_irradiance(
                p.sun_elevation_deg,
                p.cloud_cover,
                p.preset == Weather::Storm,
            ),
            ground_albedo: 0.1,
        },
    });
    desc.medium = p.visibility_m.map(|v| haze(p.preset, v));
    // Heavy rain seen at a 10 ms exposure: every drop from 1.5 mm up (the
    // ones a camera resolves as streaks), each falling at its own speed,
    // within 15 m (farther streaks cover < 0.1 % of a pixel: the haze).
    desc.rain = (p.rain_mm_per_h > 0.0).then_some(RainDesc {
        rate_mm_per_h: p.rain_mm_per_h,
        shutter_s: 0.01,
        fall_speed_m_per_s: None,
        drop_diameter_mm: 1.5,
        density_scale: 1.0,
        extent_m: 15.0,
        streak_gain: STORM_STREAK_GAIN,
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
        filter_inscatter: true,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fog_takes_three_quarters_of_a_default_sample_count_rounded_up() {
        for (spp, fog) in [(16, 12), (64, 48), (4, 3), (2, 2), (1, 1), (10, 8)] {
            assert_eq!(Weather::Foggy.default_spp(spp), fog, "{spp}");
        }
        for w in Weather::ALL.into_iter().filter(|&w| w != Weather::Foggy) {
            assert_eq!(w.default_spp(16), 16, "{w}");
        }
        // The largest count a render accepts does not overflow.
        let max = crate::sampler::MAX_SPP;
        assert_eq!(Weather::Foggy.default_spp(max), (max * 3).div_ceil(4));
    }

    #[test]
    fn moon_phase_follows_the_sun_moon_angle() {
        // Opposite the sun: full; a quarter turn away: half; next to it: new.
        let full = MoonParams::new(30.0, 200.0, -30.0, 20.0);
        assert!(full.phase_deg.abs() < 1e-9, "{full:?}");
        let half = MoonParams::new(0.0, 90.0, 0.0, 0.0);
        assert!((half.phase_deg - 90.0).abs() < 1e-9);
        let new = MoonParams::new(10.0, 45.0, 10.0, 45.0);
        assert!((new.phase_deg - 180.0).abs() < 1e-6);
        let d = glam::DVec3::from(half.direction_world);
        assert!((d - glam::DVec3::Y).length() < 1e-12);
    }

    #[test]
    fn night_moon_is_drawn_above_the_horizon_and_not_always_full() {
        let mut phases = Vec::new();
        for seed in 0..40 {
            let p = draw_params(Weather::Night, seed);
            let m = p.moon.expect("night has a moon");
            assert!((12.0..=65.0).contains(&m.elevation_deg));
            // Phase = 180° − elongation, the elongation from the spherical
            // law of cosines on (elevation, azimuth) of sun and moon.
            let (em, es) = (
                m.elevation_deg.to_radians(),
                p.sun_elevation_deg.to_radians(),
            );
            let daz = (m.azimuth_deg - p.sun_azimuth_deg).to_radians();
            let cos_psi = em.sin() * es.sin() + em.cos() * es.cos() * daz.cos();
            let phase = 180.0 - cos_psi.clamp(-1.0, 1.0).acos().to_degrees();
            assert!(
                (m.phase_deg - phase).abs() < 1e-9,
                "{} vs {phase}",
                m.phase_deg
            );
            // The stored direction: azimuth counter-clockwise from +x, z up.
            let am = m.azimuth_deg.to_radians();
            let d = m.direction_world;
            assert!((d[0] - em.cos() * am.cos()).abs() < 1e-12, "{d:?}");
            assert!((d[1] - em.cos() * am.sin()).abs() < 1e-12, "{d:?}");
            assert!((d[2] - em.sin()).abs() < 1e-12, "{d:?}");
            phases.push(m.phase_deg);
            let mut desc: SceneDesc =
                toml::from_str("[camera]\nposition = [0.0, 0.0, 1.5]\n").unwrap();
            apply(&mut desc, &p);
            let Some(SkyDesc::Night {
                moon_elevation_deg,
                moon_azimuth_deg,
                moon_phase_deg,
                ..
            }) = desc.sky
            else {
                panic!("night sky expected");
            };
            assert_eq!(
                (moon_elevation_deg, moon_azimuth_deg, moon_phase_deg),
                (m.elevation_deg, m.azimuth_deg, m.phase_deg)
            );
        }
        let (lo, hi) = phases
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(lo < 40.0 && hi > 90.0, "phases {lo}..{hi}");
        assert!(Weather::ALL
            .iter()
            .filter(|&&w| w != Weather::Night)
            .all(|&w| draw_params(w, 3).moon.is_none()));
    }
}
