//! Sun irradiance and a gradient sky as functions of the sun's elevation: the
//! simple model the presets use until the physical atmosphere drives them.
//!
//! Direct sun: Beer–Lambert through the Kasten–Young (1989) relative air mass
//! with per-channel optical depths (Rayleigh-dominated blue, aerosol-dominated
//! red), normalised so the zenith sun gives the towns' clear irradiance.
//! Sky: the towns' clear gradient scaled by a log-linear twilight curve (about
//! two decades per 6° below the horizon) and warmed near the horizon at low sun.

use super::gradient;
use crate::scene::desc::SkyDesc;

/// Irradiance of the zenith sun on a surface facing it, W·m⁻² per channel.
const ZENITH_IRRADIANCE: [f64; 3] = [980.0, 930.0, 850.0];
/// Vertical optical depth per channel (R, G, B).
const OPTICAL_DEPTH: [f64; 3] = [0.10, 0.17, 0.32];

/// Kasten–Young relative air mass for a sun `elevation_deg` above the horizon.
pub fn air_mass(elevation_deg: f64) -> f64 {
    let h = elevation_deg.max(-0.5);
    1.0 / (h.to_radians().sin().max(0.0) + 0.50572 * (h + 6.07995).powf(-1.6364))
}

/// Direct sun irradiance for a sun at `elevation_deg` (zero once the disk has set).
pub fn sun_irradiance(elevation_deg: f64) -> [f64; 3] {
    if elevation_deg <= -0.27 {
        return [0.0; 3];
    }
    let m = air_mass(elevation_deg);
    std::array::from_fn(|c| ZENITH_IRRADIANCE[c] * (-OPTICAL_DEPTH[c] * (m - 1.0)).exp())
}

/// Brightness of the clear sky relative to a high sun, continuous in elevation.
fn sky_scale(elevation_deg: f64) -> f64 {
    if elevation_deg >= 0.0 {
        // Rises from 0.15 at the horizon to 1 at 40° and above.
        0.15 + 0.85 * (elevation_deg / 40.0).min(1.0).powf(0.7)
    } else {
        // Two decades per 6° of depression, floored by night sky glow.
        (0.15 * 10f64.powf(elevation_deg / 3.0)).max(2e-6)
    }
}

/// A gradient sky for the sun at `elevation_deg` under `cloud_cover` (0–1):
/// deep blue at high sun, warm horizon at low sun, grey and flatter under cloud.
pub fn twilight_sky(elevation_deg: f64, cloud_cover: f64) -> SkyDesc {
    let s = sky_scale(elevation_deg);
    // Warmth of the horizon: 1 at the horizon, 0 above 15°.
    let warm = (1.0 - (elevation_deg.abs() / 15.0)).clamp(0.0, 1.0);
    let clear_zenith = [9.0, 16.0, 38.0];
    let clear_horizon = [30.0 + 25.0 * warm, 33.0 - 5.0 * warm, 37.0 - 20.0 * warm];
    let grey = 34.0;
    let c = cloud_cover.clamp(0.0, 1.0);
    let mix = |a: f64| (a * (1.0 - c) + grey * c) * s;
    let zenith = clear_zenith.map(mix);
    let horizon = clear_horizon.map(mix);
    let ground = [6.0, 5.6, 5.2].map(|g| g * s);
    gradient(zenith, horizon, ground)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zenith_sun_matches_the_towns_clear_irradiance() {
        let e = sun_irradiance(90.0);
        for c in 0..3 {
            assert!((e[c] - ZENITH_IRRADIANCE[c]).abs() < 1e-3 * ZENITH_IRRADIANCE[c]);
        }
    }

    #[test]
    fn sun_dims_and_reddens_as_it_sinks() {
        let mut prev = sun_irradiance(90.0);
        for h in [60.0, 30.0, 10.0, 3.0, 0.0] {
            let e = sun_irradiance(h);
            assert!(
                e.iter().zip(prev).all(|(a, b)| *a < b),
                "not dimmer at {h}°"
            );
            prev = e;
        }
        let low = sun_irradiance(2.0);
        assert!(low[0] / low[2] > 3.0, "low sun not red: {low:?}");
        assert_eq!(sun_irradiance(-1.0), [0.0; 3]);
    }

    #[test]
    fn twilight_sky_falls_monotonically_and_continuously() {
        let zenith = |h: f64| match twilight_sky(h, 0.0) {
            SkyDesc::Gradient { zenith, .. } => zenith[1],
            _ => unreachable!(),
        };
        let mut prev = zenith(60.0);
        let mut h = 60.0;
        while h > -18.0 {
            h -= 0.25;
            let z = zenith(h);
            assert!(z <= prev, "sky brighter at {h}°");
            assert!(z > 0.45 * prev, "jump at {h}°: {prev} → {z}");
            prev = z;
        }
    }
}
