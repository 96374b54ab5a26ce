//! The light along smooth glass's reflection (`denoise/direct.rs`
//! `filter_reflection`, `DenoiseSample::l_refl`): without the filters each
//! sample of a pane either reflects (seeing what the window mirrors) or
//! refracts, so a window's pixels are the share of reflected samples times
//! the mirrored light: sparkle. With them every sample traces both lobes
//! of the first pane, and the reflection, filtered as a ratio to its
//! Fresnel weight, shows the mirrored light smoothly.
//! A pane 5 m ahead filling the view, a black wall behind it, a white
//! constant sky: every pixel's light is reflected sky, about 2R/(1 + R).
//! Unit case: a pane mirroring stripes (the façades opposite) keeps them,
//! filtered against the reflected samples' own weight.

use crate::common;

use common::{mean_stderr, render_inline, Rendered};
use glam::Vec3;
use parallax::accel::Backend;
use parallax::denoise::{denoise_guided, DepthGuide, ViewInputs, Widths};
use parallax::film::Film;
use parallax::integrator::{DenoiseSample, DenoiseSum};

const W: u32 = 48;
const H: u32 = 27;

fn window_scene() -> String {
    "[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n\
     [[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 1.5\nroughness = 0.0\n\
     tint = [1.0, 1.0, 1.0]\n\
     [[material]]\nname = \"black\"\nkind = \"diffuse\"\nalbedo = [0.0, 0.0, 0.0]\n\
     [[object]]\nkind = \"box\"\nsize = [0.05, 30.0, 30.0]\nmaterial = \"glass\"\n\
     transform = { translate = [5.0, 0.0, 1.5] }\n\
     [[object]]\nkind = \"box\"\nsize = [0.2, 40.0, 40.0]\nmaterial = \"black\"\n\
     transform = { translate = [8.0, 0.0, 1.5] }\n"
        .to_string()
}

fn render_window(spp: u32, seed: u64, filter: bool) -> Rendered {
    let key = if filter {
        ""
    } else {
        "filter_indirect = false\n"
    };
    render_inline(&window_scene(), (W, H), (spp, seed, 5), key, Backend::Bvh)
}

fn green(r: &Rendered, k: usize) -> f64 {
    r.out.images[0].rgb[k].y as f64
}

#[test]
fn a_window_mirroring_the_sky_is_smooth_and_keeps_its_light() {
    let n = (W * H) as usize;
    let reference = render_window(1024, 7, false);
    let on = render_window(8, 3, true);
    let off = render_window(8, 3, false);
    let (m_ref, _) = mean_stderr(&(0..n).map(|k| green(&reference, k)).collect::<Vec<_>>());
    // Two faces of R ≈ 0.04 (more off-axis) mirror the white sky.
    assert!((0.07..0.12).contains(&m_ref), "reference mean {m_ref}");
    let mse = |r: &Rendered| {
        (0..n)
            .map(|k| (green(r, k) - green(&reference, k)).powi(2))
            .sum::<f64>()
            / n as f64
    };
    let (mse_on, mse_off) = (mse(&on), mse(&off));
    // Same sample streams: the filter moves light between pixels only.
    let diffs: Vec<f64> = (0..n).map(|k| green(&on, k) - green(&off, k)).collect();
    let (bias, se) = mean_stderr(&diffs);
    eprintln!(
        "window: MSE plain {mse_off:.3e}, filtered {mse_on:.3e} ({:.1}×); \
         filtered − plain {bias:.2e} ± {se:.1e} of mean {m_ref:.4}",
        mse_off / mse_on
    );
    // Per pixel: the share of pixels within 25 % of the reference's.
    let close = |r: &Rendered| {
        (0..n)
            .filter(|&k| (green(r, k) - green(&reference, k)).abs() < 0.25 * green(&reference, k))
            .count() as f64
            / n as f64
    };
    let (close_off, close_on) = (close(&off), close(&on));
    eprintln!("within 25 %: plain {close_off:.3}, filtered {close_on:.3}");
    // 8 samples at R ≈ 0.04: with the filter on every sample traces the
    // pane's reflection too (`PathContext::glass_lobes`), without it a
    // quarter of them reflect, so most plain pixels see the sky in two or
    // three. (Filtered: 36× and 95 % against the 1024-spp reference, whose
    // own noise at 256 spp held them to 20× and 85 %; no filter 1× and
    // 0 %.)
    assert!(mse_on * 25.0 < mse_off, "{mse_on} vs {mse_off}");
    assert!(close_on > 0.8, "{close_on} of pixels within 25 %");
    // The difference's own standard error is 2 % of the mean.
    assert!(
        bias.abs() < 0.01 * m_ref + 2.0 * se,
        "{bias} ± {se} of {m_ref}"
    );
}

