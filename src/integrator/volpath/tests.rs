//! The medium-vertex strategies change the variance, not the estimate: with
//! each on and off the volumetric path tracer must agree in expectation (fog
//! slab over a ground plane, sun low ahead, several bounces); the sun lobe
//! must lower the variance it was made for on fog's forward lobe, and the
//! albedo roulette must keep a grey medium's throughput.

use std::path::Path;

use glam::{DVec3, Vec3};
use shaders_cpu::medium::{Density, HenyeyGreenstein, Medium};

use crate::accel::{build_accel, Accel, AnyAccel, Backend, Ray};
use crate::integrator::path::PathState;
use crate::integrator::volpath::Strategies;
use crate::integrator::Shading;
use crate::sampler::{SampleStream, StreamKey};
use crate::scene::{build_scene, parse_scene_str, Scene};

mod first_vertex;
mod lobe;
mod samples;
mod shadow;
mod sky_rows;
mod spot;
mod surface;
mod thin_sun;

/// Sample `k` of the tests' stream of seed `seed` (frame 0, view 0; 256
/// samples per pixel of row 0).
pub(super) fn sample_stream(seed: u64, k: u32) -> SampleStream {
    let key = StreamKey {
        seed,
        frame: 0,
        view: 0,
    };
    SampleStream::new(key, 0, k / 256, k % 256)
}

const SCENE: &str = r#"
[camera]
width = 4
height = 4
hfov_deg = 60.0
position = [0.0, 0.0, 1.5]
[[light]]
kind = "sun"
elevation_deg = 15.0
azimuth_deg = 30.0
irradiance = [50.0, 50.0, 50.0]
[medium]
kind = "homogeneous"
sigma_t = 0.05
albedo = [0.95, 0.95, 0.95]
g = 0.85
z_max_m = 40.0
[[material]]
name = "ground"
kind = "diffuse"
albedo = [0.3, 0.3, 0.3]
[[object]]
kind = "quad"
size = [2000.0, 2000.0]
material = "ground"
"#;

/// A sky over the same scene (the medium NEE samples it beside the sun).
const SKY: &str = r#"
[sky]
kind = "gradient"
zenith = [9.0, 16.0, 38.0]
horizon = [30.0, 33.0, 37.0]
ground = [6.0, 5.6, 5.2]
"#;

/// Per direction, the green radiance of each of `n` camera samples.
fn samples(strategies: Strategies, dirs: &[Vec3], n: u32) -> Vec<Vec<f64>> {
    samples_in(SCENE, strategies, dirs, n).0
}

/// Scene `src` (TOML) built, with its BVH.
pub(in crate::integrator) fn built(src: &str) -> (Scene, AnyAccel) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    let loaded = parse_scene_str(src, &path).expect("scene parses");
    let scene = build_scene(&loaded, DVec3::ZERO).expect("scene builds");
    let accel = build_accel(Backend::Bvh, &scene.accel_geometry()).expect("accel builds");
    (scene, accel)
}

/// [`samples`] in scene `src`, and the rays they traced.
fn samples_in(src: &str, strategies: Strategies, dirs: &[Vec3], n: u32) -> (Vec<Vec<f64>>, u64) {
    let (scene, accel) = built(src);
    let shading = Shading::new(&scene, &accel);
    let ctx = shading.context(4);
    let key = StreamKey {
        seed: 7,
        frame: 0,
        view: 0,
    };
    let o = Vec3::new(0.0, 0.0, 1.5);
    let mut rays = 0;
    let l = dirs
        .iter()
        .enumerate()
        .map(|(i, &d)| {
            (0..n)
                .map(|k| {
                    let mut stream = SampleStream::new(key, i as u32, k / 256, k % 256);
                    let ray = Ray::new(o, d.normalize());
                    let hit = accel.intersect(&ray);
                    let l = ctx
                        .trace(ray, hit, &mut stream, &mut rays, strategies, None)
                        .l;
                    l.y as f64
                })
                .collect()
        })
        .collect();
    (l, rays)
}

/// Mean and variance (of one sample) of `xs`.
fn mean_var(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    (
        mean,
        xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0),
    )
}

/// Standard error of mean(a) − mean(b) for runs on the same sample streams
/// (sample k of both uses stream k, so they are correlated): from the
/// paired differences, √(var(a_k − b_k) / n).
fn paired_se(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    (mean_var(&d).1 / d.len() as f64).sqrt()
}

