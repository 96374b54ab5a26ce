//! The fixed display transform: exposure scale → filmic tone curve → sRGB OETF →
//! 8-bit quantisation, per channel.
//!
//! Tone curve: K. Narkowicz, "ACES Filmic Tone Mapping Curve" (blog, January
//! 2016), a rational fit of the ACES RRT + sRGB ODT:
//! f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), clamped to [0, 1].
//! f(0) = 0; f' > 0 on x ≥ 0 (the numerator of f' is 1.408x² + 0.7028x + 0.0042,
//! the x³ terms cancel), and f reaches 1 at x ≈ 7.24, so the clamped curve is
//! monotonic. sRGB OETF: IEC 61966-2-1:1999, piecewise linear below 0.0031308.

use super::Film;

/// Narkowicz's ACES filmic fit of exposed linear radiance `x`, clamped to [0, 1].
/// Negative and NaN inputs give 0; +inf gives 1.
#[inline]
pub fn tone_curve_aces(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if x >= 8.0 {
        // Beyond ≈7.24 the fit exceeds 1 and is clamped; this also keeps
        // inf / inf out of the rational function.
        return 1.0;
    }
    let y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    y.clamp(0.0, 1.0)
}

/// sRGB opto-electronic transfer function (IEC 61966-2-1) of a linear value in
/// [0, 1]: 12.92·v below 0.0031308, else 1.055·v^(1/2.4) − 0.055. Inputs are
/// clamped to [0, 1] first.
#[inline]
pub fn srgb_oetf(v: f32) -> f32 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// Quantises an encoded value in [0, 1] to u8 with round-to-nearest
/// (`round(v·255)`); out-of-range values saturate.
#[inline]
pub fn quantize_u8(v: f32) -> u8 {
    // `as u8` saturates and maps NaN to 0.
    (v * 255.0).round() as u8
}

/// Tone-maps a film to interleaved RGB8 sRGB (`3 * width * height` bytes,
/// row-major, top row first): each channel is multiplied by `exposure_scale`
/// (from [`super::auto_exposure`] of the frame's left view), passed through
/// [`tone_curve_aces`], [`srgb_oetf`] and [`quantize_u8`].
pub fn tonemap_to_srgb8(film: &Film, exposure_scale: f32) -> Vec<u8> {
    let mut out = Vec::with_capacity(film.rgb.len() * 3);
    for rgb in &film.rgb {
        for c in rgb.to_array() {
            out.push(quantize_u8(srgb_oetf(tone_curve_aces(c * exposure_scale))));
        }
    }
    out
}
