//! The sun-lobe vertex's shadow ray under the transmittance roulette
//! (`Strategies::shadow_per_tr`, as `medium_nee`'s): the same mean from one
//! medium point as with every kept ray traced, for fewer rays.

use glam::Vec3;

use super::{built, mean_var, paired_se, sample_stream, SCENE};
use crate::integrator::Shading;

/// Green `sun_lobe_vertex` estimates at `n` sample streams from a point
/// high in `SCENE`'s slab, the phase roulette off, with transmittance
/// roulette `per_tr`; and the rays they traced.
fn lobe_estimates(per_tr: f32, n: u32) -> (Vec<f64>, u64) {
    let (scene, accel) = built(SCENE);
    let shading = Shading::new(&scene, &accel);
    let ctx = shading.context(4);
    let m = scene.medium.as_ref().expect("the slab");
    let sl = ctx.sun_lobe.expect("a sun");
    // 28 m up, 12 m under the slab's top: toward the 15° sun, Tr ≈ 0.1.
    let p = Vec3::new(0.0, 0.0, 28.0);
    let wo = -Vec3::new(1.0, 0.2, 0.1).normalize();
    let mut rays = 0;
    let l = (0..n)
        .map(|k| {
            let mut stream = sample_stream(3, k);
            let u = (stream.next_4d(), stream.next_4d());
            let per = (f32::INFINITY, per_tr);
            ctx.sun_lobe_vertex(m, sl, p, wo, u, per, &mut rays).y as f64
        })
        .collect();
    (l, rays)
}

#[test]
fn lobe_transmittance_roulette_keeps_the_mean_for_fewer_rays() {
    let n = 65536;
    let (all, rays_all) = lobe_estimates(f32::INFINITY, n);
    let (rr, rays_rr) = lobe_estimates(4.0, n);
    let ((m_all, _), (m_rr, _)) = (mean_var(&all), mean_var(&rr));
    let se = paired_se(&all, &rr);
    eprintln!("every {m_all:.5} ({rays_all} rays), by Tr {m_rr:.5} ({rays_rr} rays), se {se:.5}");
    assert!(m_all > 0.0);
    assert!((m_all - m_rr).abs() <= 4.0 * se, "{m_all} vs {m_rr} ± {se}");
    // Each estimate traces one ray to find its segment and, kept, one
    // shadow ray: a third of the shadow rays here are dropped.
    let shadow = |rays: u64| (rays - u64::from(n)) as f64;
    assert!(
        shadow(rays_rr) < 0.8 * shadow(rays_all),
        "{rays_rr} vs {rays_all}"
    );
}
