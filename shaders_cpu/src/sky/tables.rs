//! Per-frame tables of the clear sky (Hillaire 2020 §4–5): the multiple-
//! scattering table Ψ_ms(altitude, μ_s) and the sky-view table of in-scattered
//! radiance over (azimuth relative to the source, elevation) for a viewer near
//! the ground, single scattering plus Ψ_ms, ground bounce below the horizon.
//!
//! Local frame: z up at the viewer, the light source (sun or moon) in the x–z
//! plane at azimuth 0. Rows follow Hillaire's horizon-dense map, in z = sin e
//! rather than e (no asin per lookup): v = ½ + ½·sign(z)·√|z|; a node sits
//! exactly on the horizon.

use super::atmosphere::{
    bilerp, distance_to_ground, distance_to_top, mie_phase, rayleigh_phase, sun_visibility,
    Atmosphere, TransmittanceLut, EARTH_RADIUS_M, MIE_G, TOP_RADIUS_M,
};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// Viewer altitude of the sky-view table, m (a camera above the road).
pub const VIEWER_ALTITUDE_M: f64 = 10.0;

/// Second and higher scattering orders per unit source irradiance, Ψ_ms
/// (Hillaire eq. 5–9), over (μ_s, altitude).
#[derive(Clone, Debug)]
pub struct MultipleScattering {
    data: Vec<DVec3>,
}

const MS_N: usize = 16;
const MS_DIRS: usize = 64;
const MS_STEPS: usize = 20;

impl MultipleScattering {
    /// Integrates Ψ_ms on a 16 × 16 grid, 64 directions × 20 steps per node.
    pub fn new(atmo: &Atmosphere, tr: &TransmittanceLut) -> Self {
        let dirs: Vec<DVec3> = (0..MS_DIRS).map(fibonacci_sphere).collect();
        let mut data = Vec::with_capacity(MS_N * MS_N);
        for j in 0..MS_N {
            let r = EARTH_RADIUS_M + (TOP_RADIUS_M - EARTH_RADIUS_M) * j as f64 / (MS_N - 1) as f64;
            for i in 0..MS_N {
                let mu_s = -1.0 + 2.0 * i as f64 / (MS_N - 1) as f64;
                let sun = DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s);
                let (mut l2, mut f_ms) = (DVec3::ZERO, DVec3::ZERO);
                for &w in &dirs {
                    let (l, f) = march_isotropic(atmo, tr, r.min(TOP_RADIUS_M - 1.0), w, sun);
                    l2 += l;
                    f_ms += f;
                }
                // Both are sphere means (∫ · p_u dω with p_u = 1/4π).
                l2 /= MS_DIRS as f64;
                f_ms /= MS_DIRS as f64;
                data.push(l2 / (DVec3::ONE - f_ms));
            }
        }
        MultipleScattering { data }
    }

    /// Ψ_ms per unit source irradiance at radius `r` for source cosine `mu_s`.
    pub fn lookup(&self, r: f64, mu_s: f64) -> DVec3 {
        let x = (mu_s + 1.0) * 0.5;
        let y = (r - EARTH_RADIUS_M) / (TOP_RADIUS_M - EARTH_RADIUS_M);
        bilerp(&self.data, MS_N, MS_N, x, y)
    }
}

