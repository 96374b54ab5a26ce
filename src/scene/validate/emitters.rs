//! The `[sky]` and `[[light]]` checks: directions, powers and cone angles.

use crate::scene::desc::{LightDesc, SkyDesc};
use crate::scene::load::SceneError;
use crate::scene::ranges::V;

impl V<'_> {
    /// The `[sky]` table of each sky kind.
    pub(super) fn sky(&self, sky: &SkyDesc) -> Result<(), SceneError> {
        match sky {
            SkyDesc::Constant { le } => self.range("sky.le", le, 0.0, f64::MAX),
            SkyDesc::Gradient {
                zenith,
                horizon,
                ground,
            } => {
                self.range("sky.zenith", zenith, 0.0, f64::MAX)?;
                self.range("sky.horizon", horizon, 0.0, f64::MAX)?;
                self.range("sky.ground", ground, 0.0, f64::MAX)
            }
            SkyDesc::Physical {
                sun_elevation_deg,
                sun_azimuth_deg,
                turbidity,
                ground_albedo,
                cloud_cover,
                cloud_seed: _,
            } => {
                self.range("sky.sun_elevation_deg", &[*sun_elevation_deg], -90.0, 90.0)?;
                self.finite("sky.sun_azimuth_deg", &[*sun_azimuth_deg])?;
                self.range("sky.turbidity", &[*turbidity], 0.0, 20.0)?;
                self.range("sky.ground_albedo", &[*ground_albedo], 0.0, 1.0)?;
                self.range("sky.cloud_cover", &[*cloud_cover], 0.0, 1.0)
            }
            SkyDesc::Overcast {
                irradiance,
                ground_albedo,
            } => {
                self.range("sky.irradiance", irradiance, 0.0, f64::MAX)?;
                self.range("sky.ground_albedo", &[*ground_albedo], 0.0, 1.0)
            }
            SkyDesc::Night {
                moon_elevation_deg,
                moon_azimuth_deg,
                moon_phase_deg,
                sky_glow,
                turbidity,
                ..
            } => {
                self.range(
                    "sky.moon_elevation_deg",
                    &[*moon_elevation_deg],
                    -90.0,
                    90.0,
                )?;
                self.finite("sky.moon_azimuth_deg", &[*moon_azimuth_deg])?;
                self.range("sky.moon_phase_deg", &[*moon_phase_deg], 0.0, 180.0)?;
                self.range("sky.sky_glow", &[*sky_glow], 0.0, 1.0)?;
                self.range("sky.turbidity", &[*turbidity], 0.0, 20.0)
            }
        }
    }

    /// `[[light]]` number `i`.
    pub(super) fn light(&self, i: usize, light: &LightDesc) -> Result<(), SceneError> {
        let k = |f: &str| format!("light[{i}].{f}");
        match light {
            LightDesc::Sun {
                elevation_deg,
                azimuth_deg,
                irradiance,
                angular_diameter_deg,
            } => {
                self.range(&k("elevation_deg"), &[*elevation_deg], -90.0, 90.0)?;
                self.finite(&k("azimuth_deg"), &[*azimuth_deg])?;
                self.range(&k("irradiance"), irradiance, 0.0, f64::MAX)?;
                self.positive(&k("angular_diameter_deg"), &[*angular_diameter_deg])?;
                self.range(
                    &k("angular_diameter_deg"),
                    &[*angular_diameter_deg],
                    0.0,
                    90.0,
                )
            }
            LightDesc::Point {
                position,
                intensity,
            } => {
                self.coord(&k("position"), position)?;
                self.range(&k("intensity"), intensity, 0.0, f64::MAX)
            }
            LightDesc::Spot {
                position,
                direction,
                intensity,
                inner_deg,
                outer_deg,
            } => {
                self.coord(&k("position"), position)?;
                self.finite(&k("direction"), direction)?;
                if direction.iter().all(|&x| x == 0.0) {
                    return Err(self.err(k("direction"), "must not be the zero vector"));
                }
                self.range(&k("intensity"), intensity, 0.0, f64::MAX)?;
                self.positive(&k("outer_deg"), &[*outer_deg])?;
                self.range(&k("outer_deg"), &[*outer_deg], 0.0, 179.999)?;
                self.range(&k("inner_deg"), &[*inner_deg], 0.0, *outer_deg)
            }
        }
    }
}
