//! The suns' shadow-ray roulette by the camera segment's opacity
//! (`Strategies::sun_per_opacity`) in thin haze: single scattering of the
//! sun in a thin homogeneous slab against its closed form, and the
//! multiple-scattering mean under sun and sky with and without it.

use glam::Vec3;

use super::shadow::{radiance, single_scatter};
use super::{assert_same_means, mean_var, samples_in, DIRS, SCENE, SKY};
use crate::integrator::volpath::Strategies;

/// A slab a hundred times thinner than `SCENE`'s: 4–10 % opaque along
/// the rays below, where the roulette keeps a fifth to two fifths of the
/// sun's shadow rays the phase roulette alone keeps.
const THIN_SIGMA_T: f64 = 0.0005;

fn thin(src: &str) -> String {
    src.replace("sigma_t = 0.05", &format!("sigma_t = {THIN_SIGMA_T}"))
}

#[test]
fn single_scattered_sun_in_a_thin_slab_matches_its_closed_form() {
    // Upward rays at depth 1 (they leave the slab without meeting the
    // ground): the sun's single scattering only, estimated at the camera
    // segment's in-scattering point under both roulettes.
    let scene = thin(SCENE);
    let dirs: [[f64; 3]; 3] = [[-1.0, -0.3, 0.3], [0.0, 1.0, 0.2], [0.8, 0.5, 0.4]];
    for d in dirs {
        let n = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let d = [d[0] / n.sqrt(), d[1] / n.sqrt(), d[2] / n.sqrt()];
        let dv = Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32);
        let (l, _) = radiance(&scene, Strategies::default(), dv, 1, 16384);
        let (mean, var) = mean_var(&l);
        let se = (var / l.len() as f64).sqrt();
        let want = single_scatter(THIN_SIGMA_T, d);
        eprintln!("{d:?}: {mean:.7} ± {se:.7}, closed form {want:.7}");
        assert!(
            (mean - want).abs() <= 4.0 * se + 2e-3 * want,
            "{d:?}: {mean} vs {want} ± {se}"
        );
    }
}

#[test]
fn sun_opacity_roulette_keeps_the_mean_for_fewer_rays() {
    // Under sun and sky in the thin slab, several bounces: the default
    // against the phase roulette alone.
    let n = 16384;
    let scene = thin(&format!("{SCENE}{SKY}"));
    let (rr, rays_rr) = samples_in(&scene, Strategies::default(), &DIRS, n);
    let phase_only = Strategies {
        sun_per_opacity: f32::INFINITY,
        ..Strategies::default()
    };
    let (all, rays_all) = samples_in(&scene, phase_only, &DIRS, n);
    let vars = assert_same_means(&DIRS, ("phase only", &all), ("opacity", &rr));
    eprintln!("rays: phase only {rays_all}, opacity {rays_rr}, variances {vars:?}");
    assert!(
        (rays_rr as f64) < 0.95 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}