/// Evenly spread unit direction `i` of `MS_DIRS`.
fn fibonacci_sphere(i: usize) -> DVec3 {
    let z = 1.0 - (2.0 * i as f64 + 1.0) / MS_DIRS as f64;
    let phi = i as f64 * PI * (3.0 - 5f64.sqrt());
    let s = (1.0 - z * z).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// One ray of the Ψ_ms integral: (L′ per unit irradiance with isotropic
/// phase, f′_ms = ∫ T σ_s dt · p_u-free transfer), ground bounce included.
fn march_isotropic(
    atmo: &Atmosphere,
    tr: &TransmittanceLut,
    r: f64,
    w: DVec3,
    sun: DVec3,
) -> (DVec3, DVec3) {
    let mu = w.z;
    let ground = distance_to_ground(r, mu);
    let t_max = ground.unwrap_or_else(|| distance_to_top(r, mu));
    let p_u = 1.0 / (4.0 * PI);
    let dt = t_max / MS_STEPS as f64;
    let origin = DVec3::new(0.0, 0.0, r);
    let (mut l, mut f, mut t_view) = (DVec3::ZERO, DVec3::ZERO, DVec3::ONE);
    for k in 0..MS_STEPS {
        let x = origin + w * ((k as f64 + 0.5) * dt);
        let rx = x.length();
        let up = x / rx;
        let c = atmo.coefficients(rx - EARTH_RADIUS_M);
        let mu_s = up.dot(sun);
        let sun_tr = tr.lookup(rx, mu_s) * sun_visibility(rx, mu_s);
        let sigma_s = c.rayleigh + DVec3::splat(c.mie);
        let seg = segment_weight(c.sigma_t, dt);
        l += t_view * sigma_s * sun_tr * p_u * seg;
        f += t_view * sigma_s * seg;
        t_view *= (-c.sigma_t * dt).exp();
    }
    if ground.is_some() {
        let up = (origin + w * t_max).normalize();
        let mu_g = up.dot(sun).max(0.0);
        let sun_tr = tr.lookup(EARTH_RADIUS_M, mu_g);
        l += t_view * sun_tr * mu_g * atmo.ground_albedo / PI;
    }
    (l, f)
}

/// ∫₀^dt exp(−σ_t s) ds per channel: the energy-conserving segment weight.
fn segment_weight(sigma_t: DVec3, dt: f64) -> DVec3 {
    let f = |s: f64| {
        if s * dt < 1e-6 {
            dt
        } else {
            (1.0 - (-s * dt).exp()) / s
        }
    };
    DVec3::new(f(sigma_t.x), f(sigma_t.y), f(sigma_t.z))
}

/// In-scattered radiance over (azimuth from the source ∈ [0, π], elevation),
/// for one source direction and irradiance at the top of the atmosphere.
#[derive(Clone, Debug)]
pub struct SkyView {
    data: Vec<Vec3>,
}

/// Nodes along the relative azimuth and along elevation (odd: horizon node).
pub const SKY_VIEW_SIZE: (usize, usize) = (64, 65);
const VIEW_STEPS: usize = 40;
/// Width of the horizon-to-ground blend in z (sin 3°).
const HORIZON_BLEND_Z: f32 = 0.052;

impl SkyView {
    /// Marches every node's view ray (40 steps, quadratic spacing).
    pub fn new(
        atmo: &Atmosphere,
        tr: &TransmittanceLut,
        ms: &MultipleScattering,
        source_elevation_rad: f64,
        source_irradiance: DVec3,
    ) -> Self {
        let (n_az, n_el) = SKY_VIEW_SIZE;
        let sun = DVec3::new(source_elevation_rad.cos(), 0.0, source_elevation_rad.sin());
        let mut data = Vec::with_capacity(n_az * n_el);
        for j in 0..n_el {
            let el = elevation_of(j as f64 / (n_el - 1) as f64);
            for i in 0..n_az {
                let az = PI * i as f64 / (n_az - 1) as f64;
                let w = DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
                let l = march_view(atmo, tr, ms, w, sun) * source_irradiance;
                data.push(l.as_vec3());
            }
        }
        SkyView { data }
    }

    /// Radiance towards the viewer from local direction `w` (source at azimuth
    /// 0). Below the horizon the table's ground is reached by a smoothstep over
    /// 3° from the horizon's sky (the scene's own ground covers these
    /// directions; the blend keeps `le` continuous for the sampler).
    pub fn lookup(&self, w: Vec3) -> Vec3 {
        let (n_az, n_el) = SKY_VIEW_SIZE;
        let x = w.y.abs().atan2(w.x) / std::f32::consts::PI;
        let z = w.z.clamp(-1.0, 1.0);
        let v = 0.5 + 0.5 * z.signum() * z.abs().sqrt();
        let l = bilerp_f32(&self.data, n_az, n_el, x, v);
        if z >= 0.0 {
            return l;
        }
        let t = (-z / HORIZON_BLEND_Z).min(1.0);
        let horizon = bilerp_f32(&self.data, n_az, n_el, x, 0.5);
        horizon.lerp(l, t * t * (3.0 - 2.0 * t))
    }
}

/// [`bilerp`] on an f32 table (the per-vertex lookup).
fn bilerp_f32(data: &[Vec3], nx: usize, ny: usize, x: f32, y: f32) -> Vec3 {
    let fx = x.clamp(0.0, 1.0) * (nx - 1) as f32;
    let fy = y.clamp(0.0, 1.0) * (ny - 1) as f32;
    let (ix, iy) = ((fx as usize).min(nx - 2), (fy as usize).min(ny - 2));
    let (tx, ty) = (fx - ix as f32, fy - iy as f32);
    let at = |i: usize, j: usize| data[j * nx + i];
    (at(ix, iy) * (1.0 - tx) + at(ix + 1, iy) * tx) * (1.0 - ty)
        + (at(ix, iy + 1) * (1.0 - tx) + at(ix + 1, iy + 1) * tx) * ty
}

/// Elevation (rad) of unit row coordinate `v` (inverse of the lookup's map).
fn elevation_of(v: f64) -> f64 {
    let t = 2.0 * v - 1.0;
    (t.signum() * t * t).clamp(-1.0, 1.0).asin()
}

/// One view ray from the viewer: single scattering + σ_s·Ψ_ms, ground bounce.
fn march_view(
    atmo: &Atmosphere,
    tr: &TransmittanceLut,
    ms: &MultipleScattering,
    w: DVec3,
    sun: DVec3,
) -> DVec3 {
    let r0 = EARTH_RADIUS_M + VIEWER_ALTITUDE_M;
    let mu = w.z;
    let ground = distance_to_ground(r0, mu);
    let t_max = ground.unwrap_or_else(|| distance_to_top(r0, mu));
    let nu = w.dot(sun);
    let (p_r, p_m) = (rayleigh_phase(nu), mie_phase(nu, MIE_G));
    let origin = DVec3::new(0.0, 0.0, r0);
    let (mut l, mut t_view, mut t_prev) = (DVec3::ZERO, DVec3::ONE, 0.0);
    for k in 0..VIEW_STEPS {
        // Quadratic spacing: short steps near the viewer where air is densest.
        let t_next = t_max * ((k + 1) as f64 / VIEW_STEPS as f64).powi(2);
        let dt = t_next - t_prev;
        let x = origin + w * (0.5 * (t_prev + t_next));
        t_prev = t_next;
        let rx = x.length();
        let up = x / rx;
        let c = atmo.coefficients(rx - EARTH_RADIUS_M);
        let mu_s = up.dot(sun);
        let sun_tr = tr.lookup(rx, mu_s) * sun_visibility(rx, mu_s);
        let single = (c.rayleigh * p_r + DVec3::splat(c.mie * p_m)) * sun_tr;
        let multi = (c.rayleigh + DVec3::splat(c.mie)) * ms.lookup(rx, mu_s);
        l += t_view * (single + multi) * segment_weight(c.sigma_t, dt);
        t_view *= (-c.sigma_t * dt).exp();
    }
    if ground.is_some() {
        let up = (origin + w * t_max).normalize();
        let mu_g = up.dot(sun);
        let sun_tr = tr.lookup(EARTH_RADIUS_M, mu_g) * sun_visibility(EARTH_RADIUS_M, mu_g);
        // Direct sun plus the sky's multiple-scattered light (≈ π Ψ_ms ·
        // cosine-weighted), both reflected by a Lambert ground.
        let e = sun_tr * mu_g.max(0.0) + ms.lookup(EARTH_RADIUS_M, mu_g) * PI;
        l += t_view * e * atmo.ground_albedo / PI;
    }
    l
}
