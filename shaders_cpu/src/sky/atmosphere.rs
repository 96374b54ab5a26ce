//! The clear-sky atmosphere: a spherical shell of Rayleigh, Mie and ozone
//! (Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere
//! Rendering Technique", §3 and Table 1; Bruneton & Neyret 2008 for the
//! transmittance parametrisation), with its transmittance table.
//!
//! Lengths in metres, radii from the planet's centre; `mu` is the cosine of a
//! ray's zenith angle at its origin. Coefficients are per metre, RGB channels.
//! The transmittance table ignores the ground (rays pass through the planet);
//! callers test the planet's shadow themselves ([`sun_visibility`]).

use glam::DVec3;

/// Planet radius, m.
pub const EARTH_RADIUS_M: f64 = 6_360_000.0;
/// Radius of the top of the atmosphere, m.
pub const TOP_RADIUS_M: f64 = 6_460_000.0;
/// Rayleigh scattering at sea level, 1/m (R, G, B).
pub const RAYLEIGH_SCATTERING: [f64; 3] = [5.802e-6, 13.558e-6, 33.1e-6];
/// Rayleigh density scale height, m.
pub const RAYLEIGH_SCALE_HEIGHT_M: f64 = 8_000.0;
/// Mie scattering at sea level, 1/m (grey).
pub const MIE_SCATTERING: f64 = 3.996e-6;
/// Mie extinction at sea level, 1/m (grey).
pub const MIE_EXTINCTION: f64 = 4.4e-6;
/// Mie density scale height, m.
pub const MIE_SCALE_HEIGHT_M: f64 = 1_200.0;
/// Mie asymmetry parameter of the Cornette–Shanks phase function.
pub const MIE_G: f64 = 0.8;
/// Ozone absorption at the tent's peak (25 km), 1/m (R, G, B).
pub const OZONE_ABSORPTION: [f64; 3] = [0.650e-6, 1.881e-6, 0.085e-6];
/// Extraterrestrial solar irradiance per channel, W·m⁻², in the renderer's RGB
/// units: chosen so a zenith sun through this atmosphere (turbidity 1) gives
/// the towns' clear-sun irradiance ≈ (980, 930, 850) W·m⁻² at the ground.
pub const SOLAR_IRRADIANCE: [f64; 3] = [1042.0, 1069.0, 1119.0];
/// Angular radius of the sun (and, closely, the moon), rad.
pub const SUN_ANGULAR_RADIUS_RAD: f64 = 0.004_654;

/// Parameters of one atmosphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Atmosphere {
    /// Multiplier of the Mie (aerosol) density: 1 clear, 2–4 hazy.
    pub turbidity: f64,
    /// Lambertian albedo of the ground below the horizon, 0–1.
    pub ground_albedo: f64,
}

impl Default for Atmosphere {
    fn default() -> Self {
        Atmosphere {
            turbidity: 1.0,
            ground_albedo: 0.1,
        }
    }
}

/// Scattering coefficients at one altitude.
#[derive(Clone, Copy, Debug)]
pub struct Coefficients {
    /// Rayleigh scattering, 1/m.
    pub rayleigh: DVec3,
    /// Mie scattering, 1/m.
    pub mie: f64,
    /// Total extinction, 1/m.
    pub sigma_t: DVec3,
}

impl Atmosphere {
    /// Coefficients at altitude `h` (m above the ground).
    pub fn coefficients(&self, h: f64) -> Coefficients {
        let h = h.max(0.0);
        let rd = (-h / RAYLEIGH_SCALE_HEIGHT_M).exp();
        let md = (-h / MIE_SCALE_HEIGHT_M).exp() * self.turbidity;
        // Ozone: tent of half-width 15 km around 25 km (Hillaire's profile).
        let od = (1.0 - (h - 25_000.0).abs() / 15_000.0).max(0.0);
        let rayleigh = DVec3::from(RAYLEIGH_SCATTERING) * rd;
        let sigma_t =
            rayleigh + DVec3::splat(MIE_EXTINCTION * md) + DVec3::from(OZONE_ABSORPTION) * od;
        Coefficients {
            rayleigh,
            mie: MIE_SCATTERING * md,
            sigma_t,
        }
    }

    /// Transmittance from radius `r` along `mu` to the top of the atmosphere by
    /// midpoint quadrature with `steps` intervals (ignores the ground).
    pub fn transmittance_direct(&self, r: f64, mu: f64, steps: usize) -> DVec3 {
        let d = distance_to_top(r, mu);
        let dt = d / steps as f64;
        let mut depth = DVec3::ZERO;
        for i in 0..steps {
            let t = (i as f64 + 0.5) * dt;
            depth += self
                .coefficients(radius_at(r, mu, t) - EARTH_RADIUS_M)
                .sigma_t
                * dt;
        }
        (-depth).exp()
    }
}

/// Radius reached after distance `t` from radius `r` along `mu`.
pub fn radius_at(r: f64, mu: f64, t: f64) -> f64 {
    (r * r + t * t + 2.0 * r * mu * t).max(0.0).sqrt()
}

/// Distance from radius `r` (inside the atmosphere) along `mu` to the top.
pub fn distance_to_top(r: f64, mu: f64) -> f64 {
    let disc = r * r * (mu * mu - 1.0) + TOP_RADIUS_M * TOP_RADIUS_M;
    (-r * mu + disc.max(0.0).sqrt()).max(0.0)
}

