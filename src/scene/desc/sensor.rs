//! `SensorNoiseDesc`: the camera sensor's noise model as scene/weather data
//! (ISO, full well, read noise, PRNU; EMVA 1288 terms), recorded in the
//! frame's camera file. Absent means a noiseless sensor (the default).
//! Also `SensorNoise`, the model's parameters as the film applies them
//! (`film::noise` draws the noise).
//!
//! Units: electrons for charges, ISO for sensitivity; see `film::noise`.

use serde::{Deserialize, Serialize};

/// Parameters of the sensor model (EMVA 1288 terms, in electrons).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorNoise {
    /// Sensitivity, ISO (> 0); higher means fewer electrons per exposed unit.
    pub iso: f32,
    /// Full-well capacity in electrons (> 0): the charge of exposed value 1.0 at `BASE_ISO`.
    pub full_well_e: f32,
    /// Read noise σ in electrons (≥ 0), Gaussian, signal-independent.
    pub read_noise_e: f32,
    /// PRNU: relative σ of the per-photosite gain (≥ 0, e.g. 0.005).
    pub prnu: f32,
}

/// Camera sensor noise, e.g. `sensor_noise = { iso = 800 }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorNoiseDesc {
    /// Sensitivity, ISO, in [25, 204800]; exposed value 1.0 collects
    /// full_well_e · 100 / iso electrons.
    pub iso: f64,
    /// Full-well capacity in electrons, > 0 (default 20000).
    #[serde(default = "default_full_well")]
    pub full_well_e: f64,
    /// Read noise σ in electrons, ≥ 0 (default 3).
    #[serde(default = "default_read_noise")]
    pub read_noise_e: f64,
    /// Photo-response non-uniformity: relative σ of each photosite's gain,
    /// in [0, 0.1] (default 0.005).
    #[serde(default = "default_prnu")]
    pub prnu: f64,
}

fn default_full_well() -> f64 {
    20_000.0
}
fn default_read_noise() -> f64 {
    3.0
}
fn default_prnu() -> f64 {
    0.005
}

impl SensorNoiseDesc {
    /// Default sensor (20000 e⁻ full well, 3 e⁻ read noise, 0.5% PRNU) at `iso`.
    pub fn at_iso(iso: f64) -> Self {
        SensorNoiseDesc {
            iso,
            full_well_e: default_full_well(),
            read_noise_e: default_read_noise(),
            prnu: default_prnu(),
        }
    }

    /// Checks the ranges documented on the fields; the error names the key.
    pub fn check(&self) -> Result<(), String> {
        let bad = |key: &str, v: f64, range: &str| {
            Err(format!("sensor_noise.{key} = {v}: expected {range}"))
        };
        if !(25.0..=204_800.0).contains(&self.iso) {
            return bad("iso", self.iso, "a value in [25, 204800]");
        }
        if !(self.full_well_e.is_finite() && self.full_well_e > 0.0) {
            return bad("full_well_e", self.full_well_e, "a finite value > 0");
        }
        if !(self.read_noise_e.is_finite() && self.read_noise_e >= 0.0) {
            return bad("read_noise_e", self.read_noise_e, "a finite value ≥ 0");
        }
        if !(0.0..=0.1).contains(&self.prnu) {
            return bad("prnu", self.prnu, "a value in [0, 0.1]");
        }
        Ok(())
    }

    /// The film's noise model of this description.
    pub fn model(&self) -> SensorNoise {
        SensorNoise {
            iso: self.iso as f32,
            full_well_e: self.full_well_e as f32,
            read_noise_e: self.read_noise_e as f32,
            prnu: self.prnu as f32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_alone_fills_in_defaults_and_round_trips() {
        #[derive(Deserialize, Serialize)]
        struct W {
            sensor_noise: SensorNoiseDesc,
        }
        let w: W = toml::from_str("sensor_noise = { iso = 800 }").unwrap();
        assert_eq!(w.sensor_noise, SensorNoiseDesc::at_iso(800.0));
        let back: W = toml::from_str(&toml::to_string(&w).unwrap()).unwrap();
        assert_eq!(back.sensor_noise, w.sensor_noise);
        assert!(w.sensor_noise.check().is_ok());
    }

    #[test]
    fn out_of_range_values_are_rejected_by_name() {
        let mut d = SensorNoiseDesc::at_iso(10.0);
        assert!(d.check().unwrap_err().contains("iso"));
        d.iso = 400.0;
        d.read_noise_e = -1.0;
        assert!(d.check().unwrap_err().contains("read_noise_e"));
        d.read_noise_e = 3.0;
        d.prnu = f64::NAN;
        assert!(d.check().unwrap_err().contains("prnu"));
        assert!(toml::from_str::<SensorNoiseDesc>("iso = 100\nbogus = 1").is_err());
    }
}
