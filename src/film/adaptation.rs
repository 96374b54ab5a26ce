//! Exposure with adaptation: dim scenes stay dim.
//!
//! A pure log-average auto exposure maps every scene to middle grey, so night
//! would look like an overcast day. Cameras and eyes adapt only partly: the
//! key value falls with the scene's absolute luminance. We use the key curve of
//! Krawczyk, Myszkowski and Seidel 2005 ("Lightness perception in tone
//! reproduction for HDR images", eq. 11), a(L̄) = 1.03 − 2 / (2 + log10(L̄ + 1))
//! with L̄ in cd/m², relative to its value at daylight: frames at or above
//! `DAYLIGHT_CD_M2` keep Reinhard's 0.18 exactly, darker frames get
//! proportionally less exposure (a street at night ≈ 2.5 stops under grey).

use super::exposure::{auto_exposure, log_average_luminance};
use super::Film;

/// Luminance (cd/m²) of one unit of the renderer's radiance luminance: the
/// scenes' sun of ~1000 W·m⁻² stands for ~100 klx of daylight.
pub const CD_M2_PER_UNIT: f64 = 100.0;

/// Log-average luminance (cd/m²) from which a frame is exposed as daylight.
pub const DAYLIGHT_CD_M2: f64 = 1000.0;

/// Krawczyk et al.'s key value for a log-average luminance in cd/m².
fn key_value(log_average_cd_m2: f64) -> f64 {
    1.03 - 2.0 / (2.0 + (log_average_cd_m2.max(0.0) + 1.0).log10())
}

/// Fraction of full (middle-grey) exposure a frame of log-average luminance
/// `log_average_cd_m2` receives: 1 at daylight and above, less when darker.
pub fn adaptation_factor(log_average_cd_m2: f64) -> f64 {
    (key_value(log_average_cd_m2) / key_value(DAYLIGHT_CD_M2)).clamp(1e-3, 1.0)
}

/// The frame's exposure scale from the left view: Reinhard's auto exposure
/// times the adaptation factor of the view's absolute luminance.
pub fn frame_exposure(film: &Film) -> f32 {
    match log_average_luminance(film) {
        Some(l) => auto_exposure(film) * adaptation_factor(l * CD_M2_PER_UNIT) as f32,
        None => 1.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn daylight_frames_keep_middle_grey() {
        // Grey films at and above daylight (10 units = 1000 cd/m²): the
        // log-average luminance is the level itself, and it must land on 0.18.
        for level in [10.0, 50.0, 1e3] {
            let film = Film::uniform(4, 4, Vec3::splat(level));
            assert_eq!(frame_exposure(&film), auto_exposure(&film));
            let grey = frame_exposure(&film) as f64 * level as f64;
            assert!((grey - 0.18).abs() < 1e-6, "level {level}: {grey}");
        }
        // Half the pixels at 20, half at 80 (grey, and a coloured pixel of
        // the same Rec.709 luminance): log-average √(20·80) = 40.
        let mut film = Film::uniform(4, 4, Vec3::splat(20.0));
        for (k, px) in film.rgb.iter_mut().enumerate() {
            if k % 2 == 1 {
                *px = if k == 1 {
                    // 0.2126·r + 0.7152·g + 0.0722·b = 80 with g = b = 60.
                    Vec3::new((80.0 - (0.7152 + 0.0722) * 60.0) / 0.2126, 60.0, 60.0)
                } else {
                    Vec3::splat(80.0)
                };
            }
        }
        let grey = frame_exposure(&film) as f64 * 40.0;
        assert!((grey - 0.18).abs() < 1e-6, "mixed daylight film: {grey}");
    }

    #[test]
    fn darker_frames_are_exposed_darker_but_still_lifted() {
        let mut prev_grey = f32::INFINITY;
        for level in [5.0, 0.5, 0.05, 0.005] {
            let film = Film::uniform(4, 4, Vec3::splat(level));
            let grey = frame_exposure(&film) * level;
            assert!(grey < prev_grey, "level {level}: {grey} not darker");
            assert!(grey > 0.18 * 0.02, "level {level}: crushed to {grey}");
            prev_grey = grey;
        }
        // A lit night street (~0.5 cd/m²) lands about 2–3 stops under grey.
        let night = Film::uniform(4, 4, Vec3::splat(0.5 / CD_M2_PER_UNIT as f32));
        let stops = (0.18 / (frame_exposure(&night) * 0.5 / CD_M2_PER_UNIT as f32)).log2();
        assert!((2.0..3.5).contains(&stops), "{stops} stops under grey");
    }
}
