//! The direct-light filter (`denoise/direct.rs`, on with `[render]
//! filter_indirect`): the first diffuse surface's next-event light, filtered
//! as a ratio to its albedo with an edge-stopping weight on its own noise.
//! Unit cases on a flat surface: a sun shadow's edge stays sharp while the
//! grain of the shade goes, and neither a depth step nor the seam between
//! glossy and Lambertian pixels leaks whatever the noise; lamp light
//! sampled as a next-event estimate does (16 samples, a hit or nothing):
//! a bright noisy surface does not bleed into a dark one beside it, and
//! sparse speckles on a uniform surface are still spread.
//! Through the renderer, a checker street lit by six lamps behind a wall:
//! less error against a converged plain render, the image mean kept
//! (nothing lost as fireflies), and the filtered noise of the left and
//! right views uncorrelated where both see the same point.

use crate::common;

use common::{checker_ground, mean_stderr, render_inline, Rendered};
use glam::Vec3;
use parallax::accel::Backend;
use parallax::denoise::{denoise_guided, DepthGuide, ViewInputs, Widths};
use parallax::film::Film;

/// A deterministic ±1 pattern without structure (a hash of k).
fn wiggle(k: usize) -> f32 {
    let mut x = (k as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    x ^= x >> 29;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 32;
    (x % 2001) as f32 / 1000.0 - 1.0
}

/// Filters `layer` (direct light only) over one flat surface of depths
/// `depth` and normal +z: the film before (all direct light) and after.
fn filter_direct_only(layer: &ViewInputs, depth: &[f32]) -> (Film, Film) {
    let (w, h) = (layer.width, layer.height);
    let mut film = Film {
        width: w,
        height: h,
        rgb: layer.l_direct.clone(),
    };
    let before = film.clone();
    let (opacity, normal) = (vec![0.0; w * h], vec![Vec3::Z; w * h]);
    let guide = DepthGuide {
        depth_z: depth,
        opacity: &opacity,
        normal: &normal,
    };
    denoise_guided(&mut film, layer, &guide, &Widths::for_width(w));
    (before, film)
}

/// Std of `v` about its mean.
fn spread(v: &[f32]) -> f32 {
    let m = v.iter().sum::<f32>() / v.len() as f32;
    (v.iter().map(|x| (x - m).powi(2)).sum::<f32>() / v.len() as f32).sqrt()
}

#[test]
fn a_sun_shadow_edge_stays_sharp_while_the_shade_grain_goes() {
    // One plane at 10 m, albedo 0.5: the left half in sun, light per unit
    // albedo 1 with little noise (σ 0.005); the right half in shade, 0.1
    // with ±50 % grain (its variance says so). Filtered, the shade keeps its
    // level up to the edge and loses most of its grain, the sun keeps 1.
    let (w, h) = (48, 24);
    let mut layer = ViewInputs::new(w, h);
    let rho = Vec3::splat(0.5);
    layer.rho.fill(rho);
    layer.rho_direct.fill(rho);
    let sun = |k: usize| k % w < w / 2;
    for k in 0..w * h {
        let (e, sd) = if sun(k) {
            (1.0 + 0.005 * wiggle(k), 0.005)
        } else {
            (0.1 * (1.0 + 0.5 * wiggle(k)), 0.05 / 3f32.sqrt())
        };
        layer.l_direct[k] = rho * e;
        layer.var_direct[k] = (0.5 * sd) * (0.5 * sd);
    }
    let (before, after) = filter_direct_only(&layer, &vec![10.0; w * h]);
    let e = |f: &Film, k: usize| f.rgb[k].y / 0.5;
    let shade: Vec<usize> = (0..w * h).filter(|&k| !sun(k)).collect();
    for k in 0..w * h {
        if sun(k) {
            assert!(
                (e(&after, k) - 1.0).abs() < 0.01,
                "sun pixel {k}: {}",
                e(&after, k)
            );
        } else {
            // Light from the sunlit side would lift the shade toward 0.5.
            assert!(e(&after, k) < 0.16, "shade pixel {k}: {}", e(&after, k));
        }
    }
    // The shade pixels right beside the edge included.
    let edge: Vec<f32> = (0..h).map(|j| e(&after, j * w + w / 2)).collect();
    let edge_mean = edge.iter().sum::<f32>() / h as f32;
    assert!((edge_mean - 0.1).abs() < 0.01, "edge column {edge_mean}");
    let grain = |f: &Film| spread(&shade.iter().map(|&k| e(f, k)).collect::<Vec<_>>());
    let (g0, g1) = (grain(&before), grain(&after));
    eprintln!("shade grain {g0:.4} -> {g1:.4}, edge column mean {edge_mean:.4}");
    assert!(g1 * 3.0 < g0, "{g0} -> {g1}");
    // The shade's mean is kept.
    let mean = |f: &Film| shade.iter().map(|&k| e(f, k)).sum::<f32>() / shade.len() as f32;
    assert!((mean(&after) / mean(&before) - 1.0).abs() < 0.01);
}

#[test]
fn a_depth_step_never_leaks_however_noisy() {
    // Near half (5 m) lit 1, far half (20 m) dark 0.02, both claiming huge
    // noise, so the luminance weight lets everything through: only the
    // depth keeps them apart, and the far side must keep its light exactly.
    let (w, h) = (32, 16);
    let mut layer = ViewInputs::new(w, h);
    layer.rho.fill(Vec3::splat(0.5));
    layer.rho_direct.fill(Vec3::splat(0.5));
    let near = |k: usize| k % w < w / 2;
    let depth: Vec<f32> = (0..w * h)
        .map(|k| if near(k) { 5.0 } else { 20.0 })
        .collect();
    for k in 0..w * h {
        let e = if near(k) { 1.0 } else { 0.02 };
        layer.l_direct[k] = Vec3::splat(0.5 * e);
        layer.var_direct[k] = 100.0;
    }
    let (before, after) = filter_direct_only(&layer, &depth);
    for k in 0..w * h {
        let (a, b) = (before.rgb[k].y, after.rgb[k].y);
        assert!((a - b).abs() <= 1e-6 * a, "pixel {k}: {a} -> {b}");
    }
}

#[test]
fn glossy_and_lambertian_pixels_stay_apart() {
    // One plane at 10 m: the left half glossy paint (all its light handed
    // over, 1 per unit albedo estimate), the right half Lambertian (0.3),
    // both claiming huge noise: only the glossy share keeps them apart.
    let (w, h) = (32, 16);
    let mut layer = ViewInputs::new(w, h);
    layer.rho_direct.fill(Vec3::splat(0.5));
    let paint = |k: usize| k % w < w / 2;
    for k in 0..w * h {
        layer.glossy[k] = if paint(k) { 1.0 } else { 0.0 };
        layer.l_direct[k] = Vec3::splat(if paint(k) { 0.5 } else { 0.15 });
        layer.var_direct[k] = 100.0;
    }
    let (before, after) = filter_direct_only(&layer, &vec![10.0; w * h]);
    for k in 0..w * h {
        let (a, b) = (before.rgb[k].y, after.rgb[k].y);
        assert!((a - b).abs() <= 1e-6 * a, "pixel {k}: {a} -> {b}");
    }
}

/// A deterministic uniform draw in [0, 1) from (k, s).
fn draw(k: usize, s: usize) -> f32 {
    (wiggle(k * 97 + s * 7919 + 13) + 1.0) / 2.0
}

/// A pixel's 16 samples of lamp light as a next-event estimate sees it:
/// `hit` with probability `p` each, else nothing; (mean, variance of the
/// mean from the sample moments), as the path tracer hands them over.
fn lamp_pixel(k: usize, p: f32, hit: f32) -> (f32, f32) {
    const N: usize = 16;
    let hits = (0..N).filter(|&s| draw(k, s) < p).count() as f32;
    let mean = hits * hit / N as f32;
    let second = hits * hit * hit / N as f32;
    (mean, (second - mean * mean).max(0.0) / (N as f32 - 1.0))
}

/// A flat surface (albedo 0.5, 10 m) whose light per unit albedo at pixel
/// k is `light(k)` = (mean, variance of the mean).
fn lit_plane(w: usize, h: usize, light: impl Fn(usize) -> (f32, f32)) -> ViewInputs {
    let mut layer = ViewInputs::new(w, h);
    let rho = Vec3::splat(0.5);
    layer.rho.fill(rho);
    layer.rho_direct.fill(rho);
    for k in 0..w * h {
        let (e, var) = light(k);
        layer.l_direct[k] = rho * e;
        layer.var_direct[k] = 0.25 * var;
    }
    layer
}

#[test]
fn a_noisy_bright_surface_does_not_bleed_into_a_dark_one() {
    // Top half dark (0.002 per unit albedo, ±10 % grain its variance
    // says), bottom half lit by a lamp that 16 samples hit 4 times on
    // average (0.25 × 10: mean 2.5, each pixel's mean ±50 %): a dark band
    // under a lamp-lit car boot. The dark half must keep its light, the
    // row at the edge included, while the lit half loses its grain.
    let (w, h) = (48, 24);
    let dark = |k: usize| k / w < h / 2;
    let layer = lit_plane(w, h, |k| {
        if dark(k) {
            (
                0.002 * (1.0 + 0.1 * wiggle(k)),
                (0.0002f32 / 3f32.sqrt()).powi(2),
            )
        } else {
            lamp_pixel(k, 0.25, 10.0)
        }
    });
    let (before, after) = filter_direct_only(&layer, &vec![10.0; w * h]);
    let e = |f: &Film, k: usize| f.rgb[k].y / 0.5;
    let mean = |f: &Film, ks: &[usize]| ks.iter().map(|&k| e(f, k)).sum::<f32>() / ks.len() as f32;
    let dark_px: Vec<usize> = (0..w * h).filter(|&k| dark(k)).collect();
    let edge_row: Vec<usize> = (0..w).map(|i| (h / 2 - 1) * w + i).collect();
    let lit_px: Vec<usize> = (0..w * h).filter(|&k| !dark(k)).collect();
    let (d0, d1) = (mean(&before, &dark_px), mean(&after, &dark_px));
    let edge = mean(&after, &edge_row);
    let grain = |f: &Film| spread(&lit_px.iter().map(|&k| e(f, k)).collect::<Vec<_>>());
    eprintln!(
        "dark half {d0:.5} -> {d1:.5}, edge row {edge:.5}; lit mean {:.3} -> {:.3}, grain {:.3} -> {:.3}",
        mean(&before, &lit_px),
        mean(&after, &lit_px),
        grain(&before),
        grain(&after)
    );
    // The symmetric test alone: 0.0547 and 0.497 (×27, ×250).
    assert!((d1 / d0 - 1.0).abs() < 0.5, "dark half {d0} -> {d1}");
    assert!(edge < 0.002 * 10.0, "edge row {edge}");
    assert!(grain(&after) * 2.0 < grain(&before));
    let (l0, l1) = (mean(&before, &lit_px), mean(&after, &lit_px));
    assert!((l1 / l0 - 1.0).abs() < 0.02, "lit half {l0} -> {l1}");
}

#[test]
fn sparse_lamp_light_on_a_uniform_surface_is_still_spread() {
    // A façade that 16 samples hit once on average (p 1/16, 1.6 each:
    // mean 0.1): a third of its pixels black, the rest speckles. Each
    // pixel's variance, alone, says a black pixel is noise-free; the
    // filter must still spread the speckles over it (error down ≥ 8×),
    // keeping the mean (no light lost as unspread fireflies; the
    // normalised weights move 1 % here, as with the symmetric test alone)
    // and leaving no black pixel.
    let (w, h) = (48, 24);
    let layer = lit_plane(w, h, |k| lamp_pixel(k, 1.0 / 16.0, 1.6));
    let (before, after) = filter_direct_only(&layer, &vec![10.0; w * h]);
    let e: Vec<(f32, f32)> = (0..w * h)
        .map(|k| (before.rgb[k].y / 0.5, after.rgb[k].y / 0.5))
        .collect();
    let black = e.iter().filter(|v| v.0 == 0.0).count();
    assert!(black > w * h / 5, "{black} black pixels");
    let mean = |f: fn(&(f32, f32)) -> f32| e.iter().map(f).sum::<f32>() / e.len() as f32;
    let (m0, m1) = (mean(|v| v.0), mean(|v| v.1));
    let err = |f: fn(&(f32, f32)) -> f32| {
        (e.iter().map(|v| (f(v) - 0.1).powi(2)).sum::<f32>() / e.len() as f32).sqrt()
    };
    let (r0, r1) = (err(|v| v.0), err(|v| v.1));
    let darkest = e.iter().map(|v| v.1).fold(f32::INFINITY, f32::min);
    eprintln!("mean {m0:.4} -> {m1:.4}, rms error {r0:.4} -> {r1:.4}, darkest {darkest:.4}");
    assert!((m1 / m0 - 1.0).abs() < 0.02, "mean {m0} -> {m1}");
    assert!(r1 * 8.0 < r0, "rms error {r0} -> {r1}");
    assert!(darkest > 0.03, "a pixel left at {darkest}");
}

const W: u32 = 64;
const H: u32 = 36;

/// A checker street (albedos 0.3 and 0.7) under a black sky, lit by six
/// lamps on both sides, a wall on the left casting their shadows: direct
/// light only, and noisy (one lamp chosen per sample).
fn lamp_street() -> String {
    let mut s = String::from("[sky]\nkind = \"constant\"\nle = [0.0, 0.0, 0.0]\n");
    for (k, (x, y)) in [
        (6.0, 3.0),
        (9.0, -4.0),
        (14.0, 2.5),
        (18.0, -3.5),
        (24.0, 4.0),
        (30.0, -2.0),
    ]
    .iter()
    .enumerate()
    {
        let i = 60.0 + 20.0 * k as f64;
        s += &format!(
            "[[light]]\nkind = \"point\"\nposition = [{x:?}, {y:?}, 4.5]\nintensity = [{i:?}, {i:?}, {i:?}]\n"
        );
    }
    s += "[[material]]\nname = \"wall\"\nkind = \"diffuse\"\nalbedo = [0.6, 0.6, 0.6]\n\
        [[object]]\nkind = \"box\"\nsize = [14.0, 0.3, 3.0]\nmaterial = \"wall\"\n\
        transform = { translate = [16.0, 1.5, 1.5] }\n";
    s + &checker_ground([0.3, 0.7])
}

/// The filters' key in `[render]`: on (parallax's), off, Open Image
/// Denoise, or the mean of the two.
const ON: &str = "";
const OFF: &str = "filter_indirect = false\n";
const OIDN: &str = "denoiser = \"oidn\"\n";
const BLEND: &str = "denoiser = \"blend\"\n";

fn render_street(spp: u32, seed: u64, keys: &str) -> Rendered {
    render_inline(
        &lamp_street(),
        (W, H),
        (spp, seed, 2),
        keys,
        Backend::default_backend(),
    )
}

/// Green channel of view `v` at pixel `k`.
fn green(r: &Rendered, v: usize, k: usize) -> f64 {
    r.out.images[v].rgb[k].y as f64
}

#[test]
fn lamp_light_has_less_error_keeps_its_mean_and_views_stay_independent() {
    lamp_street_against_its_reference(ON);
}

/// The same with Open Image Denoise (`tests/denoise/oidn.rs` on when it
/// runs here).
#[test]
fn with_open_image_denoise_too() {
    if super::oidn::available() {
        lamp_street_against_its_reference(OIDN);
    }
}

/// The same with the mean of the two denoisers.
#[test]
fn with_the_blend_of_both_too() {
    if super::oidn::available() {
        lamp_street_against_its_reference(BLEND);
    }
}

/// The lamp street at 8 spp denoised with `keys` against 512 spp plain:
/// less error, the same mean as the plain render of the same streams, and
/// no correlation between the views' remaining noise.
fn lamp_street_against_its_reference(keys: &str) {
    let reference = render_street(512, 77, OFF);
    let on = render_street(8, 3, keys);
    let off = render_street(8, 3, OFF);
    let n = (W * H) as usize;
    let lit = lit_pixels(&reference);
    let mse = |r: &Rendered| lit_mse(r, &reference, &lit);
    let (mse_on, mse_off) = (mse(&on), mse(&off));
    // Same streams on and off: the filter moves light, it must keep the
    // image's mean (a firefly dropped would lower it).
    let diffs: Vec<f64> = (0..n)
        .map(|k| green(&on, 0, k) - green(&off, 0, k))
        .collect();
    let (bias, se) = mean_stderr(&diffs);
    let (m_ref, _) = mean_stderr(&(0..n).map(|k| green(&reference, 0, k)).collect::<Vec<_>>());
    // The views' noise: the difference of two filtered renders of other
    // sample seeds (what the filter leaves, without its deterministic part,
    // which both views share as the scene does), pooled over 32 pairs: the
    // filter's footprint leaves few independent pixels in one small image.
    let pairs: Vec<(Rendered, Rendered)> = (0..32)
        .map(|p| {
            (
                render_street(8, 100 + 2 * p, keys),
                render_street(8, 101 + 2 * p, keys),
            )
        })
        .collect();
    let noise = pooled_correlation(
        &pairs,
        |p, v, k| green(&pairs[p].0, v, k) - green(&pairs[p].1, v, k),
        &on,
    );
    // The same with the right view's noise from the next pair: zero by
    // construction, so its size is the estimate's own spread.
    let control = pooled_correlation(
        &pairs,
        |p, v, k| {
            let q = if v == 0 { p } else { (p + 1) % pairs.len() };
            green(&pairs[q].0, v, k) - green(&pairs[q].1, v, k)
        },
        &on,
    );
    let plain = residual_correlation(|v, k| green(&off, v, k) - green(&reference, v, k), &on);
    let vs_ref = residual_correlation(|v, k| green(&on, v, k) - green(&reference, v, k), &on);
    eprintln!(
        "{} lit pixels: MSE plain {mse_off:.3e}, filtered {mse_on:.3e} ({:.1}×); \
         filtered − plain {bias:.2e} ± {se:.1e} of mean {m_ref:.4}; L/R correlation of the \
         filtered noise {noise:.4} (unpaired control {control:.4}), of residuals vs the \
         reference: plain {plain:.4}, filtered {vs_ref:.4}",
        lit.len(),
        mse_off / mse_on
    );
    assert!(mse_on * 1.5 < mse_off, "{mse_on} vs {mse_off}");
    assert!(bias.abs() < 0.01 * m_ref, "{bias} of {m_ref}");
    assert!(noise.abs() < 0.05, "L/R noise correlation {noise}");
}

/// The left view's pixels that the reference lights (more than a third).
fn lit_pixels(reference: &Rendered) -> Vec<usize> {
    let n = (W * H) as usize;
    let lit: Vec<usize> = (0..n).filter(|&k| green(reference, 0, k) > 0.0).collect();
    assert!(lit.len() > n / 3, "{} lit pixels", lit.len());
    lit
}

/// Mean squared error of `r`'s left view against `reference`'s over `lit`.
fn lit_mse(r: &Rendered, reference: &Rendered, lit: &[usize]) -> f64 {
    lit.iter()
        .map(|&k| (green(r, 0, k) - green(reference, 0, k)).powi(2))
        .sum::<f64>()
        / lit.len() as f64
}

/// The blend is the mean of the two denoisers' images of the same samples,
/// and its error is below either's (MSE measured: parallax 2.27, OIDN 1.61,
/// blend 1.49 × 10⁻³).
#[test]
fn the_blend_is_the_mean_of_both_and_closer_than_either() {
    if !super::oidn::available() {
        return;
    }
    let reference = render_street(512, 77, OFF);
    let [own, oidn, blend] = [ON, OIDN, BLEND].map(|keys| render_street(8, 3, keys));
    for k in 0..(W * H) as usize {
        let (o, d, b) = (
            own.out.images[0].rgb[k],
            oidn.out.images[0].rgb[k],
            blend.out.images[0].rgb[k],
        );
        let mean = 0.5 * (o + d);
        assert!(
            (b - mean).abs().max_element() <= 1e-5 * mean.max_element(),
            "pixel {k}: blend {b} against the mean {mean} of {o} and {d}"
        );
    }
    let lit = lit_pixels(&reference);
    let [e_own, e_oidn, e_blend] = [&own, &oidn, &blend].map(|r| lit_mse(r, &reference, &lit));
    assert!(
        e_blend < e_own && e_blend < e_oidn,
        "MSE against 512 spp: parallax {e_own:.3e}, oidn {e_oidn:.3e}, blend {e_blend:.3e}"
    );
}

/// Correlation over the left view's non-occluded surface pixels (of `r`'s
/// ground truth) of `res(0, k)` and of the right view's `res(1, ·)` warped
/// to the left pixel k by the exact disparity (x_R = x_L − d, linear between
/// the two nearest right pixels).
fn residual_correlation(res: impl Fn(usize, usize) -> f64, r: &Rendered) -> f64 {
    let (mut a, mut c) = (Vec::new(), Vec::new());
    matched_residuals(&res, r, &mut a, &mut c);
    correlation(&a, &c)
}

/// [`residual_correlation`] pooled over `pairs` (`res(pair, view, k)`).
fn pooled_correlation<T>(
    pairs: &[T],
    res: impl Fn(usize, usize, usize) -> f64,
    r: &Rendered,
) -> f64 {
    let (mut a, mut c) = (Vec::new(), Vec::new());
    for p in 0..pairs.len() {
        matched_residuals(&|v, k| res(p, v, k), r, &mut a, &mut c);
    }
    correlation(&a, &c)
}

/// Appends the left residual and the warped right residual of every
/// non-occluded left pixel of `r` to `a` and `c`.
fn matched_residuals(
    res: &dyn Fn(usize, usize) -> f64,
    r: &Rendered,
    a: &mut Vec<f64>,
    c: &mut Vec<f64>,
) {
    let (w, h) = (W as usize, H as usize);
    let b = &r.out.baselines[0];
    let start = a.len();
    for j in 0..h {
        for i in 0..w {
            let k = j * w + i;
            let d = b.disparity_left[k];
            if b.occlusion[k] != 0 || !d.is_finite() || d <= 0.0 {
                continue;
            }
            let x = i as f32 - d;
            let (x0, t) = (x.floor(), x - x.floor());
            if x0 < 0.0 || x0 as usize + 1 >= w {
                continue;
            }
            let k0 = j * w + x0 as usize;
            a.push(res(0, k));
            c.push(res(1, k0) * (1.0 - t as f64) + res(1, k0 + 1) * t as f64);
        }
    }
    assert!(a.len() - start > 500, "{} matched pixels", a.len() - start);
}

/// Pearson correlation of `a` and `c`.
fn correlation(a: &[f64], c: &[f64]) -> f64 {
    let (ma, _) = mean_stderr(a);
    let (mc, _) = mean_stderr(c);
    let cov: f64 = a.iter().zip(c).map(|(x, y)| (x - ma) * (y - mc)).sum();
    let va: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
    let vc: f64 = c.iter().map(|y| (y - mc).powi(2)).sum();
    cov / (va * vc).sqrt()
}