/// A uniform number in [0, 1) without structure (a hash of k).
fn unit(k: u64) -> f32 {
    let mut x = (k + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    x ^= x >> 29;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 32;
    (x >> 40) as f32 / (1u64 << 24) as f32
}

/// A pane of Fresnel reflectance `R` filling a `w × h` view at 5 m,
/// mirroring `seen(i, j)` (grey radiance), sampled as the path tracer does:
/// per pixel `spp` samples, each reflecting with probability 1/4 and
/// weight 4R (seeing `seen` ±20 %), all recording R. Returns the film (all
/// reflected light) before and after the filter, and the truth R·seen.
fn filter_pane(
    (w, h): (usize, usize),
    spp: u32,
    seen: impl Fn(usize, usize) -> f32,
) -> (Film, Film, Vec<f32>) {
    const R: f32 = 0.05;
    let mut inputs = ViewInputs::new(w, h);
    let mut truth = Vec::with_capacity(w * h);
    for k in 0..w * h {
        let l = seen(k % w, k / w);
        truth.push(R * l);
        let mut sum = DenoiseSum::default();
        for s in 0..spp as u64 {
            let n = (k as u64 * spp as u64 + s) * 2;
            let mut d = DenoiseSample {
                rho_refl: Vec3::splat(R),
                ..DenoiseSample::default()
            };
            if unit(n) < 0.25 {
                let l_i = l * (0.8 + 0.4 * unit(n + 1));
                d.rho_refl_hit = Vec3::splat(4.0 * R);
                d.l_refl = d.rho_refl_hit * l_i;
            }
            sum.add(&d);
        }
        inputs.set_mean(k, &sum, spp as f32);
    }
    let mut film = Film {
        width: w,
        height: h,
        rgb: inputs.l_refl.clone(),
    };
    let before = film.clone();
    let (depth, opacity) = (vec![5.0; w * h], vec![0.0; w * h]);
    let guide = DepthGuide {
        depth_z: &depth,
        opacity: &opacity,
        normal: &[],
    };
    denoise_guided(&mut film, &inputs, &guide, &Widths::for_width(w));
    (before, film, truth)
}

#[test]
fn a_pane_keeps_the_stripes_it_mirrors_and_loses_the_sparkle() {
    // Vertical stripes two pixels wide, radiance 1 and 4, in the glass.
    let (w, h) = (48, 16);
    let stripe = |i: usize, _: usize| if (i / 2).is_multiple_of(2) { 1.0 } else { 4.0 };
    let (before, after, truth) = filter_pane((w, h), 16, stripe);
    let mse = |f: &Film| {
        f.rgb
            .iter()
            .zip(&truth)
            .map(|(p, t)| (p.y - t).powi(2) as f64)
            .sum::<f64>()
            / truth.len() as f64
    };
    let (mse_plain, mse_filtered) = (mse(&before), mse(&after));
    // The stripes' contrast: mean bright over mean dark (truth 4).
    let level = |f: &Film, bright: bool| {
        let v: Vec<f32> = (0..w * h)
            .filter(|&k| (stripe(k % w, 0) > 2.0) == bright)
            .map(|k| f.rgb[k].y)
            .collect();
        v.iter().sum::<f32>() / v.len() as f32
    };
    let contrast = level(&after, true) / level(&after, false);
    let mean = |v: &mut dyn Iterator<Item = f32>| v.map(|x| x as f64).sum::<f64>() / (w * h) as f64;
    let (m_after, m_truth) = (
        mean(&mut after.rgb.iter().map(|p| p.y)),
        mean(&mut truth.iter().copied()),
    );
    eprintln!(
        "striped pane: MSE plain {mse_plain:.3e}, filtered {mse_filtered:.3e} ({:.1}×); \
         contrast {contrast:.3} (4); mean {m_after:.5} vs {m_truth:.5}",
        mse_plain / mse_filtered
    );
    // 16 samples, about 4 reflected: the sparkle (which samples reflected)
    // is most of the plain error; the ±20 % of the seen radiance is left.
    assert!(
        mse_filtered * 10.0 < mse_plain,
        "{mse_filtered} vs {mse_plain}"
    );
    // Stripes two pixels wide survive a 61-pixel kernel: a 1-to-4 step is
    // far above the reflected samples' noise. (Filtered: 46×, contrast
    // 3.69; at direct light's edge-stopping width 22×, 3.33; against the
    // Fresnel reflectance of every sample, as direct light against its
    // albedo, 1.0×: the sparkle stops every tap.)
    assert!(contrast > 3.6 && contrast < 4.2, "contrast {contrast}");
    assert!(
        (m_after / m_truth - 1.0).abs() < 0.01,
        "{m_after} vs {m_truth}"
    );
}

#[test]
fn a_pixel_with_no_reflected_sample_takes_its_neighbours_radiance() {
    // One sample per pixel: three quarters of the pixels saw no reflection
    // and keep none of it unfiltered; filtered, every pixel of a uniform
    // pane shows R · 2 within the samples' ±20 %.
    let (w, h) = (24, 12);
    let (before, after, truth) = filter_pane((w, h), 1, |_, _| 2.0);
    let dark = before.rgb.iter().filter(|p| p.y == 0.0).count();
    assert!(dark > w * h / 2, "{dark} pixels without a reflection");
    for (k, (p, t)) in after.rgb.iter().zip(&truth).enumerate() {
        assert!((p.y / t - 1.0).abs() < 0.2, "pixel {k}: {} vs {t}", p.y);
    }
}
