//! The physically based sky of one frame: the atmosphere's tables built for
//! one light source (the sun by day and at twilight, the moon at night),
//! the source's own radiance as a disk light, optional night glow, an
//! optional world-fixed cloud layer, and the sampling distribution.
//!
//! World directions, z up; the source's azimuth rotates the sky-view table.
//! Partial cloud: where the world-fixed deck is opaque along a view ray the
//! clear sky gives way to an overcast deck lit by the clear sky's horizontal
//! irradiance, so the cloud shapes that shade the ground are drawn in the
//! sky (`CloudLayer::sky_opacity`); the sky's mean stays that of a uniform
//! blend by the cover fraction.

use super::atmosphere::{sun_visibility, Atmosphere, TransmittanceLut, EARTH_RADIUS_M};
use super::clouds::CloudLayer;
use super::distribution::SkyDistribution;
use super::night::NightGlow;
use super::overcast::OvercastSky;
use super::tables::{MultipleScattering, SkyView, VIEWER_ALTITUDE_M};
use glam::{DVec3, Vec3};
use std::sync::{Arc, Mutex, OnceLock};

/// The sun-independent tables of one atmosphere.
type Shared = Arc<(TransmittanceLut, MultipleScattering)>;

/// Transmittance and Ψ_ms depend only on the atmosphere, not on the source:
/// a sequence's frames (and the day and night skies) share them.
fn shared_tables(atmo: &Atmosphere) -> Shared {
    static CACHE: OnceLock<Mutex<Vec<(Atmosphere, Shared)>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(Vec::new()));
    if let Some((_, t)) = cache.lock().unwrap().iter().find(|(a, _)| a == atmo) {
        return t.clone();
    }
    let tr = TransmittanceLut::new(atmo);
    let ms = MultipleScattering::new(atmo, &tr);
    let t = Arc::new((tr, ms));
    let mut c = cache.lock().unwrap();
    if c.len() >= 8 {
        c.remove(0);
    }
    c.push((*atmo, t.clone()));
    t
}

/// What a physical sky is built from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalSkyParams {
    /// Unit world direction towards the source (sun or moon), z up.
    pub source_dir: Vec3,
    /// Source irradiance at the top of the atmosphere, W·m⁻² per channel.
    pub source_irradiance: Vec3,
    /// The atmosphere (turbidity, ground albedo).
    pub atmosphere: Atmosphere,
    /// Optional cloud deck (shadows and a greyer, brighter sky).
    pub clouds: Option<CloudLayer>,
    /// Optional night glow (airglow, sky glow, stars).
    pub glow: Option<NightGlow>,
}

/// A tabulated physical sky (see the module header).
#[derive(Clone, Debug)]
pub struct PhysicalSky {
    params: PhysicalSkyParams,
    /// cos, sin of the source azimuth (to rotate world into table frame).
    az: (f32, f32),
    view: SkyView,
    tables: Shared,
    overcast: Option<OvercastSky>,
    /// Source irradiance at the viewer (after the atmosphere and horizon).
    source_irradiance_ground: Vec3,
    dist: SkyDistribution,
}

impl PhysicalSky {
    /// Builds the sky-view and sampling tables (~0.1 s; the atmosphere's own
    /// tables are cached per [`Atmosphere`]).
    pub fn new(params: PhysicalSkyParams) -> Self {
        let atmo = params.atmosphere;
        let s = params.source_dir.normalize();
        let elevation = (s.z as f64).clamp(-1.0, 1.0).asin();
        let tables = shared_tables(&atmo);
        let (transmittance, ms) = (&tables.0, &tables.1);
        let e_top = params.source_irradiance.as_dvec3();
        let view = SkyView::new(&atmo, transmittance, ms, elevation, e_top);
        let r0 = EARTH_RADIUS_M + VIEWER_ALTITUDE_M;
        let mu_s = elevation.sin();
        let ground = transmittance.lookup(r0, mu_s) * sun_visibility(r0, mu_s) * e_top;
        let az_len = (s.x * s.x + s.y * s.y).sqrt();
        let az = if az_len > 1e-6 {
            (s.x / az_len, s.y / az_len)
        } else {
            (1.0, 0.0)
        };
        let mut sky = PhysicalSky {
            params,
            az,
            view,
            tables: tables.clone(),
            overcast: None,
            source_irradiance_ground: ground.as_vec3(),
            dist: SkyDistribution::new(|_| Vec3::ONE),
        };
        if params.clouds.is_some_and(|c| c.cover > 0.0) {
            // The deck scatters what reaches it: the clear sky's diffuse
            // horizontal irradiance plus the direct sun's.
            let e = sky.clear_horizontal_irradiance() + sky.source_irradiance_ground * s.z.max(0.0);
            sky.overcast = Some(OvercastSky::from_irradiance(
                e * 0.6,
                atmo.ground_albedo as f32,
            ));
        }
        sky.dist = SkyDistribution::new(|d| sky.le(d));
        sky
    }

    /// The parameters this sky was built from.
    pub fn params(&self) -> &PhysicalSkyParams {
        &self.params
    }

    /// Radiance from world direction `dir` (unit, z up), source disk excluded.
    pub fn le(&self, dir: Vec3) -> Vec3 {
        let (c, s) = self.az;
        // Rotate so the source lies at azimuth 0 of the table.
        let local = Vec3::new(c * dir.x + s * dir.y, -s * dir.x + c * dir.y, dir.z);
        let mut l = self.view.lookup(local);
        if let (Some(o), Some(c)) = (&self.overcast, &self.params.clouds) {
            let a = c.sky_opacity(dir);
            l = l * (1.0 - a) + o.le(dir) * a;
        }
        if let Some(g) = &self.params.glow {
            l += g.le(dir);
        }
        l
    }

    /// Irradiance of the source disk at the viewer on a surface facing it,
    /// W·m⁻² (top-of-atmosphere irradiance × transmittance × the fraction of
    /// the disk above the horizon): red and dim at sunset, zero once set.
    pub fn source_irradiance_ground(&self) -> Vec3 {
        self.source_irradiance_ground
    }

    /// Transmittance from altitude `h_m` along `mu` to space (table lookup).
    pub fn transmittance(&self, h_m: f64, mu: f64) -> DVec3 {
        self.tables.0.lookup(EARTH_RADIUS_M + h_m, mu)
    }

    /// Sun transmittance through the cloud deck at `p_world` (1 without one).
    pub fn cloud_transmittance(&self, p_world: DVec3, dir_to_sun: Vec3) -> f32 {
        self.params
            .clouds
            .map_or(1.0, |c| c.transmittance(p_world, dir_to_sun))
    }

    /// The importance-sampling distribution of [`PhysicalSky::le`].
    pub fn distribution(&self) -> &SkyDistribution {
        &self.dist
    }

    /// ∫_{z>0} le_clear·cos θ dω by a 64 × 128 midpoint rule.
    fn clear_horizontal_irradiance(&self) -> Vec3 {
        let (nt, np) = (64, 128);
        let mut e = Vec3::ZERO;
        for j in 0..nt {
            // Uniform in z: dω = dz dφ.
            let z = (j as f32 + 0.5) / nt as f32;
            let r = (1.0 - z * z).sqrt();
            for i in 0..np {
                let phi = std::f32::consts::TAU * (i as f32 + 0.5) / np as f32;
                e += self.le(Vec3::new(r * phi.cos(), r * phi.sin(), z)) * z;
            }
        }
        e * (std::f32::consts::TAU / (nt * np) as f32)
    }
}
