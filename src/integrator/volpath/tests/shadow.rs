//! The distant lights' shadow-ray roulette by the phase value
//! (`Strategies::shadow_per_phase`): single scattering of the sun in a
//! homogeneous slab against its closed form, and the multiple-scattering
//! mean with and without the roulette.

use glam::Vec3;

use super::{assert_same_means, built, mean_var, sample_stream, samples_in, DIRS, SCENE, SKY};
use crate::accel::{Accel, Ray};
use crate::integrator::volpath::Strategies;
use crate::integrator::Shading;

/// `SCENE`'s slab and sun (no sky: black).
const SIGMA_T: f64 = 0.05;
const ALBEDO: f64 = 0.95;
const G: f64 = 0.85;
const Z_MAX: f64 = 40.0;
const CAMERA_Z: f64 = 1.5;
const SUN_ELEVATION_DEG: f64 = 15.0;
const SUN_AZIMUTH_DEG: f64 = 30.0;
const SUN_IRRADIANCE: f64 = 50.0;

fn sun_dir() -> [f64; 3] {
    let (e, a) = (SUN_ELEVATION_DEG.to_radians(), SUN_AZIMUTH_DEG.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// Single-scattered sun radiance along the upward unit direction `d` from
/// the camera in `SCENE`'s slab at extinction `sigma_t`: ∫ σ_s·e^{−σ_t t}·
/// p(d·ω_sun)·E·e^{−σ_t (z_max − z(t))/sin e} dt over the slab, in closed
/// form (the integrand is one exponential in t).
pub(super) fn single_scatter(sigma_t: f64, d: [f64; 3]) -> f64 {
    let s = sun_dir();
    let cos = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
    let hg = (1.0 - G * G) / (4.0 * std::f64::consts::PI * (1.0 + G * G - 2.0 * G * cos).powf(1.5));
    let (sin_e, h0) = (s[2], Z_MAX - CAMERA_Z);
    let t_out = h0 / d[2];
    let a = sigma_t * (1.0 - d[2] / sin_e);
    let integral = if a.abs() < 1e-12 {
        t_out
    } else {
        -(-a * t_out).exp_m1() / a
    };
    ALBEDO * sigma_t * hg * SUN_IRRADIANCE * (-sigma_t * h0 / sin_e).exp() * integral
}

/// Green radiance of `n` camera samples along `d` in scene `src` at path
/// depth `max_depth`, and the rays they traced.
pub(super) fn radiance(
    src: &str,
    strategies: Strategies,
    d: Vec3,
    max_depth: u32,
    n: u32,
) -> (Vec<f64>, u64) {
    let (scene, accel) = built(src);
    let shading = Shading::new(&scene, &accel);
    let ctx = shading.context(max_depth);
    let mut rays = 0;
    let l = (0..n)
        .map(|k| {
            let mut stream = sample_stream(11, k);
            let ray = Ray::new(Vec3::new(0.0, 0.0, CAMERA_Z as f32), d);
            let hit = accel.intersect(&ray);
            let l = ctx
                .trace(ray, hit, &mut stream, &mut rays, strategies, None)
                .l;
            l.y as f64
        })
        .collect();
    (l, rays)
}

#[test]
fn single_scattered_sun_in_a_slab_matches_its_closed_form() {
    // Upward rays (they leave the slab without meeting the ground) at
    // depth 1: only the sun's single scattering. Away from the sun the
    // phase value is a few per cent of 1/4π and the shadow rays are
    // rouletted; toward it they are always traced.
    let dirs: [[f64; 3]; 3] = [[-1.0, -0.3, 0.3], [0.0, 1.0, 0.2], [0.8, 0.5, 0.4]];
    for d in dirs {
        let n = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let d = [d[0] / n.sqrt(), d[1] / n.sqrt(), d[2] / n.sqrt()];
        let dv = Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32);
        let (l, _) = radiance(SCENE, Strategies::default(), dv, 1, 16384);
        let (mean, var) = mean_var(&l);
        let se = (var / l.len() as f64).sqrt();
        let want = single_scatter(SIGMA_T, d);
        eprintln!("{d:?}: {mean:.6} ± {se:.6}, closed form {want:.6}");
        assert!(
            (mean - want).abs() <= 4.0 * se + 2e-3 * want,
            "{d:?}: {mean} vs {want} ± {se}"
        );
    }
}

#[test]
fn phase_shadow_roulette_keeps_the_mean_for_fewer_rays() {
    // Under sun and sky, several bounces: the default roulette against
    // every shadow ray traced.
    let n = 16384;
    let scene = format!("{SCENE}{SKY}");
    let (rr, rays_rr) = samples_in(&scene, Strategies::default(), &DIRS, n);
    let always = Strategies {
        shadow_per_phase: f32::INFINITY,
        ..Strategies::default()
    };
    let (all, rays_all) = samples_in(&scene, always, &DIRS, n);
    assert_same_means(&DIRS, ("always", &all), ("roulette", &rr));
    eprintln!("rays: always {rays_all}, roulette {rays_rr}");
    assert!(
        (rays_rr as f64) < 0.9 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}

#[test]
fn transmittance_roulette_keeps_the_closed_form_and_the_mean_for_fewer_rays() {
    // The slab's sun at 15°: from most points its shadow ray crosses tens
    // of metres of fog (Tr of a few per cent), so at one per unit Tr the
    // roulette drops most of them. Single scattering against its closed
    // form, then several bounces under sun and sky against every kept ray
    // traced.
    let strict = Strategies {
        shadow_per_tr: 1.0,
        ..Strategies::default()
    };
    let d: [f64; 3] = [0.0, 1.0, 0.2];
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let d = [d[0] / n, d[1] / n, d[2] / n];
    let dv = Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32);
    let (l, _) = radiance(SCENE, strict, dv, 1, 16384);
    let (mean, var) = mean_var(&l);
    let se = (var / l.len() as f64).sqrt();
    let want = single_scatter(SIGMA_T, d);
    assert!(
        (mean - want).abs() <= 4.0 * se + 2e-3 * want,
        "{mean} vs {want} ± {se}"
    );
    let scene = format!("{SCENE}{SKY}");
    let every = Strategies {
        shadow_per_tr: f32::INFINITY,
        ..Strategies::default()
    };
    let (all, rays_all) = samples_in(&scene, every, &DIRS, 16384);
    let (rr, rays_rr) = samples_in(&scene, strict, &DIRS, 16384);
    assert_same_means(&DIRS, ("every", &all), ("by Tr", &rr));
    eprintln!("rays: every {rays_all}, by Tr {rays_rr}");
    assert!(
        (rays_rr as f64) < 0.95 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}
