//! Weather descriptions: the optional `[medium]` (fog, haze) and `[rain]`
//! sections. Heights are world z in metres; extinction in 1/m; either a
//! visibility (Koschmieder σ_t = 3.912/V) or `sigma_t` sets the density.

use serde::{Deserialize, Serialize};

/// How the medium's extinction varies with height.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MediumKindDesc {
    /// Constant extinction.
    Homogeneous,
    /// σ_t(z) = σ_t(base)·exp(−(z − base_height_m)/height_scale_m).
    HeightFog,
}

/// `[medium]`: a participating medium filling the world (both views see it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MediumDesc {
    /// `homogeneous` or `height_fog`.
    pub kind: MediumKindDesc,
    /// Meteorological visibility in metres (> 0) at `base_height_m`; exclusive with `sigma_t`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub visibility_m: Option<f64>,
    /// Extinction in 1/m (≥ 0) at `base_height_m`; exclusive with `visibility_m`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_t: Option<f64>,
    /// Single-scattering albedo per RGB channel, each in [0, 1] (default 0.99, fog).
    #[serde(default = "default_albedo")]
    pub albedo: [f64; 3],
    /// Henyey–Greenstein asymmetry g in [−0.99, 0.99] (default 0.85, fog).
    #[serde(default = "default_g")]
    pub g: f64,
    /// Height (world z, m) where the density equals `visibility_m`/`sigma_t` (default 0).
    #[serde(default)]
    pub base_height_m: f64,
    /// Scale height H in metres, > 0; `height_fog` only (default 20).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_scale_m: Option<f64>,
    /// Lower bound of the medium, world z metres (absent: unbounded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z_min_m: Option<f64>,
    /// Upper bound of the medium, world z metres (absent: unbounded; required
    /// for `homogeneous`, whose unbounded column would block sun and sky).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z_max_m: Option<f64>,
    /// Whether fog light is filtered in image space, guided by the ground
    /// truth's depth: the in-scattered light on each camera ray (the
    /// radiance whose first event is a medium scatter) and the fog light
    /// falling on the first surface when it is diffuse (its albedo kept
    /// per pixel); the surface behind each camera ray's fog is then traced
    /// at weight Tr rather than by a collide-or-pass choice (default true:
    /// far less grain at equal time; false gives the plain path-traced
    /// image bit for bit). Ground truth is never filtered.
    #[serde(
        default = "super::default_true",
        skip_serializing_if = "super::is_true"
    )]
    pub filter_inscatter: bool,
}

/// `[rain]`: falling drops seen as motion-blurred streaks, placed in world
/// space from the render seed and frame (identical in every view).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RainDesc {
    /// Rain rate in mm/h, in (0, 300] (light 1, heavy 10, storm 50).
    pub rate_mm_per_h: f64,
    /// Exposure time in seconds, in (0, 1] (default 0.01); streak length =
    /// fall speed × shutter.
    #[serde(default = "default_shutter")]
    pub shutter_s: f64,
    /// One terminal fall speed for every drop in m/s, in (0, 20] (absent:
    /// each drop's from its diameter, Atlas et al. 1973: 4 m/s at 1 mm,
    /// 9.2 at 5 mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fall_speed_m_per_s: Option<f64>,
    /// Smallest drawn drop diameter in millimetres, in (0, 8] (default 2.5);
    /// diameters from it to 6 mm follow Marshall–Palmer's e^{−ΛD}.
    #[serde(default = "default_drop_diameter")]
    pub drop_diameter_mm: f64,
    /// Only drops at least `drop_diameter_mm` are drawn: their number density
    /// (1/m³) follows Marshall–Palmer; this scales it, in (0, 100] (default 1).
    #[serde(default = "default_density_scale")]
    pub density_scale: f64,
    /// Radius in metres of the rain volume around the rig, in (0, 500] (default 30).
    #[serde(default = "default_extent")]
    pub extent_m: f64,
    /// Factor on every streak's opacity, in (0, 100] (default 1: the
    /// physical coverage, under 4 % even for a drop beside the lens, which
    /// a 10 ms exposure leaves nearly invisible). The storm preset raises it
    /// so streaks read as they do to an eye or on video.
    #[serde(default = "default_streak_gain")]
    pub streak_gain: f64,
}

fn default_albedo() -> [f64; 3] {
    [0.99; 3]
}
fn default_g() -> f64 {
    0.85
}
fn default_shutter() -> f64 {
    0.01
}
fn default_streak_gain() -> f64 {
    1.0
}
fn default_drop_diameter() -> f64 {
    2.5
}
fn default_density_scale() -> f64 {
    1.0
}
fn default_extent() -> f64 {
    30.0
}

/// A validation failure: (key path, message).
pub(crate) type KeyError = (String, String);

fn in_range(key: &str, v: f64, lo: f64, hi: f64, lo_open: bool) -> Result<(), KeyError> {
    let ok = v.is_finite() && (if lo_open { v > lo } else { v >= lo }) && v <= hi;
    if ok {
        Ok(())
    } else {
        use super::num;
        let allowed = match (hi == f64::MAX, lo_open) {
            (true, true) => format!("> {}", num(lo)),
            (true, false) => format!("≥ {}", num(lo)),
            (false, true) => format!("in ({}, {}]", num(lo), num(hi)),
            (false, false) => format!("in [{}, {}]", num(lo), num(hi)),
        };
        Err((key.into(), format!("must be {allowed}, got {}", num(v))))
    }
}

