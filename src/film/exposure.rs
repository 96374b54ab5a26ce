//! Automatic exposure: one scale factor per frame, computed from the LEFT view
//! and applied to every view of the frame.
//!
//! Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images",
//! §2 eq. 1–2: the log-average luminance L̄ = exp(mean(ln(δ + L))) is mapped to
//! the key value a = 0.18 (middle grey), scale = a / L̄. Here δ is not an
//! absolute constant but a floor relative to the 99th-percentile luminance, so
//! the exposure is exactly scale-invariant (k·film gets scale/k) and a uniform
//! film of any level maps to 0.18. Luminance is Rec.709 (ITU-R BT.709 Y).

use super::Film;

/// The key value a of Reinhard et al. 2002: the log-average maps to this.
pub const MIDDLE_GREY: f32 = 0.18;

/// Pixels darker than this fraction of the 99th-percentile luminance count as
/// that floor in the log average (about 10 stops below the bright reference):
/// Reinhard's δ, made relative so exposure does not depend on radiance units.
pub const EXPOSURE_FLOOR_FRACTION: f64 = 1e-3;

/// The exposure is clamped to `[-EXPOSURE_EV_MAX, EXPOSURE_EV_MAX]` stops,
/// a guard against overflow only; realistic frames are far inside it.
pub const EXPOSURE_EV_MAX: f32 = 40.0;

/// Rec.709 relative luminance Y of linear RGB (the one definition lives in `shaders_cpu`).
pub use shaders_cpu::sampling::luminance as luminance_rec709;

/// Exposure in stops of a linear scale factor: `exposure_ev = log2(scale)`.
/// Positive EV brightens. Precondition: `scale > 0`.
pub fn exposure_ev(scale: f32) -> f32 {
    scale.log2()
}

/// The frame's exposure scale factor from the left view's film.
///
/// Multiply every view's radiance by the result before the tone curve. Returns
/// 1.0 (EV 0) when fewer than 1% of the finite pixels have positive luminance
/// (black frames, or black with a few fireflies). Non-finite pixels are
/// ignored; negative luminance counts as 0. Fireflies barely move the result:
/// each pixel enters capped at the 99th percentile, which a few cannot move.
pub fn auto_exposure(film: &Film) -> f32 {
    match log_average_luminance(film) {
        Some(log_average) => {
            let scale = MIDDLE_GREY as f64 / log_average;
            let limit = (EXPOSURE_EV_MAX as f64).exp2();
            scale.clamp(1.0 / limit, limit) as f32
        }
        None => 1.0,
    }
}

/// The log average runs over the means of square blocks of pixels, this many
/// to the image height (blocks of 8 pixels at 180 rows, 38 at 900): a pixel's
/// noise lowers its logarithm on average (Jensen's inequality), so a per-pixel
/// log average exposes a noisy render brighter than its converged self; a
/// block's mean has a fraction of that noise. Sizing blocks by the height
/// keeps the exposure of a frame the same at every resolution.
pub const EXPOSURE_BLOCKS_PER_HEIGHT: usize = 24;

/// Side in pixels of the exposure's blocks for a film `height` pixels tall.
pub fn exposure_block_side(height: usize) -> usize {
    height.div_ceil(EXPOSURE_BLOCKS_PER_HEIGHT).max(1)
}

/// Reinhard's log-average luminance L̄ of `film` over block means (see
/// [`EXPOSURE_BLOCKS_PER_HEIGHT`]), each block weighted by its finite pixels;
/// `None` when the film is (almost) black. Pixels enter capped at the 99th
/// percentile: a block's mean would otherwise carry a firefly's whole weight.
/// The floor is relative to the same percentile, as described above.
pub fn log_average_luminance(film: &Film) -> Option<f64> {
    let lum: Vec<f32> = film.rgb.iter().map(|&rgb| luminance_rec709(rgb)).collect();
    let mut finite: Vec<f32> = lum
        .iter()
        .filter(|l| l.is_finite())
        .map(|l| l.max(0.0))
        .collect();
    if finite.is_empty() {
        return None;
    }
    // 99th percentile by selection, O(n): the bright reference.
    let k = ((finite.len() - 1) as f64 * 0.99).round() as usize;
    let (_, &mut reference, _) = finite.select_nth_unstable_by(k, f32::total_cmp);
    if reference <= 0.0 {
        return None;
    }
    let floor = reference as f64 * EXPOSURE_FLOOR_FRACTION;
    // Sums in f64: over 1.44 M terms the rounding stays far below f32
    // precision, so a uniform film maps to 0.18 to f32 precision.
    let (sums, counts) = block_sums(&lum, film.width, film.height, reference);
    let sum_ln: f64 = (sums.iter().zip(&counts))
        .filter(|(_, &n)| n > 0)
        .map(|(&sum, &n)| n as f64 * (sum / n as f64).max(floor).ln())
        .sum();
    Some((sum_ln / finite.len() as f64).exp())
}

/// Per block (raster order of blocks): the sum of its finite luminances
/// `lum` (raster order, `width × height`) clamped to [0, `cap`], and how
/// many there are.
fn block_sums(lum: &[f32], width: usize, height: usize, cap: f32) -> (Vec<f64>, Vec<usize>) {
    let side = exposure_block_side(height);
    let blocks_x = width.div_ceil(side);
    let blocks = blocks_x * height.div_ceil(side);
    let (mut sums, mut counts) = (vec![0.0f64; blocks], vec![0usize; blocks]);
    for (k, &l) in lum.iter().enumerate().filter(|(_, l)| l.is_finite()) {
        let b = (k / width / side) * blocks_x + (k % width) / side;
        sums[b] += l.clamp(0.0, cap) as f64;
        counts[b] += 1;
    }
    (sums, counts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn rec709_luminance_weights_sum_to_one() {
        assert!((luminance_rec709(Vec3::ONE) - 1.0).abs() < 1e-6);
        // ITU-R BT.709 luma coefficients.
        assert!((luminance_rec709(Vec3::X) - 0.2126).abs() < 1e-7);
        assert!((luminance_rec709(Vec3::Y) - 0.7152).abs() < 1e-7);
        assert!((luminance_rec709(Vec3::Z) - 0.0722).abs() < 1e-7);
    }

    #[test]
    fn exposure_ev_is_log2_of_scale() {
        assert_eq!(exposure_ev(8.0), 3.0);
        assert_eq!(exposure_ev(0.25), -2.0);
    }
}