/// Asserts per direction that runs `a` and `b` (named, on the same sample
/// streams) agree in mean within 4 paired standard errors; returns their
/// variances per direction.
fn assert_same_means(
    dirs: &[Vec3],
    (name_a, a): (&str, &[Vec<f64>]),
    (name_b, b): (&str, &[Vec<f64>]),
) -> Vec<(f64, f64)> {
    let pairs = dirs.iter().zip(a.iter().zip(b));
    pairs
        .map(|(d, (xa, xb))| {
            let ((ma, va), (mb, vb)) = (mean_var(xa), mean_var(xb));
            let se = paired_se(xa, xb);
            eprintln!(
                "{d}: {name_a} {ma:.4} (var {va:.3}), {name_b} {mb:.4} (var {vb:.3}), se {se:.4}"
            );
            assert!(
                (ma - mb).abs() <= 4.0 * se,
                "{d}: {name_a} {ma} vs {name_b} {mb} ± {se}"
            );
            (va, vb)
        })
        .collect()
}

/// Toward the sun's azimuth (level and up), across, and down at the ground.
const DIRS: [Vec3; 4] = [
    Vec3::new(1.0, 0.3, 0.05),
    Vec3::new(1.0, 0.6, 0.3),
    Vec3::new(0.0, 1.0, 0.1),
    Vec3::new(1.0, 0.0, -0.3),
];

#[test]
fn sun_lobe_keeps_the_mean_and_lowers_the_variance() {
    let dirs = DIRS;
    let n = 16384;
    let on = samples(Strategies::default(), &dirs, n);
    let off = samples(
        Strategies {
            sun_lobe: false,
            ..Strategies::default()
        },
        &dirs,
        n,
    );
    let vars = assert_same_means(&dirs, ("off", &off), ("on", &on));
    let var_off: f64 = vars.iter().map(|v| v.0).sum();
    let var_on: f64 = vars.iter().map(|v| v.1).sum();
    assert!(var_on < 0.8 * var_off, "variance {var_on} vs {var_off}");
}

#[test]
fn albedo_roulette_keeps_the_mean() {
    // The ground (albedo 0.3) dims paths before they scatter again in the
    // fog, where the throughput roulette would have killed and boosted them.
    let n = 16384;
    let on = samples(Strategies::default(), &DIRS, n);
    let off = samples(
        Strategies {
            albedo_roulette: false,
            ..Strategies::default()
        },
        &DIRS,
        n,
    );
    assert_same_means(&DIRS, ("throughput", &off), ("albedo", &on));
}

fn medium(albedo: Vec3) -> Medium {
    Medium {
        density: Density::Homogeneous { sigma_t: 0.1 },
        albedo,
        phase: HenyeyGreenstein { g: 0.85 },
        z_min: f64::NEG_INFINITY,
        z_max: f64::INFINITY,
    }
}

#[test]
fn albedo_roulette_keeps_grey_throughput_and_expected_weight() {
    // `keep` < 1 is the deep roulette on top: fewer survivors, each
    // divided by it, the same expected weight.
    let cases = [Vec3::splat(0.8), Vec3::new(0.9, 0.5, 0.2)]
        .into_iter()
        .flat_map(|albedo| [(albedo, 1.0), (albedo, 0.5)]);
    for (albedo, keep) in cases {
        let m = medium(albedo);
        let n = 1000;
        let mut sum = Vec3::ZERO;
        let mut survivors = 0;
        for i in 0..n {
            let mut st = PathState::new(Vec3::ZERO);
            st.beta = Vec3::splat(0.4);
            st.scatter(&m, Vec3::ZERO, 1.0);
            let u = (i as f32 + 0.5) / n as f32;
            if st.survives_albedo_roulette(&m, u, keep) {
                survivors += 1;
                // β·albedo/max(albedo): grey keeps β from before the collision.
                let expected = 0.4 * albedo / albedo.max_element() / keep;
                assert!(
                    (st.beta - expected).abs().max_element() < 1e-6,
                    "{}",
                    st.beta
                );
                sum += st.beta;
            }
        }
        // Survival probability max(albedo)·keep; expected weight β·albedo.
        let p = albedo.max_element() * keep;
        assert_eq!(survivors, (p * n as f32).round() as i32);
        let mean = sum / n as f32;
        assert!((mean - 0.4 * albedo).abs().max_element() < 1e-5, "{mean}");
    }
}