/// Distance from radius `r` along `mu` to the ground, if the ray hits it.
pub fn distance_to_ground(r: f64, mu: f64) -> Option<f64> {
    let disc = r * r * (mu * mu - 1.0) + EARTH_RADIUS_M * EARTH_RADIUS_M;
    (mu < 0.0 && disc >= 0.0).then(|| (-r * mu - disc.sqrt()).max(0.0))
}

/// Fraction of the sun's disk above the planet's horizon seen from radius `r`
/// for a sun at cosine `mu_s`: a smoothstep over the disk's angular diameter,
/// so twilight dims continuously as the sun sinks.
pub fn sun_visibility(r: f64, mu_s: f64) -> f64 {
    let sin_h = EARTH_RADIUS_M / r.max(EARTH_RADIUS_M);
    let cos_h = -(1.0 - sin_h * sin_h).max(0.0).sqrt();
    // Angle of the sun above the horizon (small-angle: Δμ / sin θ_h).
    let x = (mu_s - cos_h) / sin_h.max(1e-6);
    let t = ((x / SUN_ANGULAR_RADIUS_RAD + 1.0) * 0.5).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Rayleigh phase function, 1/sr, for `nu` = cos(scattering angle).
pub fn rayleigh_phase(nu: f64) -> f64 {
    3.0 / (16.0 * std::f64::consts::PI) * (1.0 + nu * nu)
}

/// Cornette–Shanks Mie phase function, 1/sr (Bruneton 2017's form).
pub fn mie_phase(nu: f64, g: f64) -> f64 {
    let k = 3.0 / (8.0 * std::f64::consts::PI) * (1.0 - g * g) / (2.0 + g * g);
    k * (1.0 + nu * nu) / (1.0 + g * g - 2.0 * g * nu).max(1e-9).powf(1.5)
}

/// Transmittance to the top of the atmosphere over (altitude, μ): node grid of
/// Bruneton's parametrisation (x_r = ρ/H, x_μ linear in the distance to the
/// top between its extremes), bilinear lookups.
#[derive(Clone, Debug)]
pub struct TransmittanceLut {
    n_mu: usize,
    n_r: usize,
    data: Vec<DVec3>,
}

fn h_top() -> f64 {
    (TOP_RADIUS_M * TOP_RADIUS_M - EARTH_RADIUS_M * EARTH_RADIUS_M).sqrt()
}

impl TransmittanceLut {
    /// Nodes along μ and along the radius.
    pub const SIZE: (usize, usize) = (128, 32);

    /// Integrates every node of the table (200 midpoint steps per ray).
    pub fn new(atmo: &Atmosphere) -> Self {
        let (n_mu, n_r) = Self::SIZE;
        let mut data = Vec::with_capacity(n_mu * n_r);
        for j in 0..n_r {
            for i in 0..n_mu {
                let (r, mu) = from_unit(i as f64 / (n_mu - 1) as f64, j as f64 / (n_r - 1) as f64);
                data.push(atmo.transmittance_direct(r, mu, 200));
            }
        }
        TransmittanceLut { n_mu, n_r, data }
    }

    /// Transmittance from radius `r` along `mu` to the top (ground ignored).
    pub fn lookup(&self, r: f64, mu: f64) -> DVec3 {
        let (xm, xr) = to_unit(r, mu);
        bilerp(&self.data, self.n_mu, self.n_r, xm, xr)
    }
}

/// (r, μ) → unit coordinates (x_μ, x_r).
fn to_unit(r: f64, mu: f64) -> (f64, f64) {
    let h = h_top();
    let r = r.clamp(EARTH_RADIUS_M, TOP_RADIUS_M);
    let rho = (r * r - EARTH_RADIUS_M * EARTH_RADIUS_M).max(0.0).sqrt();
    let d = distance_to_top(r, mu);
    let (d_min, d_max) = (TOP_RADIUS_M - r, rho + h);
    let xm = if d_max > d_min {
        (d - d_min) / (d_max - d_min)
    } else {
        0.0
    };
    (xm.clamp(0.0, 1.0), rho / h)
}

/// Inverse of [`to_unit`].
fn from_unit(xm: f64, xr: f64) -> (f64, f64) {
    let h = h_top();
    let rho = h * xr;
    let r = (rho * rho + EARTH_RADIUS_M * EARTH_RADIUS_M).sqrt();
    let (d_min, d_max) = (TOP_RADIUS_M - r, rho + h);
    let d = d_min + xm * (d_max - d_min);
    let mu = if d == 0.0 {
        1.0
    } else {
        ((h * h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
    };
    (r, mu)
}

/// Bilinear interpolation on an `nx` × `ny` node grid at unit coordinates.
pub(super) fn bilerp<T>(data: &[T], nx: usize, ny: usize, x: f64, y: f64) -> T
where
    T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
{
    let fx = x.clamp(0.0, 1.0) * (nx - 1) as f64;
    let fy = y.clamp(0.0, 1.0) * (ny - 1) as f64;
    let (ix, iy) = ((fx as usize).min(nx - 2), (fy as usize).min(ny - 2));
    let (tx, ty) = (fx - ix as f64, fy - iy as f64);
    let at = |i: usize, j: usize| data[j * nx + i];
    (at(ix, iy) * (1.0 - tx) + at(ix + 1, iy) * tx) * (1.0 - ty)
        + (at(ix, iy + 1) * (1.0 - tx) + at(ix + 1, iy + 1) * tx) * ty
}
