//! Closed-form sun and overcast levels as functions of the sun's elevation,
//! for the overcast presets (the clear presets use the physical atmosphere).
//!
//! Direct sun: Beer–Lambert through the Kasten–Young (1989) relative air mass
//! with per-channel optical depths (Rayleigh-dominated blue, aerosol-dominated
//! red), normalised so the zenith sun gives the towns' clear irradiance.
//! Overcast: the clear global horizontal irradiance reduced by Kasten &
//! Czeplak's (1980) cloud factor 1 − 0.75·N^3.4, rendered neutral grey.

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

/// Diffuse horizontal irradiance under a deck of `cloud_cover` (0–1) for the
/// sun at `elevation_deg`, W·m⁻² per channel; a storm deck passes a third.
pub fn overcast_irradiance(elevation_deg: f64, cloud_cover: f64, storm: bool) -> [f64; 3] {
    let sin_e = elevation_deg.to_radians().sin().max(0.0);
    let direct = sun_irradiance(elevation_deg);
    // Clear-sky diffuse ≈ 120 W·m⁻² at high sun, falling with the sun.
    let clear_y = (direct[1] * sin_e + 120.0 * sin_e.powf(0.6)).max(0.0);
    let cloud = 1.0 - 0.75 * cloud_cover.clamp(0.0, 1.0).powf(3.4);
    let y = clear_y * cloud * if storm { 0.33 } else { 1.0 };
    [0.98 * y, y, 1.04 * y]
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
    fn air_mass_is_kasten_young() {
        // Kasten & Young 1989: AM = 1 / (cos z + a (96.07995° − z)^−b), z the
        // zenith angle in degrees, a = 0.50572, b = 1.6364.
        let ky = |z_deg: f64| {
            1.0 / (z_deg.to_radians().cos() + 0.50572 * (96.07995 - z_deg).powf(-1.6364))
        };
        for z in [0.0, 30.0, 60.0, 80.0, 85.0, 90.0] {
            let m = air_mass(90.0 - z);
            assert!((m - ky(z)).abs() < 1e-9 * ky(z), "z {z}°: {m} vs {}", ky(z));
        }
        // Published values: ≈ 1 at the zenith, ≈ 2 at 60°, ≈ 37.9 at the horizon.
        assert!((air_mass(90.0) - 1.0).abs() < 1e-3);
        assert!((air_mass(30.0) - 1.994).abs() < 1e-3, "{}", air_mass(30.0));
        assert!((air_mass(0.0) - 37.92).abs() < 0.01, "{}", air_mass(0.0));
    }

    #[test]
    fn overcast_darkens_with_cover_and_storm() {
        let thin = overcast_irradiance(45.0, 0.6, false);
        let full = overcast_irradiance(45.0, 1.0, false);
        let storm = overcast_irradiance(45.0, 1.0, true);
        assert!(thin[1] > full[1] && full[1] > storm[1] && storm[1] > 0.0);
        // Kasten–Czeplak: full cover passes a quarter of the clear global.
        let clear = overcast_irradiance(45.0, 0.0, false);
        assert!((full[1] / clear[1] - 0.25).abs() < 1e-9);
        assert_eq!(overcast_irradiance(-5.0, 1.0, false), [0.0; 3]);
    }
}
