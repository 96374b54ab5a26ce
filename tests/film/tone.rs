//! Film: auto exposure (Reinhard 2002 log average to middle grey), the ACES
//! filmic tone curve, the sRGB OETF and 8-bit quantisation.

use glam::Vec3;
use parallax::film::*;

#[test]
fn auto_exposure_maps_uniform_grey_of_any_level_to_middle_grey() {
    for level in [1e-4f32, 0.01, 0.18, 1.0, 37.5, 1e4] {
        let film = Film::uniform(31, 17, Vec3::splat(level));
        let scale = auto_exposure(&film);
        let exposed = scale * level;
        assert!(
            (exposed - MIDDLE_GREY).abs() < 1e-5,
            "level {level}: {exposed}"
        );
    }
}

#[test]
fn auto_exposure_is_scale_invariant() {
    // A textured film: exposure(k·film) = exposure(film) / k.
    let mut film = Film::new(40, 30);
    for j in 0..30 {
        for i in 0..40 {
            let v = 0.01 + (i * j) as f32 * 0.003 + if (i + j) % 5 == 0 { 0.0 } else { 0.2 };
            film.set(i, j, Vec3::new(v, v * 0.5, v * 2.0));
        }
    }
    let base = auto_exposure(&film);
    for k in [1e-3f32, 0.5, 8.0, 1e3] {
        let mut scaled = film.clone();
        scaled.rgb.iter_mut().for_each(|p| *p *= k);
        let s = auto_exposure(&scaled);
        assert!((s * k / base - 1.0).abs() < 1e-4, "k {k}: {s} vs {base}");
    }
}

#[test]
fn auto_exposure_of_black_film_is_one() {
    assert_eq!(auto_exposure(&Film::new(8, 8)), 1.0);
    assert_eq!(exposure_ev(auto_exposure(&Film::new(8, 8))), 0.0);
    // Black with a few fireflies (< 1% of pixels) stays at scale 1.
    let mut film = Film::new(100, 100);
    for k in 0..5 {
        film.rgb[k * 1999] = Vec3::splat(1e6);
    }
    assert_eq!(auto_exposure(&film), 1.0);
}

#[test]
fn auto_exposure_ignores_non_finite_pixels() {
    let mut film = Film::uniform(10, 10, Vec3::splat(2.0));
    film.rgb[3] = Vec3::splat(f32::NAN);
    film.rgb[4] = Vec3::new(f32::INFINITY, 0.0, 0.0);
    let scale = auto_exposure(&film);
    assert!((scale * 2.0 - MIDDLE_GREY).abs() < 1e-5, "{scale}");
    let all_nan = Film::uniform(4, 4, Vec3::splat(f32::NAN));
    assert_eq!(auto_exposure(&all_nan), 1.0);
}

#[test]
fn auto_exposure_ignores_a_few_fireflies() {
    // 10 of 10,000 pixels 2e5× brighter: capped at the 99th percentile (the
    // grey level itself), they leave the exposure as it was; uncapped, each
    // would lift its block's mean 8000-fold (0.32 EV in all).
    let grey = Film::uniform(100, 100, Vec3::splat(0.5));
    let mut spiky = grey.clone();
    for k in 0..10 {
        spiky.rgb[k * 997] = Vec3::splat(1e5);
    }
    let (a, b) = (auto_exposure(&grey), auto_exposure(&spiky));
    let ev_shift = (exposure_ev(a) - exposure_ev(b)).abs();
    assert!(ev_shift < 1e-5, "shift {ev_shift} EV");
}

/// A film of horizontal stripes at two levels (texture the exposure must
/// see), each pixel the mean of `spp` samples of a two-valued estimator
/// (0 or 2× the pixel's level, by a fixed hash) when `spp` is given.
fn striped(spp: Option<u32>) -> Film {
    let (w, h) = (320, 180);
    let mut film = Film::new(w, h);
    for j in 0..h {
        for i in 0..w {
            let level = if (j / 3) % 2 == 0 { 0.05 } else { 1.0 };
            let v = match spp {
                None => level,
                Some(n) => {
                    let hits = (0..n)
                        .filter(|&s| {
                            let x = ((j * w + i) as u32).wrapping_mul(0x9E37_79B9)
                                ^ s.wrapping_mul(0x85EB_CA6B);
                            x.wrapping_mul(0xC2B2_AE35).rotate_left(13) & 1 == 1
                        })
                        .count();
                    level * 2.0 * hits as f32 / n as f32
                }
            };
            film.set(i, j, Vec3::splat(v));
        }
    }
    film
}

#[test]
fn auto_exposure_of_a_noisy_film_matches_its_converged_self() {
    // Four samples of a 0-or-2× estimator per pixel: a pixel is black one
    // time in 16 and its logarithm is biased low, so a per-pixel log average
    // exposes the noisy film 0.47 EV brighter than the converged one (blocks
    // of one pixel). Block means of 64 pixels carry 1/64 of the variance:
    // 0.002 EV.
    assert_eq!(exposure_block_side(180), 8);
    let converged = auto_exposure(&striped(None));
    let noisy = auto_exposure(&striped(Some(4)));
    let shift = exposure_ev(noisy) - exposure_ev(converged);
    assert!(shift.abs() < 0.05, "noisy film exposed {shift} EV off");
    // The converged film's exposure: 3-row stripes inside 8-row blocks mix
    // the levels; the mean over blocks of ln(block mean) is its log average.
    let side = exposure_block_side(180);
    let rows: Vec<f64> = (0..180)
        .map(|j| if (j / 3) % 2 == 0 { 0.05 } else { 1.0 })
        .collect();
    let ln_sum: f64 = rows
        .chunks(side)
        .map(|b| b.len() as f64 * (b.iter().sum::<f64>() / b.len() as f64).ln())
        .sum();
    let expected = MIDDLE_GREY as f64 / (ln_sum / 180.0).exp();
    assert!(
        (converged as f64 / expected - 1.0).abs() < 1e-5,
        "{converged} vs {expected}"
    );
}

