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

/// The camera and the pane 5 m ahead of it, facing it.
const PANE: &str = r#"
[camera]
width = 4
height = 4
hfov_deg = 60.0
position = [0.0, 0.0, 1.5]
[[material]]
name = "glass"
kind = "dielectric"
ior = 1.5
[[object]]
kind = "box"
size = [0.05, 30.0, 30.0]
material = "glass"
transform = { translate = [5.0, 0.0, 1.5] }
"#;

/// Behind the pane a grey emitting wall, behind the camera a red one.
const WALLS: &str = r#"
[sky]
kind = "constant"
le = [0.0, 0.0, 0.0]
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
        format!("{PANE}{WALLS}")
    } else {
        format!("{PANE}{WALLS}[render]\nfilter_indirect = false\n")
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
        let mirrored = d.l_refl + d.l_refl_sharp;
        assert_eq!(mirrored.y, 0.0, "sample {k}: {mirrored}");
        // The reflection's own branch, and at most the back face's
        // reflection inside the pane beside it.
        assert!(
            d.rho_refl_hit.x >= r_front * (1.0 - 1e-5),
            "sample {k}: rho_refl_hit {} against R {r_front}",
            d.rho_refl_hit
        );
        assert!(
            mirrored.x >= r_front * (1.0 - 1e-5),
            "sample {k}: mirrored {mirrored} against R {r_front}"
        );
    }
    // Where the back face did not reflect inside the pane as well, the
    // glass shows the branch alone: the red wall at radiance 1, weighed
    // by R exactly, seen through the reflection alone, so sharp: none of
    // it is left to the filter.
    let alone: Vec<&LiSample> = split
        .iter()
        .filter(|s| (s.denoise.rho_refl_hit.x - r_front).abs() <= 1e-6)
        .collect();
    assert!(alone.len() > split.len() / 2, "{} alone", alone.len());
    for s in alone {
        let seen = s.denoise.l_refl_sharp.x / r_front;
        assert!((seen - 1.0).abs() < 1e-5, "seen {seen}");
        assert_eq!(s.denoise.l_refl, glam::Vec3::ZERO);
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
    let (m_refl, _) = red_moments(&split, |s| s.denoise.l_refl + s.denoise.l_refl_sharp);
    assert!(m_refl > 10.0 * se, "mirrored {m_refl} vs ± {se}");
    // Which lobe a sample took at the front face is no longer noise (the
    // back face still chooses).
    assert!(
        v_split < 0.85 * v_chosen,
        "variance split {v_split} vs chosen {v_chosen}"
    );
}

/// The same pane mirroring a sunlit floor behind the camera under a
/// constant sky, a lamp panel above it: what the reflection shows sharp is
/// the floor's sun light alone, the same on every sample; the panel's
/// next-event light and the sky found by the floor's bounce (sampled, so
/// noisy) are left to the filter.
#[test]
fn the_sun_on_what_the_pane_mirrors_is_left_sharp_and_sampled_light_to_the_filter() {
    const E_SUN: f32 = 1000.0;
    const ALBEDO: f32 = 0.5;
    const ELEVATION_DEG: f32 = 45.0;
    let src = format!(
        r#"{PANE}
[sky]
kind = "constant"
le = [30.0, 30.0, 30.0]
[[light]]
kind = "sun"
elevation_deg = {ELEVATION_DEG}
azimuth_deg = 180.0
irradiance = [{E_SUN}, {E_SUN}, {E_SUN}]
[[material]]
name = "floor"
kind = "diffuse"
albedo = [{ALBEDO}, {ALBEDO}, {ALBEDO}]
[[material]]
name = "lamp"
kind = "emissive"
radiance = [500.0, 500.0, 500.0]
[[object]]
kind = "quad"
size = [400.0, 400.0]
material = "floor"
[[object]]
kind = "quad"
size = [2.0, 2.0]
material = "lamp"
transform = {{ translate = [-5.0, 0.5, 6.0], rotate_deg = [180.0, 0.0, 0.0] }}
"#
    );
    let (scene, accel) = built(&src);
    let shading = Shading::new(&scene, &accel);
    let ctx = shading.context(4);
    let key = StreamKey {
        seed: 5,
        frame: 0,
        view: 0,
    };
    // Down at the pane: its reflection meets the floor 5 m behind the
    // camera, lit by the sun from behind the camera (azimuth 180°).
    let d = Vec3::new(1.0, 0.1, -0.1).normalize();
    let r_front = fr_dielectric(d.x, 1.5);
    let floor_sun = ALBEDO / std::f32::consts::PI * E_SUN * ELEVATION_DEG.to_radians().sin();
    let n = 512;
    let (mut sharp, mut rest) = (Vec::new(), Vec::new());
    for k in 0..n {
        let mut stream = SampleStream::new(key, 0, 0, k);
        let s = ctx.li(
            Ray::new(Vec3::new(0.0, 0.0, 1.5), d),
            Default::default(),
            &mut stream,
            &mut 0,
        );
        // Where the back face also reflected inside the pane, that light
        // is the filter's: only the branch alone is checked.
        if (s.denoise.rho_refl_hit.x - r_front).abs() <= 1e-6 {
            sharp.push(s.denoise.l_refl_sharp.y as f64);
            rest.push(s.denoise.l_refl.y as f64);
        }
    }
    assert!(sharp.len() > n as usize / 2, "{} alone", sharp.len());
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let expected = (r_front * floor_sun) as f64;
    for &x in &sharp {
        // The sun's disc spans 0.5°: its cosine hardly varies.
        assert!(
            (x / expected - 1.0).abs() < 0.01,
            "sharp {x} against {expected}"
        );
    }
    // The lamp's light on the floor (about 8 % of the sun's) and the sky's
    // (up to albedo × 30 where the pane does not hide it) are sampled:
    // noisy, and the filter's.
    let (m_rest, m_sharp) = (mean(&rest), mean(&sharp));
    let spread = rest.iter().map(|x| (x - m_rest).abs()).sum::<f64>() / rest.len() as f64;
    eprintln!("sharp {m_sharp:.4} (expected {expected:.4}), rest {m_rest:.4} ± {spread:.4}");
    assert!(
        m_rest > 0.1 * expected && m_rest < 0.4 * expected,
        "rest {m_rest}"
    );
    assert!(spread > 0.1 * m_rest, "rest's spread {spread} of {m_rest}");
}
