//! The roulettes at surface vertices in a medium: the distant lights'
//! shadow rays by their transmittance (`Strategies::surface_per_tr`) and a
//! Lambertian split vertex's indirect light by the throughput reaching it
//! (`Strategies::x1_indirect_per_beta`, off by default) keep the mean for
//! fewer rays.

use super::{assert_same_means, samples_in, Strategies, DIRS, SCENE, SKY};

#[test]
fn surface_transmittance_roulette_keeps_the_mean_for_fewer_rays() {
    // Under the slab's 40 m of fog (optical depth 2 straight up, 7.7
    // toward the sun at 15°) the ground's shadow rays carry Tr ≤ 0.14:
    // at 2 per unit Tr most are dropped, the rest divided by their
    // survival. Against every one traced.
    let n = 16384;
    let scene = format!("{SCENE}{SKY}");
    let every = Strategies {
        surface_per_tr: f32::INFINITY,
        ..Strategies::default()
    };
    let (all, rays_all) = samples_in(&scene, every, &DIRS, n);
    let (rr, rays_rr) = samples_in(&scene, Strategies::default(), &DIRS, n);
    assert_same_means(&DIRS, ("every", &all), ("by Tr", &rr));
    eprintln!("rays: every {rays_all}, by Tr {rays_rr}");
    assert!(
        (rays_rr as f64) < 0.9 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}

#[test]
fn x1_indirect_roulette_keeps_the_mean_for_fewer_rays() {
    // The split camera ray (renders that filter) down through a dense, low
    // slab (σ_t 0.45/m up to 2 m) to the ground 5 m ahead, seen with β
    // about Tr ≈ 0.1: its indirect light (fog and sky by way of the
    // ground) traced half the time and doubled, against always traced.
    let n = 16384;
    let dense = SCENE
        .replace("sigma_t = 0.05", "sigma_t = 0.45")
        .replace("z_max_m = 40.0", "z_max_m = 2.0");
    let scene = format!("{dense}{SKY}");
    let split = Strategies {
        split_first: true,
        x1_indirect_per_beta: 2.0,
        ..Strategies::default()
    };
    let always = Strategies {
        x1_indirect_per_beta: f32::INFINITY,
        ..split
    };
    let ground = [DIRS[3]];
    let (all, rays_all) = samples_in(&scene, always, &ground, n);
    let (rr, rays_rr) = samples_in(&scene, split, &ground, n);
    assert_same_means(&ground, ("always", &all), ("roulette", &rr));
    eprintln!("rays: always {rays_all}, roulette {rays_rr}");
    assert!(
        (rays_rr as f64) < 0.9 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}