#[test]
fn auto_exposure_floors_black_pixels_relative_to_bright_reference() {
    // Half black, half at level L: the black half counts at 1e-3·L, so the
    // log average is L·sqrt(1e-3) and the scale 0.18 / (L·sqrt(1e-3)).
    let level = 4.0f32;
    let mut film = Film::new(10, 10);
    film.rgb[50..]
        .iter_mut()
        .for_each(|p| *p = Vec3::splat(level));
    let expected = 0.18 / (level as f64 * EXPOSURE_FLOOR_FRACTION.sqrt());
    let scale = auto_exposure(&film) as f64;
    assert!(
        (scale / expected - 1.0).abs() < 1e-5,
        "{scale} vs {expected}"
    );
}

#[test]
fn exposure_ev_reports_stops() {
    let film = Film::uniform(2, 2, Vec3::splat(0.045));
    // 0.18 / 0.045 = 4 → +2 EV.
    assert!((exposure_ev(auto_exposure(&film)) - 2.0).abs() < 1e-5);
}

#[test]
fn tone_curve_is_monotonic_from_zero_to_one() {
    assert_eq!(tone_curve_aces(0.0), 0.0);
    assert_eq!(tone_curve_aces(-1.0), 0.0);
    assert_eq!(tone_curve_aces(f32::NAN), 0.0);
    assert_eq!(tone_curve_aces(f32::INFINITY), 1.0);
    assert_eq!(tone_curve_aces(1e30), 1.0);
    let mut prev = 0.0;
    for k in 1..=20_000 {
        let x = k as f32 * 1e-3;
        let y = tone_curve_aces(x);
        assert!(y >= prev, "not monotonic at {x}");
        assert!((0.0..=1.0).contains(&y));
        prev = y;
    }
    assert!(tone_curve_aces(7.0) > 0.99);
    // Narkowicz's fit at middle grey.
    let expected = 0.18 * (2.51 * 0.18 + 0.03) / (0.18 * (2.43 * 0.18 + 0.59) + 0.14);
    assert!((tone_curve_aces(0.18) - expected).abs() < 1e-6);
}

#[test]
fn srgb_oetf_matches_iec_61966_2_1_at_edges() {
    assert_eq!(srgb_oetf(0.0), 0.0);
    assert!((srgb_oetf(1.0) - 1.0).abs() < 1e-6);
    // The linear segment ends at 0.0031308 → 12.92 · 0.0031308 = 0.04044994.
    assert!((srgb_oetf(0.003_130_8) - 0.040_449_936).abs() < 1e-7);
    // The two pieces meet: just above the knee the power law gives nearly the same value.
    assert!((srgb_oetf(0.003_130_9) - 0.040_449_936).abs() < 1e-5);
    assert!(srgb_oetf(0.003_130_9) >= srgb_oetf(0.003_130_8));
    assert!((srgb_oetf(0.18) - 0.461_356).abs() < 1e-5);
    assert_eq!(srgb_oetf(2.0), srgb_oetf(1.0));
    assert_eq!(srgb_oetf(-1.0), 0.0);
}

#[test]
fn quantize_rounds_to_nearest_and_saturates() {
    assert_eq!(quantize_u8(0.0), 0);
    assert_eq!(quantize_u8(1.0), 255);
    assert_eq!(quantize_u8(0.5 / 255.0 - 1e-6), 0);
    assert_eq!(quantize_u8(0.5 / 255.0 + 1e-6), 1);
    assert_eq!(quantize_u8(1.5), 255);
    assert_eq!(quantize_u8(-0.2), 0);
    assert_eq!(quantize_u8(f32::NAN), 0);
}

#[test]
fn tonemap_writes_interleaved_rgb_in_pixel_order() {
    let mut film = Film::new(3, 2);
    film.set(0, 0, Vec3::new(100.0, 0.0, 0.0));
    film.set(2, 1, Vec3::new(0.0, 0.0, 100.0));
    film.set(1, 0, Vec3::splat(0.18));
    let out = tonemap_to_srgb8(&film, 1.0);
    assert_eq!(out.len(), 18);
    assert_eq!(&out[0..3], &[255, 0, 0]);
    assert_eq!(&out[15..18], &[0, 0, 255]);
    let grey = quantize_u8(srgb_oetf(tone_curve_aces(0.18)));
    assert_eq!(&out[3..6], &[grey, grey, grey]);
    // The exposure scale multiplies radiance before the curve.
    let brighter = tonemap_to_srgb8(&film, 4.0);
    assert_eq!(brighter[3], quantize_u8(srgb_oetf(tone_curve_aces(0.72))));
    assert!(brighter[3] > out[3]);
}