#[test]
fn collision_only_in_scattering_keeps_the_mean() {
    // Defaults (in-scattering on every segment only before the first
    // scattering event) against it on every segment: the same expected
    // radiance, toward and across the sun.
    let n = 16384;
    let cheap = samples(Strategies::default(), &DIRS, n);
    let full = samples(
        Strategies {
            every_segment_bounces: u32::MAX,
            ..Strategies::default()
        },
        &DIRS,
        n,
    );
    // Estimated on no segment but collisions, from the camera ray on.
    let collisions = samples(
        Strategies {
            every_segment_bounces: 0,
            ..Strategies::default()
        },
        &DIRS,
        n,
    );
    assert_same_means(&DIRS, ("full", &full), ("default", &cheap));
    assert_same_means(&DIRS, ("full", &full), ("collisions only", &collisions));
}

#[test]
fn deep_sky_and_lobe_roulettes_keep_the_mean() {
    // Under sun and sky: the defaults (the sky's NEE at collisions and the
    // sun lobe after the first collision each drawn half the time) against
    // both always drawn: the same expected radiance, for fewer rays.
    let n = 16384;
    let scene = format!("{SCENE}{SKY}");
    let (rr, rays_rr) = samples_in(&scene, Strategies::default(), &DIRS, n);
    let (all, rays_all) = samples_in(
        &scene,
        Strategies {
            sky_nee_deep: 1.0,
            lobe_deep: 1.0,
            ..Strategies::default()
        },
        &DIRS,
        n,
    );
    assert_same_means(&DIRS, ("always", &all), ("roulette", &rr));
    eprintln!("rays: always {rays_all}, roulette {rays_rr}");
    assert!(
        (rays_rr as f64) < 0.95 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}

#[test]
fn deep_roulette_keeps_the_mean_for_fewer_rays() {
    // Collisions after the first scattering event survive half the time
    // (divided by 1/2), however often, against never rouletted: the same
    // expected radiance in the fog slab, under sun and sky, for fewer rays.
    let n = 16384;
    let scene = format!("{SCENE}{SKY}");
    let never = Strategies {
        deep_survival: 1.0,
        ..Strategies::default()
    };
    let (all, rays_all) = samples_in(&scene, never, &DIRS, n);
    let (rr, rays_rr) = samples_in(
        &scene,
        Strategies {
            deep_survival: 0.5,
            deep_max_boost: f32::INFINITY,
            ..Strategies::default()
        },
        &DIRS,
        n,
    );
    assert_same_means(&DIRS, ("never", &all), ("deep roulette", &rr));
    eprintln!("rays: never {rays_all}, deep roulette {rays_rr}");
    assert!(
        (rays_rr as f64) < 0.9 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}

#[test]
fn deep_roulette_with_a_bounded_boost_keeps_the_mean() {
    // The deep roulette at 1/2 stopped once it has doubled a path's
    // throughput (one survival: a survivor weighs at most twice its
    // neighbours) against never rouletted (the default): the same expected
    // radiance, for fewer rays than never, more than without the bound.
    let n = 16384;
    let scene = format!("{SCENE}{SKY}");
    let deep = |max_boost: f32| Strategies {
        deep_survival: 0.5,
        deep_max_boost: max_boost,
        ..Strategies::default()
    };
    let never = Strategies {
        deep_survival: 1.0,
        ..Strategies::default()
    };
    let (all, rays_all) = samples_in(&scene, never, &DIRS, n);
    let (bounded, rays_bounded) = samples_in(&scene, deep(2.0), &DIRS, n);
    let (_, rays_unbounded) = samples_in(&scene, deep(f32::INFINITY), &DIRS, n);
    assert_same_means(&DIRS, ("never", &all), ("bounded roulette", &bounded));
    eprintln!("rays: never {rays_all}, bounded {rays_bounded}, unbounded {rays_unbounded}");
    assert!(
        (rays_bounded as f64) < 0.97 * rays_all as f64,
        "{rays_bounded} vs {rays_all}"
    );
    assert!(
        (rays_bounded as f64) > 1.02 * rays_unbounded as f64,
        "{rays_bounded} vs {rays_unbounded}"
    );
}

#[test]
fn inscatter_roulette_keeps_the_mean_in_thin_haze() {
    // A thin slab (σ_t 0.0005/m up to 40 m) under sun and sky: up and
    // across the sun the slab's opacity is about 7 % (the sky's NEE drawn
    // about 30 % of the time at 4 per unit opacity); level rays see an
    // opaque column, always estimated.
    let thin = format!("{SCENE}{SKY}").replace("sigma_t = 0.05", "sigma_t = 0.0005");
    // The shadow rays' roulettes (phase value, transmittance) off in both:
    // they drop many of the same rays (`shadow.rs`).
    let n = 16384;
    let base = Strategies {
        shadow_per_phase: f32::INFINITY,
        shadow_per_tr: f32::INFINITY,
        ..Strategies::default()
    };
    let (rr, rays_rr) = samples_in(&thin, base, &DIRS, n);
    let (all, rays_all) = samples_in(
        &thin,
        Strategies {
            inscatter_per_opacity: f32::INFINITY,
            ..base
        },
        &DIRS,
        n,
    );
    let vars = assert_same_means(&DIRS, ("always", &all), ("roulette", &rr));
    eprintln!("rays: always {rays_all}, roulette {rays_rr}, variances {vars:?}");
    assert!(
        (rays_rr as f64) < 0.9 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}

#[test]
fn split_roulette_keeps_the_mean() {
    // The split camera segment's surface part traced by the roulette on
    // its Tr (the default, 8 per unit Tr) against always: the same
    // expected radiance toward the sunlit ground through a dense, low
    // slab (σ_t 0.45/m up to 2 m: Tr about 0.1 to the ground, kept about
    // 75 % of the time).
    let n = 16384;
    let dense = SCENE
        .replace("sigma_t = 0.05", "sigma_t = 0.45")
        .replace("z_max_m = 40.0", "z_max_m = 2.0");
    let split = Strategies {
        split_first: true,
        ..Strategies::default()
    };
    let (rr, rays_rr) = samples_in(&dense, split, &DIRS, n);
    let (all, rays_all) = samples_in(
        &dense,
        Strategies {
            split_per_tr: f32::INFINITY,
            ..split
        },
        &DIRS,
        n,
    );
    assert_same_means(&DIRS, ("always", &all), ("roulette", &rr));
    eprintln!("rays: always {rays_all}, roulette {rays_rr}");
    assert!(rays_rr < rays_all, "{rays_rr} vs {rays_all}");
}

#[test]
fn local_light_roulette_keeps_the_mean_for_fewer_rays() {
    // A point light in the fog slab beside sun and sky (about as bright
    // as the sun where the rays pass): its in-scattering (NEE and
    // equiangular sampling) under the default roulettes (the camera
    // segment's at 0.25 per unit opacity, later segments' at 0.1, each
    // divided by it) against always estimated: the same expected
    // radiance, for fewer rays.
    let lamp = "[[light]]\nkind = \"point\"\nposition = [12.0, 4.0, 3.0]\nintensity = [4000.0, 4000.0, 4000.0]\n";
    let scene = format!("{SCENE}{SKY}{lamp}");
    let n = 16384;
    let (rr, rays_rr) = samples_in(&scene, Strategies::default(), &DIRS, n);
    let always = Strategies {
        local_per_opacity: f32::INFINITY,
        local_nee_deep: 1.0,
        ..Strategies::default()
    };
    let (all, rays_all) = samples_in(&scene, always, &DIRS, n);
    // Without the lamp, to show it brings a large share of the light.
    let (dark, _) = samples_in(&format!("{SCENE}{SKY}"), always, &DIRS, n);
    assert_same_means(&DIRS, ("always", &all), ("roulette", &rr));
    let total = |runs: &[Vec<f64>]| runs.iter().map(|r| mean_var(r).0).sum::<f64>();
    let (lit, unlit) = (total(&all), total(&dark));
    eprintln!("summed means: with the lamp {lit:.3}, without {unlit:.3}");
    assert!(lit > 1.3 * unlit, "the lamp adds little: {lit} vs {unlit}");
    eprintln!("rays: always {rays_all}, roulette {rays_rr}");
    assert!(
        (rays_rr as f64) < 0.9 * rays_all as f64,
        "{rays_rr} vs {rays_all}"
    );
}
