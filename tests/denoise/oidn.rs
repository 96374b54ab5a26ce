//! Intel Open Image Denoise as the surfaces' denoiser (`denoise::oidn`,
//! `[render] denoiser = "oidn"`, `--denoiser oidn`): noise removed and
//! the light kept on analytic images, an albedo edge kept sharp, the same
//! bytes on 1 and 2 threads, and a rendered wall closer to its converged
//! image than the plain estimate.
//!
//! These need the library (`pip install pyoidn`). Where it is missing they
//! say so and pass, unless `PARALLAX_REQUIRE_OIDN` is set: `.ci/run`
//! installs it and sets that, so CI always runs them.

use crate::common;

use common::render_inline;
use glam::Vec3;
use parallax::accel::Backend;
use parallax::denoise::oidn;

const W: usize = 64;
const H: usize = 48;

/// Whether OIDN runs here; panics when it must and does not.
pub(crate) fn available() -> bool {
    match oidn::check() {
        Ok(()) => true,
        Err(e) if std::env::var_os("PARALLAX_REQUIRE_OIDN").is_some() => {
            panic!("PARALLAX_REQUIRE_OIDN is set: {e}")
        }
        Err(e) => {
            eprintln!("skipped, Open Image Denoise is not installed: {e}");
            false
        }
    }
}

/// A Monte Carlo-like factor of mean 1 per pixel and channel: the mean of
/// `n` uniform [0, 2) draws from a fixed hash, so the image is the same in
/// every run.
fn noise(k: usize, c: usize, n: u32) -> f32 {
    let mut s = 0.0;
    for i in 0..n {
        let mut x =
            (k as u64 * 3 + c as u64) * 0x9E37_79B9_7F4A_7C15 + i as u64 * 0xD1B5_4A32_D192_ED03;
        x ^= x >> 29;
        x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x ^= x >> 32;
        s += 2.0 * (x >> 40) as f32 / (1u64 << 24) as f32;
    }
    s / n as f32
}

/// A flat wall of `albedo(i)` per column lit by `e`, its radiance times
/// the noise of 4 samples; albedo and normal clean.
fn noisy_wall(
    albedo: impl Fn(usize) -> Vec3,
    e: f32,
) -> (Vec<Vec3>, Vec<Vec3>, Vec<Vec3>, Vec<Vec3>) {
    let albedos: Vec<Vec3> = (0..W * H).map(|k| albedo(k % W)).collect();
    let clean: Vec<Vec3> = albedos.iter().map(|a| *a * e).collect();
    let noisy = clean
        .iter()
        .enumerate()
        .map(|(k, c)| *c * Vec3::new(noise(k, 0, 4), noise(k, 1, 4), noise(k, 2, 4)))
        .collect();
    (noisy, clean, albedos, vec![Vec3::Z; W * H])
}

fn rms(a: &[Vec3], b: &[Vec3]) -> f32 {
    let s: f32 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).length_squared())
        .sum();
    (s / a.len() as f32).sqrt()
}

fn mean(a: &[Vec3]) -> Vec3 {
    a.iter().copied().sum::<Vec3>() / a.len() as f32
}

#[test]
fn a_noisy_flat_wall_comes_out_flat_with_its_light() {
    if !available() {
        return;
    }
    let (mut img, clean, albedo, normal) = noisy_wall(|_| Vec3::new(0.3, 0.5, 0.7), 2.0);
    let before = rms(&img, &clean);
    oidn::denoise(&mut img, &albedo, &normal, W, H, 2).unwrap();
    let after = rms(&img, &clean);
    assert!(after < 0.1 * before, "rms {before} → {after}");
    let (m, want) = (mean(&img), mean(&clean));
    assert!(
        ((m - want) / want).abs().max_element() < 0.01,
        "mean {m} against {want}"
    );
}

