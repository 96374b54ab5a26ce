//! The smooth glass a camera ray meets first, both lobes traced
//! (`PathContext::glass_lobes`): a pane 5 m ahead, a wall behind it that
//! emits grey, and behind the camera a wall that emits red only, which
//! the pane mirrors; no sky. Split, every sample sees the red wall in the
//! glass with the pane's Fresnel reflectance as its weight; the image's
//! mean is the one the reflect-or-refract choice gives, with less noise.

use glam::Vec3;

use crate::accel::Ray;
use crate::integrator::path::LiSample;
use crate::integrator::volpath::tests::built;
use crate::integrator::Shading;
use crate::sampler::{SampleStream, StreamKey};
use shaders_cpu::bsdf::fresnel::fr_dielectric;

const SCENE: &str = r#"
[camera]
width = 4
height = 4
hfov_deg = 60.0
position = [0.0, 0.0, 1.5]
[sky]
kind = "constant"
le = [0.0, 0.0, 0.0]
[[material]]
name = "glass"
kind = "dielectric"
ior = 1.5
[[material]]
name = "grey"
kind = "emissive"
radiance = [0.3, 0.3, 0.3]
[[material]]
name = "red"
kind = "emissive"
radiance = [1.0, 0.0, 0.0]
[[object]]
kind = "box"
size = [0.05, 30.0, 30.0]
material = "glass"
transform = { translate = [5.0, 0.0, 1.5] }
[[object]]
kind = "box"
size = [0.2, 40.0, 40.0]
material = "grey"
transform = { translate = [8.0, 0.0, 1.5] }
[[object]]
kind = "box"
size = [0.2, 40.0, 40.0]
material = "red"
transform = { translate = [-3.0, 0.0, 1.5] }
"#;

/// Camera samples straight at the pane (slightly off its normal), with
/// the image filters on (the glass split) or off (one lobe by chance).
fn samples(filter: bool, n: u32) -> Vec<LiSample> {
    let src = if filter {
        SCENE.to_string()
    } else {
        format!("{SCENE}[render]\nfilter_indirect = false\n")
    };
    let (scene, accel) = built(&src);
    assert_eq!(scene.filter_indirect, filter);
    let shading = Shading::new(&scene, &accel);
    let ctx = shading.context(6);
    let key = StreamKey {
        seed: 3,
        frame: 0,
        view: 0,
    };
    (0..n)
        .map(|k| {
            let mut stream = SampleStream::new(key, 0, 0, k);
            ctx.li(ray(), Default::default(), &mut stream, &mut 0)
        })
        .collect()
}

fn ray() -> Ray {
    Ray::new(
        Vec3::new(0.0, 0.0, 1.5),
        Vec3::new(1.0, 0.1, 0.05).normalize(),
    )
}

/// Mean and variance of the red channel of `f(sample)`.
fn red_moments(xs: &[LiSample], f: impl Fn(&LiSample) -> Vec3) -> (f64, f64) {
    let v: Vec<f64> = xs.iter().map(|s| f(s).x as f64).collect();
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var)
}

#[test]
fn every_sample_sees_what_the_pane_mirrors_with_its_fresnel_weight() {
    // The front face's reflectance at the ray's angle to its normal (−x).
    let r_front = fr_dielectric(ray().d.x, 1.5);
    let split = samples(true, 256);
    for (k, s) in split.iter().enumerate() {
        let d = &s.denoise;
        // The red wall emits red only: green in the glass is never mirrored.
        assert_eq!(d.l_refl.y, 0.0, "sample {k}: {}", d.l_refl);
        // The reflection's own branch, and at most the back face's
        // reflection inside the pane beside it.
        assert!(
            d.rho_refl_hit.x >= r_front * (1.0 - 1e-5),
            "sample {k}: rho_refl_hit {} against R {r_front}",
            d.rho_refl_hit
        );
        assert!(
            d.l_refl.x >= r_front * (1.0 - 1e-5),
            "sample {k}: l_refl {} against R {r_front}",
            d.l_refl
        );
    }
    // Where the back face did not reflect inside the pane as well, the
    // glass shows the branch alone: the red wall at radiance 1, weighed
    // by R exactly.
    let alone: Vec<&LiSample> = split
        .iter()
        .filter(|s| (s.denoise.rho_refl_hit.x - r_front).abs() <= 1e-6)
        .collect();
    assert!(alone.len() > split.len() / 2, "{} alone", alone.len());
    for s in alone {
        let seen = s.denoise.l_refl.x / r_front;
        assert!((seen - 1.0).abs() < 1e-5, "seen {seen}");
    }
}

#[test]
fn splitting_the_pane_keeps_the_mean_and_lowers_the_noise() {
    const N: u32 = 4096;
    let split = samples(true, N);
    let chosen = samples(false, N);
    let (m_split, v_split) = red_moments(&split, |s| s.l);
    let (m_chosen, v_chosen) = red_moments(&chosen, |s| s.l);
    let se = ((v_split + v_chosen) / N as f64).sqrt();
    eprintln!(
        "red: split {m_split:.5} (var {v_split:.2e}), chosen {m_chosen:.5} \
         (var {v_chosen:.2e}), ± {se:.1e}"
    );
    // Independent estimates of one integral (different sample dimensions).
    assert!(
        (m_split - m_chosen).abs() < 4.0 * se,
        "split {m_split} vs chosen {m_chosen} ± {se}"
    );
    // The mirrored red wall is R ≈ 4 % of the red: a split that lost its
    // branch would be many standard errors off.
    let (m_refl, _) = red_moments(&split, |s| s.denoise.l_refl);
    assert!(m_refl > 10.0 * se, "mirrored {m_refl} vs ± {se}");
    // Which lobe a sample took at the front face is no longer noise (the
    // back face still chooses).
    assert!(
        v_split < 0.85 * v_chosen,
        "variance split {v_split} vs chosen {v_chosen}"
    );
}
