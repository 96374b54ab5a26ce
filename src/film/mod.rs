//! Film: the per-view linear HDR radiance buffer, the frame's shared exposure,
//! optional sensor noise and the fixed tone curve to 8-bit sRGB. (Its
//! image-space denoising lives in `crate::denoise`; the maps a frame writes
//! are declared in `output::registry`.)
//!
//! Conventions: pixels are row-major, pixel (column i, row j) at `j * width + i`,
//! row 0 at the top of the image. Radiance is linear, in the renderer's
//! radiometric units; only the tone-mapping step turns it into display values.
//! Exposure is computed once per frame from the LEFT view and applied to every
//! view, so a surface has the same brightness in both images (GROUND_TRUTH.md).

mod adaptation;
mod exposure;
mod noise;
mod tone;

pub use adaptation::{adaptation_factor, frame_exposure, CD_M2_PER_UNIT, DAYLIGHT_CD_M2};
pub use exposure::{
    auto_exposure, exposure_block_side, exposure_ev, log_average_luminance, luminance_rec709,
    EXPOSURE_BLOCKS_PER_HEIGHT, EXPOSURE_EV_MAX, EXPOSURE_FLOOR_FRACTION, MIDDLE_GREY,
};
pub use noise::{apply_sensor_noise, NoiseKey, SensorNoise, BASE_ISO};
pub use tone::{quantize_u8, srgb_oetf, tone_curve_aces, tonemap_to_srgb8};

use glam::Vec3;

/// Linear HDR radiance of one view, one `Vec3` (linear Rec.709 RGB) per pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major radiance, `rgb[j * width + i]` for column i, row j (row 0 on top).
    pub rgb: Vec<Vec3>,
}

impl Film {
    /// A black film of `width × height` pixels.
    pub fn new(width: usize, height: usize) -> Film {
        Film {
            width,
            height,
            rgb: vec![Vec3::ZERO; width * height],
        }
    }

    /// A film filled with one radiance value (used by tests and calibration).
    pub fn uniform(width: usize, height: usize, rgb: Vec3) -> Film {
        Film {
            width,
            height,
            rgb: vec![rgb; width * height],
        }
    }

    /// Index into `rgb` of column `i`, row `j`. Precondition: `i < width`, `j < height`.
    #[inline]
    pub fn index(&self, i: usize, j: usize) -> usize {
        debug_assert!(i < self.width && j < self.height);
        j * self.width + i
    }

    /// Radiance at column `i`, row `j`.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> Vec3 {
        self.rgb[self.index(i, j)]
    }

    /// Sets the radiance at column `i`, row `j`.
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, rgb: Vec3) {
        let k = self.index(i, j);
        self.rgb[k] = rgb;
    }

    /// Number of pixels, `width * height`.
    pub fn pixel_count(&self) -> usize {
        self.width * self.height
    }
}