#[test]
fn an_albedo_edge_stays_sharp() {
    if !available() {
        return;
    }
    let dark = Vec3::splat(0.1);
    let light = Vec3::splat(0.8);
    let side = |i: usize| if i < W / 2 { dark } else { light };
    let (mut img, _, albedo, normal) = noisy_wall(side, 1.0);
    oidn::denoise(&mut img, &albedo, &normal, W, H, 2).unwrap();
    // The column two pixels from the edge on each side, averaged down the
    // image, keeps its own level: light carried across would lift the dark
    // side by 8 % per 1 % of mixing (its residual noise is about 3 %).
    for i in [W / 2 - 2, W / 2 + 1] {
        let col: Vec<Vec3> = (4..H - 4).map(|j| img[j * W + i]).collect();
        let want = side(i);
        let rel = (mean(&col) - want) / want;
        assert!(
            rel.abs().max_element() < 0.05,
            "column {i}: {} against {want}",
            mean(&col)
        );
    }
}

#[test]
fn one_and_two_threads_give_the_same_bytes() {
    if !available() {
        return;
    }
    let (img, _, albedo, normal) = noisy_wall(|i| Vec3::splat(0.2 + 0.01 * i as f32), 3.0);
    let run = |threads| {
        let mut out = img.clone();
        oidn::denoise(&mut out, &albedo, &normal, W, H, threads).unwrap();
        out
    };
    let (one, two) = (run(1), run(2));
    assert!(
        one.iter()
            .zip(&two)
            .all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)),
        "1 and 2 threads differ"
    );
    assert_ne!(one, img, "the image was denoised");
}

/// A grey wall 10 m ahead under a grey sky, lit by a sun at 35° elevation
/// from the camera's side, so its light is direct, sky and bounce light.
const WALL: &str = "[sky]\nkind = \"gradient\"\nzenith = [0.4, 0.5, 0.7]\nhorizon = [0.6, 0.6, 0.6]\nground = [0.1, 0.1, 0.1]\n\
    [[light]]\nkind = \"sun\"\nelevation_deg = 35.0\nazimuth_deg = 160.0\nirradiance = [8.0, 7.6, 7.0]\n\
    [[material]]\nname = \"wall\"\nkind = \"diffuse\"\nalbedo = [0.6, 0.5, 0.4]\n\
    [[material]]\nname = \"floor\"\nkind = \"diffuse\"\nalbedo = [0.3, 0.3, 0.3]\n\
    [[object]]\nkind = \"box\"\nsize = [0.2, 8.0, 3.0]\nmaterial = \"wall\"\ntransform = { translate = [10.0, 0.0, 1.5] }\n\
    [[object]]\nkind = \"box\"\nsize = [30.0, 30.0, 0.2]\nmaterial = \"floor\"\ntransform = { translate = [10.0, 0.0, -0.1] }\n";

/// Pixels whose 3 × 3 neighbourhood lies on one surface (depth within
/// 2 %) or all on the sky: away from edges, where a few samples' coverage
/// sets the error of any denoiser.
fn interior(depth: &[f32], w: usize, h: usize) -> Vec<usize> {
    let same = |a: f32, b: f32| (a.is_infinite() && b.is_infinite()) || (a - b).abs() < 0.02 * a;
    common::interior(w, h, |k, n| same(depth[k], depth[n]))
}

#[test]
fn a_rendered_wall_comes_out_closer_to_its_converged_image() {
    if !available() {
        return;
    }
    let (w, h) = (48, 27);
    let left = |spp, keys: &str| render_inline(WALL, (w, h), (spp, 5, 4), keys, Backend::Bvh);
    let reference = left(1024, "filter_indirect = false\n");
    let keep = interior(&reference.out.left.depth_z_f32(), w as usize, h as usize);
    assert!(
        keep.len() > w as usize * h as usize / 2,
        "{} interior pixels",
        keep.len()
    );
    let pick = |r: &common::Rendered| -> Vec<Vec3> {
        keep.iter().map(|&k| r.out.images[0].rgb[k]).collect()
    };
    let truth = pick(&reference);
    let plain = pick(&left(4, "filter_indirect = false\n"));
    let oidn = left(4, "denoiser = \"oidn\"\n");
    assert_eq!(oidn.out.left, reference.out.left, "ground truth untouched");
    let oidn = pick(&oidn);
    let (e_plain, e_oidn) = (rms(&plain, &truth), rms(&oidn, &truth));
    assert!(
        e_oidn < 0.5 * e_plain,
        "rms against 1024 spp away from edges: plain {e_plain}, oidn {e_oidn}"
    );
    let (m, want) = (mean(&oidn), mean(&truth));
    assert!(
        ((m - want) / want).abs().max_element() < 0.01,
        "mean {m} against {want}"
    );
}