impl MediumDesc {
    /// Checks ranges and exclusive keys; errors name the key under `medium.`.
    pub(crate) fn check(&self) -> Result<(), KeyError> {
        match (self.visibility_m, self.sigma_t) {
            (Some(_), Some(_)) => {
                return Err((
                    "medium.sigma_t".into(),
                    "give either visibility_m or sigma_t, not both".into(),
                ))
            }
            (None, None) => {
                return Err((
                    "medium.visibility_m".into(),
                    "missing: give visibility_m (metres) or sigma_t (1/m)".into(),
                ))
            }
            (Some(v), None) => in_range("medium.visibility_m", v, 0.0, f64::MAX, true)?,
            (None, Some(s)) => in_range("medium.sigma_t", s, 0.0, 1e3, false)?,
        }
        for &a in &self.albedo {
            in_range("medium.albedo", a, 0.0, 1.0, false)?;
        }
        in_range("medium.g", self.g, -0.99, 0.99, false)?;
        in_range("medium.base_height_m", self.base_height_m, -1e5, 1e5, false)?;
        match (self.kind, self.height_scale_m) {
            (MediumKindDesc::Homogeneous, Some(_)) => {
                return Err((
                    "medium.height_scale_m".into(),
                    "only a height_fog medium has a scale height".into(),
                ))
            }
            (MediumKindDesc::HeightFog, Some(h)) => {
                in_range("medium.height_scale_m", h, 0.0, 1e5, true)?
            }
            _ => {}
        }
        if self.kind == MediumKindDesc::Homogeneous && self.z_max_m.is_none() {
            // Unbounded haze has infinite optical depth toward the sun and sky.
            return Err((
                "medium.z_max_m".into(),
                "a homogeneous medium needs a top (e.g. 1000): without one no sun or sky light gets in".into(),
            ));
        }
        for (key, z) in [
            ("medium.z_min_m", self.z_min_m),
            ("medium.z_max_m", self.z_max_m),
        ] {
            if let Some(z) = z {
                in_range(key, z, -1e5, 1e5, false)?;
            }
        }
        if let (Some(lo), Some(hi)) = (self.z_min_m, self.z_max_m) {
            if lo >= hi {
                return Err((
                    "medium.z_max_m".into(),
                    format!("must be above z_min_m = {lo}, got {hi}"),
                ));
            }
        }
        Ok(())
    }

    /// Extinction at `base_height_m`, 1/m.
    pub fn sigma_t_base(&self) -> f64 {
        match (self.visibility_m, self.sigma_t) {
            (Some(v), _) => shaders_cpu::medium::sigma_t_from_visibility(v),
            (None, Some(s)) => s,
            (None, None) => 0.0,
        }
    }

    /// Scale height H in metres (the default 20 when absent).
    pub fn height_scale(&self) -> f64 {
        self.height_scale_m.unwrap_or(20.0)
    }
}

impl RainDesc {
    /// Checks ranges; errors name the key under `rain.`.
    pub(crate) fn check(&self) -> Result<(), KeyError> {
        in_range("rain.rate_mm_per_h", self.rate_mm_per_h, 0.0, 300.0, true)?;
        in_range("rain.shutter_s", self.shutter_s, 0.0, 1.0, true)?;
        if let Some(v) = self.fall_speed_m_per_s {
            in_range("rain.fall_speed_m_per_s", v, 0.0, 20.0, true)?;
        }
        in_range(
            "rain.drop_diameter_mm",
            self.drop_diameter_mm,
            0.0,
            8.0,
            true,
        )?;
        in_range("rain.density_scale", self.density_scale, 0.0, 100.0, true)?;
        in_range("rain.extent_m", self.extent_m, 0.0, 500.0, true)?;
        in_range("rain.streak_gain", self.streak_gain, 0.0, 100.0, true)
    }
}

/// The render-space medium of a description (heights minus `origin_world.z`).
pub fn build_medium(m: &MediumDesc, origin_world: glam::DVec3) -> shaders_cpu::medium::Medium {
    use shaders_cpu::medium::{Density, HenyeyGreenstein, Medium};
    let sigma = m.sigma_t_base();
    let dz = origin_world.z;
    let density = match m.kind {
        MediumKindDesc::Homogeneous => Density::Homogeneous { sigma_t: sigma },
        MediumKindDesc::HeightFog => Density::HeightExp {
            sigma0: sigma,
            z0: m.base_height_m - dz,
            height_scale: m.height_scale(),
        },
    };
    Medium {
        density,
        albedo: glam::DVec3::from(m.albedo).as_vec3(),
        phase: HenyeyGreenstein { g: m.g as f32 },
        z_min: m.z_min_m.map_or(f64::NEG_INFINITY, |z| z - dz),
        z_max: m.z_max_m.map_or(f64::INFINITY, |z| z - dz),
    }
}

/// The rain field of a description around the rig at `origin_world`
/// (seed 0 and no pixel size: the renderer sets the frame's seed and its
/// camera's pixel, `Rain::for_frame`).
pub fn build_rain(r: &RainDesc, origin_world: glam::DVec3) -> shaders_cpu::medium::Rain {
    use shaders_cpu::medium::{marshall_palmer_count, marshall_palmer_lambda, Rain};
    let density = marshall_palmer_count(r.rate_mm_per_h, r.drop_diameter_mm) * r.density_scale;
    let rain = Rain::new(
        density,
        r.drop_diameter_mm,
        marshall_palmer_lambda(r.rate_mm_per_h),
        r.shutter_s,
        r.fall_speed_m_per_s,
        r.extent_m,
        origin_world,
        0.0,
    );
    Rain {
        opacity_gain: r.streak_gain,
        ..rain
    }
}
